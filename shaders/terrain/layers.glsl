// The terrain's layered albedo (needs common/material.glsl): rock, grass by slope, sand below and snow
// above a height. Names from app/scene/scene_programs.c (layer_uniforms). The program declares
// uTerrainHeightMin and uTerrainHeightMax, its surface's height range (metres).
uniform float uSandLine;   // sand below this height (metres)
uniform float uSnowLine;   // snow above this height (metres)
uniform float uGrassSlope; // grass where normal.y exceeds this
uniform int uLayerSand, uLayerGrass, uLayerRock, uLayerSnow; // material indices
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

vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    const float BLEND = 0.08; // width of the transitions (slope units / fraction of the height range)
    float range = max(uTerrainHeightMax - uTerrainHeightMin, 1e-3);
    float grass = smoothstep(uGrassSlope - BLEND, uGrassSlope + BLEND, n.y);
    float snow = smoothstep(uSnowLine - BLEND * range, uSnowLine + BLEND * range, p.y) *
                 smoothstep(0.5, 0.7, n.y);
    float sand = 1.0 - smoothstep(uSandLine - 0.02 * range, uSandLine + 0.02 * range, p.y);
    vec3 c = mix(layerColor(uLayerRock, p, n, dpdx, dpdy), layerColor(uLayerGrass, p, n, dpdx, dpdy), grass);
    c = mix(c, layerColor(uLayerSand, p, n, dpdx, dpdy), sand);
    return mix(c, layerColor(uLayerSnow, p, n, dpdx, dpdy), snow);
}
