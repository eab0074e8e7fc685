// @formula Sierpinski tetrahedron as a kaleidoscopic IFS (Hart 1996 for IFS distance bounds): fold by the three planes x + y, x + z, y + z, then scale about a vertex
// @iterations 12 [1, 30]
// @bound 1.74 * offset
// @step 1
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

float sierpinskiDE(vec3 p, out float trap)
{
    vec3 z = p, v = vec3(uOffset);
    mat3 twist = twistMatrix(uTwist);
    float scale = 1.0;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        if (z.x + z.y < 0.0) z.xy = -z.yx;
        if (z.x + z.z < 0.0) z.xz = -z.zx;
        if (z.y + z.z < 0.0) z.yz = -z.zy;
        z = twist * z;
        z = z * uScale - v * (uScale - 1.0);
        scale *= uScale;
        trap = min(trap, dot(z, z));
        if (dot(z, z) > KIFS_ESCAPE2)
            break;
    }
    return (length(z) - 1.7320508 * uOffset) / scale;
}

vec2 map(vec3 p)
{
    float d, trap;
    return outsideBound(p, d) ? vec2(d, MATERIAL_BOUND) : vec2(sierpinskiDE(p, trap), 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    sierpinskiDE(p, trap);
    return base * paletteColor(sqrt(trap) / (3.0 * uOffset));
}
