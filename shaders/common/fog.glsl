// Exponential height fog (the height-field lab): density σ(y) = σ0 · e^(−b (y − y0)), and light
// scattered in proportional to it, so along a segment of length s the radiance becomes
// L = L_surface · T + C · (1 − T), T = e^(−τ), τ = ∫ σ dt, C the fog colour.
// The lab's closed form τ = σ0 e^(−b(y_o−y0)) (1 − e^(−b d_y s)) / (b d_y) is 0/0 for level rays and
// overflows when the ray runs far downhill into steep fog. Rewritten around the segment's densest end
// y_d (its lower end for b > 0): τ = σ0 · s · e^(−b (y_d − y0)) · f(u), u = |b d_y| s ≥ 0,
// f(u) = (1 − e^(−u)) / u, with its series near 0. Every factor is finite for every slope.
uniform vec3 uFogColor;
uniform float uFogDensity; // σ0 per metre at uFogHeight
uniform float uFogFalloff; // b per metre
uniform float uFogHeight;  // y0

const float FOG_SERIES_BELOW = 1e-3;
const float FOG_MAX_EXPONENT = 80.0; // e^80 ≈ 5e34: well inside float, and already opaque

float fogOpticalDepth(float oy, float dy, float s)
{
    float sigma0 = uFogDensity, b = uFogFalloff;
#ifdef FOG_NAIVE // the lab's form as written (tests show what it gets wrong)
    return sigma0 * exp(-b * (oy - uFogHeight)) * (1.0 - exp(-b * dy * s)) / (b * dy);
#else
    float y1 = oy + dy * s;
    float yDense = b >= 0.0 ? min(oy, y1) : max(oy, y1);
    float u = abs(b * dy) * s;
    float f = u < FOG_SERIES_BELOW ? 1.0 - u * (0.5 - u / 6.0) : (1.0 - exp(-u)) / u;
    float e = min(-b * (yDense - uFogHeight), FOG_MAX_EXPONENT);
    return sigma0 * s * exp(e) * f;
#endif
}

vec3 applyFog(vec3 col, vec3 ro, vec3 rd, float s)
{
    float T = exp(-fogOpticalDepth(ro.y, rd.y, s));
    return col * T + uFogColor * (1.0 - T);
}
