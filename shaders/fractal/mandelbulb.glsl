// @formula The Mandelbulb (D. White and P. Nylander, 2009): z → zⁿ + c with the triplex power in spherical coordinates
// @iterations 12 [1, 64]
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
// origin at |z| ≈ 0.4 … 1.1: @trap spreads that over the palette.
#include "fractal/common.glsl"
uniform float uPower;   // @param 8 [2, 16] the exponent n of z → zⁿ + c
uniform float uBailout; // @param 2 [1.5, 64] escape radius

void formulaStep(inout real3 z, inout real dr, inout float trap)
{
    trap = min(trap, float(length(z)));
    dr *= real(uPower) * bulbPower(z, uPower);
}
