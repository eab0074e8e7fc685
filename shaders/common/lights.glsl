// Direct light from point lights (radiant intensity, 1/d² falloff as the course task insists) and
// directional lights (irradiance), each with its own shadow mode.
#if NUM_LIGHTS > 0 // GLSL has no arrays of size 0
uniform vec3 uLightVec[NUM_LIGHTS];        // position (point) or unit direction toward it (directional)
uniform bool uLightDirectional[NUM_LIGHTS];
uniform vec3 uLightColor[NUM_LIGHTS];      // colour × intensity
uniform int uLightShadow[NUM_LIGHTS];      // 0 none, 1 hard, 2 soft (scene_light.shadow)
uniform float uLightSoftness[NUM_LIGHTS];

// Shadow rays start SURFACE_OFFSET_K thresholds off the surface, measured in map()'s units: where
// map() is a bound that grows much slower than distance (PROGRAM_SLOW_BOUND: the noise terrain's
// Lipschitz-scaled field), the offset grows by 1/|∇map| so the ray does not start inside its own
// threshold: a hit on the surface (refined: common/march.glsl) has no threshold of slack to spare.
float shadowOffset(vec3 p, vec3 n, float pathT)
{
    const float MIN_GRADIENT = 0.02; // at most 50× the plain offset
    float off = SURFACE_OFFSET_K * hitEps(pathT);
#if FX_SHADOWS && MARCH_REFINES && defined(PROGRAM_SLOW_BOUND)
    float g = (map(p + n * off).x - map(p).x) / off;
    off /= clamp(g, MIN_GRADIENT, 1.0);
#endif
    return off;
}

#ifdef PROGRAM_LIGHT_MEDIUM
// Light from direction l reaching a point `depth` under a level surface of a medium (index ior, absorption
// sigma): Fresnel's transmitted share at the light's angle, then Beer–Lambert over the refracted path,
// depth / cos θt. None from below the surface's horizon. (Its shadow rays go straight, unrefracted.)
vec3 throughSurface(vec3 l, float depth, float ior, vec3 sigma)
{
    if (l.y <= 0.0)
        return vec3(0.0);
    float cosT = sqrt(1.0 - (1.0 - l.y * l.y) / (ior * ior));
    return (1.0 - fresnelDielectric(l.y, 1.0 / ior)) * exp(-sigma * depth / cosT);
}
#endif

// The radiance light i sends to p, its unit direction l from p and its distance (MAX_DIST for a
// directional light): the model and the path tracer (common/pathtrace.glsl) both light by it.
vec3 lightArriving(int i, vec3 p, out vec3 l, out float dist)
{
    vec3 radiance;
    if (uLightDirectional[i]) {
        l = uLightVec[i];
        dist = float(MAX_DIST);
        radiance = uLightColor[i];
    } else {
        vec3 toLight = uLightVec[i] - worldApprox(p);
        float d2 = max(dot(toLight, toLight), 1e-8);
        dist = sqrt(d2);
        l = toLight / dist;
        radiance = uLightColor[i] / d2;
    }
#ifdef PROGRAM_LIGHT_MEDIUM // p under a program's medium (a terrain's water): the light crosses its surface
    float depth, ior;
    vec3 sigma;
    if (programLightMedium(p, depth, ior, sigma))
        radiance *= throughSurface(l, depth, ior, sigma);
#endif
    return radiance;
}

vec3 directLight(vec3 p, vec3 n, vec3 v, Material m, vec3 F0, float pathT)
{
    vec3 sum = vec3(0.0);
#if FX_SHADOWS
    float offset = shadowOffset(p, n, pathT);
#endif
    for (int i = 0; i < NUM_LIGHTS; i++) {
        vec3 l;
        float dist;
        vec3 radiance = lightArriving(i, p, l, dist);
        vec3 f = cookTorrance(n, v, l, m.albedo, m.metallic, m.roughness, F0);
        if (all(lessThanEqual(f, vec3(0.0))))
            continue;
        float vis = 1.0;
#if FX_SHADOWS
        int mode = uLightShadow[i];
        if (mode > 0 && fxOn(FX_SHADOWS_BIT)) {
            vec3 ro = p + n * offset;
#if FX_SOFT_SHADOWS
            if (mode == 2 && fxOn(FX_SOFT_SHADOWS_BIT))
                vis = softShadow(ro, l, dist, uLightSoftness[i], pathT);
            else
#endif
                vis = hardShadow(ro, l, dist, pathT);
        }
#endif
        sum += f * radiance * vis;
    }
    return sum;
}
#else
vec3 directLight(vec3 p, vec3 n, vec3 v, Material m, vec3 F0, float pathT) { return vec3(0.0); }
#endif
