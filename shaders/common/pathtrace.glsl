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

uniform int uSampleIndex; // the image's sample number: seeds each sample's random numbers

// PCG hash (M. O'Neill; the "pcg" of Jarzynski and Olano, "Hash functions for GPU rendering", JCGT 2020).
uint pcgHash(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct Rng {
    uint state;
};

float rand01(inout Rng r)
{
    r.state = pcgHash(r.state);
    return float(r.state >> 8) * (1.0 / 16777216.0); // 24 bits: [0, 1)
}

// A unit vector about n: (t, b, n) orthonormal (Duff et al., "Building an orthonormal basis, revisited", JCGT 2017).
vec3 aboutNormal(vec3 n, vec3 local)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z), b = n.x * n.y * a;
    vec3 t = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    vec3 bt = vec3(b, s + n.y * n.y * a, -n.y);
    return local.x * t + local.y * bt + local.z * n;
}

// The BRDF × cos θ_l of common/brdf.glsl's model, with the exact Fresnel for a dielectric.
vec3 pathBrdf(vec3 n, vec3 v, vec3 l, Material m)
{
    float NdotL = dot(n, l), NdotV = dot(n, v);
    if (NdotL <= 0.0 || NdotV <= 0.0)
        return vec3(0.0);
    vec3 h = normalize(v + l);
    float r = max(m.roughness, MIN_ROUGHNESS);
    float k = (r + 1.0) * (r + 1.0) / 8.0;
    float D = ggxD(max(dot(n, h), 0.0), r * r);
    float G = schlickG1(NdotV, k) * schlickG1(NdotL, k);
    float VdotH = max(dot(v, h), 0.0);
    vec3 F = mix(vec3(fresnelDielectric(VdotH, 1.0 / max(m.ior, 1.0))), fresnelSchlick(VdotH, m.albedo), m.metallic);
    vec3 specular = D * G * F / (4.0 * NdotV * NdotL);
    vec3 kd = (1.0 - F) * (1.0 - m.metallic);
    return (kd * m.albedo / PI + specular) * NdotL;
}

// How often the specular lobe is sampled: its share of the reflectance at normal view, kept in
// [0.1, 0.9] so neither lobe is starved; 0 where there is no specular (ior 1, not metal).
float specularChance(vec3 n, vec3 v, Material m)
{
    if (m.ior <= 1.0 && m.metallic <= 0.0) // no interface: no specular at all (Fd would round to ~1e-16)
        return 0.0;
    float Fd = fresnelDielectric(max(dot(n, v), 0.0), 1.0 / max(m.ior, 1.0));
    float spec = mix(Fd, 1.0, m.metallic), diff = (1.0 - Fd) * (1.0 - m.metallic) * dot(m.albedo, vec3(1.0 / 3.0));
    return spec <= 0.0 ? 0.0 : clamp(spec / max(spec + diff, 1e-6), 0.1, 0.9);
}

// The density of the mixture's directions.
float pathPdf(vec3 n, vec3 v, vec3 l, Material m, float pSpec)
{
    float NdotL = dot(n, l);
    if (NdotL <= 0.0)
        return 0.0;
    vec3 h = normalize(v + l);
    float r = max(m.roughness, MIN_ROUGHNESS);
    float specPdf = ggxD(max(dot(n, h), 0.0), r * r) * max(dot(n, h), 0.0) / (4.0 * max(dot(v, h), 1e-6));
    return (1.0 - pSpec) * NdotL / PI + pSpec * specPdf;
}

// A direction from the mixture: Malley's cosine-weighted hemisphere, or a GGX normal reflected.
vec3 sampleDirection(vec3 n, vec3 v, Material m, float pSpec, inout Rng rng)
{
    float u1 = rand01(rng), u2 = rand01(rng);
    if (rand01(rng) >= pSpec) {
        float rr = sqrt(u1), phi = 2.0 * PI * u2;
        return aboutNormal(n, vec3(rr * cos(phi), rr * sin(phi), sqrt(max(0.0, 1.0 - u1))));
    }
    float a = max(m.roughness, MIN_ROUGHNESS);
    a *= a;
    float cosT = sqrt((1.0 - u1) / (1.0 + (a * a - 1.0) * u1)), sinT = sqrt(max(0.0, 1.0 - cosT * cosT));
    float phi = 2.0 * PI * u2;
    vec3 h = aboutNormal(n, vec3(sinT * cos(phi), sinT * sin(phi), cosT));
    return reflect(-v, h);
}

#if FX_FOG
bool fogOnPath() { return fxOn(FX_FOG_BIT) && uFogDensity > 0.0; }

// The transmittance of the fog along a segment of length s from world height oy, direction dy.
float fogTransmittance(float oy, float dy, float s) { return fogOnPath() ? exp(-fogOpticalDepth(oy, dy, s)) : 1.0; }

// Where a photon leaving world height oy with vertical direction dy is first scattered: the distance
// t at which the optical depth τ(t) = σ0 e^(−b(oy−y0)) (1 − e^(−b dy t)) / (b dy) (common/fog.glsl)
// reaches tau, a sample of the unit exponential; −1 when the whole ray's depth is less (it goes
// up out of the fog, or past MAX_DIST). Inverting: t = −ln(1 − tau·c/A) / c with A = σ0 e^(−b(oy−y0)),
// c = b dy; t = tau / A for a level ray.
float fogFreeFlight(float oy, float dy, float tau)
{
    float A = uFogDensity * exp(min(-uFogFalloff * (oy - uFogHeight), FOG_MAX_EXPONENT));
    float c = uFogFalloff * dy, x = tau * c / A;
    if (x >= 1.0)
        return -1.0;
    float t = abs(x) < FOG_SERIES_BELOW ? tau / A * (1.0 + x * (0.5 + x / 3.0)) : -log(1.0 - x) / c;
    return t;
}
#else
float fogTransmittance(float oy, float dy, float s) { return 1.0; }
#endif

// The power heuristic's weight of a strategy of density a against one of density b (Veach 1997, §9.2.1).
float powerWeight(float a, float b) { return a * a / max(a * a + b * b, 1e-30); }

#if NUM_LIGHTS > 0
// A soft light (uLightShadow 2) is a disc of angular radius α = 1/(2k): 1 − cos α, as 2 sin²(α/2) (no
// cancellation for a small disc). Its solid angle is Ω = 2π(1 − cos α), its radiance E/Ω.
float discOneMinusCos(int i)
{
    float s = sin(0.25 / uLightSoftness[i]);
    return 2.0 * s * s;
}
#endif

#if FX_ENVMAP
// The sky's own distribution (app/gpu/res_envmap.c): a cumulative table over the cube map's cells,
// uEnvCells across a face (0: none, a black sky), each cell as likely as the light it sends (its mean
// luminance times its solid angle), cells in the order face, row, column. A cube map's sky is found
// by next-event estimation from it as well as by the path's own samples, weighted as for discs: a
// small bright patch (a sun in the map) is found by the first, a glossy reflection by the second.
// A constant sky is found by the path's samples alone: they are already drawn as the surface
// reflects (cosine or GGX), which is all a uniform sky asks.
uniform samplerBuffer uEnvCdf;
uniform int uEnvCells;

bool skySampled() { return fxOn(FX_ENVMAP_BIT) && uEnvCells > 0; }

// The face of direction c in the cube map's own axes (envDir) and its point q in [−1, 1]² on that
// face: (sc, tc) / |ma| in the GL specification's table of cube-map faces (+X, −X, +Y, −Y, +Z, −Z).
int cubeFace(vec3 c, out vec2 q)
{
    vec3 a = abs(c);
    if (a.x >= a.y && a.x >= a.z) {
        q = (c.x > 0.0 ? vec2(-c.z, -c.y) : vec2(c.z, -c.y)) / a.x;
        return c.x > 0.0 ? 0 : 1;
    }
    if (a.y >= a.z) {
        q = (c.y > 0.0 ? vec2(c.x, c.z) : vec2(c.x, -c.z)) / a.y;
        return c.y > 0.0 ? 2 : 3;
    }
    q = (c.z > 0.0 ? vec2(c.x, -c.y) : vec2(-c.x, -c.y)) / a.z;
    return c.z > 0.0 ? 4 : 5;
}

// The inverse: the (unnormalized) direction through point q of face f.
vec3 cubeDirection(int f, vec2 q)
{
    if (f == 0) return vec3(1.0, -q.y, -q.x);
    if (f == 1) return vec3(-1.0, -q.y, q.x);
    if (f == 2) return vec3(q.x, 1.0, q.y);
    if (f == 3) return vec3(q.x, -1.0, -q.y);
    if (f == 4) return vec3(q.x, -q.y, 1.0);
    return vec3(-q.x, -q.y, -1.0);
}

// Density per steradian of cell k's uniform points at face point q: the cell's probability over its
// area (2/n)², times the area a steradian covers there, (1 + |q|²)^(3/2) on a face at distance 1.
float envCellPdf(int k, vec2 q)
{
    float p = texelFetch(uEnvCdf, k + 1).r - texelFetch(uEnvCdf, k).r, r2 = 1.0 + dot(q, q);
    return p * float(uEnvCells * uEnvCells) * 0.25 * r2 * sqrt(r2);
}

// The density with which envSample draws world direction d.
float envPdf(vec3 d)
{
    vec2 q;
    int f = cubeFace(envDir(d), q), n = uEnvCells;
    ivec2 ij = clamp(ivec2((q * 0.5 + 0.5) * float(n)), ivec2(0), ivec2(n - 1));
    return envCellPdf((f * n + ij.y) * n + ij.x, q);
}

// A world direction from the sky's distribution: a cell by its cumulative table, a uniform point in it.
vec3 envSample(inout Rng rng, out float pdf)
{
    int n = uEnvCells, lo = 0, hi = 6 * n * n;
    float u = rand01(rng);
    while (hi - lo > 1) { // the cell k with cdf[k] <= u < cdf[k + 1]
        int mid = (lo + hi) / 2;
        if (texelFetch(uEnvCdf, mid).r <= u)
            lo = mid;
        else
            hi = mid;
    }
    int f = lo / (n * n), ij = lo - f * n * n;
    vec2 q = (vec2(float(ij % n) + rand01(rng), float(ij / n) + rand01(rng)) / float(n)) * 2.0 - 1.0;
    pdf = envCellPdf(lo, q);
    return envDir(normalize(cubeDirection(f, q))); // envDir is its own inverse
}
#endif

// Light arriving at p from every light (a direction within a soft light's disc) and from a cube
// map's sky, each seen or not by a shadow ray and dimmed by the fog on its way; n = vec3(0) is a point
// in the fog (isotropic phase 1/4π in place of the BRDF). A disc's and the sky's shares are weighted
// against the path's own sampling (density pathPdf with pSpec; the phase's 1/4π in fog), except at
// the path's last vertex (last), whose sampled direction is never traced.
vec3 nextEvent(vec3 p, vec3 n, vec3 v, Material m, float pSpec, bool last, float pathT, inout Rng rng)
{
    vec3 sum = vec3(0.0);
    bool medium = n == vec3(0.0);
#if NUM_LIGHTS > 0
    float offset = medium ? 0.0 : SURFACE_OFFSET_K * hitEps(pathT);
    for (int i = 0; i < NUM_LIGHTS; i++) {
        vec3 l;
        float dist, oneMinusCos = discOneMinusCos(i);
        vec3 radiance = lightArriving(i, p, l, dist);
        bool disc = uLightShadow[i] == 2;
        float u1 = rand01(rng), u2 = rand01(rng); // drawn for every light: the sequence stays in step
        if (disc) { // a direction uniform in the cone: cos θ uniform in [cos α, 1]
            float cosT = 1.0 - u1 * oneMinusCos, sinT = sqrt(max(0.0, 1.0 - cosT * cosT)), phi = 2.0 * PI * u2;
            l = aboutNormal(l, vec3(sinT * cos(phi), sinT * sin(phi), cosT));
        }
        vec3 f = medium ? vec3(1.0 / (4.0 * PI)) : pathBrdf(n, v, l, m);
        if (all(lessThanEqual(f, vec3(0.0))))
            continue;
        if (disc && !last) // Le / (1/Ω) = E, weighted against the path's own sampling of l
            radiance *= powerWeight(1.0 / (2.0 * PI * oneMinusCos), medium ? 1.0 / (4.0 * PI) : pathPdf(n, v, l, m, pSpec));
        Hit s = castRay(p + n * offset, l, dist - offset, 1.0, pathT);
        if (!s.hit)
            sum += f * radiance * fogTransmittance(worldApprox(p).y, l.y, min(dist, float(MAX_DIST)));
    }
#endif
#if FX_ENVMAP
    if (skySampled()) { // the sky, to where the path's own rays meet it (MAX_DIST from the eye)
        float pdf, reach = float(MAX_DIST) - pathT;
        vec3 l = envSample(rng, pdf);
        vec3 f = medium ? vec3(1.0 / (4.0 * PI)) : pathBrdf(n, v, l, m);
        float offset = medium ? 0.0 : SURFACE_OFFSET_K * hitEps(pathT);
        if (pdf > 0.0 && any(greaterThan(f, vec3(0.0))) && !castRay(p + n * offset, l, reach, 1.0, pathT).hit) {
            float w = last ? 1.0 : powerWeight(pdf, medium ? 1.0 / (4.0 * PI) : pathPdf(n, v, l, m, pSpec));
            sum += f * environment(l) * (w / pdf) * fogTransmittance(worldApprox(p).y, l.y, reach);
        }
    }
#endif
    return sum;
}

// What the path's segment from o along d meets of the soft lights' discs before `reach` (its
// surface, its scattering point in fog, or 1e30): each disc whose cone holds d and whose light is
// nearer. pdf: the density the direction was sampled with at a surface or in fog (weighted against
// next-event estimation there); −1 after glass (no shadow ray passes it: weight 1); 0 before
// anything scattered the path (lights unseen).
vec3 discsMet(vec3 o, vec3 d, float reach, float pdf)
{
    vec3 sum = vec3(0.0);
#if NUM_LIGHTS > 0
    if (pdf == 0.0)
        return sum;
    for (int i = 0; i < NUM_LIGHTS; i++) {
        if (uLightShadow[i] != 2)
            continue;
        vec3 c;
        float dist, oneMinusCos = discOneMinusCos(i);
        vec3 E = lightArriving(i, o, c, dist);
        // within the cone: the chord |d − c|² = 2(1 − cos θ) against 2(1 − cos α), exact for small discs
        if (dist >= reach || dot(d - c, d - c) > 2.0 * oneMinusCos)
            continue;
        float pdfLight = 1.0 / (2.0 * PI * oneMinusCos);
        sum += E * pdfLight * (pdf > 0.0 ? powerWeight(pdf, pdfLight) : 1.0); // Le = E/Ω
    }
#endif
    return sum;
}

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
    int steps;
    bool exhausted;
};

// A path on its way: the segment it is on, what it carries and has gathered.
struct Walk {
    vec3 ro, rd;      // the segment's origin and direction
    vec3 from;        // where the segment left a surface (ro is pushed off it): Beer's length runs from here
    vec3 throughput, radiance;
    float side;       // +1 outside solids, −1 inside glass
    float pathT;      // path length so far: thresholds grow with it
    float dirPdf;     // how the segment's direction was drawn (discsMet): 0 nothing scattered it yet
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
    W.pathT = W.dirPdf = 0.0;
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
    W.radiance += W.throughput * discsMet(W.ro, W.rd, tf, W.dirPdf);
    vec3 q = W.ro + W.rd * tf;
    W.pathT += tf;
    W.throughput *= uFogColor; // the albedo: what is not absorbed
    Material none = Material(vec3(0.0), 0.0, 1.0, 0.0, 1.0, vec3(0.0), vec3(0.0));
    W.radiance += W.throughput * nextEvent(q, vec3(0.0), -W.rd, none, 0.0, last, W.pathT, W.rng);
    float z = 1.0 - 2.0 * rand01(W.rng), r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * PI * rand01(W.rng);
    turn(W, q, vec3(r * cos(phi), r * sin(phi), z), vec3(0.0));
    W.dirPdf = 1.0 / (4.0 * PI);
    return true;
}
#endif

// The segment left the scene: the sky, weighted against its own sampling where it had a share.
void meetSky(inout Walk W)
{
    float w = 1.0; // the camera's view, or after glass (no shadow ray passes it)
#if FX_ENVMAP
    if (W.dirPdf > 0.0 && skySampled())
        w = powerWeight(W.dirPdf, envPdf(W.rd));
#endif
    W.radiance += W.throughput * environment(W.rd) * w;
}

// Glass at p (outward normal n): reflect or refract with the probability of the exact Fresnel split.
void crossGlass(inout Walk W, vec3 p, vec3 n, Material m, float eps)
{
    W.dirPdf = W.dirPdf == 0.0 ? 0.0 : -1.0; // a delta: lights met after it are weighted 1
    bool entering = dot(W.rd, n) < 0.0;
    vec3 nf = entering ? n : -n;
    float eta = entering ? 1.0 / m.ior : m.ior;
    if (rand01(W.rng) < fresnelDielectric(-dot(W.rd, nf), eta)) {
        turn(W, p, reflect(W.rd, nf), nf * (SURFACE_OFFSET_K * eps));
    } else {
        turn(W, p, refract(W.rd, nf, eta), -nf * (SURFACE_OFFSET_K * eps));
        W.side = -W.side;
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
    W.dirPdf = pdf;
    turn(W, p, l, nf * (SURFACE_OFFSET_K * eps));
    return true;
}

#if FX_DROPLETS
// A droplet's surface at p (outward normal nOut) from the air (entering) or the liquid: the path
// reflects or refracts by the exact Fresnel split, drawn at random.
void dropletSurface(inout Walk W, int id, vec3 p, vec3 nOut, bool entering)
{
    W.dropEvents++;
    W.dirPdf = W.dirPdf == 0.0 ? 0.0 : -1.0; // a delta, as glass
    vec3 n = entering ? nOut : -nOut;        // faces the coming ray
    float eta = entering ? 1.0 / uDropletIor : uDropletIor;
    if (rand01(W.rng) < fresnelDielectric(max(-dot(W.rd, n), 0.0), eta)) {
        turn(W, p, reflect(W.rd, n), vec3(0.0));
        W.dropSkip = entering ? id : -1;
    } else {
        turn(W, p, refract(W.rd, n, eta), vec3(0.0));
        W.dropIn = entering ? id : -1;
        W.dropSkip = entering ? -1 : id;
    }
}

// Inside droplet W.dropIn: Beer over the chord to its surface, then its surface; true (with h) when
// the scene's surface comes first (a droplet the scene cuts: the path leaves the liquid there).
bool throughLiquid(inout Walk W, out Hit h)
{
    vec4 s = droplet(W.dropIn);
    float t0, tOut;
    sphereRoots(W.ro, W.rd, s, t0, tOut);
    tOut = max(tOut, 0.0);
    h = Hit(false, 0.0, -1.0, 0, false, 0);
    if (map(s.xyz).x < s.w)
        h = castRay(W.ro, W.rd, tOut, W.side, W.pathT);
    W.throughput *= exp(-uDropletAbsorption * (h.hit ? h.t : tOut));
    if (h.hit) {
        W.dropIn = -1;
        return true;
    }
    vec3 p = W.ro + W.rd * tOut;
    W.pathT += tOut;
    int next = dropletAt(p, W.dropIn);
    if (next >= 0) { // overlapping droplets are one body of liquid: no surface here
        W.dropEvents++;
        W.dropIn = next;
        turn(W, p, W.rd, vec3(0.0));
        return false;
    }
    dropletSurface(W, W.dropIn, p, normalize(p - s.xyz), false);
    return false;
}

// The nearest droplet the air segment meets before `end` (its surface, or the march's end): its
// number and distance, or −1; droplets below the level of detail on the way dim the path.
int dropletAhead(inout Walk W, float end, out float tDrop)
{
    tDrop = 1e30;
    if (W.dropIn >= 0 || W.dropEvents >= DROPLET_EVENTS || !fxOn(FX_DROPLETS_BIT))
        return -1;
    vec3 reflected = vec3(0.0);
    int cells;
    int id = dropletsWalk(W.ro, W.rd, 0.0, DROPLET_CULL != 0 ? end : float(MAX_DIST) - W.pathT, end, W.dropSkip,
                          W.pathT, W.throughput, reflected, tDrop, cells);
    W.radiance += reflected * environmentBlurred(W.rd, 1.0);
    W.dropSkip = -1;
    if (id < 0 || tDrop >= end)
        tDrop = 1e30;
    return tDrop < 1e30 ? id : -1;
}
#endif

PathSample tracePathSample(Ray ray, vec2 pixel)
{
    Rng rng = Rng(pcgHash(uint(pixel.x) ^ pcgHash(uint(pixel.y) ^ pcgHash(uint(uSampleIndex) * 9781u + 1u))));
    PathSample S = PathSample(vec3(0.0), vec3(0.0), ray.d, -1.0, 0, false);
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
                S.firstN = calcNormal(W.ro + W.rd * h.t, normalEps(hitEps(h.t), h.t), -W.rd);
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
        W.radiance += W.throughput * discsMet(W.ro, W.rd, min(h.hit ? h.t : 1e30, tDrop), W.dirPdf);
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
        vec3 n = firstHit ? S.firstN : calcNormal(p, normalEps(eps, W.pathT), -W.rd); // outward
        Material m = getMaterial(h.mat, p, n, vec3(0.0), vec3(0.0));
        if (W.side < 0.0) // the segment ran inside glass, from surface to surface: the offsets off each
            W.throughput *= exp(-m.absorption * distance(W.from, p)); // would cut a thin slab's length
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
