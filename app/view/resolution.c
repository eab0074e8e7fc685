#include "view/resolution.h"

#include <math.h>

res_controller res_init(float target_fps, float min_scale)
{
    return (res_controller){.target_ms = 1000.0f / target_fps, .min_scale = min_scale, .scale = 1.0f};
}

float res_update(res_controller *c, double frame_ms, double pixels, double window_pixels)
{
    if (!(frame_ms > 0) || !(pixels > 0) || !(window_pixels > 0))
        return c->scale;
    /* the fixed part: what a frame costs however small (HUD, swap, probes): taken as a tenth of the
     * smallest frame seen, at most half the target, so the model never asks for a negative area */
    double fixed = fmin(0.5 * c->target_ms, c->measurements ? fmin(c->fixed_ms, 0.1 * frame_ms) : 0.1 * frame_ms);
    double per_pixel = fmax(frame_ms - fixed, 1e-9) / pixels;
    c->fixed_ms = (float)fixed;
    c->per_pixel_ms = c->measurements ? (float)(RES_SMOOTHING * per_pixel + (1 - RES_SMOOTHING) * c->per_pixel_ms)
                                      : (float)per_pixel;
    c->measurements++;
    double want_pixels = (c->target_ms - fixed) / c->per_pixel_ms;
    float want = (float)fmin(1.0, fmax(c->min_scale, sqrt(want_pixels / window_pixels)));
    if (fabsf(want - c->scale) > RES_HYSTERESIS * c->scale || (want == 1.0f && c->scale != 1.0f && want > c->scale))
        c->scale = want;
    return c->scale;
}

int res_side(int window_side, float scale)
{
    int s = (int)lroundf((float)window_side * scale);
    if (s > 2)
        s &= ~1;
    return s < 1 ? 1 : (s > window_side ? window_side : s);
}
