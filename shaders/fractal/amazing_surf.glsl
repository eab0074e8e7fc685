// @formula Amazing Surf, a Mandelbox variant (after T. Lowe's Mandelbox, 2010): the box fold on x and z only, a sphere fold, scale, + c
// @iterations 14 [1, 64]
// @bound 2 * (abs(scale) + 1) / (abs(scale) - 1) * 1.7320508
// @step 0.7
// @require min_radius < fixed_radius "fractal.min_radius must be below fixed_radius"
//
// As mandelbox.glsl, but y is never box-folded, so the set is a surface-like sheet instead of a box,
// and a rotation each iteration (the twist) lifts the sheet into relief.
// The estimate is the Mandelbox's |z| / |dr| with dr → |s| · k · dr + 1 (k the sphere fold's scale);
// the unfolded axis makes it less tight, hence the smaller step factor.
#include "fractal/common.glsl"
uniform float uScale;       // @param 2.2 [-4, 4] not (-1.05, 1.05) the scale factor s
uniform float uMinRadius;   // @param 0.4 [0.01, 10] sphere fold: inner radius
uniform float uFixedRadius; // @param 1 [0.01, 10] sphere fold: outer radius
uniform float uFoldLimit;   // @param 1 [0.01, 10] box fold (x and z): the limit
uniform vec3 uTwist;        // @param 0.35,0,0.15 [-3.1416, 3.1416] rotation (radians about x, y, z) each iteration

const float SURF_ESCAPE2 = 1e8;

float surfDE(vec3 c, out float trap)
{
    mat3 twist = twistMatrix(uTwist);
    float minR2 = uMinRadius * uMinRadius, fixedR2 = uFixedRadius * uFixedRadius;
    vec3 z = c;
    float dr = 1.0;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        z.xz = clamp(z.xz, -uFoldLimit, uFoldLimit) * 2.0 - z.xz;
        float r2 = dot(z, z);
        trap = min(trap, r2);
        float k = r2 < minR2 ? fixedR2 / minR2 : (r2 < fixedR2 ? fixedR2 / r2 : 1.0);
        z = uScale * k * (twist * z) + c; // a rotation keeps |z|: the derivative is unchanged
        dr = dr * abs(uScale) * k + 1.0;
        if (dot(z, z) > SURF_ESCAPE2)
            break;
    }
    return length(z) / abs(dr);
}

vec2 map(vec3 p)
{
    float d, trap;
    return outsideBound(p, d) ? vec2(d, MATERIAL_BOUND) : vec2(surfDE(p, trap), 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    surfDE(p, trap);
    return base * paletteColor(sqrt(trap) / uFixedRadius);
}
