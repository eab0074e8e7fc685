// Adaptive sampling's stopping rule (app/gpu/render.c, quality.tolerance): a pixel takes further
// samples while the standard error of its mean, as it is displayed, is above uTolerance. The sums of
// the pixel's own samples give it: target 0 holds Σx (alpha: n, the pixel's sample count), target 3
// Σx²; the sample variance s² = (Σx² − n·m²)/(n − 1) and the mean's standard error √(s²/n). The error
// is carried to the display by the tone curve and sRGB encoding (display.frag's), as half the
// displayed spread of m ± error, so an error in the dark counts as it is seen. A pixel with fewer than
// two samples (the window's edge mask left it at its centre sample) stays stopped. A pixel goes on
// while any pixel of its 3×3 block is above the tolerance: two samples that agree say little about a
// thread thinner than the pixel that a third may find, but its neighbours have often seen it (the
// Mandelbulb at 240×135, tolerance 0.008, tests/gpu/test_gl.c: RMSE to every pixel's 16 samples 0.0126
// alone, 0.0007 with the block, at 3.9 and 7.0 samples a pixel). Bands and tiles of an image are
// rendered with margin rows for it (app/jobs/capture/offline.c), so they agree with the whole image.
uniform sampler2D uAccum;   // target 0: Σ radiance, alpha the pixel's samples
uniform sampler2D uSquares; // target 3: Σ radiance²
uniform float uExposure;
uniform float uTolerance;
uniform ivec2 uSize; // the active image
out vec4 oMask;

vec3 shown(vec3 linear) // display.frag's curve: the ACES fit, then sRGB's encoding
{
    vec3 x = max(linear * uExposure, 0.0);
    vec3 t = clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    return mix(12.92 * t, 1.055 * pow(t, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, t));
}

// The displayed standard error of pixel p's mean (0: fewer than two samples).
float displayedError(ivec2 p)
{
    vec4 sum = texelFetch(uAccum, p, 0);
    float n = sum.a;
    if (n < 2.0)
        return 0.0;
    vec3 m = sum.rgb / n;
    vec3 s2 = max(texelFetch(uSquares, p, 0).rgb - n * m * m, 0.0) / (n - 1.0);
    vec3 e = sqrt(s2 / n);
    vec3 spread = 0.5 * (shown(m + e) - shown(m - e));
    return max(spread.r, max(spread.g, spread.b));
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    bool more = false;
    if (texelFetch(uAccum, p, 0).a >= 2.0)
        for (int dy = -1; dy <= 1 && !more; dy++)
            for (int dx = -1; dx <= 1 && !more; dx++)
                more = displayedError(clamp(p + ivec2(dx, dy), ivec2(0), uSize - 1)) > uTolerance;
    oMask = vec4(more ? 1.0 : 0.0);
}
