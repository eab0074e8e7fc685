// @formula Octahedral kaleidoscopic IFS (Hart 1996 for IFS distance bounds): fold into the octahedron's fundamental wedge, turn, scale about a vertex
// @iterations 10 [1, 30]
// @bound 1.01 * offset
// @step 1
// @trap 0 2 * offset
// @deep
//
// abs() and three swaps carry a point into the wedge x ≥ y ≥ z ≥ 0 (the octahedral group's 48 mirror
// images, as the Menger sponge folds), a rotation turns it, and it is scaled by s about the vertex
// (offset, 0, 0). Every map is s-Lipschitz, and a point farther than |v| = offset from the origin
// only grows (|f(z)| ≥ s|z| − (s − 1)|v| > |z|), so the set lies in the ball of radius offset and
// (|z_n| − offset) / sⁿ is a lower bound on the distance to it (as in sierpinski.glsl).
#include "fractal/common.glsl"
uniform float uScale;  // @param 2 [1.2, 4] the scale factor s about the vertex
uniform float uOffset; // @param 1 [0.1, 4] the vertex (offset, 0, 0)
uniform vec3 uTwist;   // @param 0.2,0.1,0 [-3.1416, 3.1416] rotation (radians about x, y, z) after each fold

const float OCTA_ESCAPE2 = 1e6;

real formulaDE(real3 p, out float trap)
{
    real3 z = p, v = real3(uOffset, 0.0, 0.0);
    realMat3 twist = realMat3(twistMatrix(uTwist));
    real scale = 1.0, s = uScale;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        z = twist * foldOctahedral(z);
        z = z * s - v * (s - 1.0);
        scale *= s;
        trap = min(trap, float(length(z)));
        if (dot(z, z) > OCTA_ESCAPE2)
            break;
    }
    return (length(z) - real(uOffset)) / scale;
}
