// The environment: light arriving from infinitely far in direction dir.
// With FX_ENVMAP a cube map (seamless filtering), else a constant colour (the course task's
// "environment light without a texture"). uEnvColor already includes the intensity.
uniform vec3 uEnvColor;
#if FX_ENVMAP
uniform samplerCube uEnvMap;
uniform float uEnvMaxLod; // log2 of the face size
#endif

#if FX_SKY
#include "common/sky.glsl"
#endif

// Cube maps follow the RenderMan (left-handed) face convention; flipping Z maps fathom's
// right-handed world onto it so the sky is not mirrored.
vec3 envDir(vec3 dir) { return vec3(dir.xy, -dir.z); }

vec3 environment(vec3 dir)
{
#if FX_SKY
    if (fxOn(FX_SKY_BIT))
        return skyRadiance(dir, true);
#endif
#if FX_ENVMAP
    return fxOn(FX_ENVMAP_BIT) ? textureLod(uEnvMap, envDir(dir), 0.0).rgb * uEnvColor : uEnvColor;
#else
    return uEnvColor;
#endif
}

// Radiance seen in a lobe: the cube map's coarser levels stand in for a pre-filtered map
// (roughness 1 → the 4×4 level, whose texels cover about a hemisphere's worth of directions).
vec3 environmentBlurred(vec3 dir, float roughness)
{
#if FX_SKY
    if (fxOn(FX_SKY_BIT)) // the air's light without the sun's disc (the lights carry the sun)
        return skyRadiance(dir, false);
#endif
#if FX_ENVMAP
    return fxOn(FX_ENVMAP_BIT) ? textureLod(uEnvMap, envDir(dir), roughness * (uEnvMaxLod - 2.0)).rgb * uEnvColor
                               : uEnvColor;
#else
    return uEnvColor;
#endif
}

// The sky's mean radiance over all directions: the mean of the six faces' 1 × 1 levels (faces subtend
// equal solid angles). The diffuse ambient of a renderer without image-based light (quality.ambient 0).
vec3 environmentMean()
{
#if FX_ENVMAP
    if (!fxOn(FX_ENVMAP_BIT))
        return uEnvColor;
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 3; i++) {
        vec3 axis = vec3(i == 0, i == 1, i == 2);
        sum += textureLod(uEnvMap, axis, uEnvMaxLod).rgb + textureLod(uEnvMap, -axis, uEnvMaxLod).rgb;
    }
    return sum / 6.0 * uEnvColor;
#else
    return uEnvColor;
#endif
}

// The diffuse ambient light at normal n (quality.ambient: the sky around n, or its mean).
vec3 ambientLight(vec3 n)
{
#if FX_SKY // the physical sky's cosine-weighted mean over the upper hemisphere, from the CPU (scene_sun.c)
    if (fxOn(FX_SKY_BIT))
        return uEnvColor;
#endif
#if AMBIENT
    return environmentBlurred(n, 1.0);
#else
    return environmentMean();
#endif
}
