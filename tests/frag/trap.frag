#info A unit sphere whose orbit trap is the constant (0.2, 0.4, 0.6, 0.25): the renderers' colouring
#include "DE-Raytracer.frag"
float DE(vec3 p) {
    orbitTrap = min(orbitTrap, vec4(0.2, 0.4, 0.6, 0.25));
    return length(p) - 1.0;
}
