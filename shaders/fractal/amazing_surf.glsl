// @formula Amazing Surf, a Mandelbox variant (after T. Lowe's Mandelbox, 2010): the box fold on x and z only, a sphere fold, scale, + c
// @iterations 14 [1, 64]
// @bound 2 * (abs(scale) + 1) / (abs(scale) - 1) * 1.7320508 * max(fold_limit, fixed_radius)
// @step 0.7
// @require min_radius < fixed_radius "fractal.min_radius must be below fixed_radius"
// @escape 1e4
// @de linear
// @trap 0 fixed_radius
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

void formulaStep(inout real3 z, inout real dr, inout float trap)
{
    z.xz = clamp(z.xz, -real(uFoldLimit), real(uFoldLimit)) * 2.0 - z.xz;
    trap = min(trap, float(length(z)));
    real k = sphereFold(z, uMinRadius, uFixedRadius);
    z = real(uScale) * (realMat3(twistMatrix(uTwist)) * z); // a rotation keeps |z|: the derivative is unchanged
    dr *= abs(real(uScale)) * k;
}
