// @formula Menger sponge as a kaleidoscopic IFS with a twist (after Knighty's KIFS, fractalforums 2010): octahedral fold, rotation, scale 3 about (1,1,1), the middle slab shifted out
// @iterations 6 [1, 20]
// @bound 1.7320508 * 1.2
// @step 0.8
// @trap 0 3
// @deep
//
// Unlike menger.glsl (exact distance, no rotation), this iterates: fold into x ≥ y ≥ z ≥ 0, turn by
// the twist, scale by s about the corner (1, 1, 1), and move the points of the middle slab (z above
// half a cell) back by one cell, which carves the cross-shaped holes. With the twist the set is no
// longer a sponge but its relatives. The estimate (|z_n| − √3) / sⁿ bounds the distance where the
// maps are s-Lipschitz; the slab's shift is not continuous, so the step factor stays below 1 (and
// check-formula measures the overshoot).
#include "fractal/common.glsl"
uniform float uScale; // @param 3 [2, 4] the scale factor s
uniform vec3 uTwist;  // @param 0.1,0.08,0 [-3.1416, 3.1416] rotation (radians about x, y, z) each iteration

const float MKIFS_ESCAPE2 = 1e6;

real formulaDE(real3 p, out float trap)
{
    real3 z = p;
    realMat3 twist = realMat3(twistMatrix(uTwist));
    real scale = 1.0, s = uScale;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        z = twist * foldOctahedral(z);
        z.xy = z.xy * s - (s - 1.0);
        z.z = z.z * s;
        if (z.z > 0.5 * (s - 1.0))
            z.z -= s - 1.0;
        scale *= s;
        trap = min(trap, float(length(z)));
        if (dot(z, z) > MKIFS_ESCAPE2)
            break;
    }
    return (length(z) - 1.7320508) / scale;
}
