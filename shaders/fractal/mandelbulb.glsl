// @formula The Mandelbulb (D. White and P. Nylander, 2009): z → zⁿ + c with the triplex power in spherical coordinates
// @iterations 12 [1, 64]
// @bound 1.6
// @step 0.9
//
// The Mandelbulb (D. White and P. Nylander, 2009): z → zⁿ + c with the "triplex" power in spherical
// coordinates (Y up: θ from +Y, φ around Y). Distance estimate from the running derivative:
// DE = ½ · ln r · r / dr, dr → n rⁿ⁻¹ dr + 1 (J. Hart et al. 1989; the form Quilez and others use).
// Guards (tests/test_fractal.c fails without each): at r → 0, acos(y/r) is 0/0, atan(0, 0) is
// undefined in GLSL and ln 0 = −∞ (times r = 0 gives NaN): each falls back to its limit.
#include "fractal/common.glsl"
uniform float uPower;   // @param 8 [2, 16] the exponent n of z → zⁿ + c
uniform float uBailout; // @param 2 [1.5, 64] escape radius

#ifndef BULB_GUARDS // tests compile them out (0) to show what each prevents
#define BULB_GUARDS 1
#endif
const float BULB_TINY = BULB_GUARDS != 0 ? 1e-30 : -1.0;

float bulbDE(vec3 c, out float trap)
{
    float power = uPower, bailout = uBailout;
    vec3 z = c;
    float dr = 1.0, r = length(z);
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        r = length(z);
        if (r > bailout)
            break;
        trap = min(trap, r);
        float theta = r > BULB_TINY ? acos(clamp(z.y / r, -1.0, 1.0)) : 0.0;
        float phi = (BULB_GUARDS == 0 || z.x != 0.0 || z.z != 0.0) ? atan(z.z, z.x) : 0.0;
        float rn1 = r > BULB_TINY ? pow(r, power - 1.0) : 0.0;
        dr = power * rn1 * dr + 1.0;
        theta *= power;
        phi *= power;
        z = rn1 * r * vec3(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi)) + c;
    }
    r = length(z);
    return r > BULB_TINY ? 0.5 * log(r) * r / dr : 0.0;
}

vec2 map(vec3 p)
{
    float d, trap;
    return outsideBound(p, d) ? vec2(d, MATERIAL_BOUND) : vec2(bulbDE(p, trap), 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    bulbDE(p, trap);
    // surface orbits come closest to the origin at |z| ≈ 0.4 … 1.1: spread that over the palette
    return base * paletteColor(smoothstep(0.4, 1.1, trap));
}
