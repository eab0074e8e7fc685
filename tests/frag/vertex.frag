#info A sphere whose radius a #vertex section computes (Fragmentarium runs it once a vertex): fathom's test of vertex sections (tests/fractal/test_frag_render.c)
#vertex
#define providesInit
#endvertex
#include "DE-Raytracer.frag"
#vertex
#group Vertex
// half the sphere's radius
uniform float S; slider[0.1,0.5,2]
varying float K;
void init() { K = 2.0 * S; }
#endvertex
varying float K;
uniform float S;
float DE(vec3 p) { return length(p) - K; }
