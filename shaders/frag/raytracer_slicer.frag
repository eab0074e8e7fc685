// DE-Raytracer-Slicer for fathom (app/scene/formula/frag.h): the DE renderer contract of frag/raytracer.frag
// for fragments whose estimate takes a second argument, DE(pos, type), the renderer asking type 0 for
// the surface it draws.
#include "DE-Raytracer.frag"
float DE(vec3 pos, int type);
float DE(vec3 pos) { return DE(pos, 0); }
