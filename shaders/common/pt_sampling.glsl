// The path tracer's random numbers and how a surface scatters a path (common/pathtrace.glsl): the
// model's BRDF with the exact Fresnel, and the one-sample mixture of a cosine lobe and GGX's normals.
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
// How a path segment's direction was drawn, which decides how the lights and the sky it meets are
// weighted: DIR_UNSCATTERED (the camera's own ray: lights are not seen), DIR_DELTA (after glass or a
// droplet's surface, which no shadow ray passes: weight 1), DIR_SAMPLED (drawn with `density` at a
// surface or in fog: weighted against next-event estimation there).
const int DIR_UNSCATTERED = 0, DIR_DELTA = 1, DIR_SAMPLED = 2;
struct DirPdf {
    int kind;
    float density; // DIR_SAMPLED only
};
DirPdf dirSampled(float density) { return DirPdf(DIR_SAMPLED, density); }
// A delta scattering (a mirror-like split): the camera's ray stays the camera's.
DirPdf dirAfterDelta(DirPdf d) { return DirPdf(d.kind == DIR_UNSCATTERED ? DIR_UNSCATTERED : DIR_DELTA, 0.0); }

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
