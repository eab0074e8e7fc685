// fathom's Classic-Noise.frag for Fragmentarium fragments (app/scene/formula/frag.h): cnoise(), classic
// gradient ("Perlin") noise over 2 and 3 dimensions (K. Perlin, "Improving noise", SIGGRAPH 2002: a
// pseudo-random gradient at each lattice point, blended with the quintic 6t⁵ − 15t⁴ + 10t³), about
// −1 to 1. The gradients come from fathom's own integer hash, so the pattern is not Fragmentarium's
// own (any fragment that draws it looks alike, not equal).

uint fragNoiseHash(uvec3 q)
{
    uint h = q.x * 0x8da6b343u ^ q.y * 0xd8163841u ^ q.z * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    return h ^ (h >> 16);
}

// one of the 12 edge directions of a cube (Perlin 2002), chosen by the lattice point's hash
vec3 fragGradient(vec3 cell)
{
    uint h = fragNoiseHash(uvec3(ivec3(cell))) % 12u;
    vec3 g = h < 4u ? vec3(1.0, 1.0, 0.0) : h < 8u ? vec3(1.0, 0.0, 1.0) : vec3(0.0, 1.0, 1.0);
    float a = (h & 1u) != 0u ? -1.0 : 1.0, b = (h & 2u) != 0u ? -1.0 : 1.0;
    return h < 4u ? g * vec3(a, b, 1.0) : h < 8u ? g * vec3(a, 1.0, b) : g * vec3(1.0, a, b);
}

vec3 fragFade(vec3 t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

float cnoise(vec3 p)
{
    vec3 i = floor(p), f = p - i, u = fragFade(f);
    float n[8];
    for (int k = 0; k < 8; k++) {
        vec3 o = vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        n[k] = dot(fragGradient(i + o), f - o);
    }
    vec4 x = mix(vec4(n[0], n[2], n[4], n[6]), vec4(n[1], n[3], n[5], n[7]), u.x);
    vec2 y = mix(x.xz, x.yw, u.y);
    return mix(y.x, y.y, u.z);
}

float cnoise(vec2 p) { return cnoise(vec3(p, 0.5)); }

// four dimensions (a fragment animates 3D noise along w): gradients along the 32 edges of a
// tesseract (one component 0, the others ±1), 16 corners blended by the same quintic
vec4 fragGradient4(vec4 cell)
{
    ivec4 q = ivec4(cell);
    uint h = fragNoiseHash(uvec3(q.xyz) + uvec3(uint(q.w) * 0x9e3779b9u));
    vec4 g = vec4((h & 4u) != 0u ? -1.0 : 1.0, (h & 8u) != 0u ? -1.0 : 1.0, (h & 16u) != 0u ? -1.0 : 1.0,
                  (h & 32u) != 0u ? -1.0 : 1.0);
    g[int(h & 3u)] = 0.0;
    return g;
}

float cnoise(vec4 p)
{
    vec4 i = floor(p), f = p - i, u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    float n[16];
    for (int k = 0; k < 16; k++) {
        vec4 o = vec4(k & 1, (k >> 1) & 1, (k >> 2) & 1, (k >> 3) & 1);
        n[k] = dot(fragGradient4(i + o), f - o);
    }
    for (int k = 0; k < 8; k++) // along x, then y, z and w, halving the corners each time
        n[k] = mix(n[2 * k], n[2 * k + 1], u.x);
    for (int k = 0; k < 4; k++)
        n[k] = mix(n[2 * k], n[2 * k + 1], u.y);
    for (int k = 0; k < 2; k++)
        n[k] = mix(n[2 * k], n[2 * k + 1], u.z);
    return mix(n[0], n[1], u.w);
}
