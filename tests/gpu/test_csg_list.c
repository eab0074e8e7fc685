/* The csg program's primitive list (shaders/csg/list.glsl behind app/data/droplets/bvh.c): map() from the list is
 * the same function as map() compiled as code, and for 10,000 spheres the exact distance to the
 * nearest one (brute force in double); such a scene compiles and renders within this test's timeout. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "gltest.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"

static double frand(unsigned *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (*seed >> 8) / 16777216.0;
}

static const char *const SHAPE_JSON[] = {
    "\"shape\": \"sphere\", \"radius\": %.3f",
    "\"shape\": \"box\", \"size\": [%.3f, 0.3, 0.5]",
    "\"shape\": \"round_box\", \"size\": [%.3f, 0.4, 0.5], \"radius\": 0.04",
    "\"shape\": \"torus\", \"major\": %.3f, \"minor\": 0.06",
    "\"shape\": \"cylinder\", \"radius\": %.3f, \"height\": 0.5",
    "\"shape\": \"capsule\", \"radius\": %.3f, \"height\": 0.4",
    "\"shape\": \"cone\", \"radius_bottom\": %.3f, \"radius_top\": 0.05, \"height\": 0.6",
};

/* n primitives of every kind, rotated, in a 4 m cube: JSON nodes "{...}, {...}". */
static void mixed(strbuf *out, int n, unsigned seed)
{
    for (int i = 0; i < n; i++) {
        int kind = i % 7;
        sb_printf(out, "%s{", i ? ", " : "");
        sb_printf(out, SHAPE_JSON[kind], 0.1 + 0.3 * frand(&seed));
        sb_printf(out, ", \"position\": [%.3f, %.3f, %.3f], \"rotation\": [%.1f, %.1f, %.1f], \"material\": \"%s\"}",
                  4 * frand(&seed) - 2, 4 * frand(&seed) - 2, 4 * frand(&seed) - 2, 360 * frand(&seed) - 180,
                  360 * frand(&seed) - 180, 360 * frand(&seed) - 180, i % 2 ? "a" : "b");
    }
}

static void probe(const scene *s, const float *pts, int n, float *out)
{
    err_t e;
    if (!render_set_scene(s, NULL, &e) || !render_probe(s, NULL, pts, n, out, &e))
        fail_msg("%s", e.msg);
}

/* The same 64 primitives as a list (top level) and as code (a union moved by zero is not plain). */
static void list_equals_code(void **st)
{
    (void)st;
    enum { N = 64, P = 4096 };
    static const char HEAD[] = "{\"program\": \"csg\", \"materials\": {\"a\": {}, \"b\": {}}, \"objects\": ";
    strbuf as_list = {0}, as_code = {0};
    sb_printf(&as_list, "%s[", HEAD);
    mixed(&as_list, N, 7);
    sb_append(&as_list, "]}");
    sb_printf(&as_code, "%s[{\"op\": \"union\", \"position\": [0, 0, 0], \"children\": [", HEAD);
    mixed(&as_code, N, 7);
    sb_append(&as_code, "]}]}");
    scene a, b;
    load_text(as_list.data, NULL, 0, &a);
    load_text(as_code.data, NULL, 0, &b);
    assert_int_equal(a.csg_list_count, N);
    assert_int_equal(b.csg_list_count, 0);
    static float pts[P * 3], da[P * 2], db[P * 2];
    unsigned seed = 99;
    for (int i = 0; i < P * 3; i++)
        pts[i] = (float)(6 * frand(&seed) - 3);
    probe(&a, pts, P, da);
    probe(&b, pts, P, db);
    double worst = 0;
    int material_differs = 0;
    for (int i = 0; i < P; i++) {
        worst = fmax(worst, fabs((double)da[2 * i] - db[2 * i]));
        material_differs += da[2 * i + 1] != db[2 * i + 1];
    }
    fprintf(stderr, "  list vs code, %d points: worst distance difference %.3g m, %d materials differ\n", P, worst,
            material_differs);
    assert_true(worst <= 1e-5);
    assert_true(material_differs <= 2); /* exact ties between two primitives only */
    scene_free(&a);
    scene_free(&b);
    sb_free(&as_list);
    sb_free(&as_code);
}

/* 10,000 spheres of random sizes: the list's distance is the exact nearest-sphere distance. */
static void ten_thousand_spheres_exact(void **st)
{
    (void)st;
    enum { N = 10000, P = 8192 };
    static double c[N][4];
    strbuf j = {0};
    sb_append(&j, "{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"quality\": {\"preset\": \"final\"},"
                  " \"camera\": {\"position\": [0, 0, 60], \"look_at\": [0, 0, 0]}, \"objects\": [");
    unsigned seed = 5;
    for (int i = 0; i < N; i++) {
        for (int a = 0; a < 3; a++)
            c[i][a] = round((40 * frand(&seed) - 20) * 1000) / 1000;
        c[i][3] = round((0.02 + 0.4 * frand(&seed) * frand(&seed)) * 1000) / 1000;
        sb_printf(&j, "%s{\"shape\": \"sphere\", \"radius\": %.3f, \"position\": [%.3f, %.3f, %.3f], \"material\": \"a\"}",
                  i ? ", " : "", c[i][3], c[i][0], c[i][1], c[i][2]);
    }
    sb_append(&j, "]}");
    double t0 = util_now();
    scene s;
    load_text(j.data, NULL, 0, &s);
    double t1 = util_now();
    static float pts[P * 3], d[P * 2];
    for (int i = 0; i < P * 3; i++)
        pts[i] = (float)(50 * frand(&seed) - 25);
    probe(&s, pts, P, d);
    double t2 = util_now();
    double worst = 0;
    for (int i = 0; i < P; i++) {
        double best = INFINITY;
        for (int k = 0; k < N; k++) {
            double dx = pts[3 * i] - c[k][0], dy = pts[3 * i + 1] - c[k][1], dz = pts[3 * i + 2] - c[k][2];
            best = fmin(best, sqrt(dx * dx + dy * dy + dz * dz) - c[k][3]);
        }
        worst = fmax(worst, fabs(best - d[2 * i]) / fmax(1.0, fabs(best)));
    }
    /* and a picture of it: many hits, nothing non-finite */
    enum { RW = 160, RH = 90 };
    static float aov[RW * RH * AOV], rgba[RW * RH * 4];
    camera cam = cam_at(0, 0, 60, 0, 0, 0, 40);
    draw(&s, &cam, RW, RH, 1, NULL, aov, rgba);
    double t3 = util_now();
    check_finite("10,000 spheres", aov, rgba, RW * RH);
    /* the hit mask against ray–sphere intersection in double: only pixels on a true edge may differ */
    static bool ref[RW * RH];
    for (int y = 0; y < RH; y++)
        for (int x = 0; x < RW; x++) {
            dray r = pixel_ray(&cam, x, y, RW, RH);
            bool hit = false;
            for (int k = 0; k < N && !hit; k++) {
                double o[3] = {r.o[0] - c[k][0], r.o[1] - c[k][1], r.o[2] - c[k][2]};
                double b = o[0] * r.d[0] + o[1] * r.d[1] + o[2] * r.d[2];
                double cc = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - c[k][3] * c[k][3];
                hit = b * b - cc >= 0 && -b + sqrt(b * b - cc) > 0;
            }
            ref[y * RW + x] = hit;
        }
    int hits = 0, wrong = 0, edge = 0;
    for (int y = 0; y < RH; y++)
        for (int x = 0; x < RW; x++) {
            bool got = isfinite(aov[(y * RW + x) * AOV + AOV_SLOT_DEPTH]), want = ref[y * RW + x];
            hits += want;
            if (got == want)
                continue;
            bool on_edge = false; /* the reference changes within a pixel of here */
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int xx = x + dx, yy = y + dy;
                    on_edge |= xx >= 0 && yy >= 0 && xx < RW && yy < RH && ref[yy * RW + xx] != want;
                }
            edge += on_edge;
            wrong += !on_edge;
        }
    fprintf(stderr, "  10,000 spheres: parse %.2f s, compile + probe %.2f s, render %dx%d %.2f s; worst distance "
                    "error %.2g (relative); %d pixels hit, %d differ on an edge, %d elsewhere\n", t1 - t0, t2 - t1,
            RW, RH, t3 - t2, worst, hits, edge, wrong);
    assert_true(worst < 1e-5);
    assert_true(hits > 1000);
    assert_int_equal(wrong, 0);
    assert_true(edge < hits / 50);
    scene_free(&s);
    sb_free(&j);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(list_equals_code),
        cmocka_unit_test(ten_thousand_spheres_exact),
    };
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
