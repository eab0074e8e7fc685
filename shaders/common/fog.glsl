// Homogeneous exponential fog on the primary segment: transmittance T = exp(−σ t),
// colour = c·T + fog·(1 − T). A miss counts as t = MAX_DIST.
uniform vec3 uFogColor;
uniform float uFogDensity;

vec3 applyFog(vec3 col, float t)
{
    float T = exp(-uFogDensity * t);
    return col * T + uFogColor * (1.0 - T);
}
