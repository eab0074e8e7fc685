// The program contract: what a scene program supplies and what it may override. Every program's
// fragment shader (sdf.frag, probe.frag) includes this file, which brings in the
// program as the virtual file program.glsl (app/scene/scene.c writes it: the csg program's generated map(),
// or an #include of the program's file from PROGRAM_LIST in app/scene/program.h).
//
// A program MUST define
//   vec2 map(vec3 p)      x: a signed distance bound (|x| ≤ the distance to the surface, negative
//                         inside; a fractal's step factor is the named STEP_FACTOR knob, never a
//                         hidden scale), y: the material index (0 … NUM_MATERIALS − 1).
//                         A conservative bound that is not a surface (a bounding sphere) is
//                         returned with material MATERIAL_BOUND (common/hit.glsl): marchers step
//                         by it and never stop on it.
// A program MAY define, each announced by a #define before the shared code tests it:
//   PROGRAM_CAST_RAY   Hit castRay(vec3 ro, vec3 rd, float tmax, float side, float pathT)
//                      its own primary/secondary marcher (terrain: max-mipmap or the lab's search);
//                      default: sphere tracing in common/march.glsl.
//   PROGRAM_MAP_ALONG  vec2 mapAlong(vec3 p, vec3 dir): a bound on the distance to the surface along
//                      the unit direction dir only (common/march.glsl steps rays by it); map() stays
//                      a bound in every direction (normals, AO, the camera's probes use it).
//   PROGRAM_NORMAL     vec3 calcNormal(vec3 p, float eps, vec3 fallback)
//                      its own normals (terrain: from the heightfield; noise: analytic gradient);
//                      default: central differences of map().
//   PROGRAM_NORMAL_OUTWARD  its surface is only ever hit from outside (a heightfield): a shading
//                      normal facing away from the viewer is bent toward it, not flipped (flipping is
//                      for a camera inside a solid).
//   PROGRAM_SHADOWS    float hardShadow(…), float softShadow(…) as in common/shadow.glsl
//                      (terrain: its own marcher toward the sun).
//   PROGRAM_FOOTPRINT_SURFACE  the footprint rule (a ray within HIT_K pixel footprints has hit)
//                      defines the surface at a level of detail, so hits are not refined to the
//                      zero crossing (fractals). Without it, hits are surfaces: common/march.glsl.
//   PROGRAM_SLOW_BOUND map() is a bound far below the distance (a globally Lipschitz-scaled field):
//                      shadow rays step off by the offset in map()'s units (common/lights.glsl);
//                      with NEAR_MIN_STEP its hits converge within the step budget (march.glsl).
//   PROGRAM_PIXEL_START a function (vec3 ro, vec3 rd) run once a pixel sample with its primary ray, before any
//                      march (a fragment's 3D.frag values: frag/glue.glsl).
//   PROGRAM_ALBEDO     vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
//                      colours its surface (fractals: orbit traps; terrains: layers); textures then
//                      do not apply.
// A program reads its parameters from uniforms it declares itself, one named uniform per parameter
// (uPower, uSize, uTerrainSpacing…); a formula declares its own (app/scene/formula/formula.h). It
// reads the #defines of the preamble (app/scene/scene.c scene_preamble): PROGRAM_<name>, FX_<EFFECT>,
// the quality knobs (MAX_STEPS, HIT_K, … from QUALITY_KNOBS in app/scene/quality.h), NUM_LIGHTS,
// NUM_MATERIALS, and its own (FRACTAL_ITERATIONS, TERRAIN_MAXMIP).
#include "common/sdf.glsl"
#include "common/budget.glsl"
#include "common/hit.glsl"
#include "program.glsl"
