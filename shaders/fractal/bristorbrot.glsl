// @formula The Bristorbrot (D. Bristor, 2010): a polynomial 3D Mandelbrot, (x, y, z) → (x² − y² − z², y(2x − z), z(2x + y)) + c
// @iterations 10 [1, 64]
// @bound 2.2
// @step 0.7
// @escape bailout
// @de log
// @trap 0 1.2
// @deep
//
// No trigonometry: a quadratic map whose x-y plane is the Mandelbrot set (z = 0 stays 0). The running
// derivative is the Jacobian's norm, bounded by 2|z|·√2·|dz| + 1 (each row of the Jacobian has norm at
// most 2·√2·|z|), so the estimate ½ · |z| · ln |z| / |dz| (Hart et al. 1989) holds with the step factor
// below; check-formula measures how far.
#include "fractal/common.glsl"
uniform float uBailout; // @param 4 [2, 64] escape radius

// The map works on (y, x, z): the Mandelbrot plane stands upright (the swap is an isometry, so the
// derivative does not see it).
void formulaStep(inout real3 z, inout real dr, inout float trap)
{
    trap = min(trap, float(length(z)));
    real3 w = z.yxz;
    dr *= 2.0 * 1.41421356 * length(w);
    z = real3(w.x * w.x - w.y * w.y - w.z * w.z, w.y * (2.0 * w.x - w.z), w.z * (2.0 * w.x + w.y)).yxz;
}
