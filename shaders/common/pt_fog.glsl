// The path tracer's fog as a medium (common/pathtrace.glsl): its transmittance along a segment, and
// where a photon is first scattered, sampled exactly from the closed-form optical depth.
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
