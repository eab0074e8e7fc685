// The csg program: distance-field primitives combined by a CSG tree. app/scene.c writes the tree as
// `vec2 map(vec3 p)` into the virtual file scene_map.glsl; everything else is shared.
#include "common/sdf.glsl"
#include "scene_map.glsl"
#include "common/sdf_main.glsl"
