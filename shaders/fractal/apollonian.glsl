// @formula An Apollonian sphere packing (after the limit sets of inversion groups; Mumford, Series and Wright, "Indra's Pearls", 2002): fold into a lattice cell, invert in a sphere, repeat
// @iterations 8 [1, 20]
// @bound size * 1.7320508
// @step 0.3
// @trap 0 1
// @deep
//
// Space is tiled by cubes of side 2 (the fold z → 2 fract(z/2 + ½) − 1 carries a point into the cell
// about the origin, an isometry), then inverted in the sphere of radius √k about the cell's centre
// (z → k z / |z|², conformal with scale k / |z|²). The packing is what these maps make of the plane
// y = 0: after n iterations the point's distance to that plane, |z_y|, divided by the product of the
// scales, estimates its distance to the packing (a conformal map's local scale; its distortion across
// a step is why the step factor is below 1). The infinite packing is cut to a cube of half-side
// `size` (the maximum of two distance bounds is a bound of the intersection).
#include "fractal/common.glsl"
uniform float uInversion; // @param 1.15 [0.5, 2.5] k: the inverting sphere's radius is √k (a cell is 2 wide)
uniform float uSize;      // @param 1.5 [0.1, 10] half the side of the cube cut from the infinite packing

real formulaDE(real3 p, out float trap)
{
    real3 z = p;
    real scale = 1.0, k = uInversion;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        z = 2.0 * fract(0.5 * z + 0.5) - 1.0;
        real r2 = max(dot(z, z), real(1e-30));
        trap = min(trap, float(r2));
        z *= k / r2;
        scale *= k / r2;
    }
    real packing = abs(z.y) / scale;
    return max(packing, realBox(p, real(uSize)));
}
