// @formula The Mandelbox (T. Lowe, 2010): z → s · sphereFold(boxFold(z)) + c
// @iterations 12 [1, 64]
// @bound 2 * (abs(scale) + 1) / (abs(scale) - 1) * 1.7320508 * max(fold_limit, fixed_radius)
// @step 0.8
// @require min_radius < fixed_radius "fractal.min_radius must be below fixed_radius"
// @escape 1e4
// @de linear
// @trap 0 fixed_radius
// @deep
//
// With |s| > 1 and the folds at 1 the set lies in the cube of half-side 2(|s|+1)/(|s|-1) (Lowe's
// Mandelbox): @bound is the sphere around that cube. Scaling the fold limit and both radii by λ scales
// the set by λ (each fold commutes with the scaling), so the bound grows with the larger length (at
// fold_limit 2 the fixed bound drew a ball: IoU 0.40). At |s| ≤ 1 the set is unbounded or empty, so
// |s| < 1.05 is refused.
// The Mandelbox (T. Lowe, 2010): z → s · sphereFold(boxFold(z)) + c. The box fold reflects each
// coordinate beyond ±fold limit; the sphere fold inverts radii between min and fixed radius (scaling
// inside min radius by a constant, so r = 0 needs no guard). DE = |z| / |dr| with the running
// derivative dr → |s| · k · dr + 1 (k the fold's scale).
#include "fractal/common.glsl"
uniform float uScale;       // @param 2 [-4, 4] not (-1.05, 1.05) the scale factor s
uniform float uMinRadius;   // @param 0.5 [0.01, 10] sphere fold: inner radius
uniform float uFixedRadius; // @param 1 [0.01, 10] sphere fold: outer radius
uniform float uFoldLimit;   // @param 1 [0.01, 10] box fold: the limit

void formulaStep(inout real3 z, inout real dr, inout float trap)
{
    z = boxFold(z, uFoldLimit);
    trap = min(trap, float(length(z)));
    real k = sphereFold(z, uMinRadius, uFixedRadius);
    z *= real(uScale);
    dr *= abs(real(uScale)) * k;
}
