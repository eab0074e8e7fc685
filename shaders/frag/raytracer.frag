// fathom's DE renderer for Fragmentarium fragments (app/scene/formula/frag.h): what a fragment gets from
// DE-Raytracer.frag and the other DE renderers it may include: the orbitTrap its DE lowers, the
// colouring parameters, the hooks, and the renderers' controls of their look, under their names, groups
// and defaults (fractal.look = fragment: frag/look.glsl; the post ones: display.frag). Written here from
// the documented contract; the march and the camera are fathom's (a preset's Detail, FudgeFactor and
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
// the colour where a ray meets nothing
uniform vec3 BackgroundColor; color[0.6,0.6,0.45]
// how much the background darkens toward the image's edges
uniform float GradientBackground; slider[0.0,0.3,5.0]

#group Raytracer
// the ambient-occlusion samples' spacing, log10 (0: occlusion from the steps taken instead)
uniform float DetailAO; slider[-7,-0.5,0]
// a random share of the occlusion samples' spacing, against banding
uniform float Dither; slider[0,0.5,1]
// the normal is taken this many hit thresholds back along the ray
uniform float NormalBackStep; slider[0,1,10]

#group Light
// the occlusion's colour, and its strength (w)
uniform vec4 AO; color[0,0.7,1,0.0,0.0,0.0]
// the spot light's highlight (Fast-Raytracer's Phong highlight takes up to 10, its default 4: frag_presets.c)
uniform float Specular; slider[0,0.4,10.0]
// the highlight's exponent (larger: smaller)
uniform float SpecularExp; slider[0,16.0,100.0]
// the highlight's largest value
uniform float SpecularMax; slider[0,10,100]
// the directional light's colour and strength (w)
uniform vec4 SpotLight; color[0.0,0.4,1.0,1.0,1.0,1.0]
// the directional light's direction (spherical coordinates)
uniform vec2 SpotLightDir; slider[(-1,-1),(0.1,0.1),(1,1)]
// the light at the camera: its colour and strength (w)
uniform vec4 CamLight; color[0,1,2,1.0,1.0,1.0]
// the camera light's least share, whatever the surface faces
uniform float CamLightMin; slider[0.0,0.0,1.0]
// the glow of the steps a ray takes near the surface: colour and strength (w)
uniform vec4 Glow; color[0,0.0,1,1.0,1.0,1.0]
// the steps that make the glow full
uniform int GlowMax; slider[0,20,1000]
// fog toward the background with distance
uniform float Fog; slider[0,0.0,2]
// shadows toward the spot light (0: none, 1: full)
uniform float HardShadow; slider[0,0,1]
// the shadows' softness
uniform float ShadowSoft; slider[0.0,2.0,20]

#group Post
// the display gamma (colours are taken to this power before lighting, and back after)
uniform float Gamma; slider[0.0,2.0,5.0]
// 1 linear, 2 exponential, 3 filmic, 4 Reinhard, 5 sigmoid
uniform int ToneMapping; slider[1,4,5]
uniform float Exposure; slider[0.0,1.0,3.0]
uniform float Brightness; slider[0.0,1.0,5.0]
uniform float Contrast; slider[0.0,1.0,5.0]
uniform float Saturation; slider[0.0,1.0,5.0]
#group Coloring

// 3D.frag's values of this pixel, which a fragment may read: its ray's origin and direction (from, dir), the
// camera's axes (Dir, UpOrtho, Right), its screen position (viewCoord in [-1, 1]; coord the same, x times the
// aspect, times FOV) and the size of a pixel there (pixelSize). Set each pixel: fragHost (frag/glue.glsl).
vec3 from, dir, Dir, UpOrtho, Right;
vec2 coord, viewCoord, pixelSize;

// the fragment's estimate (declared first: a fragment may call it above its definition)
float DE(vec3 pos);

// lowered by the fragment's DE along the orbit: (|x|, |y|, |z|, r²) at their smallest, by convention
vec4 orbitTrap = vec4(10000.0);
