// @formula The quaternion Mandelbrot set (Norton 1982): q → q² + c with c the point itself (w at the slice), a 3D slice of a 4D set
// @iterations 12 [1, 64]
// @bound 2.1
// @step 0.9
// @trap 0 1.5
// @deep
//
// As quaternion_julia.glsl, but c is the point drawn, so the running derivative gains the "+ 1" of
// the Mandelbrot set: q' → 2 q q' + 1 (|q'| bounded by 2|q||q'| + 1). The estimate is
// ½ · |q| · ln |q| / |q'| (Hart, Sandin and Kauffman 1989). Its slices are surfaces of revolution
// about the real axis, which the slice's w bends.
#include "fractal/common.glsl"
uniform float uSlice; // @param 0.0 [-2, 2] the w of the 3D slice drawn

const float QM_ESCAPE2 = 256.0;

real formulaDE(real3 p, out float trap)
{
    real4 c = real4(p.y, p.x, p.z, uSlice); // the real axis upright: the set's axis of revolution is y
    real4 q = c;
    real q2 = dot(q, q), dq = 1.0;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        dq = 2.0 * sqrt(q2) * dq + 1.0;
        q = real4(q.x * q.x - dot(q.yzw, q.yzw), 2.0 * q.x * q.yzw) + c;
        q2 = dot(q, q);
        trap = min(trap, float(sqrt(q2)));
        if (q2 > QM_ESCAPE2)
            break;
    }
    return q2 > 1.0 ? 0.25 * sqrt(q2) * realLog(q2) / dq : real(0.0);
}
