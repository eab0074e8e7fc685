// DE-Raytracer 0.9.1 for fathom (app/scene/formula/frag.h): the DE renderer contract of frag/raytracer.frag,
// whose colour hook (providesColor) was then named color(point, normal).
#include "DE-Raytracer.frag"
#define FRAG_COLOR_HOOK color
