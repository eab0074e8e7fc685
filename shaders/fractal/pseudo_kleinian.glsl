// @formula A pseudo-Kleinian set (after Knighty, fractalforums.com 2010): a box fold and an inversion in a sphere, whose limit set resembles a Kleinian group's
// @iterations 10 [1, 30]
// @bound size * 1.7320508
// @step 0.33
// @trap 0 2
// @deep
//
// Each iteration reflects every coordinate beyond ±fold back inside (the Mandelbox's box fold, an
// isometry) and inverts the points inside the sphere of radius √k (z → k z / |z|², a conformal map
// that scales by k / |z|² ≥ 1; points outside it are left alone). The set drawn is the image of the
// slab |z_z| < thickness under these maps: the slab's distance in the final coordinates divided by
// the accumulated scale bounds the distance to it. Folds repeat space without end, so the set is cut
// to a cube of half-side `size`. The scale at a point is not the scale between it and the set (an
// inversion scales more nearer its centre), so the estimate overshoots: up to 2.95 times at thickness
// 0.001 and 2.6 at the defaults (check-formula; its first version, 96 random rays, passed 0.45): the
// step factor is 0.33.
#include "fractal/common.glsl"
uniform float uFold;      // @param 1 [0.2, 4] the box fold's limit
uniform float uInversion; // @param 1.2 [0.2, 4] k: points inside the sphere of radius √k are inverted in it
uniform float uThickness; // @param 0.08 [0.001, 1] half the thickness of the slab the maps carry around
uniform float uSize;      // @param 2 [0.1, 10] half the side of the cube the set is cut to

real formulaDE(real3 p, out float trap)
{
    real3 z = p;
    real scale = 1.0, k = uInversion;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        z = boxFold(z, uFold);
        real r2 = max(dot(z, z), real(1e-30)), s = max(k / r2, real(1.0));
        trap = min(trap, float(sqrt(r2)));
        z *= s;
        scale *= s;
    }
    real set = (abs(z.z) - real(uThickness)) / scale;
    return max(set, realBox(p, real(uSize)));
}
