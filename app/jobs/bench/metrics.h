/* metrics — how far a render is from a reference render of the same view. Pure.
 *
 * Colour: RMSE and PSNR of the display colour (8-bit sRGB after tone mapping, scaled to 0..1: what a
 * person sees). Depth: over pixels both renders hit, the error in pixel footprints,
 * |t − t_ref| / (t_ref · pixel angle), mean and max. Flips: share of pixels that hit in one render
 * and miss in the other; silhouettes: IoU of the two hit masks, and how far the edge moved: over
 * flipped pixels, the largest distance (pixels) to the nearest reference pixel that agrees with the
 * test there (a silhouette one pixel too fat gives 1). Edges: the colour RMSE over the reference's
 * silhouette pixels alone (a 4-neighbour misses where it hits, or lies 5 % nearer or farther), where
 * anti-aliasing shows. Steps: mean primary-ray march steps of the render under test, and the share of
 * its pixels that ran out of steps (negative steps AOV).
 */
#ifndef FATHOM_METRICS_H
#define FATHOM_METRICS_H

#include <stdbool.h>
#include <stdint.h>

typedef struct image_view {
    int width, height;
    const uint8_t *srgb; /* RGBA 8-bit, rows top first */
    const float *aov;    /* AOV_FLOATS a pixel (view/aov.h): depth at [3] (+inf on a miss), steps at [4] */
    double footprint_t0; /* the reference's: a pixel is pixel_angle · (depth + this) wide (camera.h) */
} image_view;

typedef struct metrics {
    double rmse, psnr_db; /* psnr: +inf when identical */
    double depth_mean_fp, depth_max_fp;
    double flip_share;
    double iou;          /* hit masks: |both| / |either| (1 when neither hits anything) */
    double edge_max_px;  /* how far the edge moved (pixels; 0: no flip) */
    double edge_rmse;    /* colour RMSE over the reference's silhouette pixels (0 when it has none) */
    int edge_pixels;
    double mean_steps;
    double exhausted_share; /* pixels of the test render whose primary ray was left unresolved */
    int depth_pixels; /* pixels both hit */
} metrics;

/* Compares test with ref (same size). pixel_angle: of the reference camera at this height. */
metrics metrics_compare(const image_view *test, const image_view *ref, double pixel_angle);

/* Resizes an 8-bit RGBA image (bilinear) and an AOV image (nearest) to w × h, for a render made at a
 * lower resolution scale. Outputs are malloc'd. */
void metrics_upscale(const image_view *in, int w, int h, uint8_t **srgb, float **aov);

/* The median of n timings and a distribution-free interval that holds the true median with at least
 * 95 % confidence where n allows: order statistics [x(k), x(n+1-k)] for the largest k with
 * 2 P(Bin(n, 1/2) <= k - 1) <= 0.05. Below n = 6 no k qualifies and the interval is [min, max] (94 %
 * confidence at n = 5, 88 % at 4). Two settings differ measurably only where their intervals part. */
double metrics_median_interval(const double *v, int n, double *lo, double *hi);

/* Marks the points on the lower-left Pareto front of (time, error), each time an interval [lo, hi]
 * (metrics_median_interval): a point leaves the front for another that is measurably faster (its hi
 * below this lo) and no worse, or better and not measurably slower (its lo at most this hi). Noise
 * alone never puts a worse setting on the front: with point times (lo = hi) it is the usual front. */
void metrics_pareto(const double *lo, const double *hi, const double *error, int n, bool *front);

#endif
