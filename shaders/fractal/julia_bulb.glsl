// @formula The Mandelbulb's Julia sets (White and Nylander's triplex power, 2009): z → zⁿ + c with c fixed for the whole set
// @iterations 10 [1, 64]
// @bound 1.6
// @step 0.7
//
// The same iteration as mandelbulb.glsl, but c is one point (the parameter julia) instead of the
// point being drawn, so the running derivative has no "+ 1": dr → n rⁿ⁻¹ dr, and the estimate is
// ½ · ln r · r / dr (Hart, Sandin and Kauffman 1989, "Ray tracing deterministic 3-D fractals").
// Guards as in the Mandelbulb: at r → 0 the angles and ln r take their limits.
#include "fractal/common.glsl"
uniform float uPower;   // @param 8 [2, 16] the exponent n of z → zⁿ + c
uniform vec3 uJulia;    // @param -0.6,0.4,0.2 [-2, 2] the fixed c (x, y, z) that picks the Julia set
uniform float uBailout; // @param 2 [1.5, 64] escape radius

const float JULIA_TINY = 1e-30;

float juliaBulbDE(vec3 p, out float trap)
{
    vec3 z = p;
    float dr = 1.0, r = length(z);
    bool escaped = false;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        r = length(z);
        escaped = r > uBailout;
        if (escaped)
            break;
        trap = min(trap, r);
        float theta = r > JULIA_TINY ? acos(clamp(z.y / r, -1.0, 1.0)) : 0.0;
        float phi = (z.x != 0.0 || z.z != 0.0) ? atan(z.z, z.x) : 0.0;
        float rn1 = r > JULIA_TINY ? pow(r, uPower - 1.0) : 0.0;
        dr = uPower * rn1 * dr;
        theta *= uPower;
        phi *= uPower;
        z = rn1 * r * vec3(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi)) + uJulia;
    }
    // an orbit still bounded after every iteration is inside (its dr has no "+ 1" to keep it from
    // shrinking, so the estimate there overshot 1.4-fold: check-formula); dr = 0 likewise
    r = length(z);
    return (escaped || r > uBailout) && dr > 0.0 ? 0.5 * log(r) * r / dr : 0.0;
}

vec2 map(vec3 p)
{
    float d, trap;
    return outsideBound(p, d) ? vec2(d, MATERIAL_BOUND) : vec2(juliaBulbDE(p, trap), 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    juliaBulbDE(p, trap);
    return base * paletteColor(smoothstep(0.2, 1.2, trap));
}
