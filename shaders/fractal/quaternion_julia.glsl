// @formula Quaternion Julia sets (Norton 1982; Hart, Sandin and Kauffman 1989): q → q² + c in the quaternions, a 3D slice at w
// @iterations 12 [1, 64]
// @bound 1.8
// @step 0.9
//
// q = (x, y, z, w) with the point's w fixed at the slice; q² = (a² − |v|², 2 a v) for q = (a, v).
// The running derivative of q² + c is 2 q q', so |q'| → 2 |q| |q'|, and the distance estimate is
// ½ · |q| · ln |q| / |q'| (Hart, Sandin and Kauffman 1989), written with squared norms below.
#include "fractal/common.glsl"
uniform vec3 uC;      // @param -0.2,0.6,0.2 [-2, 2] c's first three components (1, i, j)
uniform float uCw;    // @param 0.0 [-2, 2] c's fourth component (k)
uniform float uSlice; // @param 0.0 [-2, 2] the w of the 3D slice drawn

const float QJ_ESCAPE2 = 256.0; // |q|² beyond which q only grows

float quatJuliaDE(vec3 p, out float trap)
{
    vec4 q = vec4(p, uSlice), c = vec4(uC, uCw);
    float q2 = dot(q, q), dq2 = 1.0; // |q|², |q'|²
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        dq2 *= 4.0 * q2;
        q = vec4(q.x * q.x - dot(q.yzw, q.yzw), 2.0 * q.x * q.yzw) + c;
        q2 = dot(q, q);
        trap = min(trap, q2);
        if (q2 > QJ_ESCAPE2)
            break;
    }
    // ½ |q| ln|q| / |q'| = ¼ sqrt(|q|² / |q'|²) ln |q|²; an orbit that stays small is inside
    return q2 > 1.0 ? 0.25 * sqrt(q2 / dq2) * log(q2) : 0.0;
}

vec2 map(vec3 p)
{
    float d, trap;
    return outsideBound(p, d) ? vec2(d, MATERIAL_BOUND) : vec2(quatJuliaDE(p, trap), 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    quatJuliaDE(p, trap);
    return base * paletteColor(smoothstep(0.0, 1.0, sqrt(trap)));
}
