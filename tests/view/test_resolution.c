/* The window's resolution controller against simulated frame times (cost = fixed + per-pixel ·
 * pixels, with noise): it settles where frames meet the target, does not oscillate under noise,
 * follows a scene that gets slower or faster, and keeps the limits. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>

#include "view/resolution.h"

enum { WW = 1280, WH = 720 };

static double noise(unsigned *seed, double amplitude)
{
    *seed = *seed * 1664525u + 1013904223u;
    return amplitude * (2.0 * ((*seed >> 8) / 16777216.0) - 1.0);
}

typedef struct run {
    double final_ms; /* median-ish: the mean of the last 20 frame times */
    int changes_after_settling;
    float scale;
} run;

/* frames of a scene costing fixed + ns_per_pixel · pixels, ±noise relative */
static run simulate(res_controller *c, int frames, double fixed, double ns_per_pixel, double rel_noise, unsigned seed)
{
    run r = {0};
    double sum = 0;
    float last = c->scale;
    for (int i = 0; i < frames; i++) {
        int w = res_side(WW, c->scale), h = res_side(WH, c->scale);
        double ms = (fixed + ns_per_pixel * 1e-6 * w * h) * (1 + noise(&seed, rel_noise));
        res_update(c, ms, (double)w * h, (double)WW * WH);
        if (i >= frames - 20)
            sum += ms;
        if (i >= 15 && c->scale != last)
            r.changes_after_settling++;
        last = c->scale;
    }
    r.final_ms = sum / 20;
    r.scale = c->scale;
    return r;
}

static void settles_on_the_target(void **st)
{
    (void)st;
    /* llvmpipe-like: 1280x720 costs 1.2 s; a GPU-like one costs 4 ms; one in between */
    static const double COST_NS[] = {1300.0, 4.0, 60.0};
    for (int k = 0; k < 3; k++) {
        res_controller c = res_init(30, 0.125f);
        run r = simulate(&c, 120, 3.0, COST_NS[k], 0.15, 7u + (unsigned)k);
        fprintf(stderr, "  %6.0f ns/px: scale %.3f, last 20 frames %.1f ms (target %.1f), %d changes after settling\n",
                COST_NS[k], (double)r.scale, r.final_ms, (double)c.target_ms, r.changes_after_settling);
        if (k == 1) { /* fast enough at full size: stays at 1 */
            assert_true(r.scale == 1.0f);
            continue;
        }
        assert_true(fabs(r.final_ms - c.target_ms) < 0.2 * c.target_ms);
        assert_true(r.changes_after_settling <= 3); /* ±15 % noise must not make it breathe */
    }
}

static void follows_a_changing_scene_and_keeps_limits(void **st)
{
    (void)st;
    res_controller c = res_init(30, 0.125f);
    simulate(&c, 60, 3.0, 1300.0, 0.05, 1);
    float slow = c.scale;
    simulate(&c, 60, 3.0, 300.0, 0.05, 2); /* the view turned to sky: cheaper pixels */
    assert_true(c.scale > 1.5f * slow);
    run r = simulate(&c, 60, 3.0, 1e6, 0.05, 3); /* hopeless: the floor holds */
    assert_true(r.scale == 0.125f);
    assert_int_equal(res_side(WW, 0.125f), 160);
    assert_int_equal(res_side(3, 0.01f), 1);
    /* nonsense measurements change nothing */
    float before = c.scale;
    res_update(&c, NAN, 100, 100);
    res_update(&c, -1, 100, 100);
    res_update(&c, 10, 0, 100);
    assert_true(c.scale == before);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(settles_on_the_target),
        cmocka_unit_test(follows_a_changing_scene_and_keeps_limits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
