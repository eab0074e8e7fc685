// @formula Sierpinski tetrahedron as a kaleidoscopic IFS (Hart 1996 for IFS distance bounds): fold by the three planes x + y, x + z, y + z, then scale about a vertex
// @iterations 12 [1, 30]
// @bound 1.74 * offset
// @step 1
// @trap 0 3 * offset
// @deep
//
// Each iteration folds space by the tetrahedron's three mirror planes through the origin (a point on
// the negative side is reflected to the positive one), so every point is carried into the part of
// space nearest the vertex (offset, offset, offset); then it is scaled by s about that vertex. The
// set is the attractor of the 4 similarities; after n iterations a point z_n lies within distance
// (|z_n| − R) / sⁿ of it, R = √3 · offset (the vertices' radius) bounding the attractor: a lower bound
// on the true distance, so the march never passes the surface (Hart 1996, "Sphere tracing").
#include "fractal/common.glsl"
uniform float uScale;  // @param 2 [1.2, 4] the scale factor s about the vertex
uniform float uOffset; // @param 1 [0.1, 4] the vertex (offset, offset, offset) the points are scaled about
uniform vec3 uTwist;   // @param 0,0,0 [-3.1416, 3.1416] rotation (radians about x, y, z) after each fold

const float KIFS_ESCAPE2 = 1e6;

real formulaDE(real3 p, out float trap)
{
    real3 z = p, v = real3(uOffset);
    realMat3 twist = realMat3(twistMatrix(uTwist));
    real scale = 1.0, s = uScale;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        z = twist * foldTetrahedral(z);
        z = z * s - v * (s - 1.0);
        scale *= s;
        trap = min(trap, float(length(z)));
        if (dot(z, z) > KIFS_ESCAPE2)
            break;
    }
    return (length(z) - 1.7320508 * real(uOffset)) / scale;
}
