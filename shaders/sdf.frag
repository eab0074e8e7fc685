// Every distance-field program: app/scene.c writes program.glsl (a virtual file) with the scene's
// `vec2 map(vec3 p)`: the CSG tree as code, or an #include of shaders/fractal/NAME.glsl.
#include "common/sdf.glsl"
#include "program.glsl"
#include "common/sdf_main.glsl"
