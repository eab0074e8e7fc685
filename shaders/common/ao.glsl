// Ambient occlusion for distance fields (the course task): step along the normal; at height h an
// open surface would read distance h, so h − map() measures nearby geometry. Nearer samples weigh more.
#ifndef AO_RADIUS
#define AO_RADIUS 0.6     // metres probed along the normal
#endif
// The radius probed for a point seen `t` from the eye: a program with detail at every scale (a
// fractal seen in a deep zoom) ties it to the view (fractal/common.glsl); the rest probe AO_RADIUS.
#ifndef AO_RADIUS_AT
#define AO_RADIUS_AT(t) AO_RADIUS
#endif
#ifndef AO_STRENGTH
#define AO_STRENGTH 1.5
#endif

float calcAO(vec3 p, vec3 n, float t)
{
    float occ = 0.0, weight = 1.0, total = 0.0, radius = AO_RADIUS_AT(t);
    for (int i = 1; i <= AO_SAMPLES; i++) {
        float h = radius * float(i) / float(AO_SAMPLES);
        float d = map(p + n * h).x;
        occ += weight * clamp((h - d) / h, 0.0, 1.0);
        total += weight;
        weight *= 0.7;
    }
    return clamp(1.0 - AO_STRENGTH * occ / max(total, 1e-6), 0.0, 1.0);
}
