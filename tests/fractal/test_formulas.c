/* Every shipped formula draws its view with the set in view, the set at every range end drawn with its
 * bound equals the set drawn with a bound 4 times larger, and a user's formula in a temporary folder
 * draws, reloads and fails naming its own file and line. */
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

#include "check.h"
#include "gltest.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "jobs/check/check.h"

/* ---- formulas as data: every shipped formula draws; a user's file is one file and no C ----------- */

/* Every formula fathom finds draws its shipped view with no NaN, and the set is in the picture (at
 * least 2 % of the pixels hit it), at two presets. */
static void every_formula_draws(void **st)
{
    (void)st;
    strbuf names = {0};
    formula_list(&names);
    int count = 0;
    static float aov[W * H * AOV], rgba[W * H * 4];
    for (char *name = names.data, *nl; name && *name; name = nl + 1) {
        nl = strchr(name, '\n');
        *nl = '\0';
        for (int preset = 0; preset < 2; preset++) {
            scene s;
            err_t e;
            const char *sets[] = {preset ? "quality.preset=final" : "quality.preset=draft", "quality.spp=1"};
            if (!scene_load(name, sets, 2, &s, &e))
                fail_msg("formula %s: its scene: %s", name, e.msg);
            assert_true(program_is_fractal(s.program));
            assert_string_equal(s.fractal.formula.name, name);
            camera cam = camera_look_at_deg(s.cam_position, s.cam_look_at, s.cam_fov_deg);
            draw(&s, &cam, W, H, 1, NULL, aov, rgba);
            check_finite(name, aov, rgba, W * H);
            int hits = 0;
            for (int i = 0; i < W * H; i++)
                hits += isfinite(aov[i * AOV + AOV_SLOT_DEPTH]);
            if (hits < W * H / 50)
                fail_msg("formula %s: its view shows %d pixels of the set", name, hits);
            scene_free(&s);
        }
        count++;
    }
    sb_free(&names);
    fprintf(stderr, "  %d formulas draw their views\n", count);
    assert_true(count >= 12);
}

/* Whether the set itself (an estimate below 1e-5 of the bound: inside) lies within 4 hit thresholds
 * behind a hit at depth z along r: a hit on the set, not a loose estimate's halo where there is none. */
static bool set_behind(const scene *s, const dray *r, double z, double eps)
{
    enum { N = 128 };
    float pts[N * 3], d[N * 2];
    for (int i = 0; i < N; i++)
        for (int k = 0; k < 3; k++)
            pts[i * 3 + k] = (float)(r->o[k] + (z + 4 * eps * i / (N - 1)) * r->d[k]);
    gl_probe(s, NULL, pts, N, d);
    for (int i = 0; i < N; i++)
        if (d[2 * i] < 1e-5 * s->fractal.bound_radius)
            return true;
    return false;
}

/* A slider is a promise: at every range end of every shipped formula (check_corners), the set drawn
 * with the formula's own bounding sphere is the set drawn with a sphere 4 times as large, from a camera
 * that frames the bound (the hit pixels' intersection over union). A bound that clips the set at some
 * value its ranges allow (the Mandelbox's at fold_limit 2 drew a ball: 0.40) fails here. */
static void range_ends_draw_the_whole_set(void **st)
{
    (void)st;
    enum { CW = 64, CH = 40 };
    static float aov[CW * CH * AOV], wide_aov[CW * CH * AOV];
    strbuf names = {0};
    formula_list(&names);
    int sets = 0, cuts = 0;
    double worst = 1;
    char worst_at[200] = "";
    for (char *name = strtok(names.data, "\n"); name; name = strtok(NULL, "\n")) {
        if (!strncmp(name, "note:", 5))
            continue;
        formula f;
        err_t e;
        if (!formula_load(name, NULL, &f, &e))
            fail_msg("%s", e.msg);
        char corners[CHECK_CORNERS_MAX][CHECK_SET_MAX], formula_set[96];
        int n = check_corners(&f, &(check_desc){0}, corners, CHECK_CORNERS_MAX);
        snprintf(formula_set, sizeof formula_set, "fractal.formula=%s", name);
        double formula_worst = 1;
        for (int k = -1; k < n; k++) { /* the defaults, then each end */
            const char *over[] = {formula_set, "quality.preset=interactive", "quality.spp=1", k < 0 ? "quality.spp=1" : corners[k]};
            scene s;
            if (!scene_load("fractal", over, 4, &s, &e)) {
                if (!strstr(e.msg, "(formula ")) /* only a @require may refuse an end */
                    fail_msg("%s %s: %s", name, k < 0 ? "" : corners[k], e.msg);
                continue;
            }
            double R = s.fractal.bound_radius, eye[3] = {0.55 * 2.6 * R, 0.42 * 2.6 * R, 0.72 * 2.6 * R}, at[3] = {0, 0, 0};
            camera cam = camera_look_at_deg(eye, at, 45);
            draw(&s, &cam, CW, CH, 1, NULL, aov, NULL);
            scene wide = s;
            wide.fractal.bound_radius = (float)(4 * R);
            draw(&wide, &cam, CW, CH, 1, NULL, wide_aov, NULL);
            /* what a bound cuts: the pixels only the wide sphere's image hits, at a point past the bound
             * and the margin beyond it where map() still gives the estimate (fractal/common.glsl: 0.1, or
             * 4 hit thresholds), with the set itself behind the hit. A silhouette's pixel may go either
             * way, the two marches starting from different spheres, and a loose estimate far out of its
             * bound may draw a halo where there is no set (the Amazing Surf at scale 1.05): neither is
             * a cut. */
            int both = 0, either = 0, cut = 0;
            for (int i = 0; i < CW * CH; i++) {
                float za = aov[i * AOV + AOV_SLOT_DEPTH], zb = wide_aov[i * AOV + AOV_SLOT_DEPTH];
                bool a = isfinite(za), b = isfinite(zb);
                both += a && b, either += a || b;
                if (b && !a) {
                    dray r = pixel_ray(&cam, i % CW, i / CW, CW, CH);
                    double q[3] = {r.o[0] + zb * r.d[0], r.o[1] + zb * r.d[1], r.o[2] + zb * r.d[2]};
                    double eps = s.quality.hit_k * camera_pixel_angle(&cam, CH) * zb, margin = fmax(0.1, 4 * eps);
                    cut += sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) > R + margin && set_behind(&wide, &r, zb, eps);
                }
            }
            double iou = either ? (double)both / either : 1;
            if (iou < formula_worst)
                formula_worst = iou;
            if (iou < worst) {
                worst = iou;
                snprintf(worst_at, sizeof worst_at, "%s %s", name, k < 0 ? "(defaults)" : corners[k]);
            }
            if (iou < 0.97 || cut)
                fprintf(stderr, "    %s %s: IoU %.4f (%d of %d pixels hit either), %d cut off\n", name,
                        k < 0 ? "(defaults)" : corners[k], iou, either, CW * CH, cut);
            cuts += cut;
            sets++;
            scene_free(&s);
        }
        fprintf(stderr, "  %-22s %2d range ends: the set within its bound against 4 times it, IoU at worst %.4f\n", name, n,
                formula_worst);
    }
    sb_free(&names);
    fprintf(stderr, "  %d parameter sets; the worst IoU %.4f (%s); %d pixels cut off\n", sets, worst, worst_at, cuts);
    assert_true(sets > 100);
    assert_int_equal(cuts, 0);
    if (worst < 0.95)
        fail_msg("%s: the bound clips the set (IoU %.4f)", worst_at, worst);
}

static char user_dir[] = "/tmp/fathom-formulas-XXXXXX";

/* A sphere as a user's formula (in $FATHOM_FORMULAS, found by name, no rebuild): the first hit of the
 * centre pixel is where the sphere of the declared radius is, and --set of the radius moves it. Then
 * the file is broken: the reload fails naming the file and line, and the last good program draws. */
static void user_formula(void **st)
{
    (void)st;
    assert_non_null(mkdtemp(user_dir));
    setenv("FATHOM_FORMULAS", user_dir, 1);
    char path[256];
    snprintf(path, sizeof path, "%s/ball.glsl", user_dir);
    static const char BALL[] =
        "// @formula A ball (a test's own formula)\n"
        "// @iterations 1 [1, 1]\n"
        "// @bound radius\n"
        "#include \"fractal/common.glsl\"\n"
        "uniform float uRadius; // @param 0.5 [0.1, 2] the ball's radius\n"
        "real formulaDE(real3 p, out float trap) { trap = 0.0; return length(p) - uRadius; }\n";
    write_text(path, BALL);
    static float aov[W * H * AOV], rgba[W * H * 4];
    camera cam = cam_at(0, 0, 3, 0, 0, 0, 40);
    const float radii[] = {0.5f, 1.25f};
    for (int k = 0; k < 2; k++) {
        scene s;
        char set[64];
        snprintf(set, sizeof set, "fractal.radius=%g", (double)radii[k]);
        const char *sets[] = {set};
        load_text("{\"program\": \"ball\", \"environment\": {\"intensity\": 0.5}, \"quality\": {\"preset\": \"final\"}}",
                  sets, 1, &s);
        assert_near(s.fractal.bound_radius, radii[k], 0);
        draw(&s, &cam, W, H, 1, NULL, aov, rgba);
        float depth = aov[((H / 2) * W + W / 2) * AOV + AOV_SLOT_DEPTH];
        assert_near(depth, 3.0 - radii[k], 1e-3);
        scene_free(&s);
    }
    /* broken on disk: the reload names the user's file and line and keeps the last good program */
    scene s;
    load_text("{\"program\": \"ball\", \"environment\": {\"intensity\": 0.5}}", NULL, 0, &s);
    draw(&s, &cam, W, H, 1, NULL, aov, rgba);
    char broken[sizeof BALL + 64];
    snprintf(broken, sizeof broken, "%s", BALL);
    char *line6 = strstr(broken, "real formulaDE");
    static const char BROKEN[] = "real formulaDE(real3 p, out float trap) { return undeclared; }\n";
    memcpy(line6, BROKEN, sizeof BROKEN); /* with its NUL */
    write_text(path, broken);
    err_t e;
    assert_false(render_reload(&e));
    char want[300];
    snprintf(want, sizeof want, "%s:6:", path);
    if (!strstr(e.msg, want))
        fail_msg("the reload's error '%.300s' does not point at %s", e.msg, want);
    camera c2 = cam;
    render_begin(&c2);
    render_sample();
    float again[W * H * AOV];
    render_read_aovs(again);
    assert_near(again[((H / 2) * W + W / 2) * AOV + AOV_SLOT_DEPTH], 2.5, 1e-3);
    scene_free(&s);
    assert_int_equal(remove_tree(user_dir), 0);
    unsetenv("FATHOM_FORMULAS");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_formula_draws),
        cmocka_unit_test(range_ends_draw_the_whole_set),
        cmocka_unit_test(user_formula),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='far*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
