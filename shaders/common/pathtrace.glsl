// A path tracer through the same map(), marcher, normals and materials as the shading model
// (quality.integrator = 1): the Monte Carlo truth the model's approximations are priced against.
// Unbiased for what it covers:
//   - opaque surfaces: the model's BRDF (Cook–Torrance GGX + Lambert, common/brdf.glsl) with the
//     exact dielectric Fresnel in place of Schlick's (a surface of ior 1 reflects nothing), sampled
//     by a one-sample mixture of a cosine-weighted diffuse lobe and GGX's distribution of normals
//     (Walter et al. 2007, "Microfacet models for refraction through rough surfaces", eq. 33–38);
//   - light: next-event estimation to every light and to a cube map's sky (a shadow ray by the
//     primary marcher, never a penumbra rule); the sky and emission met by the sampled paths;
//   - glass: reflect or refract with the probability of the exact Fresnel split, total internal
//     reflection, Beer–Lambert absorption inside;
//   - lights whose shadow is "soft" are discs of angular radius 1/(2k) seen from the shaded point
//     (k the light's softness: the model's penumbra rule ramps from dark to lit over h/t in [0, 1/k],
//     and a disc of that radius has a penumbra as wide), their irradiance unchanged: radiance
//     Le = E/Ω over the cone's solid angle Ω. Two strategies find them, weighted by the power
//     heuristic (multiple importance sampling: Veach & Guibas 1995, "Optimally combining sampling
//     techniques for Monte Carlo rendering"): next-event estimation, uniform over the cone, and the
//     path's own sampled direction when it runs into the disc (no surface before the light). A
//     near-mirror reflecting a disc is found by the second, a rough surface under a small disc by
//     the first; each alone is unbiased but one of them is noisy by orders of magnitude. The other
//     lights are points or directions (deltas): next-event estimation only. Lights are not
//     geometry: the camera does not see them, nor through glass; a path meets them only after it
//     has scattered off a surface or in fog (then through glass too: a caustic, weight 1, as no
//     shadow ray passes glass);
//   - fog (effects.fog) as a participating medium: the model's height density σ(y) is the
//     extinction, the fog colour the single-scattering albedo, the phase isotropic; free flights
//     sampled exactly from the closed-form optical depth (fogFreeFlight), each scattering event
//     lit by next-event estimation through the fog (its transmittance to the light) and by the
//     paths it scatters on (multiple scattering). The model's fog is its cheap stand-in: a constant
//     colour, unshadowed, on the primary ray only;
//   - Russian roulette after three bounces, at most BOUNCES + 1 segments (a scattering event in fog
//     counts as one).
//   - droplets (common/droplets.glsl, a layer over any program): smooth liquid spheres, each surface
//     reflecting or refracting with the probability of its exact Fresnel split (total internal
//     reflection included), Beer–Lambert over the chord inside; overlapping droplets one body of
//     liquid. Their events spend their own budget, DROPLET_EVENTS, not bounces (as in the model); once
//     it is spent the path goes on straight. Droplets below the level of detail (droplet_lod > 0) are
//     the model's stand-in here too, dimmed by their mean transmittance, their mean reflectance of the
//     blurred sky: none at the reference preset, which traces every droplet.
// The first segment's hit gives the AOVs, as in the model's path.

#include "common/pt_sampling.glsl"
#include "common/pt_fog.glsl"
#include "common/pt_lights.glsl"

// Russian roulette from the fourth segment on: paths that carry little end, the rest carry more.
bool roulette(inout vec3 throughput, int bounce, inout Rng rng)
{
    if (bounce < 3)
        return true;
    float q = clamp(max(throughput.r, max(throughput.g, throughput.b)), 0.05, 1.0);
    if (rand01(rng) >= q)
        return false;
    throughput /= q;
    return true;
}

struct PathSample {
    vec3 radiance, firstN, exitDir;
    float firstT;
    vec3 firstAlbedo; // the first hit's material colour (the albedo AOV); 0 on a miss
    int steps;
    bool exhausted;
};

// A path on its way: the segment it is on, what it carries and has gathered.
struct Walk {
    vec3 ro, rd;      // the segment's origin and direction
    vec3 from;        // where the segment left a surface (ro is pushed off it): Beer's length runs from here
    vec3 throughput, radiance;
    float side;       // +1 outside solids, −1 inside glass
    vec3 medium;      // inside (side −1): the absorption of the glass (or water) entered last
    float pathT;      // path length so far: thresholds grow with it
    DirPdf dir;       // how the segment's direction was drawn (pt_sampling.glsl)
    Rng rng;
#if FX_DROPLETS
    int dropIn;       // the droplet the path is in (−1: air)
    int dropSkip;     // the droplet whose surface the segment starts on (it is not met again at once)
    int dropEvents;   // droplet surfaces crossed or reflected at, against DROPLET_EVENTS
#endif
};

Walk startWalk(Ray ray, Rng rng)
{
    Walk W;
    W.ro = W.from = ray.o;
    W.rd = ray.d;
    W.throughput = vec3(1.0);
    W.radiance = vec3(0.0);
    W.side = 1.0;
    W.medium = vec3(0.0);
#ifdef PROGRAM_START_INSIDE // a camera in a program's body (a terrain's water): inside it
    int inside = programStartInside(ray.o);
    if (inside >= 0) {
        W.side = -1.0;
        W.medium = uMatAbsorption[inside];
    }
#endif
    W.pathT = 0.0;
    W.dir = DirPdf(DIR_UNSCATTERED, 0.0);
    W.rng = rng;
#if FX_DROPLETS
    W.dropIn = fxOn(FX_DROPLETS_BIT) ? dropletAt(ray.o, -1) : -1;
    W.dropSkip = -1;
    W.dropEvents = 0;
#endif
    return W;
}

// The segment goes on from p in direction d, pushed `push` off the surface along nf.
void turn(inout Walk W, vec3 p, vec3 d, vec3 push)
{
    W.rd = d;
    W.ro = p + push;
    W.from = p;
}

#if FX_FOG
// Does the fog scatter the photon before the segment's end (reach)? Then: the discs it passed, the
// light at the scattering point, and a new direction (isotropic: phase / pdf = 1); true.
bool scatterInFog(inout Walk W, float reach, bool last)
{
    if (W.side < 0.0 || !fogOnPath())
        return false;
    float tf = fogFreeFlight(worldApprox(W.ro).y, W.rd.y, -log(1.0 - rand01(W.rng)));
    if (tf < 0.0 || tf >= reach)
        return false;
    W.radiance += W.throughput * discsMet(W.ro, W.rd, tf, W.dir);
    vec3 q = W.ro + W.rd * tf;
    W.pathT += tf;
    W.throughput *= uFogColor; // the albedo: what is not absorbed
    Material none = noMaterial();
    W.radiance += W.throughput * nextEvent(q, vec3(0.0), -W.rd, none, 0.0, last, W.pathT, W.rng);
    float z = 1.0 - 2.0 * rand01(W.rng), r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * PI * rand01(W.rng);
    turn(W, q, vec3(r * cos(phi), r * sin(phi), z), vec3(0.0));
    W.dir = dirSampled(1.0 / (4.0 * PI));
    return true;
}
#endif

// The segment left the scene: the sky, weighted against its own sampling where it had a share.
void meetSky(inout Walk W)
{
    float w = 1.0; // the camera's view, or after glass (no shadow ray passes it)
#if FX_ENVMAP
    if (W.dir.kind == DIR_SAMPLED && skySampled())
        w = powerWeight(W.dir.density, envPdf(W.rd));
#endif
    W.radiance += W.throughput * environment(W.rd) * w;
}

// Glass at p (outward normal n): reflect or refract with the probability of the exact Fresnel split.
void crossGlass(inout Walk W, vec3 p, vec3 n, Material m, float eps)
{
    W.dir = dirAfterDelta(W.dir); // lights met after it are weighted 1
    bool entering = dot(W.rd, n) < 0.0;
    vec3 nf = entering ? n : -n;
    float eta = entering ? 1.0 / m.ior : m.ior;
    if (rand01(W.rng) < fresnelDielectric(-dot(W.rd, nf), eta)) {
        turn(W, p, reflect(W.rd, nf), nf * (SURFACE_OFFSET_K * eps));
    } else {
        turn(W, p, refract(W.rd, nf, eta), -nf * (SURFACE_OFFSET_K * eps));
        W.side = -W.side;
        if (entering)
            W.medium = m.absorption;
    }
}

// An opaque surface at p: the light it gets by next-event estimation, then a direction of its own
// sampling; false when that direction has no density (the path ends).
bool reflectOff(inout Walk W, vec3 p, vec3 n, Material m, float eps, bool last)
{
    vec3 v = -W.rd, nf = dot(n, v) < 0.0 ? -n : n; // the side the path sees
    float pSpec = specularChance(nf, v, m);
    W.radiance += W.throughput * nextEvent(p, nf, v, m, pSpec, last, W.pathT, W.rng);
    vec3 l = sampleDirection(nf, v, m, pSpec, W.rng);
    float pdf = pathPdf(nf, v, l, m, pSpec);
    if (pdf <= 0.0)
        return false;
    W.throughput *= pathBrdf(nf, v, l, m) / pdf;
    W.dir = dirSampled(pdf);
    turn(W, p, l, nf * (SURFACE_OFFSET_K * eps));
    return true;
}

#include "common/pt_droplets.glsl"

PathSample tracePathSample(Ray ray, vec2 pixel)
{
    Rng rng = Rng(pcgHash(uint(pixel.x) ^ pcgHash(uint(pixel.y) ^ pcgHash(uint(uSampleIndex) * 9781u + 1u))));
    PathSample S = PathSample(vec3(0.0), vec3(0.0), ray.d, -1.0, vec3(0.0), 0, false);
    Walk W = startWalk(ray, rng);
    bool primary = true; // the next segment is the camera's: it gives the AOVs
    // a bounce is spent at a surface or in fog; droplet events spend DROPLET_EVENTS, which ends the loop
    for (int bounce = 0; bounce <= BOUNCES;) {
        Hit h;
        bool liquidHit = false;
#if FX_DROPLETS
        if (W.dropIn >= 0 && W.dropEvents >= DROPLET_EVENTS)
            W.dropIn = -1; // out of droplet events: the path leaves the liquid unbent
        if (W.dropIn >= 0 && !(liquidHit = throughLiquid(W, h)))
            continue;
#endif
        if (!liquidHit)
            h = castRay(W.ro, W.rd, float(MAX_DIST) - W.pathT, W.side, W.pathT);
        float end = h.hit ? h.t : float(MAX_DIST) - W.pathT, tDrop = 1e30;
#if FX_DROPLETS
        int drop = liquidHit ? -1 : dropletAhead(W, end, tDrop);
#endif
        bool firstHit = primary && h.hit && tDrop >= end;
        if (primary) {
            S.steps = h.steps;
            S.exhausted = h.exhausted;
            if (firstHit) { // the AOVs are the primary ray's, whether or not fog scatters it first
                S.firstT = h.t;
                S.firstN = hitNormal(h.mat, W.ro + W.rd * h.t, normalEps(hitEps(h.t), h.t), -W.rd);
            }
        }
        S.exitDir = W.rd;
#if FX_FOG
        if (scatterInFog(W, min(end, tDrop), bounce == BOUNCES)) {
            primary = false;
            if (!roulette(W.throughput, bounce, W.rng))
                break;
            bounce++;
            continue;
        }
#endif
        W.radiance += W.throughput * discsMet(W.ro, W.rd, min(h.hit ? h.t : 1e30, tDrop), W.dir);
#if FX_DROPLETS
        if (tDrop < end) { // a droplet before the scene's surface
            vec3 p = W.ro + W.rd * tDrop, nOut = normalize(p - droplet(drop).xyz);
            if (primary) {
                S.firstT = tDrop;
                S.firstN = nOut;
            }
            primary = false;
            W.pathT += tDrop;
            dropletSurface(W, drop, p, nOut, true);
            continue;
        }
#endif
        primary = false;
        if (!h.hit) {
            meetSky(W);
            break;
        }
        vec3 p = W.ro + W.rd * h.t;
        W.pathT += h.t;
        float eps = hitEps(W.pathT);
        vec3 n = firstHit ? S.firstN : hitNormal(h.mat, p, normalEps(eps, W.pathT), -W.rd); // outward
        Material m = getMaterial(h.mat, p, n, vec3(0.0), vec3(0.0));
        if (firstHit)
            S.firstAlbedo = m.albedo;
        if (W.side < 0.0) // the segment ran inside glass (or water), from surface to surface: the offsets off
            W.throughput *= exp(-W.medium * distance(W.from, p)); // each would cut a thin slab's length
        W.radiance += W.throughput * m.emission;
        if (m.transmission > 0.0 && rand01(W.rng) < m.transmission)
            crossGlass(W, p, n, m, eps);
        else if (!reflectOff(W, p, n, m, eps, bounce == BOUNCES))
            break;
        if (!roulette(W.throughput, bounce, W.rng))
            break;
        bounce++;
    }
    S.radiance = W.radiance;
    return S;
}
