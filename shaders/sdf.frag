// Every distance-field program's image: the program (see common/contract.glsl), then the shared main().
#include "common/contract.glsl"
#include "common/sdf_main.glsl"
