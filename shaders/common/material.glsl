// Materials: metal/roughness PBR parameters, one uniform array per parameter (app/scene/scene.c names them).
uniform vec3 uMatBaseColor[NUM_MATERIALS];
uniform float uMatMetallic[NUM_MATERIALS];
uniform float uMatRoughness[NUM_MATERIALS];
uniform float uMatTransmission[NUM_MATERIALS]; // 0 opaque, 1 glass
uniform float uMatIor[NUM_MATERIALS];
uniform vec3 uMatAbsorption[NUM_MATERIALS];    // Beer–Lambert coefficient per metre
uniform vec3 uMatEmission[NUM_MATERIALS];
uniform int uMatTexture[NUM_MATERIALS];        // colour texture index, −1 none
uniform float uMatUvScale[NUM_MATERIALS];      // texture repeats per metre

struct Material {
    vec3 albedo;
    float metallic, roughness, transmission, ior;
    vec3 absorption, emission;
};

// Materials made by name, not by the struct's argument order: a clear dielectric that transmits (a
// droplet's liquid), and none at all (a point in fog: the phase function stands in for the BRDF).
Material dielectricMaterial(float roughness, float ior, vec3 absorption)
{
    return Material(vec3(0.0), 0.0, roughness, 1.0, ior, absorption, vec3(0.0));
}
Material noMaterial() { return Material(vec3(0.0), 0.0, 1.0, 0.0, 1.0, vec3(0.0), vec3(0.0)); }

#if FX_TEXTURES || FX_RELIEF
uniform sampler2D uTex0, uTex1, uTex2, uTex3;
#endif
#if FX_TEXTURES

// GLSL 330 indexes sampler arrays only with constants, hence the branches.
vec3 texSample(int i, vec2 uv, vec2 dx, vec2 dy)
{
    if (i == 0) return textureGrad(uTex0, uv, dx, dy).rgb;
    if (i == 1) return textureGrad(uTex1, uv, dx, dy).rgb;
    if (i == 2) return textureGrad(uTex2, uv, dx, dy).rgb;
    return textureGrad(uTex3, uv, dx, dy).rgb;
}

// Anisotropic filtering by several trilinear taps spread along the footprint's major axis, each
// filtering 1/n of it (McCormack et al., "Feline: fast elliptical lines for anisotropic texture
// mapping", SIGGRAPH 1999). n = the footprint's axis ratio, at most ANISO_TAPS.
vec3 texAniso(int i, vec2 uv, vec2 dx, vec2 dy)
{
#if ANISO_TAPS > 1
    float lx = dot(dx, dx), ly = dot(dy, dy);
    vec2 major = lx > ly ? dx : dy, minor = lx > ly ? dy : dx;
    float ratio = sqrt(max(lx, ly) / max(min(lx, ly), 1e-20));
    int n = int(clamp(ceil(ratio), 1.0, float(ANISO_TAPS)));
    vec2 step = major / float(n);
    vec3 c = vec3(0.0);
    for (int k = 0; k < ANISO_TAPS; k++) {
        if (k >= n)
            break;
        c += texSample(i, uv + step * (float(k) + 0.5 - 0.5 * float(n)), step, minor);
    }
    return c / float(n);
#else
    return texSample(i, uv, dx, dy);
#endif
}

// Triplanar projection: each axis plane contributes by |n|^4. The texture gradients come from the
// ray differentials (dpdx, dpdy: surface offset to the neighbouring pixels' hits), so filtering
// (mipmaps + anisotropic taps) works after any number of steps and bounces.
vec3 triplanar(int i, vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, float scale)
{
    const float MIN_WEIGHT = 0.02;
    vec3 w = n * n;
    w *= w;
    w /= w.x + w.y + w.z;
    vec3 c = vec3(0.0);
    p *= scale;
    dpdx *= scale;
    dpdy *= scale;
    if (w.x > MIN_WEIGHT) c += w.x * texAniso(i, p.zy, dpdx.zy, dpdy.zy);
    if (w.y > MIN_WEIGHT) c += w.y * texAniso(i, p.xz, dpdx.xz, dpdy.xz);
    if (w.z > MIN_WEIGHT) c += w.z * texAniso(i, p.xy, dpdx.xy, dpdy.xy);
    return c / max(dot(w, vec3(greaterThan(w, vec3(MIN_WEIGHT)))), 1e-6);
}
#endif

Material getMaterial(float id, vec3 p, vec3 n, vec3 dpdx, vec3 dpdy)
{
    int i = clamp(int(id + 0.5), 0, NUM_MATERIALS - 1);
    Material m;
    m.albedo = uMatBaseColor[i];
    m.metallic = uMatMetallic[i];
    m.roughness = uMatRoughness[i];
    m.transmission = uMatTransmission[i];
    m.ior = uMatIor[i];
    m.absorption = uMatAbsorption[i];
    m.emission = uMatEmission[i];
#ifdef PROGRAM_ALBEDO // the program colours its surface (fractals: orbit traps; terrain: layers), not its water
    if (!isWater(id)) {
        m.albedo = programAlbedo(p, n, dpdx, dpdy, m.albedo);
        return m;
    }
#endif
#if FX_TEXTURES
    int tex = uMatTexture[i];
    if (tex >= 0 && fxOn(FX_TEXTURES_BIT))
        m.albedo *= triplanar(tex, p, n, dpdx, dpdy, uMatUvScale[i]);
#endif
    return m;
}
