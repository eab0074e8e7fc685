// The terrain's layered albedo (needs common/material.glsl): rock, grass by slope, sand below and snow
// above a height. Names from app/scene/scene_programs.c (scene_layer_uniforms). The program declares
// uTerrainHeightMin and uTerrainHeightMax, its surface's height range (metres).
uniform float uSandLine;   // sand below this height (metres)
uniform float uSnowLine;   // snow above this height (metres)
uniform float uGrassSlope; // grass where normal.y exceeds this
uniform int uLayerSand, uLayerGrass, uLayerRock, uLayerSnow; // material indices
uniform int uElevationRamp;   // 1: colour by true height (terrain.colors = elevation) instead of layers
uniform float uExaggeration;  // heights are true heights times this
#ifdef TERRAIN_IMAGERY
// The draped imagery (app/gpu/res_imagery.c): the DEM's whole extent, row 0 north, sRGB (read linear),
// alpha its coverage. Filtered by the footprint's own gradients: mipmaps and anisotropy like any texture.
uniform sampler2D uImagery;
#endif

// A hypsometric tint, the map makers' colours for height above the sea (true metres): lowland greens,
// upland tans and browns, grey rock, then snow; each surface keeps its texture's light and shade.
// (Written as a chain of mixes: constant arrays indexed in a loop made llvmpipe's terrain shader a
// hundred times slower.)
vec3 elevationRamp(float m)
{
    vec3 c = mix(vec3(0.30, 0.52, 0.30), vec3(0.52, 0.66, 0.38), clamp(m / 300.0, 0.0, 1.0));
    c = mix(c, vec3(0.82, 0.78, 0.50), clamp((m - 300.0) / 500.0, 0.0, 1.0));
    c = mix(c, vec3(0.70, 0.54, 0.36), clamp((m - 800.0) / 700.0, 0.0, 1.0));
    c = mix(c, vec3(0.58, 0.50, 0.46), clamp((m - 1500.0) / 1000.0, 0.0, 1.0));
    c = mix(c, vec3(0.80, 0.80, 0.80), clamp((m - 2500.0) / 1500.0, 0.0, 1.0));
    return mix(c, vec3(0.97, 0.97, 1.00), clamp((m - 4000.0) / 1500.0, 0.0, 1.0));
}

vec3 layerColor(int m, vec3 p, vec3 n, vec3 dpdx, vec3 dpdy)
{
    if (m < 0)
        return vec3(0.5);
    vec3 c = uMatBaseColor[m];
#if FX_TEXTURES
    int tex = uMatTexture[m];
    if (tex >= 0 && fxOn(FX_TEXTURES_BIT))
        c *= triplanar(tex, p, n, dpdx, dpdy, uMatUvScale[m]);
#endif
    return c;
}

#ifndef TERRAIN_ALTITUDE // a point's altitude (terrain.glsl's with the Earth's curvature)
#define TERRAIN_ALTITUDE(p) (p).y
#endif
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    const float BLEND = 0.08; // width of the transitions (slope units / fraction of the height range)
    float range = max(uTerrainHeightMax - uTerrainHeightMin, 1e-3);
    float grass = smoothstep(uGrassSlope - BLEND, uGrassSlope + BLEND, n.y);
    float snow = smoothstep(uSnowLine - BLEND * range, uSnowLine + BLEND * range, TERRAIN_ALTITUDE(p)) *
                 smoothstep(0.5, 0.7, n.y);
    float sand = 1.0 - smoothstep(uSandLine - 0.02 * range, uSandLine + 0.02 * range, TERRAIN_ALTITUDE(p));
    // a layer is sampled only where it shows (three triplanar textures of up to 16 taps each were 18 % of
    // the noise terrain's final frame): mix(c, x, 1) is x and mix(c, x, 0) is c, bit for bit
    vec3 c = grass < 1.0 ? layerColor(uLayerRock, p, n, dpdx, dpdy) : vec3(0.0);
    if (grass > 0.0)
        c = mix(c, layerColor(uLayerGrass, p, n, dpdx, dpdy), grass);
    if (sand > 0.0)
        c = mix(c, layerColor(uLayerSand, p, n, dpdx, dpdy), sand);
    if (snow > 0.0)
        c = mix(c, layerColor(uLayerSnow, p, n, dpdx, dpdy), snow);
    // the ramp keeps the layers' light and shade (their luminance about its mean), not their colour
    float shade = dot(c, vec3(0.299, 0.587, 0.114));
    if (uElevationRamp != 0)
        c = elevationRamp(TERRAIN_ALTITUDE(p) / uExaggeration) * (0.65 + 0.5 * shade);
#ifdef TERRAIN_IMAGERY
    vec2 extent = vec2(uTerrainSize) * uTerrainSpacing; // the DEM's texels edge to edge, as the imagery
    vec4 img = textureGrad(uImagery, (p.xz - uTerrainOrigin) / extent, dpdx.xz / extent, dpdy.xz / extent);
    c = mix(c, img.rgb, img.a);
#endif
    return c;
}
