// The physical sky (FX_SKY): the Earth's atmosphere after Hillaire 2020 (app/data/sky/sky.h has the model,
// its parameters and its double-precision twin, which the tests compare with this): the sun's single
// scattering by Rayleigh and Mie along the view ray, Hillaire's isotropic multiple scattering Ψ_ms from
// a table by altitude the CPU fills for the scene's sun, ozone absorbing, the Earth's shadow; the sun's
// disc with limb darkening; and aerial perspective: a hit's light dimmed by the air between it and the
// eye, the air's own in-scattered light added. World heights are metres × uSkyScale (a terrain's
// exaggeration); y = 0 is the sea.
uniform vec3 uSkySun;        // unit, toward the sun
uniform vec3 uSkyIrradiance; // the sun's irradiance above the atmosphere (the light's colour × intensity)
uniform vec3 uSkyMs[32];     // Ψ_ms by altitude: row i at 100 km · (i / 31)²
uniform float uSkyScale;     // world height units per metre

const float SKY_R = 6360000.0, SKY_TOP = 100000.0;
const vec3 SKY_RAYLEIGH = vec3(5.802e-6, 13.558e-6, 33.1e-6);
const float SKY_MIE = 3.996e-6, SKY_MIE_EXT = 4.40e-6, SKY_G = 0.8;
const vec3 SKY_OZONE = vec3(0.650e-6, 1.881e-6, 0.085e-6);
const float SKY_SUN_RADIUS = 0.004654; // radians: 0.2667°

vec3 skyExtinction(float h)
{
    return SKY_RAYLEIGH * exp(-h / 8000.0) + SKY_MIE_EXT * exp(-h / 1200.0) +
           SKY_OZONE * max(0.0, 1.0 - abs(h - 25000.0) / 15000.0);
}

// The altitude t metres along a ray from altitude h with zenith cosine mu, written so that a float keeps
// its metres: sqrt(r² + x) − r = x / (sqrt(r² + x) + r).
float skyAltitude(float h, float mu, float t)
{
    float r = SKY_R + h, x = t * (2.0 * r * mu + t);
    return h + x / (sqrt(r * r + x) + r);
}

// The ray's length to the top of the atmosphere, or to the ground (ground = true).
float skyRayEnd(float h, float mu, out bool ground)
{
    float r = SKY_R + h, b = r * mu;
    float toGround = b * b - h * (2.0 * SKY_R + h);
    ground = b < 0.0 && toGround >= 0.0;
    if (ground)
        return max(-b - sqrt(toGround), 0.0);
    return max(-b + sqrt(max(b * b + (SKY_TOP - h) * (2.0 * SKY_R + SKY_TOP + h), 0.0)), 0.0);
}

// Transmittance toward the sun (zenith cosine mu) from altitude h: 0 in the Earth's shadow.
vec3 skySunTransmittance(float h, float mu)
{
    bool ground;
    float end = skyRayEnd(h, mu, ground);
    if (ground)
        return vec3(0.0);
    vec3 od = vec3(0.0);
    const int N = 8;
    for (int i = 0; i < N; i++) {
        float a = float(i) / float(N), b = float(i + 1) / float(N), m = 0.5 * (a + b);
        od += skyExtinction(skyAltitude(h, mu, end * m * m)) * end * (b * b - a * a);
    }
    return exp(-od);
}

vec3 skyMs(float h)
{
    float u = sqrt(clamp(h / SKY_TOP, 0.0, 1.0)) * 31.0;
    int i = min(int(u), 30);
    return mix(uSkyMs[i], uSkyMs[i + 1], u - float(i));
}

// In-scattered light along dir from altitude h over len metres (len < 0: to the top or the ground, whose
// lit Lambertian face is added), per unit of the sun's irradiance; T: the transmittance over it.
vec3 skyScatter(float h, vec3 dir, float len, out vec3 T)
{
    bool ground;
    float end = skyRayEnd(h, dir.y, ground);
    bool whole = len < 0.0;
    len = whole ? end : min(len, end);
    float mu = dot(dir, uSkySun), g = SKY_G;
    float pr = 3.0 / (16.0 * PI) * (1.0 + mu * mu);
    float pm = 3.0 / (8.0 * PI) * (1.0 - g * g) * (1.0 + mu * mu) / ((2.0 + g * g) * pow(1.0 + g * g - 2.0 * g * mu, 1.5));
    vec3 L = vec3(0.0);
    T = vec3(1.0);
    const int N = 16;
    for (int i = 0; i < N; i++) {
        float a = float(i) / float(N), b = float(i + 1) / float(N), m = 0.5 * (a + b);
        float t = len * m * m, dt = len * (b * b - a * a);
        vec3 p = vec3(0.0, SKY_R + h, 0.0) + dir * t;
        float hp = skyAltitude(h, dir.y, t), sunMu = dot(p, uSkySun) / length(p);
        vec3 ray = SKY_RAYLEIGH * exp(-hp / 8000.0);
        float mie = SKY_MIE * exp(-hp / 1200.0);
        vec3 e = skyExtinction(hp), seg = exp(-e * dt);
        vec3 w = T * (1.0 - seg) / max(e, vec3(1e-12)); // the stretch's share, exact for constant air
        L += w * ((ray * pr + mie * pm) * skySunTransmittance(hp, sunMu) + (ray + mie) * skyMs(hp));
        T *= seg;
    }
    if (whole && ground) { // the Earth's ground beyond the scene, lit by the sun
        vec3 p = vec3(0.0, SKY_R + h, 0.0) + dir * len;
        float sunMu = dot(p, uSkySun) / length(p);
        L += T * 0.3 / PI * max(sunMu, 0.0) * skySunTransmittance(0.0, sunMu);
    }
    return L;
}

// The sky's radiance seen from the eye along dir: the air's light, and (disc) the sun's disc
// (limb-darkened, its irradiance spread over its solid angle) where dir points at it.
vec3 skyRadiance(vec3 dir, bool disc)
{
    float h = max(uCamPos.y / uSkyScale, 0.0);
    vec3 T;
    vec3 L = skyScatter(h, dir, -1.0, T);
    float c = dot(dir, uSkySun), cosR = cos(SKY_SUN_RADIUS);
    if (disc && c > cosR) {
        float r = sqrt(max(1.0 - c * c, 0.0)) / sin(SKY_SUN_RADIUS); // 0 at the centre, 1 at the limb
        float limb = 1.0 - 0.6 * (1.0 - sqrt(max(1.0 - r * r, 0.0))); // linear limb darkening, u = 0.6
        L += T * limb / (PI * SKY_SUN_RADIUS * SKY_SUN_RADIUS * 0.8); // 0.8: the darkened disc's mean
    }
    return L * uSkyIrradiance;
}

// Aerial perspective: what reaches the eye from a hit `dist` world units along the world ray dir.
vec3 skyAerial(vec3 col, vec3 ro, vec3 dir, float dist)
{
    vec3 d = vec3(dir.x, dir.y / uSkyScale, dir.z); // world units to metres
    float metres = dist * length(d);
    vec3 T;
    vec3 L = skyScatter(max(ro.y / uSkyScale, 0.0), normalize(d), metres, T);
    return col * T + L * uSkyIrradiance;
}
