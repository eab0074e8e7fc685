#info A sphere whose radius is Locked: a compile-time constant
#include "DE-Raytracer.frag"
uniform float Radius; slider[0.1,1,2] Locked
float DE(vec3 p) { return length(p) - Radius; }
