// @formula The Bristorbrot (D. Bristor, 2010): a polynomial 3D Mandelbrot, (x, y, z) → (x² − y² − z², y(2x − z), z(2x + y)) + c
// @iterations 10 [1, 64]
// @bound 2.2
// @step 0.7
//
// No trigonometry: a quadratic map whose x-y plane is the Mandelbrot set (z = 0 stays 0). The running
// derivative is the Jacobian's norm, bounded by 2|z|·√2·|dz| + 1 (each row of the Jacobian has norm at
// most 2·√2·|z|), so the estimate ½ · |z| · ln |z| / |dz| (Hart et al. 1989) holds with the step factor
// below; check-formula measures how far.
#include "fractal/common.glsl"
uniform float uBailout; // @param 4 [2, 64] escape radius

float bristorDE(vec3 c, out float trap)
{
    vec3 z = c;
    float r = length(z), dr = 1.0;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        r = length(z);
        if (r > uBailout)
            break;
        trap = min(trap, r);
        dr = 2.0 * 1.41421356 * r * dr + 1.0;
        z = vec3(z.x * z.x - z.y * z.y - z.z * z.z, z.y * (2.0 * z.x - z.z), z.z * (2.0 * z.x + z.y)) + c;
    }
    r = length(z);
    return r > 1.0 ? 0.5 * log(r) * r / dr : 0.0;
}

vec2 map(vec3 p)
{
    float d, trap;
    vec3 q = p.yxz; // the Mandelbrot plane upright
    return outsideBound(p, d) ? vec2(d, MATERIAL_BOUND) : vec2(bristorDE(q, trap), 0.0);
}

#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    bristorDE(p.yxz, trap);
    return base * paletteColor(smoothstep(0.0, 1.2, trap));
}
