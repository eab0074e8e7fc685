/* Terrain on the real Jacksboro DEM: both marchers' first hits against an exact ray–bilinear-heightfield
 * intersection in double (tests/lib/terrain_ref.c) for every pixel of five views, a thin ridge that only
 * the exact method never tunnels through, no wall below the floor, and a march out of steps that is no
 * miss. (Generated grids: test_terrain_grids.c; shading, probes and fog: test_terrain_shading.c.) */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <epoxy/gl.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include "check.h"
#include "gltest.h"
#include "data/media/image_io.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "data/geo/terrain.h"
#include "terrain_ref.h"

static void check_views(const char *method, const char *const *sets, int nsets, bool exact, const view *views, int nv)
{
    check_views_in("jacksboro", method, sets, nsets, exact, views, nv);
}

static void maxmip_first_hits(void **st)
{
    (void)st;
    const char *sets[] = {"terrain.method=maxmip", "quality.spp=1", "quality.max_steps=4096"};
    check_views("maxmip", sets, 3, true, VIEWS, 5);
}

static void linear_first_hits(void **st)
{
    (void)st;
    /* the lab's method at the reference preset: steps of a quarter texel, no growth, 12 bisections */
    const char *sets[] = {"terrain.method=linear", "quality.preset=reference", "quality.spp=1", "quality.max_steps=4096"};
    check_views("linear", sets, 4, false, VIEWS + 1, 4); /* grazing rays: see the ridge test */
}

/* An n × n float DEM in a new directory made from dir (a mkdtemp template) as NAME.exr (path[128]), and a
 * terrain scene on it with 1 m texels in json[1024]; more: more of the quality block (", \"k\": v"). */
static void square_dem(char *dir, const char *name, const float *heights, int n, const char *more, char *path,
                       char *json)
{
    assert_non_null(mkdtemp(dir));
    snprintf(path, 128, "%s/%s.exr", dir, name);
    err_t e;
    assert_true(image_write_f32(path, n, n, 1, (const char *const[]){"Y"}, heights, &e));
    snprintf(json, 1024,
             "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"quality\": {\"spp\": 1%s},"
             " \"terrain\": {\"heightmap\": \"%s\", \"spacing\": [1, 1]}}", more, path);
}

/* ---- a thin ridge and grazing rays ------------------------------------------------------------------ */

static void thin_ridge(void **st)
{
    (void)st;
    enum { N = 64 };
    static float heights[N * N];
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++)
            heights[j * N + i] = i == N / 2 ? 10.0f : 0.0f; /* one texel column: a 2-texel-wide tent, 10 m high */
    char dir[] = "/tmp/fathom-ridge-XXXXXX", path[128], json[1024];
    square_dem(dir, "ridge", heights, N, ", \"max_steps\": 1024", path, json);
    /* level rays at 7 m cross the ridge where it is 0.6 texel wide */
    camera cam = cam_at(-30, 7, 0.3, 30, 7, -0.2, 1.0);
    static float aov[W * H * AOV];
    const char *methods[][3] = {{"terrain.method=maxmip", "quality.preset=draft", "maxmip, draft"},
                                {"terrain.method=linear", "quality.preset=reference", "linear, reference"},
                                {"terrain.method=linear", "quality.preset=draft", "linear, draft"}};
    int hit_share[3];
    for (int m = 0; m < 3; m++) {
        scene s;
        const char *sets[] = {methods[m][0], methods[m][1], "quality.spp=1"};
        load_text(json, sets, 3, &s);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int hits = 0;
        for (int i = 0; i < W * H; i++)
            hits += !isinf(aov[i * AOV + 3]) && fabs(aov[i * AOV + 3] - 29.7) < 1.0; /* at the ridge */
        hit_share[m] = 100 * hits / (W * H);
        fprintf(stderr, "ridge, %-18s: %3d %% of level rays stop at the ridge\n", methods[m][2], hit_share[m]);
        scene_free(&s);
    }
    unlink(path);
    rmdir(dir);
    assert_int_equal(hit_share[0], 100); /* exact: never tunnels, at any preset */
    assert_int_equal(hit_share[1], 100); /* quarter-texel steps catch a 0.6-texel ridge */
    assert_true(hit_share[2] < 50);      /* 2-texel steps jump it: the test can fail */
}

/* The terrain is a solid from its lowest height up to the ground. Rays going down reach a little below
 * the lowest height (so ground lying exactly there, a sea clamped flat, is met inside the slab, not
 * decided by rounding at its exit); a ray that enters a side wall in that sliver is under the floor
 * and must miss. Before, it hit the wall 1–2 mm below the floor (a strip along the bottom edge). */
static void no_wall_below_the_floor(void **st)
{
    (void)st;
    enum { N = 64 };
    static float heights[N * N];
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) /* flat at 0 (the minimum) with a 10 m hill in the middle */
            heights[j * N + i] = (float)fmax(0, 10 - 0.5 * hypot(i - N / 2, j - N / 2));
    char dir[] = "/tmp/fathom-floor-XXXXXX", path[128], json[1024];
    square_dem(dir, "floor", heights, N, "", path, json);
    static float aov[W * H * AOV];
    const char *methods[] = {"terrain.method=maxmip", "terrain.method=linear"};
    for (int m = 0; m < 2; m++) {
        scene s;
        const char *sets[] = {methods[m], "quality.spp=1"};
        load_text(json, sets, 2, &s);
        /* from outside the footprint, level with the floor, looking a hair down at the side wall */
        camera cam = cam_at(-20, 0.0005, 31.7, 40, -0.004, 32.2, 20);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int below = 0, hits = 0;
        double lowest = INFINITY;
        for (int row = 0; row < H; row++)
            for (int x = 0; x < W; x++) {
                float t = aov[(row * W + x) * AOV + AOV_SLOT_DEPTH];
                if (isinf(t))
                    continue;
                dray r = pixel_ray(&cam, x, row, W, H);
                double y = r.o[1] + r.d[1] * t;
                hits++;
                lowest = fmin(lowest, y);
                below += y < -1e-5;
            }
        fprintf(stderr, "  %s: %d hits, %d below the floor (lowest at %.3g m)\n", methods[m], hits, below, lowest);
        assert_true(hits > 20); /* the hill and the floor beyond the wall; before the fix 4 more below */
        assert_int_equal(below, 0);
        scene_free(&s);
    }
    unlink(path);
    rmdir(dir);
}

/* ---- running out of steps is not a miss ---------------------------------------------------------------
 * At every preset, from the shipped camera and a grazing one, no pixel may be a miss where a march
 * with a budget a hundred times longer hits: a ray that exhausts its steps near the ground returns
 * its best candidate (flagged by negative steps) instead of the sky. */
/* A ray that runs out of steps is resolved (the tail: common/march.glsl, within its stated tolerance)
 * or flagged, never drawn as a guess: against a march with 100x the steps, every pixel whose hit, miss
 * or depth differs either went into the tail (more steps than max_steps) or is flagged unresolved
 * (negative steps); and the noise terrain, whose horizon ran out of steps by the thousand and showed a
 * false band there, leaves none unresolved at the interactive and final presets. */
static void out_of_steps_is_not_a_miss(void **st)
{
    (void)st;
    static const char *const SCENES[] = {"noise", "jacksboro", "himalaya"};
    static float test[W * H * AOV], longer[W * H * AOV];
    for (size_t k = 0; k < sizeof SCENES / sizeof SCENES[0]; k++)
        for (int p = 0; p < PRESET_COUNT; p++) {
            char preset[64], steps[64];
            snprintf(preset, sizeof preset, "quality.preset=%s", preset_name((quality_preset)p));
            snprintf(steps, sizeof steps, "quality.max_steps=%d", 100 * (int)fmin(preset_quality((quality_preset)p).max_steps, 1000));
            const char *sa[] = {preset, "quality.spp=1"}, *sb[] = {preset, "quality.spp=1", steps};
            scene a, b;
            load_text_file(SCENES[k], sa, 2, &a);
            load_text_file(SCENES[k], sb, 3, &b);
            double eye[3], at[3]; /* grazing: just above the ground at the look-at point, level */
            for (int i = 0; i < 3; i++)
                eye[i] = a.cam_position[i], at[i] = a.cam_look_at[i];
            camera cams[2] = {camera_look_at_deg(eye, at, a.cam_fov_deg)};
            at[1] = eye[1] = (float)(a.cam_position[1] * 0.25 + a.cam_look_at[1] * 0.75);
            cams[1] = camera_look_at_deg(eye, at, a.cam_fov_deg);
            int silent = 0, flagged = 0, differ = 0, tail = 0;
            for (int c = 0; c < 2; c++) {
                draw(&a, &cams[c], W, H, 1, NULL, test, NULL);
                draw(&b, &cams[c], W, H, 1, NULL, longer, NULL);
                for (int i = 0; i < W * H; i++) {
                    float za = test[i * AOV + AOV_SLOT_DEPTH], zb = longer[i * AOV + AOV_SLOT_DEPTH];
                    float used = test[i * AOV + AOV_SLOT_STEPS];
                    bool unresolved = used < 0, tailed = used > (float)a.quality.max_steps;
                    bool differs = isinf(za) != isinf(zb) || (!isinf(za) && fabsf(za - zb) > 0.01f * zb);
                    flagged += unresolved;
                    tail += tailed;
                    differ += differs;
                    silent += differs && !unresolved && !tailed;
                }
            }
            fprintf(stderr, "%s %s: %d rays went on past max_steps, %d were left unresolved; %d pixels differ from "
                    "100x the steps, %d of them neither\n", SCENES[k], preset_name((quality_preset)p), tail, flagged,
                    differ, silent);
            assert_int_equal(silent, 0);
            if (k == 0 && (p == PRESET_INTERACTIVE || p == PRESET_FINAL))
                assert_int_equal(flagged, 0);
            scene_free(&a);
            scene_free(&b);
        }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(maxmip_first_hits),
        cmocka_unit_test(linear_first_hits),
        cmocka_unit_test(thin_ridge),
        cmocka_unit_test(no_wall_below_the_floor),
        cmocka_unit_test(out_of_steps_is_not_a_miss),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='far*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
