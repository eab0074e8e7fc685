// @formula Quaternion Julia sets (Norton 1982; Hart, Sandin and Kauffman 1989): q → q² + c in the quaternions, a 3D slice at w
// @iterations 12 [1, 64]
// @bound 1.8
// @step 0.9
// @trap 0 1
// @deep
//
// q = (x, y, z, w) with the point's w fixed at the slice; q² = (a² − |v|², 2 a v) for q = (a, v).
// The running derivative of q² + c is 2 q q', so |q'| → 2 |q| |q'|, and the distance estimate is
// ½ · |q| · ln |q| / |q'| (Hart, Sandin and Kauffman 1989), written with squared norms below.
#include "fractal/common.glsl"
uniform vec3 uC;      // @param -0.2,0.6,0.2 [-2, 2] c's first three components (1, i, j)
uniform float uCw;    // @param 0.0 [-2, 2] c's fourth component (k)
uniform float uSlice; // @param 0.0 [-2, 2] the w of the 3D slice drawn

const float QJ_ESCAPE2 = 256.0; // |q|² beyond which q only grows

real formulaDE(real3 p, out float trap)
{
    real4 q = real4(p, uSlice), c = real4(uC, uCw);
    real q2 = dot(q, q), dq2 = 1.0; // |q|², |q'|²
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        dq2 *= 4.0 * q2;
        q = real4(q.x * q.x - dot(q.yzw, q.yzw), 2.0 * q.x * q.yzw) + c;
        q2 = dot(q, q);
        trap = min(trap, float(sqrt(q2)));
        if (q2 > QJ_ESCAPE2)
            break;
    }
    // ½ |q| ln|q| / |q'| = ¼ sqrt(|q|² / |q'|²) ln |q|²; an orbit that stays small is inside
    return q2 > 1.0 ? 0.25 * sqrt(q2 / dq2) * realLog(q2) : real(0.0);
}
