// @formula The Mandelbulb (D. White and P. Nylander, 2009): z → zⁿ + c with the triplex power in spherical coordinates
// @iterations 12 [8, 64]
// @bound 1.6
// @step 0.9
// @escape bailout
// @de log
// @trap 0.4 1.1
// @deep whole power
//
// The power is bulbPower() in fractal/common.glsl (trigonometry in float, exact complex products in
// double, which needs a whole n). The running derivative gains n rⁿ⁻¹ a step and the estimate is
// ½ · ln r · r / dr (J. Hart et al. 1989): fractal/iterate.glsl. Surface orbits come closest to the
// origin at |z| ≈ 0.4 … 1.1: @trap spreads that over the palette. The set lies within
// |c| ≤ 2^(1/(n−1)) (beyond it |z|ⁿ − |c| > |z| at every step: |zⁿ| = |z|ⁿ for the triplex power), at
// most 1.41 over the powers allowed (at power 3): @bound 1.6 holds them all.
//
// The running derivative takes the step's largest stretch (formulaStep: the azimuthal one near the
// pole axis, which the usual n rⁿ⁻¹ misses): with it the worst estimate / distance check-formula finds
// is 0.69 to 0.76 at every power from 3 to 16, 8 iterations or more and bailouts 2 to 16, over four
// seeds of its random points and rays; without it 1.4 to 6.4 (random spots near the poles, which 96
// rays had missed). Where it still fails the ranges stop: power 2 (8.7 at 20 iterations, a seed in
// four), fewer than 8 iterations (3.3 at 4: the orbits have too few steps to grow before they are cut),
// a bailout under 2 (1.9 at power 3) or past 16 (the estimate overflows: +Inf at 64 and power 12).
#include "fractal/common.glsl"
uniform float uPower;   // @param 8 [3, 16] the exponent n of z → zⁿ + c
uniform float uBailout; // @param 2 [2, 16] escape radius

void formulaStep(inout real3 z, inout real dr, inout float trap)
{
    trap = min(trap, float(length(z)));
    // How far the step stretches: n rⁿ⁻¹ along r and θ, but n rⁿ⁻¹ · |sin nθ| / sin θ around the pole
    // axis (a circle of radius r sin θ becomes one of rⁿ |sin nθ|, its angle times n): up to n times
    // more near the poles. The usual n rⁿ⁻¹ alone made the estimate overshoot up to 6.4 times there
    // (check-formula over seeds). The angle from the axis and its sine in the estimate's precision, the
    // trigonometry in float (the factor needs no more).
    float rho = float(length(z.xz)), r = float(length(z)), theta = atan(rho, float(z.y));
    float stretch = rho > 1e-6 * r ? abs(sin(uPower * theta)) * r / rho : uPower;
    dr *= real(uPower) * bulbPower(z, uPower) * max(real(1.0), real(stretch));
}
