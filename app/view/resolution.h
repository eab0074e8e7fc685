/* resolution — dynamic resolution for the window while it moves: picks the internal scale (a fraction
 * of the window's side) each frame so frames take about the target time. Pure C.
 *
 * Model: a frame costs fixed + per_pixel · pixels. Each measurement updates per_pixel (an exponential
 * average, so one slow frame does not halve the image), and the scale is the one the model says meets
 * the target, with hysteresis: it changes only when the new one differs by more than RES_HYSTERESIS, so
 * the image does not breathe from frame to frame under noise. Scale in [min_scale, 1].
 */
#ifndef FATHOM_RESOLUTION_H
#define FATHOM_RESOLUTION_H

#define RES_HYSTERESIS 0.08f /* relative change of the scale below which it stays */
#define RES_SMOOTHING 0.3f   /* weight of the newest measurement in the per-pixel cost */
#define RES_MIN_SCALE 0.0625f /* the window and bench --interactive: at least 1/16 of the side (80x45 of 720p) */

typedef struct res_controller {
    float target_ms;  /* frame time to aim for (1000 / fps) */
    float min_scale;  /* never fewer pixels than this (e.g. 1/8 of the side) */
    float scale;      /* current: internal side = window side × scale */
    float per_pixel_ms, fixed_ms;
    int measurements;
} res_controller;

res_controller res_init(float target_fps, float min_scale);

/* Feeds the time of a frame rendered at `pixels` pixels (at the current scale) of a window of
 * `window_pixels`; returns the scale for the next frame. */
float res_update(res_controller *c, double frame_ms, double pixels, double window_pixels);

/* The internal size for a window side at scale (at least 1 pixel, even where possible). */
int res_side(int window_side, float scale);

#endif
