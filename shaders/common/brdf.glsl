// Cook–Torrance microfacet BRDF (the PBR lecture): GGX normal distribution D, Schlick's Fresnel F,
// Smith's shadowing with the Schlick-GGX G1 (k = (r+1)²/8 for direct light), Lambert c/π diffuse
// weighted by (1 - F)(1 - metallic) so that diffuse + specular never reflect more than arrives.
// And the exact Fresnel reflectance of a dielectric for unpolarized light (droplets paper).

const float PI = 3.14159265358979;
// GGX with alpha = roughness² → 0 is a delta: its peak overflows float. Smooth mirrors are traced instead.
const float MIN_ROUGHNESS = 0.03;
// N·V → 0 on silhouettes: the specular term divides by it.
const float MIN_COSINE = 1e-4;

float ggxD(float NdotH, float alpha)
{
    float a2 = alpha * alpha;
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

float schlickG1(float NdotX, float k) { return NdotX / (NdotX * (1.0 - k) + k); }

vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    float m = clamp(1.0 - cosTheta, 0.0, 1.0);
    float m2 = m * m;
    return F0 + (1.0 - F0) * (m2 * m2 * m);
}

// For light from the whole environment a rough surface does not reach full reflectance at grazing
// angles: S. Lagarde, "Adopting a physically based shading model" (2011), max(1 − r, F0) as the limit.
vec3 fresnelSchlickRoughness(float cosTheta, vec3 F0, float roughness)
{
    float m = clamp(1.0 - cosTheta, 0.0, 1.0);
    float m2 = m * m;
    return F0 + (max(vec3(1.0 - roughness), F0) - F0) * (m2 * m2 * m);
}

// Reflected radiance factor for one light: BRDF × cos θ_l.
vec3 cookTorrance(vec3 n, vec3 v, vec3 l, vec3 albedo, float metallic, float roughness, vec3 F0)
{
    float NdotL = dot(n, l);
    if (NdotL <= 0.0)
        return vec3(0.0);
    float NdotV = max(dot(n, v), MIN_COSINE);
    vec3 h = normalize(v + l);
    float r = max(roughness, MIN_ROUGHNESS);
    float k = (r + 1.0) * (r + 1.0) / 8.0;
    float D = ggxD(max(dot(n, h), 0.0), r * r);
    float G = schlickG1(NdotV, k) * schlickG1(NdotL, k);
    vec3 F = fresnelSchlick(max(dot(h, v), 0.0), F0);
    vec3 specular = D * G * F / (4.0 * NdotV * NdotL);
    vec3 kd = (1.0 - F) * (1.0 - metallic);
    return (kd * albedo / PI + specular) * NdotL;
}

// Unpolarized Fresnel reflectance at a dielectric boundary: cosI = cos of the incidence angle (> 0),
// eta = n_incident / n_transmitted. Returns 1 on total internal reflection.
// R = (r_s² + r_p²) / 2, r_s = (η cos i − cos t)/(η cos i + cos t), r_p = (cos i − η cos t)/(cos i + η cos t).
float fresnelDielectric(float cosI, float eta)
{
    float sin2T = eta * eta * max(0.0, 1.0 - cosI * cosI);
    if (sin2T >= 1.0)
        return 1.0;
    float cosT = sqrt(1.0 - sin2T);
    float rs = (eta * cosI - cosT) / (eta * cosI + cosT);
    float rp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5 * (rs * rs + rp * rp);
}
