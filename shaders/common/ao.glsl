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

// The nearest probe stays AO_FLOOR_K float steps of the position off the surface (common/march.glsl's
// positionFloor): nearer, map() there measures the hit's own rounding, not geometry. Far from the origin
// (the Himalaya 640 km out: 0.4 m a step) a 0.12 m probe read noise as full occlusion: black speckles
// along sunless slopes, different pixels on every driver (4 "dashes" on an NVIDIA H100, 0-6 here as
// the camera moved by 0.3 m).
#ifndef AO_FLOOR_K
#define AO_FLOOR_K 16.0
#endif

float calcAO(vec3 p, vec3 n, float t)
{
    float occ = 0.0, weight = 1.0, total = 0.0;
    float radius = max(AO_RADIUS_AT(t), AO_FLOOR_K * float(AO_SAMPLES) * positionFloor(t));
    for (int i = 1; i <= AO_SAMPLES; i++) {
        float h = radius * float(i) / float(AO_SAMPLES);
        float d = map(p + n * h).x;
        occ += weight * clamp((h - d) / h, 0.0, 1.0);
        total += weight;
        weight *= 0.7;
    }
    return clamp(1.0 - AO_STRENGTH * occ / max(total, 1e-6), 0.0, 1.0);
}
