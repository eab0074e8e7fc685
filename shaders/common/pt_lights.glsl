// Light at a path's vertex (common/pathtrace.glsl): next-event estimation to every light and the
// sky, soft lights as discs weighted against the path's own directions (multiple importance sampling).
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
// nearer, weighted by how d was drawn (DirPdf).
vec3 discsMet(vec3 o, vec3 d, float reach, DirPdf dir)
{
    vec3 sum = vec3(0.0);
#if NUM_LIGHTS > 0
    if (dir.kind == DIR_UNSCATTERED)
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
        sum += E * pdfLight * (dir.kind == DIR_SAMPLED ? powerWeight(dir.density, pdfLight) : 1.0); // Le = E/Ω
    }
#endif
    return sum;
}
