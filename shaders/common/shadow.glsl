// Shadow rays toward a light, started SURFACE_OFFSET_K hit thresholds off the surface.
// hardShadow: 0 or 1. softShadow: the penumbra estimate of I. Quilez, "soft shadows in raymarched
// SDFs" (2010): a ray that passes at distance h from an occluder at distance t is k·h/t lit.

#ifndef PROGRAM_SHADOWS // a program may cast shadow rays its own way (terrain)
float hardShadow(vec3 ro, vec3 rd, float tmax, float pathT)
{
    float t = 0.0;
    for (int i = 0; i < SHADOW_STEPS && loopSpend(1); i++) {
        vec2 d = marchMap(ro + rd * t, rd); // along the ray: how far it is free (common/march.glsl)
        float h = d.x;
        if (h < hitEps(pathT + t) && !isBound(d))
            return 0.0;
        t += h;
        if (t > tmax)
            break;
    }
    return 1.0;
}

#if FX_SOFT_SHADOWS
float softShadow(vec3 ro, vec3 rd, float tmax, float k, float pathT)
{
    float res = 1.0, t = 0.0;
    for (int i = 0; i < SHADOW_STEPS && loopSpend(1); i++) {
        vec2 d = marchMap(ro + rd * t, rd);
        float h = d.x, eps = hitEps(pathT + t);
        if (!isBound(d)) { // a bound is not an occluder: neither a hit nor a penumbra
            if (h < eps)
                return 0.0;
            res = min(res, k * h / max(t, eps));
        }
        t += clamp(h, eps, tmax / 4.0);
        if (t > tmax)
            break;
    }
    res = clamp(res, 0.0, 1.0);
    return res * res * (3.0 - 2.0 * res); // smoothstep: no visible kink at the penumbra's edge
}
#endif
#endif
