/* Lakes from a DEM (data/geo/water.h) against a brute force that shares only the definition: every
 * cell's spill height found by relaxation (Planchon & Darboux 2001's fixed point: W = the ground on cells
 * that drain, +inf elsewhere, then W(c) = max(ground(c), min W over the 8 neighbours) until nothing
 * changes), no queue, no order. Then closed forms: a bowl's lake stands at its notch, two basins under
 * one rim are one lake, a basin open to the edge or to nodata holds nothing; the thresholds. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "data/geo/geo.h"
#include "data/geo/water.h"

static bool is_drain(const float *g, int w, int h, int i, int j)
{
    if (i == 0 || j == 0 || i == w - 1 || j == h - 1)
        return true;
    for (int b = -1; b <= 1; b++)
        for (int a = -1; a <= 1; a++)
            if (isnan(g[(j + b) * w + i + a]))
                return true;
    return false;
}

/* The spill heights by relaxation; NaN where dry (not raised) or nodata. */
static void brute(const float *g, int w, int h, float *out)
{
    int n = w * h;
    double *W = malloc((size_t)n * sizeof *W);
    for (int c = 0; c < n; c++)
        W[c] = isnan(g[c]) ? NAN : is_drain(g, w, h, c % w, c / w) ? g[c] : INFINITY;
    for (bool changed = true; changed;) {
        changed = false;
        for (int c = 0; c < n; c++) {
            if (isnan(W[c]) || is_drain(g, w, h, c % w, c / w))
                continue;
            double lo = INFINITY;
            for (int b = -1; b <= 1; b++)
                for (int a = -1; a <= 1; a++)
                    if ((a || b) && !isnan(W[c + b * w + a]))
                        lo = fmin(lo, W[c + b * w + a]);
            double v = fmax(g[c], lo);
            if (v < W[c]) {
                W[c] = v;
                changed = true;
            }
        }
    }
    for (int c = 0; c < n; c++)
        out[c] = !isnan(W[c]) && W[c] > g[c] ? (float)W[c] : NAN;
    free(W);
}

static uint32_t rng = 7;
static uint32_t next(void) { return rng = rng * 1664525u + 1013904223u; }

static water_fill_stats fill(const float *g, int w, int h, double depth, double area, float *out)
{
    water_fill_desc d = {.ground = g, .w = w, .h = h, .dx = 2, .dz = 3, .min_depth = depth, .min_area = area};
    water_fill_stats st;
    err_t err = {0};
    assert_true(water_fill(&d, out, &st, &err));
    return st;
}

/* Random grids, 1 × 1 to 40 × 40: integer heights 0-9 (flats and ties everywhere) or floats, a tenth nodata
 * or none: every cell equal to the relaxation's, wet or dry. */
static void test_random_against_brute_force(void **state)
{
    (void)state;
    long wet = 0;
    for (int trial = 0; trial < 400; trial++) {
        int w = 1 + (int)(next() >> 8) % 40, h = 1 + (int)(next() >> 8) % 40;
        float *g = malloc((size_t)(w * h) * sizeof *g), *a = malloc((size_t)(w * h) * sizeof *a),
              *b = malloc((size_t)(w * h) * sizeof *b);
        bool ints = trial % 2, holes = trial % 3 == 0;
        for (int c = 0; c < w * h; c++) {
            g[c] = ints ? (float)((next() >> 8) % 10) : (float)(next() >> 8) / 16777216.0f * 100.0f;
            if (holes && (next() >> 8) % 10 == 0)
                g[c] = NAN;
        }
        fill(g, w, h, 0, 0, a);
        brute(g, w, h, b);
        for (int c = 0; c < w * h; c++) {
            if (isnan(a[c]) != isnan(b[c]) || (!isnan(a[c]) && a[c] != b[c]))
                fail_msg("trial %d (%d x %d): cell %d, %d: fill %g, brute force %g (ground %g)", trial, w, h, c % w,
                         c / w, (double)a[c], (double)b[c], (double)g[c]);
            wet += !isnan(a[c]);
        }
        free(g);
        free(a);
        free(b);
    }
    assert_true(wet > 10000); /* the grids do hold lakes */
}

/* A bowl (height r² about the centre) inside a rim at 100, with a notch down to 40 on its east side: the
 * lake stands at 40 exactly, over every cell lower than 40 and no other. */
static void test_bowl_stands_at_its_notch(void **state)
{
    (void)state;
    enum { N = 41 };
    float g[N * N], s[N * N];
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            float r2 = (float)((i - 20) * (i - 20) + (j - 20) * (j - 20));
            g[j * N + i] = r2 / 4.0f > 100.0f || i == 0 || j == 0 || i == N - 1 || j == N - 1 ? 100.0f : r2 / 4.0f;
        }
    for (int i = 20; i < N; i++) /* the notch: a channel at 40 from the bowl to the east edge */
        if (g[20 * N + i] > 40.0f)
            g[20 * N + i] = 40.0f;
    water_fill_stats st = fill(g, N, N, 0, 0, s);
    assert_int_equal(st.lakes, 1);
    for (int c = 0; c < N * N; c++)
        if (g[c] < 40.0f)
            assert_true(s[c] == 40.0f);
        else
            assert_true(isnan(s[c]));
    assert_true(fabs(st.deepest - 40.0) < 1e-9);
}

/* Two pits under one rim (the saddle between them lower than the rim): one lake at the rim's spill; a pit
 * opened to the edge, or with a nodata cell in it, holds nothing, and the other then stands at the saddle. */
static void test_basins_merge_and_drain(void **state)
{
    (void)state;
    enum { W = 9, H = 5 };
    float g[W * H], s[W * H];
    for (int c = 0; c < W * H; c++)
        g[c] = 10;
    g[2 * W + 2] = 1, g[2 * W + 6] = 2;                 /* two pits */
    g[2 * W + 3] = g[2 * W + 4] = g[2 * W + 5] = 5;     /* the saddle between them */
    g[0 * W + 4] = 8;                                     /* the rim's lowest point: a notch on the north edge */
    g[1 * W + 4] = 8;
    water_fill_stats st = fill(g, W, H, 0, 0, s);
    assert_int_equal(st.lakes, 1);
    for (int i = 2; i <= 6; i++)
        assert_true(s[2 * W + i] == 8.0f);
    assert_true(isnan(s[1 * W + 4])); /* the notch itself is the spill: dry */
    assert_int_equal(st.wet, 5);
    assert_true(fabs(st.volume - (7 + 3 + 3 + 3 + 6) * 2.0 * 3.0) < 1e-9);
    g[2 * W + 0] = 1, g[2 * W + 1] = 1; /* the west pit opened to the edge: it drains; the east one stands at the saddle */
    fill(g, W, H, 0, 0, s);
    for (int c = 0; c < W * H; c++)
        if (c == 2 * W + 6 ? s[c] != 5.0f : !isnan(s[c]))
            fail_msg("cell %d, %d: %g", c % W, c / W, (double)s[c]);
    g[2 * W + 0] = g[2 * W + 1] = 10;
    g[2 * W + 6] = NAN; /* nodata in the east pit: it drains there, and the west pit spills over the saddle */
    fill(g, W, H, 0, 0, s);
    for (int c = 0; c < W * H; c++)
        if (c == 2 * W + 2 ? s[c] != 5.0f : !isnan(s[c]))
            fail_msg("cell %d, %d: %g", c % W, c / W, (double)s[c]);
}

/* min_depth and min_area leave a lake dry by its deepest cell and its area. */
static void test_thresholds(void **state)
{
    (void)state;
    enum { W = 12, H = 5 };
    float g[W * H], s[W * H];
    for (int c = 0; c < W * H; c++)
        g[c] = 10;
    g[2 * W + 2] = 9.5f;                   /* a puddle: 0.5 deep, one cell (6 m²) */
    g[2 * W + 6] = g[2 * W + 7] = g[2 * W + 8] = 4; /* a lake: 6 deep, three cells (18 m²) */
    water_fill_stats st = fill(g, W, H, 0, 0, s);
    assert_int_equal(st.lakes, 2);
    st = fill(g, W, H, 1.0, 0, s);
    assert_int_equal(st.lakes, 1);
    assert_int_equal(st.dropped, 1);
    assert_true(isnan(s[2 * W + 2]) && s[2 * W + 7] == 10.0f);
    st = fill(g, W, H, 0, 10.0, s);        /* 6 m² < 10 m² < 18 m² */
    assert_int_equal(st.lakes, 1);
    assert_true(isnan(s[2 * W + 2]) && s[2 * W + 6] == 10.0f);
    st = fill(g, W, H, 6.0, 18.0, s);      /* exactly the lake's depth and area: kept */
    assert_int_equal(st.lakes, 1);
    st = fill(g, W, H, 6.5, 0, s);         /* deeper than both */
    assert_int_equal(st.lakes, 0);
    assert_int_equal(st.wet, 0);
}

/* A river down a plane sloping 0.5 m a texel east (10 m texels), given from its lower end: it runs from the higher
 * one, each texel within half its width (15 m) of the course at the level of the ground under its nearest step
 * plus the depth (2 m), none farther; over a bump it never climbs. */
static void test_river_runs_downhill(void **state)
{
    (void)state;
    enum { RW = 40, RH = 20 };
    float g[RW * RH], out[RW * RH];
    for (int j = 0; j < RH; j++)
        for (int i = 0; i < RW; i++)
            g[j * RW + i] = 100.0f - 0.5f * (float)i;
    double course[2][2] = {{35, 10}, {5, 10}};
    geo_river r = {.pt = course, .n = 2, .width = 30, .depth = 2};
    for (int c = 0; c < RW * RH; c++)
        out[c] = WATER_DRY;
    water_rivers(g, RW, RH, 10, 10, 1, &r, 1, out);
    int wet = 0;
    for (int j = 0; j < RH; j++)
        for (int i = 0; i < RW; i++) {
            double pi = fmin(fmax(i, 5), 35), d = hypot((i - pi) * 10, (j - 10) * 10); /* to the course, in metres */
            float want = d <= 15 ? 102.0f - 0.5f * (float)pi : WATER_DRY;
            if (out[j * RW + i] != want)
                fail_msg("texel %d, %d: level %g, want %g (%.2f m from the course)", i, j, (double)out[j * RW + i],
                         (double)want, d);
            wet += d <= 15;
        }
    assert_true(wet > 90);
    for (int j = 0; j < RH; j++) /* a bump across its course: the water goes on at the level it had */
        g[j * RW + 20] += 10;
    for (int c = 0; c < RW * RH; c++)
        out[c] = WATER_DRY;
    water_rivers(g, RW, RH, 10, 10, 1, &r, 1, out);
    for (int i = 6; i <= 35; i++)
        assert_true(out[10 * RW + i] <= out[10 * RW + i - 1]);
    assert_true(out[10 * RW + 20] == out[10 * RW + 19] && out[10 * RW + 20] < g[10 * RW + 20]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_against_brute_force),
        cmocka_unit_test(test_bowl_stands_at_its_notch),
        cmocka_unit_test(test_basins_merge_and_drain),
        cmocka_unit_test(test_thresholds),
        cmocka_unit_test(test_river_runs_downhill),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
