// Runs the droplets' GLSL (common/droplets.glsl) on rays (origin in uPoints, direction in uDirs, one per
// texel), for tests against double precision. One of three modes:
//   (default)             the grid walk: (t of the nearest droplet entered, its number or −1,
//                         cells visited, the droplet holding the origin or −1)
//   DROPLET_PROBE_PASS    through the first droplet as the renderer goes: in, the chord, out:
//                         (direction it leaves in, Beer–Lambert factor of the first channel)
//   DROPLET_PROBE_FRESNEL uPoints holds (cos of incidence, eta): (Fresnel reflectance, 0, 0, 0)
#include "common/uniforms.glsl"
#include "common/brdf.glsl"
#include "common/droplets.glsl"

uniform sampler2D uPoints, uDirs;
out vec4 oResult;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 a = texelFetch(uPoints, px, 0).xyz;
#ifdef DROPLET_PROBE_FRESNEL
    oResult = vec4(fresnelDielectric(a.x, a.y), 0.0, 0.0, 0.0);
#else
    vec3 rd = normalize(texelFetch(uDirs, px, 0).xyz);
    vec3 throughput = vec3(1.0), reflected = vec3(0.0);
    float t;
    int cells;
    int id = dropletsWalk(a, rd, 0.0, 1e30, 1e30, -1, 0.0, throughput, reflected, t, cells);
#ifdef DROPLET_PROBE_PASS
    if (id < 0) {
        oResult = vec4(0.0, 0.0, 0.0, -1.0);
        return;
    }
    vec4 s = droplet(id);
    vec3 p = a + rd * t;
    dropletCross(rd, normalize(p - s.xyz), true);
    float t0, tOut;
    sphereRoots(p, rd, s, t0, tOut);
    vec3 q = p + rd * tOut;
    dropletCross(rd, normalize(q - s.xyz), false);
    oResult = vec4(rd, exp(-uDropletAbsorption.x * tOut));
#else
    oResult = vec4(id >= 0 ? t : -1.0, float(id), float(cells), float(dropletAt(a, -1)));
#endif
#endif
}
