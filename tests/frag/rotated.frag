#info A ball at MathUtils' rotationMatrix3(z, 90°) applied to (1, 0, 0), through a helper of the fragment's own folder
#include "MathUtils.frag"
#include "DE-Raytracer.frag"
#include "helpers.frag"
// a helper named like one of fathom's own (fractal/common.glsl), with other qualifiers: it stays the fragment's
void boxFold(inout vec3 z) { z = z; }
bool floor = false;
float DE(vec3 p) {
    vec3 q = p;
    boxFold(q);
    return length(q - turned(vec3(1.0, 0.0, 0.0))) - 0.4;
}
