// Procedural terrain from the height-field lab: the implicit surface f(p) = p.y − base − A · n(p)
// where n is 3D fractal value noise, so overhangs and arches are possible (it is not a height map).
// Normals come from the analytic gradient of n (quintic-smoothed value noise: I. Quilez, "value noise
// derivatives"). Sphere tracing needs a distance bound: |∇f| ≤ 1 + A · Σ fᵢ aᵢ · 30/16 · √3 (the
// quintic's steepest slope is 30/16 per unit on each axis), so f / that is one.
uniform float uNoiseBase;      // base height (metres)
uniform float uNoiseAmplitude; // A (metres)
uniform float uNoiseFrequency; // base frequency (1/m)
uniform int uNoiseOctaves;
uniform float uNoiseBound; // 1 / (the bound on |∇f| above), from C

#define PROGRAM_NORMAL 1
// map() is |∇f|-scaled by a global bound (about 20× below the distance on the shipped scene): plain
// steps below the threshold would not reach the surface within the step budget (common/march.glsl).
#define NEAR_MIN_STEP 0.25
#define PROGRAM_SLOW_BOUND 1
#define PROGRAM_ALBEDO 1

// An integer mixer ("lowbias32", C. Wellons, 2018: the constants are his published search result),
// chained over the three coordinates so neighbouring lattice points are uncorrelated.
uint mix32(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

float hash3(ivec3 c)
{
    uint h = mix32(uint(c.x) + mix32(uint(c.y) + mix32(uint(c.z))));
    return float(h) * (1.0 / 4294967295.0);
}

// value noise in [0, 1] and its gradient (xyz)
vec4 valueNoise(vec3 p)
{
    ivec3 i = ivec3(floor(p));
    vec3 f = fract(p);
    vec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    vec3 du = 30.0 * f * f * (f * (f - 2.0) + 1.0);
    float a = hash3(i), b = hash3(i + ivec3(1, 0, 0)), c = hash3(i + ivec3(0, 1, 0)), d = hash3(i + ivec3(1, 1, 0));
    float e = hash3(i + ivec3(0, 0, 1)), g = hash3(i + ivec3(1, 0, 1)), h = hash3(i + ivec3(0, 1, 1)), k = hash3(i + ivec3(1, 1, 1));
    float k1 = b - a, k2 = c - a, k3 = e - a, k4 = a - b - c + d, k5 = a - c - e + h, k6 = a - b - e + g;
    float k7 = -a + b + c - d + e - g - h + k;
    float v = a + k1 * u.x + k2 * u.y + k3 * u.z + k4 * u.x * u.y + k5 * u.y * u.z + k6 * u.z * u.x + k7 * u.x * u.y * u.z;
    vec3 grad = du * vec3(k1 + k4 * u.y + k6 * u.z + k7 * u.y * u.z, k2 + k5 * u.z + k4 * u.x + k7 * u.z * u.x,
                          k3 + k6 * u.x + k5 * u.y + k7 * u.x * u.y);
    return vec4(v, grad);
}

// fractal sum: amplitude halves and frequency doubles per octave; value and gradient (per metre)
vec4 fbm(vec3 p)
{
    vec4 sum = vec4(0.0);
    float amp = 0.5, freq = uNoiseFrequency;
    for (int o = 0; o < uNoiseOctaves; o++) {
        vec4 n = valueNoise(p * freq + vec3(float(o) * 17.31));
        sum += amp * vec4(n.x, n.yzw * freq);
        amp *= 0.5;
        freq *= 2.0;
    }
    return sum;
}

float noiseField(vec3 p) { return p.y - uNoiseBase - uNoiseAmplitude * fbm(p).x; }

// Above base + A (the fbm stays below 1) the surface cannot be: the height above that plane bounds the
// distance too, and grows fast on rays that leave upward. It is a bound, not a surface.
vec2 map(vec3 p)
{
    float field = noiseField(p) * uNoiseBound, above = p.y - (uNoiseBase + uNoiseAmplitude);
    return above > field ? vec2(above, MATERIAL_BOUND) : vec2(field, 0.0);
}

vec3 calcNormal(vec3 p, float eps, vec3 fallback)
{
    vec3 g = vec3(0.0, 1.0, 0.0) - uNoiseAmplitude * fbm(p).yzw;
    float len = length(g);
    return len > 1e-20 ? g / len : fallback;
}

// The shared layered albedo (terrain/layers.glsl), over the noise's height range.
uniform float uTerrainHeightMin, uTerrainHeightMax;
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base);
#include "common/uniforms.glsl"
#include "common/material.glsl"
#include "terrain/layers.glsl"
