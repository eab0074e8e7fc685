// @formula The Mandelbox (T. Lowe, 2010): z → s · sphereFold(boxFold(z)) + c
// @iterations 12 [1, 64]
// @bound 2 * (abs(scale) + 1) / (abs(scale) - 1) * 1.7320508
// @step 0.8
// @require min_radius < fixed_radius "fractal.min_radius must be below fixed_radius"
//
// With |s| > 1 the set lies in the cube of half-side 2(|s|+1)/(|s|-1) (Lowe's Mandelbox): @bound is
// the sphere around that cube. At |s| ≤ 1 the set is unbounded or empty, so |s| ≤ 1.05 is refused.
// The Mandelbox (T. Lowe, 2010): z → s · sphereFold(boxFold(z)) + c. The box fold reflects each
// coordinate beyond ±fold limit; the sphere fold inverts radii between min and fixed radius (scaling
// inside min radius by a constant, so r = 0 needs no guard). DE = |z| / |dr| with the running
// derivative dr → |s| · k · dr + 1 (k the fold's scale).
#include "fractal/common.glsl"
uniform float uScale;       // @param 2 [-4, 4] not (-1.05, 1.05) the scale factor s
uniform float uMinRadius;   // @param 0.5 [0.01, 10] sphere fold: inner radius
uniform float uFixedRadius; // @param 1 [0.01, 10] sphere fold: outer radius
uniform float uFoldLimit;   // @param 1 [0.01, 10] box fold: the limit

const float BOX_ESCAPE2 = 1e8; // |z|² beyond which z only grows: stop before float overflows

float boxDE(vec3 c, out float trap)
{
    float scale = uScale, minR2 = uMinRadius * uMinRadius;
    float fixedR2 = uFixedRadius * uFixedRadius, limit = uFoldLimit;
    vec3 z = c;
    float dr = 1.0;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        z = clamp(z, -limit, limit) * 2.0 - z;
        float r2 = dot(z, z);
        trap = min(trap, r2);
        float k = r2 < minR2 ? fixedR2 / minR2 : (r2 < fixedR2 ? fixedR2 / r2 : 1.0);
        z = scale * k * z + c;
        dr = dr * abs(scale) * k + 1.0;
        if (dot(z, z) > BOX_ESCAPE2)
            break;
    }
    return length(z) / abs(dr);
}

vec2 map(vec3 p)
{
    float d, trap;
    return outsideBound(p, d) ? vec2(d, MATERIAL_BOUND) : vec2(boxDE(p, trap), 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    boxDE(p, trap);
    return base * paletteColor(sqrt(trap) / uFixedRadius);
}
