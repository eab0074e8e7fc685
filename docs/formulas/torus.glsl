// @formula A torus: the smallest formula file, to copy when you write your own (fathom's docs/formulas/)
// @iterations 1 [1, 1]
// @bound radius + tube
// @step 1
//
// A formula file is GLSL that defines map() (the distance estimate, and 0 as the material) and may
// define programAlbedo() (its colouring, announced by #define PROGRAM_ALBEDO); fractal/common.glsl
// gives the bounding sphere and the palette. Each annotated uniform is a parameter: its scene key is
// its name without the 'u', in snake case, and fathom checks the range declared here. Try it:
//   fathom --formula docs/formulas/torus.glsl --set fractal.tube=0.4
// then copy it into ~/.config/fathom/formulas/ to use it by name ("formula": "torus").
#include "fractal/common.glsl"
uniform float uRadius; // @param 1 [0.1, 10] from the centre to the middle of the tube
uniform float uTube;   // @param 0.3 [0.01, 5] the tube's radius

vec2 map(vec3 p)
{
    // exact: the distance to the circle of the given radius in the xz plane, less the tube
    vec2 q = vec2(length(p.xz) - uRadius, p.y);
    return vec2(length(q) - uTube, 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    return base * paletteColor(0.5 + 0.5 * atan(p.z, p.x) / 3.14159265);
}
