// Adaptive sampling's stopping rule (app/gpu/render.c, quality.tolerance). From the pixel's own
// sums (target 0: Σx, alpha n, its sample count; target 3: Σx², alpha the samples that passed a
// surface by) a pixel takes another sample while any of these holds:
// - Its mean's standard error, as displayed, is above uTolerance in any pixel of its 3×3 block. The
//   sample variance s² = (Σx² − n·m²)/(n − 1), the error √(s²/n), carried to the display by the tone
//   curve and sRGB encoding (display.frag's) as half the displayed spread of m ± error, so an error in
//   the dark counts as it is seen. Two samples that agree say little about a thread thinner than the
//   pixel, but its neighbours have often seen it.
// - A ray of one of its samples passed a surface or a droplet by within its footprint
//   (common/hit.glsl): something lies in the pixel's cone that its samples missed, and only more
//   samples find its share of the pixel. Such a pixel takes every sample.
// - Its block's means differ by more than the samples it has can resolve: an edge of displayed
//   contrast C is estimated by n stratified samples within about C/n, so the pixel takes
//   C / uEdgeStep samples (uEdgeStep = 2.5 tolerances) before its error may stop it. Two samples that
//   both fell on one side of an edge (a horizon, a hole in a face) agree, and so would their block.
// Against every pixel's 16 samples at 640×360 final (tests/gpu/test_adaptive.c, docs/bench/final.md),
// the error alone left pixels 138–150 levels off (csg, menger, spray: glints on droplets, the thin
// mirror's frame, holes in the sponge's faces); with the three rules the worst is 23 levels.
// A pixel with fewer than two samples (the window's edge mask left it at its centre sample) stays
// stopped. Bands and tiles of an image are rendered with margin rows for the block
// (app/jobs/capture/offline.c), so they agree with the whole image.
uniform sampler2D uAccum;   // target 0: Σ radiance, alpha the pixel's samples
uniform sampler2D uSquares; // target 3: Σ radiance²
uniform float uExposure;
uniform float uTolerance;
uniform ivec2 uSize; // the active image
uniform float uEdgeStep;  // the displayed contrast one sample of an edge resolves
out vec4 oMask;

vec3 shown(vec3 linear) // display.frag's curve: the ACES fit, then sRGB's encoding
{
    vec3 x = max(linear * uExposure, 0.0);
    vec3 t = clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    return mix(12.92 * t, 1.055 * pow(t, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, t));
}

// The displayed standard error of the mean of a pixel with sums `sum` (Σx, n) and squares `sq` (Σx²)
// (0: fewer than two samples).
float displayedError(vec4 sum, vec3 sq)
{
    float n = sum.a;
    if (n < 2.0)
        return 0.0;
    vec3 m = sum.rgb / n;
    vec3 s2 = max(sq - n * m * m, 0.0) / (n - 1.0);
    vec3 e = sqrt(s2 / n);
    vec3 spread = 0.5 * (shown(m + e) - shown(m - e));
    return max(spread.r, max(spread.g, spread.b));
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 own = texelFetch(uAccum, p, 0);
    bool more = texelFetch(uSquares, p, 0).a > 0.0; // passed something by
    vec3 lo = vec3(1e9), hi = vec3(-1e9);
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), uSize - 1);
            vec4 sum = texelFetch(uAccum, q, 0);
            vec3 m = shown(sum.rgb / max(sum.a, 1.0));
            lo = min(lo, m);
            hi = max(hi, m);
            more = more || displayedError(sum, texelFetch(uSquares, q, 0).rgb) > uTolerance;
        }
    vec3 contrast = hi - lo;
    more = more || own.a < max(contrast.r, max(contrast.g, contrast.b)) / uEdgeStep;
    oMask = vec4(own.a >= 2.0 && more ? 1.0 : 0.0);
}
