// fathom's DE renderer for Fragmentarium fragments (app/scene/formula/frag.h): what a fragment gets from
// DE-Raytracer.frag and the other DE renderers it may include: the orbitTrap its DE lowers, the
// colouring parameters and the hooks. Written here from the documented contract; the march, the
// lights, the camera and the hit rule are fathom's own (a preset's Detail, FudgeFactor and
// MaxRaySteps are mapped onto them: frag_presets.c). The colouring: frag/glue.glsl.
#define FRAG_RAYTRACER 1
#group Coloring
// the surface's colour where the orbit trap adds none
uniform vec3 BaseColor; color[1.0,1.0,1.0]
// how far the orbit trap's colour replaces BaseColor (0: BaseColor alone)
uniform float OrbitStrength; slider[0,0,1]
// the colour the trap's |x| adds, and its weight
uniform vec4 X; color[-1,0.7,1,0.5,0.6,0.6]
// the colour the trap's |y| adds, and its weight
uniform vec4 Y; color[-1,0.4,1,1.0,0.6,0.0]
// the colour the trap's |z| adds, and its weight
uniform vec4 Z; color[-1,0.5,1,0.8,0.78,1.0]
// the colour the trap's radius adds, and its weight
uniform vec4 R; color[-1,0.12,1,0.4,0.7,1.0]
// each trap colour cycles with its trap value (a cosine palette)
uniform bool CycleColors; checkbox[false]
// the cycling palette's frequency
uniform float Cycles; slider[0.1,1.1,32.3]

// the fragment's estimate (declared first: a fragment may call it above its definition)
float DE(vec3 pos);

// lowered by the fragment's DE along the orbit: (|x|, |y|, |z|, r²) at their smallest, by convention
vec4 orbitTrap = vec4(10000.0);
