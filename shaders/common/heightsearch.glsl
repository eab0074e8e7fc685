// The height-field lab's search, shared by the terrain marcher and parallax occlusion mapping:
// from t0, step linearly (first step dt, each next one STEP_GROWTH longer) until the point is at or
// below the surface, then bisect the last step BINARY_STEPS times. The includer defines
// `float hsSurfaceY(vec2 xz)`, the surface height over the horizontal plane of its frame (world for
// terrain, tangent space for relief). Returns the hit t, or −1; `samples` counts height lookups.
float hsSurfaceY(vec2 xz);

// The search ends where the ray leaves [t0, t1], however many steps that takes (the step knobs set
// its cost); this bound only stops a degenerate step from looping forever.
#ifndef HEIGHT_SEARCH_MAX_STEPS
#define HEIGHT_SEARCH_MAX_STEPS 1000000
#endif

float heightSearch(vec3 ro, vec3 rd, float t0, float t1, float dt, inout int samples)
{
    float t = t0;
    vec3 p = ro + rd * t;
    samples++;
    if (p.y <= hsSurfaceY(p.xz))
        return t; // starts below the surface
    for (int i = 0; i < HEIGHT_SEARCH_MAX_STEPS; i++) {
        float tPrev = t;
        t = min(t + dt, t1);
        dt *= float(STEP_GROWTH);
        p = ro + rd * t;
        samples++;
        if (p.y <= hsSurfaceY(p.xz)) {
            float lo = tPrev, hi = t;
            for (int k = 0; k < BINARY_STEPS; k++) {
                float mid = 0.5 * (lo + hi);
                vec3 q = ro + rd * mid;
                samples++;
                if (q.y <= hsSurfaceY(q.xz))
                    hi = mid;
                else
                    lo = mid;
            }
            return 0.5 * (lo + hi);
        }
        if (t >= t1)
            break;
    }
    return -1.0;
}
