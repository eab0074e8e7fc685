// main() for every distance-field program: the scene program defines map() and includes this.
//
// One path per sample: the primary ray, then up to BOUNCES further segments through mirrors
// (reflection) and glass (refraction). Glass splits the path: the reflected part (Fresnel F) takes
// the environment, the transmitted part (1 − F) goes on; inside, Beer–Lambert absorption e^(−σ l)
// (droplets paper); total internal reflection turns the path back inside.
//
// Outputs (sample 0 of each frame writes the AOVs; later samples only add colour):
//   0: linear RGB radiance, alpha 1 (accumulated by additive blending)
//   1: world normal of the first hit, depth along the unit ray (−1 on a miss: C turns it into +inf)
//   2: primary-ray march steps (negative when the ray ran out of them and took its best candidate),
//      direction in which the path left the scene

#include "common/uniforms.glsl"
#include "common/camera.glsl"
#include "common/march.glsl"
#include "common/brdf.glsl"
#include "common/env.glsl"
#include "common/material.glsl"
#include "common/shadow.glsl"
#include "common/lights.glsl"
#if FX_AO
#include "common/ao.glsl"
#endif
#if FX_FOG
#include "common/fog.glsl"
#endif
#if FX_RELIEF
#include "common/relief.glsl"
#endif
#if FX_DROPLETS
#include "common/droplets.glsl"
#endif

#if FX_GLOW
uniform vec3 uGlowColor;
uniform float uGlowStrength;
#endif

layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oNormalDepth;
layout(location = 2) out vec4 oAux;

// Opaque surfaces: direct light + environment light (diffuse, and specular unless traced).
vec3 shadeSurface(vec3 p, vec3 n, vec3 v, Material m, vec3 F0, float pathT, bool tracedMirror)
{
    vec3 col = m.emission + directLight(p, n, v, m, F0, pathT);
    float ao = 1.0;
#if FX_AO
    if (fxOn(FX_AO_BIT))
        ao = calcAO(p, n);
#endif
    float NdotV = max(dot(n, v), MIN_COSINE);
    vec3 F = fresnelSchlickRoughness(NdotV, F0, m.roughness);
    col += (1.0 - F) * (1.0 - m.metallic) * m.albedo * environmentBlurred(n, 1.0) * ao;
    if (!tracedMirror)
        col += F * environmentBlurred(reflect(-v, n), m.roughness) * ao;
    return col;
}

void main()
{
    if (uAdaptive != 0 && texelFetch(uEdgeMask, ivec2(gl_FragCoord.xy), 0).r < 0.5)
        discard; // adaptive sampling: the centre sample is this pixel's mean already
    Ray ray = primaryRay(gl_FragCoord.xy);
    vec3 ro = ray.o, rd = ray.d;
    vec3 radiance = vec3(0.0), throughput = vec3(1.0);
    float pathT = 0.0;     // path length so far: sets thresholds and texture footprints
    float side = 1.0;      // +1 outside solids, −1 inside glass
    float firstT = -1.0, primaryT = float(MAX_DIST);
    vec3 firstN = vec3(0.0);
    int firstSteps = 0, firstBoundSteps = 0;
    bool firstExhausted = false; // the primary ray ran out of steps (its hit is a best candidate)
    bool escaped = false;
    bool primary = true; // nothing met yet: the next hit is the first (its normal and depth are the AOVs)
#if FX_DROPLETS
    // Droplets (common/droplets.glsl): the path is in air or inside droplet dropIn. A droplet's
    // surfaces are found analytically, so they do not count against BOUNCES but against their own
    // budget, DROPLET_EVENTS; once it is spent the path goes on straight, ignoring droplets.
    bool drops = fxOn(FX_DROPLETS_BIT);
    int dropIn = drops ? dropletAt(ro, -1) : -1;
    int dropSkip = -1; // the droplet the path just left: the ray starts on its surface
    int dropEvents = 0;
#endif
#if FX_REFRACTION
    // A camera inside glass starts on the inside: march to where the path leaves.
    vec2 start = map(ro);
    if (start.x < 0.0 && uMatTransmission[clamp(int(start.y + 0.5), 0, NUM_MATERIALS - 1)] > 0.0 && fxOn(FX_REFRACTION_BIT))
        side = -1.0;
#endif

    for (int bounce = 0; bounce <= BOUNCES; bounce++) {
        float tmax = float(MAX_DIST) - pathT;
        Hit h;
#if FX_DROPLETS
        if (dropIn >= 0 && dropEvents >= DROPLET_EVENTS)
            dropIn = -1; // out of droplet events: the path leaves the liquid unbent
        if (dropIn >= 0) {
            // Inside liquid: the path runs to the droplet's surface, unless the scene cuts the droplet
            // (map() at its centre closer than its radius) and its surface comes first.
            vec4 s = droplet(dropIn);
            float t0, tOut;
            sphereRoots(ro, rd, s, t0, tOut);
            tOut = max(tOut, 0.0);
            h.hit = false;
            if (map(s.xyz).x < s.w)
                h = castRay(ro, rd, tOut, side, pathT);
            if (!h.hit) {
                vec3 p = ro + rd * tOut;
                throughput *= exp(-uDropletAbsorption * tOut);
                pathT += tOut;
                ro = p;
                dropEvents++;
                bounce--;
                int next = dropletAt(p, dropIn);
                if (next >= 0) { // overlapping droplets are one body of liquid: no surface here
                    dropIn = next;
                    continue;
                }
                float F = dropletCross(rd, normalize(p - s.xyz), false);
                if (F < 1.0) { // out into the air (else totally reflected: still inside)
                    throughput *= 1.0 - F;
                    dropSkip = dropIn;
                    dropIn = -1;
                }
                continue;
            }
            throughput *= exp(-uDropletAbsorption * h.t); // a surface in the liquid, seen through it
        } else
#endif
        h = castRay(ro, rd, tmax, side, pathT);
        if (primary) {
            firstSteps = h.steps;
            firstBoundSteps = h.boundSteps;
            firstExhausted = h.exhausted;
        }
#if FX_DROPLETS
        if (drops && dropIn < 0 && dropEvents < DROPLET_EVENTS) {
            // The nearest droplet before the scene's hit: with DROPLET_CULL the grid walk stops at the
            // surface, so droplets behind it are never visited; without, it walks on through the grid
            // and the surface wins afterwards (the same image, to measure what culling saves).
            // Sub-pixel droplets on the way dim the ray.
            float tDrop, tSurface = h.hit ? h.t : tmax;
            int cells;
            vec3 reflected = vec3(0.0);
            int id = dropletsWalk(ro, rd, 0.0, DROPLET_CULL != 0 ? tSurface : tmax, tSurface, dropSkip, pathT,
                                  throughput, reflected, tDrop, cells);
            if (tDrop >= tSurface)
                id = -1;
            radiance += reflected * environmentBlurred(rd, 1.0);
            if (id >= 0) {
                vec4 s = droplet(id);
                vec3 p = ro + rd * tDrop;
                vec3 nOut = normalize(p - s.xyz);
                float T = pathT + tDrop;
                if (primary) {
                    firstT = primaryT = tDrop;
                    firstN = nOut;
                    primary = false;
                }
                // the surface: the environment mirrored, and the lights' highlights (Cook–Torrance, as
                // the droplets paper's §3.2.2); then the transmitted part goes on inside
                vec3 v = -rd;
                vec3 dirIn = rd;
                float F = dropletCross(rd, nOut, true);
                radiance += throughput * F * environment(reflect(dirIn, nOut));
                Material liquid = Material(vec3(0.0), 0.0, uDropletRoughness, 1.0, uDropletIor, uDropletAbsorption, vec3(0.0));
                vec3 F0 = vec3(pow((uDropletIor - 1.0) / (uDropletIor + 1.0), 2.0));
                radiance += throughput * directLight(p, nOut, v, liquid, F0, T);
                throughput *= 1.0 - F;
                ro = p;
                pathT = T;
                dropIn = id;
                dropSkip = -1;
                dropEvents++;
                bounce--;
                continue;
            }
        }
        dropSkip = -1;
#endif
        if (!h.hit) {
            radiance += throughput * environment(rd);
            escaped = true;
            break;
        }
        vec3 p = ro + rd * h.t;
        float T = pathT + h.t;
        float eps = hitEps(T);
        vec3 nOut = calcNormal(p, normalEps(eps, T), -rd); // outward normal of the solid
        bool firstHit = primary;
        if (primary) {
            firstT = h.t;
            primaryT = h.t;
            firstN = nOut;
            primary = false;
        }
        // Where the neighbouring pixels' rays meet the tangent plane (texture filtering).
        float dn = dot(rd, nOut);
        dn = sign(dn) * max(abs(dn), 1e-3) + (dn == 0.0 ? 1e-3 : 0.0);
        vec3 dpdx = T * (ray.dDdx - rd * dot(ray.dDdx, nOut) / dn);
        vec3 dpdy = T * (ray.dDdy - rd * dot(ray.dDdy, nOut) / dn);
        vec3 pSurface = p; // shadows and AO start on the real surface, not inside a relief
#if FX_RELIEF
        int reliefSteps = 0;
        vec3 nFace = nOut;
        nOut = applyRelief(clamp(int(h.mat + 0.5), 0, NUM_MATERIALS - 1), p, nOut, rd, reliefSteps);
        if (side * map(p).x > 0.0) {
            // The relief the search found lies outside the solid (past the face's edge: the carved layer
            // has no side walls in tangent space). Shading there drew dark blotches along the far edge;
            // the flat face is shown instead.
            p = pSurface;
            nOut = nFace;
        }
        if (firstHit) {
            firstN = nOut;
            firstSteps += reliefSteps;
        }
#endif
        Material m = getMaterial(h.mat, p, nOut, dpdx, dpdy);

        if (side < 0.0) // the segment just travelled was inside glass
            throughput *= exp(-m.absorption * h.t);

#if FX_REFRACTION
        if (m.transmission > 0.0 && fxOn(FX_REFRACTION_BIT)) {
            bool entering = dot(rd, nOut) < 0.0;
            vec3 n = entering ? nOut : -nOut;        // faces the incoming ray
            float eta = entering ? 1.0 / m.ior : m.ior;
            float cosI = -dot(rd, n);
            float F = fresnelDielectric(cosI, eta);
            vec3 refl = reflect(rd, n);
            pathT = T;
            if (F >= 1.0) { // total internal reflection: stay on this side
                rd = refl;
                ro = p + n * (SURFACE_OFFSET_K * eps);
                continue;
            }
            if (entering) // reflected part: the environment (one level; the path follows the light inside)
                radiance += throughput * F * m.transmission * environment(refl);
            vec3 F0 = vec3(pow((m.ior - 1.0) / (m.ior + 1.0), 2.0));
            if (entering && m.transmission < 1.0)
                radiance += throughput * (1.0 - m.transmission) * shadeSurface(p, n, -rd, m, F0, T, false);
            throughput *= (1.0 - F) * m.transmission;
            rd = refract(rd, n, eta);
            ro = p - n * (SURFACE_OFFSET_K * eps);
            side = -side;
            continue;
        }
#endif
        vec3 v = -rd;
        vec3 n = nOut;
#ifdef PROGRAM_NORMAL_OUTWARD
        // a heightfield is always hit from outside: a shading normal that faces away (a ridge's smoothed
        // normal seen from its back slope) is bent just enough to face the viewer, never flipped into
        // the ground (which drew black dashes along ridges)
        if (dot(n, v) < 0.02)
            n = normalize(n + (0.02 - dot(n, v)) * v);
#else
        if (dot(n, v) < 0.0) // camera inside a solid or a ray along the surface: light the side we see
            n = -n;
#endif
        float ior = max(m.ior, 1.0);
        vec3 F0 = mix(vec3(pow((ior - 1.0) / (ior + 1.0), 2.0)), m.albedo, m.metallic);
        bool mirror = false;
#if FX_REFLECTIONS
        mirror = m.transmission == 0.0 && m.roughness <= MIRROR_ROUGHNESS && bounce < BOUNCES && fxOn(FX_REFLECTIONS_BIT);
#endif
        radiance += throughput * shadeSurface(pSurface, n, v, m, F0, T, mirror);
        if (!mirror)
            break;
        throughput *= fresnelSchlick(max(dot(n, v), MIN_COSINE), F0);
        rd = reflect(rd, n);
        ro = p + n * (SURFACE_OFFSET_K * eps);
        pathT = T;
    }
    if (!escaped && side < 0.0) // the path ran out of bounces inside glass: let it leave unbent
        radiance += throughput * environment(rd);

#if FX_GLOW // light gathered where the primary ray crept along the surface (many steps)
    // Only steps near the shape count: steps on a bound (approaching the bounding sphere at a grazing
    // angle) drew a faint ring around the bounding sphere's silhouette.
    float crept = float(firstSteps - firstBoundSteps) / float(MAX_STEPS);
    if (fxOn(FX_GLOW_BIT))
        radiance += uGlowColor * uGlowStrength * crept * crept;
#endif
#if FX_FOG
    if (fxOn(FX_FOG_BIT))
        radiance = applyFog(radiance, ray.o, ray.d, primaryT);
#endif
    oColor = vec4(radiance, 1.0);
    oNormalDepth = vec4(firstN, firstT);
    oAux = vec4(firstExhausted ? -float(firstSteps) : float(firstSteps), rd); // negative: out of steps
}
