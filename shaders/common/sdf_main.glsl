// The path of one sample, shared by both entry points: sdf.frag (a full-screen triangle, the fragment
// path) and sdf.comp (a compute dispatch). The scene program defines map(); the entry point includes
// the contract, then this, then calls renderPixel().
//
// One path per sample: the primary ray, then up to BOUNCES further segments through mirrors
// (reflection) and glass (refraction). Glass splits the path: the reflected part (Fresnel F) takes
// the environment, the transmitted part (1 − F) goes on; inside, Beer–Lambert absorption e^(−σ l)
// (droplets paper); total internal reflection turns the path back inside.
//
// renderPixel's outputs (sample 0 of each frame writes the AOVs; later samples only add colour):
//   0: linear RGB radiance, alpha 1 (accumulated by additive blending)
//   1: world normal of the first hit, depth along the unit ray (−1 on a miss: C turns it into +inf)
//   2: primary-ray march steps (negative when the ray was left unresolved: its budget and the tail ran
//      out before a hit or a miss; drawn as a miss),
//      direction in which the path left the scene
//   3 (the entry points): the radiance squared, summed (the variance AOV)
//   4: the first hit's material colour (the albedo AOV; 0 on a miss)

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
#include "common/liquid.glsl"
#endif
#if INTEGRATOR // quality.integrator = 1: the path tracer instead of the model's path below
#include "common/pathtrace.glsl"
#endif

#if FX_GLOW
uniform vec3 uGlowColor;
uniform float uGlowStrength;
#endif

#if MARCH_COVERAGE // coverage anti-aliasing (coveredRadiance below) applies to the centre sample only
bool coverOn() { return uJitter == vec2(0.0); }
#endif

// Opaque surfaces: direct light + environment light (diffuse, and specular unless traced).
vec3 shadeSurface(vec3 p, vec3 n, vec3 v, Material m, vec3 F0, float pathT, bool tracedMirror)
{
    vec3 col = m.emission + directLight(p, n, v, m, F0, pathT);
    float ao = 1.0;
#if FX_AO
    if (fxOn(FX_AO_BIT))
        ao = calcAO(p, n, pathT);
#endif
    float NdotV = max(dot(n, v), MIN_COSINE);
    vec3 F = fresnelSchlickRoughness(NdotV, F0, m.roughness);
    col += (1.0 - F) * (1.0 - m.metallic) * m.albedo * ambientLight(n) * ao;
    if (!tracedMirror)
        col += F * environmentBlurred(reflect(-v, n), m.roughness) * ao;
    return col;
}

// The state of one sample's path: where it is, what it carries, and what its first hit gives the AOVs.
struct Path {
    vec3 ro, rd;            // the current segment's origin and direction
    vec3 from;              // the surface point it left (ro is pushed off it): Beer's length runs from here
    vec3 radiance, throughput;
    float pathT;            // path length so far: sets thresholds and texture footprints
    float side;             // +1 outside solids, −1 inside glass
    vec3 medium;            // inside (side −1): the absorption of the glass (or water) entered last
#if FX_WATER
    int waterEvents;        // water surfaces met: they spend no bounce but these, up to WATER_EVENTS
#endif
    float firstT, primaryT; // the first hit's depth (−1: none) and the primary ray's (fog)
    vec3 firstN;
    vec3 firstAlbedo; // the first hit's material colour (the albedo AOV); 0 on a miss
    int firstSteps, firstBoundSteps;
    bool firstExhausted;    // the primary ray ran out of steps (its hit is a best candidate)
    bool escaped;           // the path left the scene
    bool primary;           // nothing met yet: the next hit is the first (its normal and depth are the AOVs)
    bool passBy;            // the hit is a silhouette the ray passed by, from outside (coverage)
#if FX_DROPLETS
    // Droplets (common/droplets.glsl): the path is in air or inside droplet dropIn. A droplet's
    // surfaces are found analytically, so they do not count against BOUNCES but against their own
    // budget, DROPLET_EVENTS; once it is spent the path goes on straight, ignoring droplets.
    bool drops;
    int dropIn;
    int dropSkip;           // the droplet the path just left: the ray starts on its surface
    int dropEvents;
#endif
};

// What a path segment leaves for the loop: the next segment (a bounce), the next segment without
// spending a bounce (a droplet event), or the end.
const int SEGMENT_BOUNCE = 0, SEGMENT_FREE = 1, SEGMENT_END = 2;

Path startPath(Ray ray)
{
    Path P;
    P.ro = ray.o;
    P.from = ray.o;
    P.rd = ray.d;
    P.radiance = vec3(0.0);
    P.throughput = vec3(1.0);
    P.pathT = 0.0;
    P.side = 1.0;
    P.medium = vec3(0.0);
#if FX_WATER
    P.waterEvents = 0;
#endif
    P.firstT = -1.0;
    P.primaryT = float(MAX_DIST);
    P.firstN = vec3(0.0);
    P.firstAlbedo = vec3(0.0);
    P.firstSteps = 0;
    P.firstBoundSteps = 0;
    P.firstExhausted = false;
    P.escaped = false;
    P.primary = true;
    P.passBy = false;
#if FX_DROPLETS
    P.drops = fxOn(FX_DROPLETS_BIT);
    P.dropIn = P.drops ? dropletAt(P.ro, -1) : -1;
    P.dropSkip = -1;
    P.dropEvents = 0;
#endif
#if FX_REFRACTION
    // A camera inside glass starts on the inside: march to where the path leaves.
    vec2 start = map(P.ro);
    int inside = clamp(int(start.y + 0.5), 0, NUM_MATERIALS - 1);
#ifdef PROGRAM_START_INSIDE // a body the program finds by its own rule (a terrain's water)
    if (programStartInside(P.ro) >= 0)
        start.x = -1.0, inside = programStartInside(P.ro);
#endif
    if (start.x < 0.0 && uMatTransmission[inside] > 0.0 && fxOn(FX_REFRACTION_BIT)) {
        P.side = -1.0;
        P.medium = uMatAbsorption[inside];
    }
#endif
    return P;
}

void recordFirst(inout Path P, float t, vec3 n)
{
    if (P.primary) {
        P.firstT = t;
        P.primaryT = t;
        P.firstN = n;
        P.primary = false;
    }
}

#if FX_DROPLETS
// Inside liquid: the path runs to the droplet's surface, unless the scene cuts the droplet (map() at
// its centre closer than its radius) and its surface comes first. True with h when the scene's
// surface is met in the liquid; false when the path crossed (or reflected at) the droplet's surface.
bool insideDroplet(inout Path P, inout Hit h)
{
    vec4 s = droplet(P.dropIn);
    float tOut;
    if (liquidChord(P.dropIn, P.ro, P.rd, P.side, P.pathT, tOut, h)) {
        P.throughput *= exp(-uDropletAbsorption * h.t); // a surface in the liquid, seen through it
        return true;
    }
    vec3 p = P.ro + P.rd * tOut;
    P.throughput *= exp(-uDropletAbsorption * tOut);
    P.pathT += tOut;
    P.ro = p;
    P.from = p;
    P.dropEvents++;
    int next = dropletAt(p, P.dropIn);
    if (next >= 0) { // overlapping droplets are one body of liquid: no surface here
        P.dropIn = next;
        return false;
    }
    float F = dropletCross(P.rd, normalize(p - s.xyz), false);
    if (F < 1.0) { // out into the air (else totally reflected: still inside)
        P.throughput *= 1.0 - F;
        P.dropSkip = P.dropIn;
        P.dropIn = -1;
    }
    return false;
}

// The path meets droplet id at tDrop: the surface mirrors the environment and shows the lights'
// highlights (Cook–Torrance, as the droplets paper's §3.2.2); the transmitted part goes on inside.
void enterDroplet(inout Path P, int id, float tDrop)
{
    vec4 s = droplet(id);
    vec3 p = P.ro + P.rd * tDrop;
    vec3 nOut = normalize(p - s.xyz);
    float T = P.pathT + tDrop;
    recordFirst(P, tDrop, nOut);
    vec3 v = -P.rd;
    vec3 dirIn = P.rd;
    float F = dropletCross(P.rd, nOut, true);
    P.radiance += P.throughput * F * environment(reflect(dirIn, nOut));
    Material liquid = dielectricMaterial(uDropletRoughness, uDropletIor, uDropletAbsorption);
    vec3 F0 = vec3(pow((uDropletIor - 1.0) / (uDropletIor + 1.0), 2.0));
    P.radiance += P.throughput * directLight(p, nOut, v, liquid, F0, T);
    P.throughput *= 1.0 - F;
    P.ro = p;
    P.from = p;
    P.pathT = T;
    P.dropIn = id;
    P.dropSkip = -1;
    P.dropEvents++;
}

// The nearest droplet before the scene's hit: with DROPLET_CULL the grid walk stops at the surface,
// so droplets behind it are never visited; without, it walks on through the grid and the surface wins
// afterwards (the same image, to measure what culling saves). Sub-pixel droplets on the way dim the
// ray. True when the path entered a droplet.
bool meetDroplet(inout Path P, Hit h, float tmax)
{
    float tDrop, tSurface = h.hit ? h.t : tmax;
    int cells;
    vec3 reflected = vec3(0.0);
    int id = dropletsWalk(P.ro, P.rd, 0.0, DROPLET_CULL != 0 ? tSurface : tmax, tSurface, P.dropSkip, P.pathT,
                          P.throughput, reflected, tDrop, cells);
    if (tDrop >= tSurface)
        id = -1;
    P.radiance += reflected * environmentBlurred(P.rd, 1.0);
    if (id < 0)
        return false;
    enterDroplet(P, id, tDrop);
    return true;
}
#endif

#if FX_RELIEF
// Parallax-occlusion relief moves the hit into the carved layer and bends its normal.
void reliefSurface(inout Path P, Hit h, bool firstHit, vec3 pSurface, inout vec3 p, inout vec3 nOut)
{
    int reliefSteps = 0;
    vec3 nFace = nOut;
    nOut = applyRelief(clamp(int(h.mat + 0.5), 0, NUM_MATERIALS - 1), p, nOut, P.rd, reliefSteps);
    if (P.side * map(p).x > 0.0) {
        // The relief the search found lies outside the solid (past the face's edge: the carved layer
        // has no side walls in tangent space). Shading there drew dark blotches along the far edge;
        // the flat face is shown instead.
        p = pSurface;
        nOut = nFace;
    }
    if (firstHit) {
        P.firstN = nOut;
        P.firstSteps += reliefSteps;
    }
}
#endif

#if FX_REFRACTION
// What glass mirrors: the environment; with water on a terrain (its only glass) also the terrain itself, one
// traced level shaded without further bounces (mountains in a lake).
vec3 reflectedLight(vec3 ro, vec3 rd, float T)
{
#if FX_WATER
    if (fxOn(FX_WATER_BIT)) {
        Hit h = castRay(ro, rd, float(MAX_DIST) - T, 1.0, T);
        if (h.hit) {
            vec3 q = ro + rd * h.t;
            float e = hitEps(T + h.t);
            vec3 n = hitNormal(h.mat, q, normalEps(e, T + h.t), -rd);
            Material m = getMaterial(h.mat, q, n, vec3(0.0), vec3(0.0));
            vec3 F0 = mix(vec3(0.04), m.albedo, m.metallic), v = -rd;
            if (dot(n, v) < 0.02) // a heightfield's normal is bent toward the viewer, never flipped (opaqueSurface)
                n = normalize(n + (0.02 - dot(n, v)) * v);
            vec3 c = shadeSurface(q, n, v, m, F0, T + h.t, false);
#if FX_FOG
            if (fxOn(FX_FOG_BIT)) // the air between the water and what it mirrors
                c = applyFog(c, worldApprox(ro), rd, h.t);
#endif
            return c;
        }
    }
#endif
    return environment(rd);
}

// Glass splits the path: the reflected part (Fresnel F) takes the environment, the transmitted part
// (1 − F) goes on, refracted; total internal reflection turns it back inside.
// off: how far the next segment starts off the surface (the footprint's offset; a hair off a terrain's level
// water, whose plane is exact: the footprint's offset at a shore can start a ray inside the ground the water
// laps, and shortens the path in the water by offset · (1/cos − cos) at an angle).
void refractThrough(inout Path P, Material m, vec3 p, vec3 nOut, float T, float off)
{
    bool entering = dot(P.rd, nOut) < 0.0;
    vec3 n = entering ? nOut : -nOut;        // faces the incoming ray
    float eta = entering ? 1.0 / m.ior : m.ior;
    float cosI = -dot(P.rd, n);
    float F = fresnelDielectric(cosI, eta);
    vec3 refl = reflect(P.rd, n);
    P.pathT = T;
    if (F >= 1.0) { // total internal reflection: stay on this side
        P.rd = refl;
        P.ro = p + n * off;
        P.from = p;
        return;
    }
    if (entering) // reflected part: the environment (one level; the path follows the light inside)
        P.radiance += P.throughput * F * m.transmission * reflectedLight(p + n * off, refl, T);
    vec3 F0 = vec3(pow((m.ior - 1.0) / (m.ior + 1.0), 2.0));
    if (entering && m.transmission < 1.0)
        P.radiance += P.throughput * (1.0 - m.transmission) * shadeSurface(p, n, -P.rd, m, F0, T, false);
    P.throughput *= (1.0 - F) * m.transmission;
    P.rd = refract(P.rd, n, eta);
    P.ro = p - n * off;
    P.from = p;
    P.side = -P.side;
    if (entering)
        P.medium = m.absorption;
}
#endif

// An opaque surface: its light, and for a smooth one the traced mirror image (true: the path goes on).
bool opaqueSurface(inout Path P, Material m, vec3 p, vec3 pSurface, vec3 nOut, float T, float eps, int bounce)
{
    vec3 v = -P.rd;
    vec3 n = nOut;
#ifdef PROGRAM_NORMAL_OUTWARD
    // a heightfield is always hit from outside: a shading normal that faces away (a ridge's smoothed
    // normal seen from its back slope) is bent just enough to face the viewer, never flipped into
    // the ground (which drew black dashes along ridges)
    if (dot(n, v) < 0.02)
        n = normalize(n + (0.02 - dot(n, v)) * v);
#else
    if (P.passBy && dot(n, v) < 0.02) // a silhouette passed by: its normal is across the ray, and
        n = normalize(n + (0.02 - dot(n, v)) * v); // a flip would point into the solid (black AO)
    else if (dot(n, v) < 0.0) // camera inside a solid or a ray along the surface: light the side we see
        n = -n;
#endif
    float ior = max(m.ior, 1.0);
    vec3 F0 = mix(vec3(pow((ior - 1.0) / (ior + 1.0), 2.0)), m.albedo, m.metallic);
    bool mirror = false;
#if FX_REFLECTIONS
    mirror = m.transmission == 0.0 && m.roughness <= MIRROR_ROUGHNESS && bounce < BOUNCES && fxOn(FX_REFLECTIONS_BIT);
#endif
    P.radiance += P.throughput * shadeSurface(pSurface, n, v, m, F0, T, mirror);
    if (!mirror)
        return false;
    P.throughput *= fresnelSchlick(max(dot(n, v), MIN_COSINE), F0);
    P.rd = reflect(P.rd, n);
    P.ro = p + n * (SURFACE_OFFSET_K * eps);
    P.from = p;
    P.pathT = T;
    return true;
}

// The scene's surface at h: normal, texture footprint, material, then glass or an opaque surface.
int shadeHit(inout Path P, Ray ray, Hit h, int bounce)
{
    vec3 p = P.ro + P.rd * h.t;
    float T = P.pathT + h.t;
    float eps = hitEps(T);
    vec3 nOut = hitNormal(h.mat, p, normalEps(eps, T), -P.rd); // outward normal of the solid
    bool firstHit = P.primary;
    recordFirst(P, h.t, nOut);
    // Where the neighbouring pixels' rays meet the tangent plane (texture filtering).
    float dn = dot(P.rd, nOut);
    dn = sign(dn) * max(abs(dn), 1e-3) + (dn == 0.0 ? 1e-3 : 0.0);
    float Tf = T + uFootprintT0; // orthographic: a pixel is as wide at the start
    vec3 dpdx = Tf * (ray.dDdx - P.rd * dot(ray.dDdx, nOut) / dn);
    vec3 dpdy = Tf * (ray.dDdy - P.rd * dot(ray.dDdy, nOut) / dn);
    vec3 pSurface = p; // shadows and AO start on the real surface, not inside a relief
#if FX_RELIEF
    reliefSurface(P, h, firstHit, pSurface, p, nOut);
#endif
    Material m = getMaterial(h.mat, p, nOut, dpdx, dpdy);
    if (firstHit)
        P.firstAlbedo = m.albedo;
    if (P.side < 0.0) // the segment just travelled was inside glass (or water): surface to surface (the offsets
        P.throughput *= exp(-P.medium * distance(P.from, p)); // off each face cut a thin slab's length by 20 %)
#if FX_REFRACTION
    if (m.transmission > 0.0 && fxOn(FX_REFRACTION_BIT)) {
        bool water = isWater(h.mat);
        refractThrough(P, m, p, nOut, T, water ? 1e-5 * (abs(p.y) + 1.0) : SURFACE_OFFSET_K * eps);
#if FX_WATER // a terrain's water spends no bounce (a lake shows its bed at any quality.bounces), but its own budget
        if (water && P.waterEvents++ < WATER_EVENTS)
            return SEGMENT_FREE;
#endif
        return SEGMENT_BOUNCE;
    }
#endif
    return opaqueSurface(P, m, p, pSurface, nOut, T, eps, bounce) ? SEGMENT_BOUNCE : SEGMENT_END;
}

// One segment of the path: march to the next surface (through liquid, past droplets), then shade it.
int traceSegment(inout Path P, Ray ray, int bounce)
{
    float tmax = float(MAX_DIST) - P.pathT;
    Hit h;
#if FX_DROPLETS
    if (P.dropIn >= 0 && P.dropEvents >= DROPLET_EVENTS)
        P.dropIn = -1; // out of droplet events: the path leaves the liquid unbent
    if (P.dropIn >= 0) {
        if (!insideDroplet(P, h))
            return SEGMENT_FREE;
    } else
#endif
    {
#if MARCH_COVERAGE
        coverTrack = P.primary && coverOn(); // the primary ray's pass-bys: main()
#endif
        h = castRay(P.ro, P.rd, tmax, P.side, P.pathT);
#if MARCH_COVERAGE
        coverTrack = false;
#endif
    }
    if (P.primary) {
        P.firstSteps = h.steps;
        P.firstBoundSteps = h.boundSteps;
        P.firstExhausted = h.exhausted;
    }
#if FX_DROPLETS
    if (P.drops && P.dropIn < 0 && P.dropEvents < DROPLET_EVENTS && meetDroplet(P, h, tmax))
        return SEGMENT_FREE;
    P.dropSkip = -1;
#endif
    if (!h.hit) {
        P.radiance += P.throughput * environment(P.rd);
        P.escaped = true;
        return SEGMENT_END;
    }
    return shadeHit(P, ray, h, bounce);
}

// Glow and fog over the whole path: the colour it brings.
vec3 pathRadiance(Path P, Ray ray)
{
    vec3 radiance = P.radiance;
#if FX_GLOW // light gathered where the primary ray crept along the surface (many steps)
    // Only steps near the shape count: steps on a bound (approaching the bounding sphere at a grazing
    // angle) drew a faint ring around the bounding sphere's silhouette.
    float crept = float(P.firstSteps - P.firstBoundSteps) / float(MAX_STEPS);
    if (fxOn(FX_GLOW_BIT))
        radiance += uGlowColor * uGlowStrength * crept * crept;
#endif
#if FX_SKY // the air between the eye and the first hit (a miss saw the whole sky already)
    if (fxOn(FX_SKY_BIT) && P.firstT >= 0.0)
        radiance = skyAerial(radiance, worldApprox(ray.o), ray.d, P.primaryT);
#endif
#if FX_FOG
    if (fxOn(FX_FOG_BIT))
        radiance = applyFog(radiance, worldApprox(ray.o), ray.d, P.primaryT);
#endif
    return radiance;
}

// The path's segments from bounce `from` on (none when `from` is past BOUNCES or the path has `ended`: at an
// opaque surface or in the sky), then its way out of glass it could not leave.
void followPath(inout Path P, Ray ray, int from, bool ended)
{
    for (int bounce = from; bounce <= BOUNCES && !ended; bounce++) {
        int next = traceSegment(P, ray, bounce);
        if (next == SEGMENT_FREE)
            bounce--; // a droplet event spends no bounce
        ended = next == SEGMENT_END;
    }
    // the path ran out of bounces inside glass: let it leave unbent (not one that ended on an opaque surface
    // inside it: a lake's bed added the sky's light under the water)
    if (!ended && !P.escaped && P.side < 0.0)
        P.radiance += P.throughput * environment(P.rd);
}

#if MARCH_COVERAGE
// Coverage anti-aliasing from the cone, for the centre sample (later jittered samples are point
// samples of the same box-filtered pixel, so the two estimates may be averaged). A surface the
// primary ray passed by nearer than its hit, within half a pixel width of the pixel's centre, covers
// the share 1/2 − ratio of the pixel (a straight edge across a box pixel, ratio pixel widths from its
// centre); that share gets the colour of a second path that takes the pass-by point as its hit. Where
// the centre hit a surface, nothing is known of how far inside its silhouette it lies: such pixels
// count as covered (the half of an edge's error this does not remove).
vec3 coveredRadiance(Path P, Ray ray, vec3 radiance)
{
    float share = clamp(0.5 - coverRatio, 0.0, 1.0);
    if (share <= 0.0 || (P.firstT >= 0.0 && P.firstT <= coverT))
        return radiance;
    Path Q = startPath(ray);
    Hit h = Hit(true, coverT, map(ray.o + ray.d * coverT).y, 0, false, 0);
    Q.passBy = true;
    int next = shadeHit(Q, ray, h, 0);
    Q.passBy = false;
    followPath(Q, ray, 1, next == SEGMENT_END);
    return mix(radiance, pathRadiance(Q, ray), share);
}
#endif

#if defined(FRAG_LOOK) && !INTEGRATOR
#include "frag/look.glsl" // a fragment's own look (fractal.look = fragment)
#endif

// One sample of the pixel whose centre is fragCoord (gl_FragCoord's convention: pixel + 0.5): its
// colour (alpha 1: one sample) and the AOVs of the centre ray's own path. The entry points (sdf.frag,
// sdf.comp) write them to the targets.
void renderPixel(vec2 fragCoord, out vec4 color, out vec4 normalDepth, out vec4 aux, out vec4 albedo)
{
    Ray ray = primaryRay(fragCoord);
    if (!ray.sees) { // outside a fisheye's circle: black, a miss
        color = vec4(0.0, 0.0, 0.0, 1.0);
        normalDepth = vec4(0.0, 0.0, 0.0, -1.0);
        aux = vec4(0.0, ray.d);
        albedo = vec4(0.0);
        return;
    }
#ifdef PROGRAM_PIXEL_START // what a program sets from the pixel's ray (a fragment's 3D.frag values)
    PROGRAM_PIXEL_START(ray.o, ray.d);
#endif
#if INTEGRATOR
    PathSample S = tracePathSample(ray, fragCoord + uTileOffset); // seeded by the whole image's pixel
    color = vec4(S.radiance, 1.0);
    normalDepth = vec4(S.firstN, S.firstT);
    bool cut = loopOut || loopsWereCut(); // common/budget.glsl: flagged, as below
    aux = vec4(cut ? -float(S.steps) - 0.5 : S.exhausted ? -float(S.steps) : float(S.steps), S.exitDir);
    albedo = vec4(S.firstAlbedo, 0.0);
    return;
#endif
#if defined(FRAG_LOOK) && !INTEGRATOR // a fragment's own look: its renderer's image (frag/look.glsl)
    fragPixel(ray.o, ray.d, color, normalDepth, aux, albedo);
    return;
#endif
    Path P = startPath(ray);
    followPath(P, ray, 0, false);
    vec3 radiance = pathRadiance(P, ray);
#if MARCH_COVERAGE
    if (coverOn())
        radiance = coveredRadiance(P, ray, radiance);
#endif
    color = vec4(radiance, 1.0);
    normalDepth = vec4(P.firstN, P.firstT);
    // negative: unresolved (out of steps); −(steps + ½): out of the loop budget or cut by the driver
    // (common/budget.glsl). A primary ray out of the budget is a miss (castRay); one that ran out later,
    // in its shadows or bounces, keeps what it found, flagged
    bool loopsRanOut = loopOut || loopsWereCut();
    aux = vec4(loopsRanOut ? -float(P.firstSteps) - 0.5 : P.firstExhausted ? -float(P.firstSteps) : float(P.firstSteps),
               P.rd);
    albedo = vec4(P.firstAlbedo, 0.0);
}
