// @formula Menger sponge as a kaleidoscopic IFS with a twist (after Knighty's KIFS, fractalforums 2010): octahedral fold, rotation, scale 3 about (1,1,1), the middle slab shifted out
// @iterations 6 [1, 20]
// @bound 1.7320508 * 1.2
// @step 0.8
//
// Unlike menger.glsl (exact distance, no rotation), this iterates: fold into x ≥ y ≥ z ≥ 0, turn by
// the twist, scale by s about the corner (1, 1, 1), and move the points of the middle slab (z above
// half a cell) back by one cell, which carves the cross-shaped holes. With the twist the set is no
// longer a sponge but its relatives. The estimate (|z_n| − √3) / sⁿ bounds the distance where the
// maps are s-Lipschitz; the slab's shift is not continuous, so the step factor stays below 1 (and
// check-formula measures the overshoot).
#include "fractal/common.glsl"
uniform float uScale; // @param 3 [2, 4] the scale factor s
uniform vec3 uTwist;  // @param 0.1,0.08,0 [-3.1416, 3.1416] rotation (radians about x, y, z) each iteration

const float MKIFS_ESCAPE2 = 1e6;

float mengerKifsDE(vec3 p, out float trap)
{
    vec3 z = p;
    mat3 twist = twistMatrix(uTwist);
    float scale = 1.0, s = uScale;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        z = abs(z);
        if (z.x < z.y) z.xy = z.yx;
        if (z.x < z.z) z.xz = z.zx;
        if (z.y < z.z) z.yz = z.zy;
        z = twist * z;
        z.xy = z.xy * s - (s - 1.0);
        z.z = z.z * s;
        if (z.z > 0.5 * (s - 1.0))
            z.z -= s - 1.0;
        scale *= s;
        trap = min(trap, dot(z, z));
        if (dot(z, z) > MKIFS_ESCAPE2)
            break;
    }
    return (length(z) - 1.7320508) / scale;
}

vec2 map(vec3 p)
{
    float d, trap;
    return outsideBound(p, d) ? vec2(d, MATERIAL_BOUND) : vec2(mengerKifsDE(p, trap), 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    mengerKifsDE(p, trap);
    return base * paletteColor(sqrt(trap) / 3.0);
}
