// Runs the march (common/march.glsl) on rays (origin in uPoints, direction in uDirs, one per texel), for
// tests against double precision. One of two modes:
//   (default)           castRay as the renderer casts a primary ray: (t, steps, hit, exhausted)
//   MARCH_PROBE_REFINE  the bracket from the origin (outside) to origin + direction (inside) narrowed
//                       by refineCrossing: (t, map() there, regula-falsi steps, 0)
#include "common/uniforms.glsl"
#include "common/contract.glsl"
#include "common/march.glsl"

uniform sampler2D uPoints, uDirs;
out vec4 oResult;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 ro = texelFetch(uPoints, px, 0).xyz, dir = texelFetch(uDirs, px, 0).xyz;
    vec3 rd = normalize(dir);
#ifdef MARCH_PROBE_REFINE
    float b = length(dir), fa = map(ro).x, fb = map(ro + rd * b).x;
    int steps = 0;
    float t = refineCrossing(ro, rd, 1.0, 0.0, fa, b, fb, 0.0, steps);
    oResult = vec4(t, map(ro + rd * t).x, float(steps), 0.0);
#else
    Hit h = castRay(ro, rd, float(MAX_DIST), 1.0, 0.0);
    oResult = vec4(h.t, float(h.steps), h.hit ? 1.0 : 0.0, h.exhausted ? 1.0 : 0.0);
#endif
}
