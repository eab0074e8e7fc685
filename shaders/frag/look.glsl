// A fragment's own look (fractal.look = fragment, app/scene/formula/frag.h): the image Fragmentarium's DE
// renderers make, evaluated from the preset's values of their controls (declared in frag/raytracer.frag).
// Written from what DE-Raytracer.frag's trace(), lighting(), ambientOcclusion() and shadow() compute (Syntopia's
// Fragmentarium and 3Dickulus' FragM): the surface's colour (orbit trap or baseColor()) taken to the power
// Gamma, mixed toward the AO colour by ambient occlusion, lit by a directional spot light (diffuse and a
// normalised Blinn-Phong specular with Schlick's term) and a light at the camera (its diffuse, at least
// CamLightMin), hard or soft shadows toward the spot light, exponential-squared fog toward the background;
// a miss is the background (darkened toward the image's edge by GradientBackground) plus the glow of the
// steps taken. The sample is that colour before the host's post (exposure, tone mapping, gamma), which the
// display applies to the mean of the samples (display.frag), as Fragmentarium's BufferShader does.
// The march is fathom's castRay with Fragmentarium's rule (common/march.glsl, HIT_RELATIVE). Included by
// common/sdf_main.glsl after the fragment, whose names are its own again: the fragment's estimate, trap colour
// and background come through frag/glue.glsl (fragDE, fragSurface, fragBackgroundHook).

// Fragmentarium's hash: fract(sin(dot(co, (12.9898, 78.233))) · 43758.5453)
float fragRand(vec2 co) { return fract(sin(dot(co, vec2(12.9898, 78.233))) * 43758.5453); }

// the spot light's direction from SpotLightDir (spherical coordinates in units of π and π/2)
vec3 fragSpotDir()
{
    vec2 a = SpotLightDir * vec2(3.1415, 3.1415 / 2.0);
    return normalize(vec3(sin(a.x) * cos(a.y), sin(a.y) * sin(a.x), cos(a.x)));
}

// central differences of half the threshold at p (the renderers' normal())
vec3 fragNormal(vec3 p, float eps)
{
    float h = max(eps * 0.5, 1.0e-7);
    vec3 e = vec3(0.0, h, 0.0);
    vec3 n = vec3(fragDE(p + e.yxx) - fragDE(p - e.yxx), fragDE(p + e.xyx) - fragDE(p - e.xyx),
                  fragDE(p + e.xxy) - fragDE(p - e.xxy));
    return length(n) > 0.0 ? normalize(n) : -uCamForward;
}

// five samples along the normal at i² · 10^DetailAO: how far the estimate falls short of the distance moved
float fragAO(vec3 p, vec3 n)
{
    float aoEps = pow(10.0, DetailAO), de = fragDE(p), ao = 0.0, wSum = 0.0, w = 1.0;
    float d = 1.0 - Dither * fragRand(p.xy);
    for (float i = 1.0; i < 6.0; i++) {
        float D = (fragDE(p + d * n * i * i * aoEps) - de) / (d * i * i * aoEps);
        w *= 0.6;
        ao += w * clamp(1.0 - D, 0.0, 1.0);
        wSum += w;
    }
    return clamp(AO.w * ao / wSum, 0.0, 1.0);
}

// the soft shadow toward sdir (Quilez's rule: the narrowest cone the march passes), 1 = fully shadowed
float fragShadow(vec3 pos, vec3 sdir, float eps)
{
    float t = 2.0 * eps, s = 1.0;
    for (int i = 0; i < MAX_STEPS && t < uFragMaxDistance && loopSpend(1); i++) {
        float dist = fragDE(pos + t * sdir);
        if (dist < eps)
            return 1.0;
        s = min(s, ShadowSoft * pow(dist / t, 0.5));
        t += dist;
    }
    return 1.0 - s;
}

vec3 fragLighting(vec3 n, vec3 color, vec3 pos, vec3 dir, float eps)
{
    vec3 spotDir = fragSpotDir();
#ifdef FRAG_LIGHT_PHONG // Fast-Raytracer and DE-Raytracer 0.9.1: lit toward -spotDir, Phong's highlight
    vec3 r = spotDir - 2.0 * dot(n, spotDir) * n;
    float diffuse = max(0.0, dot(-n, spotDir)) * SpotLight.w;
    float ambient = max(CamLightMin, dot(-n, dir)) * CamLight.w;
    float specular = SpecularExp <= 0.0 ? 0.0 : pow(max(0.0, dot(dir, -r)), SpecularExp) * Specular;
#ifdef FRAG_LIGHT_PHONG_SHADOWS // 0.9.1: no highlight on a face turned away, shadows toward -spotDir
    if (dot(n, dir) > 0.0)
        specular = 0.0;
    if (HardShadow > 0.0) {
        float shadowed = fragShadow(pos + n * eps, -spotDir, eps);
        ambient = mix(ambient, 0.0, HardShadow * shadowed);
        diffuse = mix(diffuse, 0.0, HardShadow * shadowed);
        if (shadowed > 0.0)
            specular = 0.0;
    }
#endif
    return (SpotLight.xyz * diffuse + CamLight.xyz * ambient + specular * SpotLight.xyz) * color;
#else
    float nDotL = max(0.0, dot(n, spotDir));
    vec3 halfVector = normalize(-dir + spotDir);
    float diffuse = nDotL * SpotLight.w;
    float ambient = max(CamLightMin, dot(-n, dir)) * CamLight.w;
    float hDotN = max(0.0, dot(n, halfVector));
    // Blinn-Phong normalised ((n + 2) / 8) with Schlick's Fresnel term (Hoffman, "Physically based shading",
    // SIGGRAPH 2010 course), as the renderers have it
    float specular = ((SpecularExp + 2.0) / 8.0) * pow(hDotN, SpecularExp) *
                     (SpecularExp + (1.0 - SpecularExp) * pow(1.0 - hDotN, 5.0)) * nDotL * Specular;
    specular = min(SpecularMax, specular);
    if (HardShadow > 0.0) {
        float shadowed = fragShadow(pos + n * eps, spotDir, eps);
#ifdef FRAG_SHADOW_CAMERA_LIGHT // Syntopia's Fragmentarium; FragM keeps the camera light in shadow
        ambient = mix(ambient, 0.0, HardShadow * shadowed);
#endif
        diffuse = mix(diffuse, 0.0, HardShadow * shadowed);
        if (shadowed > 0.0)
            specular = 0.0;
    }
    return (SpotLight.xyz * diffuse + CamLight.xyz * ambient + specular * SpotLight.xyz) * color;
#endif
}

// the background where a ray meets nothing: BackgroundColor (or the fragment's backgroundColor()), darker
// toward the edge by GradientBackground (3D.frag's screen coordinate, times FOV)
vec3 fragBackground(vec3 dir)
{
#ifdef FRAG_BACKGROUND
    return fragBackgroundHook(dir);
#else
    vec2 coord = vec2(dot(dir, uCamRight), dot(dir, uCamUp)) / max(dot(dir, uCamForward), 1e-6);
    return GradientBackground > 0.0 ? mix(BackgroundColor, vec3(0.0), length(coord) * GradientBackground)
                                    : BackgroundColor;
#endif
}

// One sample: the renderer's colour and the AOVs of the hit.
void fragPixel(vec3 ro, vec3 rd, out vec4 color, out vec4 normalDepth, out vec4 aux, out vec4 albedo)
{
    fragInit();
    Hit h = castRay(ro, rd, float(MAX_DIST), 1.0, 0.0);
    float stepFactor = clamp(float(h.steps) / float(GlowMax), 0.0, 1.0);
    vec3 back = fragBackground(rd);
    aux = vec4(h.exhausted ? -float(h.steps) : float(h.steps), rd);
    if (!h.hit) {
        color = vec4(back + Glow.xyz * stepFactor * Glow.w, 1.0);
        normalDepth = vec4(0.0, 0.0, 0.0, -1.0);
        albedo = vec4(0.0);
        return;
    }
    vec3 hit = ro + rd * h.t;
    float eps = hitEps(h.t);
    fragTrapReset(); // the trap of the last step and the normal's estimates, as the renderers leave it
    fragDE(hit);
    vec3 n = fragNormal(hit - NormalBackStep * eps * rd, eps);
    vec3 c = pow(clamp(fragSurface(hit, n), 0.0, 1.0), vec3(Gamma));
    albedo = vec4(c, 0.0);
    float ao = DetailAO < 0.0 ? fragAO(hit, n) : AO.w * stepFactor;
    c = mix(c, AO.xyz, ao);
    c = fragLighting(n, c, hit, rd, eps);
    c = mix(c, back, 1.0 - exp(-pow(Fog, 4.0) * h.t * h.t)); // GL_EXP2-like fog
    color = vec4(c, 1.0);
    normalDepth = vec4(n, h.t);
}
