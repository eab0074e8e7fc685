// @formula A torus: the smallest formula file, to copy when you write your own (fathom's docs/formulas/)
// @iterations 1 [1, 1]
// @bound radius + tube
// @step 1
// @trap -3.1416 3.1416
//
// A formula file is GLSL that defines formulaDE(): a distance bound at a world point and an orbit
// trap, a number that @trap spreads over the palette (here the angle around the ring). Each
// annotated uniform is a parameter: its scene key is its name without the 'u', in snake case, and
// fathom checks the range declared here. app/scene/formula/formula.h has the whole format (step formulas,
// deep zoom). Try it:
//   fathom --formula docs/formulas/torus.glsl --set fractal.tube=0.4
// then copy it into ~/.config/fathom/formulas/ to use it by name ("formula": "torus").
#include "fractal/common.glsl"
uniform float uRadius; // @param 1 [0.1, 10] from the centre to the middle of the tube
uniform float uTube;   // @param 0.3 [0.01, 5] the tube's radius

real formulaDE(real3 p, out float trap)
{
    trap = atan(float(p.z), float(p.x));
    // exact: the distance to the circle of the given radius in the xz plane, less the tube
    vec2 q = vec2(float(length(p.xz)) - uRadius, float(p.y));
    return real(length(q) - uTube);
}
