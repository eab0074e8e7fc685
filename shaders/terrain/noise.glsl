// Procedural terrain from the height-field lab: the implicit surface f(p) = p.y − base − A · n(p)
// where n is 3D fractal value noise, so overhangs and arches are possible (it is not a height map).
// Normals come from the analytic gradient of n (quintic-smoothed value noise: I. Quilez, "value noise
// derivatives").
//
// Filtered to the pixel: an octave whose wavelength is within OCTAVE_FADE pixel footprints of the
// camera's view of p fades out (its weight w goes from 1 at 4 footprints to 0 at 2), so far terrain
// is as smooth as the pixels can show: no aliasing, and fewer octaves to bound. The surface is the
// filtered one: f(p) = p.y − base − A · Σ wᵢ(p) aᵢ nᵢ(p), with wᵢ a function of p's distance to the
// eye (the same for every ray, shadows and normals included).
//
// A local distance bound (after Keinert et al. 2014, "Enhanced Sphere Tracing", and Galin et al. 2020,
// "Segment tracing using local Lipschitz bounds"): |∇f| ≤ 1 + A · Σ aᵢ (wᵢ fᵢ S + |∇wᵢ|), S = 30/16 · √3
// the quintic's steepest slope, counted over the ball the step may take: the step is at most half
// the distance to the eye, so within it footprints are at least half p's, and the weights at half
// the footprint bound those in the ball. Far away the fine octaves are gone from the bound too: the
// global bound (every octave at full weight) was about 20 times below the distance there.
#include "common/uniforms.glsl" // the eye and the pixel's angle: the filter's footprint
uniform float uNoiseBase;      // base height (metres)
uniform float uNoiseAmplitude; // A (metres)
uniform float uNoiseFrequency; // base frequency (1/m)
uniform int uNoiseOctaves;
uniform float uNoiseSlope; // the steepest slope of one octave along an axis, per unit of its frequency (30/16)

// An octave fades out between 4 and 2 footprints a wavelength (the footprint: the pixel's width at p)
const float OCTAVE_FADE_FULL = 4.0, OCTAVE_FADE_GONE = 2.0;
// Steps stay within this share of the distance to the eye (the footprints the bound assumes)
const float BOUND_REACH = 0.5;
// A rising ray's step is cut this share of the amplitude past the top plane (base + A, which the fbm
// never reaches: nothing lies above it), so it lands clear of the plane, not on it by rounding
const float PLANE_MARGIN = 1e-3;

#define PROGRAM_NORMAL 1
// map() is |∇f|-scaled by a global bound (about 20× below the distance on the shipped scene): plain
// steps below the threshold would not reach the surface within the step budget (common/march.glsl).
#define NEAR_MIN_STEP 0.25
#define PROGRAM_SLOW_BOUND 1
// Tail steps of at least 2 thresholds (4 elsewhere): on this slow bound a ray that runs into the tail
// near a ridge crest could step over the crest's last 4 thresholds (the double reference's deep pixel).
#define TAIL_MIN_STEP 2.0
#define PROGRAM_ALBEDO 1

// A lattice point's value in [0, 1]: its coordinates times three large odd constants, combined by XOR
// (the spatial hash of Teschner et al. 2003, "Optimized spatial hashing for collision detection of
// deformable objects", their constants), then one multiply-xorshift round (the multiplier of T. Wang's
// integer hashes). Over a 128³ block its values are uniform (16 bins within 1 %) and neighbours
// uncorrelated (|r| < 0.002), as with the two-round lowbias32 it replaced at 5 operations a corner
// instead of 8; the products of a cell's eight corners come from two per axis (was: three chained
// lowbias32 mixes a corner, a third of the march).
const uvec3 LATTICE_PRIMES = uvec3(73856093u, 19349663u, 83492791u);
float latticeValue(uint x, uint y, uint z)
{
    uint h = (x ^ y ^ z) * 0x27d4eb2du;
    return float(h ^ (h >> 15)) * (1.0 / 4294967295.0);
}

// value noise in [0, 1] and its gradient (xyz)
vec4 valueNoise(vec3 p)
{
    ivec3 i = ivec3(floor(p));
    vec3 f = fract(p);
    vec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    vec3 du = 30.0 * f * f * (f * (f - 2.0) + 1.0);
    uvec3 lo = uvec3(i) * LATTICE_PRIMES, hi = lo + LATTICE_PRIMES;
    float a = latticeValue(lo.x, lo.y, lo.z), b = latticeValue(hi.x, lo.y, lo.z), c = latticeValue(lo.x, hi.y, lo.z);
    float d = latticeValue(hi.x, hi.y, lo.z), e = latticeValue(lo.x, lo.y, hi.z), g = latticeValue(hi.x, lo.y, hi.z);
    float h = latticeValue(lo.x, hi.y, hi.z), k = latticeValue(hi.x, hi.y, hi.z);
    float k1 = b - a, k2 = c - a, k3 = e - a, k4 = a - b - c + d, k5 = a - c - e + h, k6 = a - b - e + g;
    float k7 = -a + b + c - d + e - g - h + k;
    float v = a + k1 * u.x + k2 * u.y + k3 * u.z + k4 * u.x * u.y + k5 * u.y * u.z + k6 * u.z * u.x + k7 * u.x * u.y * u.z;
    vec3 grad = du * vec3(k1 + k4 * u.y + k6 * u.z + k7 * u.y * u.z, k2 + k5 * u.z + k4 * u.x + k7 * u.z * u.x,
                          k3 + k6 * u.x + k5 * u.y + k7 * u.x * u.y);
    return vec4(v, grad);
}

// An octave's weight at a footprint (metres a pixel), and how fast it changes with the footprint.
float octaveWeight(float freq, float footprint, out float dWeight)
{
    float x = footprint * freq; // footprints a wavelength: 1 / x
    float w = (1.0 / x - OCTAVE_FADE_GONE) / (OCTAVE_FADE_FULL - OCTAVE_FADE_GONE);
    dWeight = w > 0.0 && w < 1.0 ? 1.0 / (x * footprint * (OCTAVE_FADE_FULL - OCTAVE_FADE_GONE)) : 0.0;
    return clamp(w, 0.0, 1.0);
}

// The filtered fractal sum at p: amplitude halves and frequency doubles per octave; value and gradient
// (per metre: the octaves' own and their weights', which change with the distance to the eye).
vec4 fbm(vec3 p)
{
    vec3 toEye = p - uCamPos;
    float dist = length(toEye), footprint = max(footprintAt(dist), 1e-30);
    vec3 dDist = dist > 0.0 ? toEye / dist : vec3(0.0);
    vec4 sum = vec4(0.0);
    float amp = 0.5, freq = uNoiseFrequency;
    for (int o = 0; o < uNoiseOctaves; o++) {
        float dw, w = octaveWeight(freq, footprint, dw);
        if (w <= 0.0)
            break; // finer octaves are gone too
        vec4 n = valueNoise(p * freq + vec3(float(o) * 17.31));
        sum += amp * vec4(w * n.x, w * n.yzw * freq - n.x * dw * uPixelAngle * dDist);
        amp *= 0.5;
        freq *= 2.0;
    }
    return sum;
}

// The distance bound, octave by octave (after Keinert et al. 2014 and Galin et al. 2020 on local
// Lipschitz bounds). Split the sum after octave k: the coarse octaves 0 … k−1 are taken as they are,
// the fine ones k … at their extremes (value noise lies in [0, 1]). Then
//   h_k = y − base − A (coarse_k + fine_k max)  ≤ f  ≤  u_k = y − base − A coarse_k
// everywhere, and h_k, u_k change no faster than L_k = 1 + A Σ_{o<k} aₒ (wₒ fₒ S + |∇wₒ|), the coarse
// octaves' slope alone. So where h_k > 0 the surface is at least h_k / L_k away, and where u_k < 0 at
// least −u_k / L_k: far above or below the fine octaves' band, the steps are the coarse octaves'
// (long); k = every octave is the plain bound f / L. The largest of these bounds is one. Weights and
// slopes are taken over the ball a step may cover (footprints down to BOUND_REACH of p's: the step is
// kept within BOUND_REACH of the distance to the eye where an octave is fading there).
// dir = vec3(0): around p (map); else along the unit dir only (mapAlong: the y term is |dir.y| and an
// octave's slope along dir is at most its per-axis slope times |dx| + |dy| + |dz|, not √3).
float fieldBound(vec3 p, vec3 dir, out bool filtered)
{
    float footprint = max(footprintAt(length(p - uCamPos)), 1e-30), ball = footprint * BOUND_REACH;
    bool along = dir != vec3(0.0);
    float yRate = along ? abs(dir.y) : 1.0, axes = along ? abs(dir.x) + abs(dir.y) + abs(dir.z) : 1.7320508;
    const float FADE = 1.0 / (OCTAVE_FADE_FULL - OCTAVE_FADE_GONE);
    // the fine octaves' largest sum first: weights over the ball (footprints down to BOUND_REACH of p's)
    float rest = 0.0, a = 0.5, f = uNoiseFrequency;
    for (int o = 0; o < uNoiseOctaves; o++, a *= 0.5, f *= 2.0)
        rest += a * clamp((1.0 / (ball * f) - OCTAVE_FADE_GONE) * FADE, 0.0, 1.0);
    float y = p.y - uNoiseBase, amp = 0.5, freq = uNoiseFrequency;
    float coarse = 0.0, slope = yRate, best = -1e30, inside = 1e30;
    filtered = false;
    for (int o = 0; o <= uNoiseOctaves; o++) {
        best = max(best, (y - uNoiseAmplitude * (coarse + rest)) / max(slope, 1e-6));
        inside = min(inside, (y - uNoiseAmplitude * coarse) / max(slope, 1e-6));
        if (o == uNoiseOctaves)
            break;
        float perWave = 1.0 / (footprint * freq); // footprints a wavelength at p
        float w = clamp((perWave - OCTAVE_FADE_GONE) * FADE, 0.0, 1.0);
        float wBall = clamp((perWave / BOUND_REACH - OCTAVE_FADE_GONE) * FADE, 0.0, 1.0);
        filtered = filtered || wBall < 1.0;
        if (wBall <= 0.0)
            break; // this one and the finer are gone in the whole ball
        if (w > 0.0)
            coarse += amp * w * valueNoise(p * freq + vec3(float(o) * 17.31)).x;
        rest -= amp * wBall;
        // the weight's slope at its steepest in the ball (the smallest footprint there)
        float dwMax = wBall < 1.0 ? uPixelAngle * FADE / (ball * ball * freq) : 0.0;
        slope += uNoiseAmplitude * amp * (wBall * freq * uNoiseSlope * axes + dwMax);
        amp *= 0.5;
        freq *= 2.0;
    }
    return best > 0.0 ? best : (inside < 0.0 ? inside : 0.0);
}

// The bound, then kept within the ball its weights hold for, and above base + A (the fbm stays below 1)
// the height over that plane (along dir: how far dir goes before it reaches the plane; never, upward).
// Along dir the field's bound holds backward as far as forward (its slopes are |dir.y| and Σ|dirᵢ|,
// the same for −dir), which over-relaxation's check of overlapping balls needs (common/march.glsl);
// the plane's does not: rising from below it, a bound reaching past the plane is cut there, so a
// relaxed step that overshoots lands above it, where nothing is, and the check stays true.
vec2 boundAt(vec3 p, vec3 dir)
{
    bool filtered;
    float field = fieldBound(p, dir, filtered), above = p.y - (uNoiseBase + uNoiseAmplitude);
    if (filtered && field > 0.0) // within the ball the weights are bounded for
        field = min(field, BOUND_REACH * length(p - uCamPos));
    if (above >= 0.0 && dir != vec3(0.0))
        above = dir.y < 0.0 ? above / -dir.y : 1e30;
    else if (dir.y > 0.0 && field > (-above + PLANE_MARGIN * uNoiseAmplitude) / dir.y)
        return vec2((-above + PLANE_MARGIN * uNoiseAmplitude) / dir.y, MATERIAL_BOUND); // rising: just past the plane
    return above > field ? vec2(above, MATERIAL_BOUND) : vec2(field, 0.0);
}

vec2 map(vec3 p) { return boundAt(p, vec3(0.0)); }

#define PROGRAM_MAP_ALONG 1
vec2 mapAlong(vec3 p, vec3 dir) { return boundAt(p, dir); }

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
