// @formula The Bristorbrot (D. Bristor, 2010): a polynomial 3D Mandelbrot, (x, y, z) → (x² − y² − z², y(2x − z), z(2x + y)) + c
// @iterations 10 [8, 64]
// @bound 2.2
// @step 0.7
// @escape bailout
// @de log
// @trap 0 1.2
// @deep
//
// No trigonometry: a quadratic map whose x-y plane is the Mandelbrot set (z = 0 stays 0). The running
// derivative grows by the Jacobian's norm, its largest singular value (fractal/common.glsl), and the
// estimate is ½ · |z| · ln |z| / |dz| (Hart et al. 1989) with the step factor below (check-formula
// measures it). The bound 2√2 |z| used before is √2 times that norm on the axes, and compounded over
// the iterations it made the estimate about 8 times too short: the surface drawn, where the estimate
// falls under a footprint, stood 37 % wider than the footprint allows. With the true norm the estimate
// holds from 8 iterations (at 5 to 7 it overshot 3 to 234 times: the orbits have too few steps to grow,
// as the Mandelbulb's at a low power), so they start there.
#include "fractal/common.glsl"
uniform float uBailout; // @param 4 [3, 64] escape radius

// The map works on (y, x, z): the Mandelbrot plane stands upright (the swap is an isometry, so the
// derivative does not see it).
void formulaStep(inout real3 z, inout real dr, inout float trap)
{
    trap = min(trap, float(length(z)));
    real3 w = z.yxz;
    vec3 v = vec3(w); // the Jacobian's largest singular value (its columns; the swap does not change it)
    dr *= real(largestSingular(mat3(2.0 * v, vec3(-2.0 * v.y, 2.0 * v.x - v.z, v.z), vec3(-2.0 * v.z, -v.y, 2.0 * v.x + v.y))));
    z = real3(w.x * w.x - w.y * w.y - w.z * w.z, w.y * (2.0 * w.x - w.z), w.z * (2.0 * w.x + w.y)).yxz;
}
