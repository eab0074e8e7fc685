// The terrain's layered albedo (declared in terrain/terrain.glsl, needs common/material.glsl).
vec3 layerColor(int m, vec3 p, vec3 n, vec3 dpdx, vec3 dpdy)
{
    if (m < 0)
        return vec3(0.5);
    vec3 c = uMatBase[m].rgb;
#if FX_TEXTURES
    int tex = int(uMatParams[m].w);
    if (tex >= 0 && fxOn(FX_TEXTURES_BIT))
        c *= triplanar(tex, p, n, dpdx, dpdy, uMatAbsorb[m].a);
#endif
    return c;
}

vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    const float BLEND = 0.08; // width of the transitions (slope units / fraction of the height range)
    float range = max(uTerrainRange.y - uTerrainRange.x, 1e-3);
    float grass = smoothstep(uTerrainLayers.z - BLEND, uTerrainLayers.z + BLEND, n.y);
    float snow = smoothstep(uTerrainLayers.y - BLEND * range, uTerrainLayers.y + BLEND * range, p.y) *
                 smoothstep(0.5, 0.7, n.y);
    float sand = 1.0 - smoothstep(uTerrainLayers.x - 0.02 * range, uTerrainLayers.x + 0.02 * range, p.y);
    vec3 c = mix(layerColor(uLayerMaterial.z, p, n, dpdx, dpdy), layerColor(uLayerMaterial.y, p, n, dpdx, dpdy), grass);
    c = mix(c, layerColor(uLayerMaterial.x, p, n, dpdx, dpdy), sand);
    return mix(c, layerColor(uLayerMaterial.w, p, n, dpdx, dpdy), snow);
}
