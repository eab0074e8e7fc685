#info init() sets the radius once a pixel; baseColor() colours the surface; orbitTrap is a known constant
#define providesInit
#define providesColor
#include "DE-Raytracer.frag"
uniform float Radius; slider[0.1,0.5,2]
uniform bool UseHook; checkbox[true]
float radius;
void init() { radius = 2.0 * Radius; }
float DE(vec3 p) {
    orbitTrap = vec4(0.2, 0.4, 0.6, 0.25);
    return length(p) - radius;
}
vec3 baseColor(vec3 p, vec3 n) { return vec3(0.2, 0.5, 0.8); }
