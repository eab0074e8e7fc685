// @formula A hybrid: Mandelbox iterations (T. Lowe 2010) alternating with Mandelbulb ones (White and Nylander 2009), one running derivative through both
// @iterations 12 [2, 64]
// @bound 4
// @step 0.7
// @require min_radius < fixed_radius "fractal.min_radius must be below fixed_radius"
//
// Iteration i is a Mandelbox step when i mod (box_steps + 1) < box_steps, else a Mandelbulb step.
// The derivative of the composition is the product of the steps' derivatives, so one scalar dr is
// carried through: the box step multiplies it by |s|·k and adds 1 (its "+ c"), the bulb step by
// n·rⁿ⁻¹ and adds 1. The estimate is the bulb's ½ · ln r · r / dr (log form: the bulb's power makes
// the orbit grow faster than linearly).
#include "fractal/common.glsl"
uniform float uScale;       // @param -1.5 [-4, 4] not (-1.05, 1.05) Mandelbox: the scale factor s
uniform float uMinRadius;   // @param 0.5 [0.01, 10] Mandelbox: sphere fold inner radius
uniform float uFixedRadius; // @param 1 [0.01, 10] Mandelbox: sphere fold outer radius
uniform float uPower;       // @param 8 [2, 16] Mandelbulb: the exponent n
uniform int uBoxSteps;      // @param 1 [1, 8] Mandelbox steps before each Mandelbulb step

const float HYBRID_ESCAPE = 64.0, HYBRID_TINY = 1e-30;

float hybridDE(vec3 c, out float trap)
{
    float minR2 = uMinRadius * uMinRadius, fixedR2 = uFixedRadius * uFixedRadius;
    vec3 z = c;
    float dr = 1.0;
    bool escaped = false;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS && !escaped; i++) {
        float r = length(z);
        escaped = r > HYBRID_ESCAPE;
        if (escaped)
            break;
        trap = min(trap, r);
        if (i % (uBoxSteps + 1) < uBoxSteps) {
            z = clamp(z, -1.0, 1.0) * 2.0 - z;
            float r2 = dot(z, z);
            float k = r2 < minR2 ? fixedR2 / minR2 : (r2 < fixedR2 ? fixedR2 / r2 : 1.0);
            z = uScale * k * z + c;
            dr = dr * abs(uScale) * k + 1.0;
        } else {
            float theta = r > HYBRID_TINY ? acos(clamp(z.y / r, -1.0, 1.0)) * uPower : 0.0;
            float phi = (z.x != 0.0 || z.z != 0.0) ? atan(z.z, z.x) * uPower : 0.0;
            float rn1 = r > HYBRID_TINY ? pow(r, uPower - 1.0) : 0.0;
            dr = uPower * rn1 * dr + 1.0;
            z = rn1 * r * vec3(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi)) + c;
        }
    }
    // an orbit still bounded after every iteration is taken as inside: a bulb step from |z| < 1 resets
    // dr to about 1, and the estimate there overshot 19-fold (check-formula)
    float r = length(z);
    return escaped || r > HYBRID_ESCAPE ? 0.5 * log(r) * r / dr : 0.0;
}

vec2 map(vec3 p)
{
    float d, trap;
    return outsideBound(p, d) ? vec2(d, MATERIAL_BOUND) : vec2(hybridDE(p, trap), 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    hybridDE(p, trap);
    return base * paletteColor(smoothstep(0.3, 2.5, trap));
}
