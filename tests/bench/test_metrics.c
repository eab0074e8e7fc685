/* Error metrics on synthetic images with answers worked out by hand. */
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
#include "jobs/bench/gnuplot.h"
#include "jobs/bench/metrics.h"
#include "view/aov.h"

enum { W = 5, H = 3, N = W * H };

static void fill(uint8_t *srgb, float *aov, uint8_t grey, float depth)
{
    for (int i = 0; i < N; i++) {
        srgb[i * 4] = srgb[i * 4 + 1] = srgb[i * 4 + 2] = grey;
        srgb[i * 4 + 3] = 255;
        for (int k = 0; k < AOV_FLOATS; k++)
            aov[i * AOV_FLOATS + k] = 0;
        aov[i * AOV_FLOATS + 3] = depth;
        aov[i * AOV_FLOATS + 4] = 10;
    }
}

static void identical_images(void **st)
{
    (void)st;
    uint8_t a[N * 4];
    float aov[N * AOV_FLOATS];
    fill(a, aov, 100, 2.0f);
    image_view v = {W, H, a, aov, 0};
    metrics m = metrics_compare(&v, &v, 0.01);
    assert_near(m.rmse, 0, 0);
    assert_true(isinf(m.psnr_db));
    assert_near(m.depth_mean_fp, 0, 0);
    assert_near(m.flip_share, 0, 0);
    assert_near(m.mean_steps, 10, 0);
    assert_int_equal(m.depth_pixels, N);
}

static void known_errors(void **st)
{
    (void)st;
    uint8_t a[N * 4], b[N * 4];
    float aa[N * AOV_FLOATS], ab[N * AOV_FLOATS];
    fill(a, aa, 0, 2.0f);
    fill(b, ab, 0, 2.0f);
    /* one pixel's red channel off by 255: squared error 1 over 3N channel values */
    a[7 * 4] = 255;
    /* depth: one pixel 0.01 m further at t = 2 with pixel angle 0.005 → 1 footprint; another 3 */
    aa[2 * AOV_FLOATS + 3] = 2.01f;
    aa[4 * AOV_FLOATS + 3] = 2.03f;
    /* two pixels flip: a hit that misses, a miss that hits */
    aa[9 * AOV_FLOATS + 3] = INFINITY;
    ab[11 * AOV_FLOATS + 3] = INFINITY;
    aa[0 * AOV_FLOATS + 4] = 25; /* steps: one pixel 25, the rest 10 */
    image_view va = {W, H, a, aa, 0}, vb = {W, H, b, ab, 0};
    metrics m = metrics_compare(&va, &vb, 0.005);
    assert_near(m.rmse, sqrt(1.0 / (3.0 * N)), 1e-12);
    assert_near(m.psnr_db, 20 * log10(1 / sqrt(1.0 / (3.0 * N))), 1e-9);
    assert_int_equal(m.depth_pixels, N - 2);
    assert_near(m.depth_max_fp, 3.0, 1e-4);
    assert_near(m.depth_mean_fp, 4.0 / (N - 2), 1e-4);
    assert_near(m.flip_share, 2.0 / N, 1e-12);
    assert_near(m.mean_steps, (10.0 * (N - 1) + 25) / N, 1e-12);
}

/* Silhouettes on a 9×5 image: the reference hits a 3×3 square (columns 3–5, rows 1–3). The test
 * hits the same square grown by one column to the right (column 6, rows 1–3: each one pixel from a
 * reference hit) plus one stray pixel at (0, 4), whose nearest reference hit is (3, 3): √(3² + 1²).
 * IoU = 9 / (9 + 3 + 1) = 9/13. One pixel of the test ran out of steps (negative steps). */
static void silhouette_iou_and_edge(void **st)
{
    (void)st;
    enum { SW = 9, SH = 5 };
    uint8_t a[SW * SH * 4] = {0}, b[SW * SH * 4] = {0};
    float aa[SW * SH * AOV_FLOATS], ab[SW * SH * AOV_FLOATS];
    for (int i = 0; i < SW * SH; i++) {
        int x = i % SW, y = i / SW;
        for (int k = 0; k < AOV_FLOATS; k++)
            aa[i * AOV_FLOATS + k] = ab[i * AOV_FLOATS + k] = 0;
        aa[i * AOV_FLOATS + 4] = ab[i * AOV_FLOATS + 4] = 1;
        bool ref = x >= 3 && x <= 5 && y >= 1 && y <= 3;
        bool test = (x >= 3 && x <= 6 && y >= 1 && y <= 3) || (x == 0 && y == 4);
        ab[i * AOV_FLOATS + 3] = ref ? 2.0f : INFINITY;
        aa[i * AOV_FLOATS + 3] = test ? 2.0f : INFINITY;
    }
    aa[(1 * SW + 4) * AOV_FLOATS + 4] = -7; /* ran out of steps */
    image_view va = {SW, SH, a, aa, 0}, vb = {SW, SH, b, ab, 0};
    metrics m = metrics_compare(&va, &vb, 0.01);
    assert_near(m.iou, 9.0 / 13.0, 1e-12);
    assert_near(m.edge_max_px, sqrt(10.0), 1e-12);
    assert_near(m.exhausted_share, 1.0 / (SW * SH), 1e-12);
    assert_near(m.mean_steps, (SW * SH - 1 + 7.0) / (SW * SH), 1e-12);
    metrics same = metrics_compare(&vb, &vb, 0.01);
    assert_near(same.iou, 1, 0);
    assert_near(same.edge_max_px, 0, 0);
}

/* The edge RMSE counts the reference's silhouette pixels only: a 3 x 3 block of hits in a 9 x 5 image
 * has 8 rim pixels and 12 misses beside it; an error at the block's centre is not counted until the
 * centre lies 10 % deeper than its neighbours (one surface behind another), one beside it always. */
static void edge_rmse_counts_silhouettes_only(void **st)
{
    (void)st;
    enum { SW = 9, SH = 5 };
    uint8_t a[SW * SH * 4] = {0}, b[SW * SH * 4] = {0};
    float aa[SW * SH * AOV_FLOATS] = {0}, ab[SW * SH * AOV_FLOATS] = {0};
    for (int i = 0; i < SW * SH; i++) {
        int x = i % SW, y = i / SW;
        aa[i * AOV_FLOATS + 3] = ab[i * AOV_FLOATS + 3] = x >= 3 && x <= 5 && y >= 1 && y <= 3 ? 2.0f : INFINITY;
    }
    a[(2 * SW + 4) * 4] = 255;                                           /* the centre: red off by 1 */
    a[(2 * SW + 2) * 4] = a[(2 * SW + 2) * 4 + 1] = a[(2 * SW + 2) * 4 + 2] = 51; /* beside: 0.2 each */
    image_view va = {SW, SH, a, aa, 0}, vb = {SW, SH, b, ab, 0};
    metrics m = metrics_compare(&va, &vb, 0.01);
    assert_int_equal(m.edge_pixels, 20);
    assert_near(m.edge_rmse, sqrt(3 * 0.04 / (3 * 20)), 1e-12);
    ab[(2 * SW + 4) * AOV_FLOATS + 3] = 2.2f;
    m = metrics_compare(&va, &vb, 0.01);
    assert_int_equal(m.edge_pixels, 21);
    assert_near(m.edge_rmse, sqrt((3 * 0.04 + 1) / (3 * 21)), 1e-12);
}

/* The median's interval from order statistics, against the binomial tables: n = 9 gives [x(2), x(8)]
 * (2 P(X <= 1) = 0.039), n = 20 [x(6), x(15)] (2 P(X <= 5) = 0.041, 2 P(X <= 6) = 0.115); n = 5 has no
 * such k and gives the whole range; one value is its own interval. Order of the input does not matter. */
static void median_interval_from_order_statistics(void **st)
{
    (void)st;
    double v[20], lo, hi;
    for (int i = 0; i < 20; i++)
        v[i] = (double)((i * 7) % 20 + 1); /* 1 … 20, shuffled */
    assert_near(metrics_median_interval(v, 20, &lo, &hi), 10.5, 0);
    assert_near(lo, 6, 0);
    assert_near(hi, 15, 0);
    double nine[9] = {9, 1, 8, 2, 7, 3, 6, 4, 5};
    assert_near(metrics_median_interval(nine, 9, &lo, &hi), 5, 0);
    assert_near(lo, 2, 0);
    assert_near(hi, 8, 0);
    double five[5] = {30, 10, 50, 20, 40};
    assert_near(metrics_median_interval(five, 5, &lo, &hi), 30, 0);
    assert_near(lo, 10, 0);
    assert_near(hi, 50, 0);
    double one = 3;
    assert_near(metrics_median_interval(&one, 1, &lo, &hi), 3, 0);
    assert_near(lo, 3, 0);
    assert_near(hi, 3, 0);
    /* every n from 2 to 120 against the definition, computed another way: each binomial term on its own
     * from lgamma (not the recurrence), the largest k with 2 P(Bin(n, 1/2) <= k - 1) <= 0.05 */
    static double many[120];
    for (int n = 2; n <= 120; n++) {
        for (int i = 0; i < n; i++)
            many[i] = (double)((i * 127) % n + 1); /* 1 … n, shuffled (127: prime, above every n) */
        int k = 1;
        for (int j = 1; j < n; j++) {
            double tail = 0;
            for (int i = 0; i <= j - 1; i++)
                tail += exp(lgamma(n + 1.0) - lgamma(i + 1.0) - lgamma(n - i + 1.0) - n * log(2.0));
            if (2 * tail <= 0.05)
                k = j;
        }
        metrics_median_interval(many, n, &lo, &hi);
        if (lo != k || hi != n + 1 - k)
            fail_msg("n = %d: [x(%g), x(%g)], not [x(%d), x(%d)]", n, lo, hi, k, n + 1 - k);
    }
}

static void upscale_is_exact_on_flat_and_keeps_layout(void **st)
{
    (void)st;
    /* 2×1 → 4×2: left half red, right half blue; depth left 1, right 5 */
    uint8_t in[2 * 4] = {255, 0, 0, 255, 0, 0, 255, 255};
    float aov[2 * AOV_FLOATS] = {0};
    aov[AOV_SLOT_DEPTH] = 1, aov[AOV_SLOT_STEPS] = 7;
    aov[AOV_FLOATS + AOV_SLOT_DEPTH] = 5, aov[AOV_FLOATS + AOV_SLOT_STEPS] = 9;
    image_view v = {2, 1, in, aov, 0};
    uint8_t *out;
    float *oa;
    metrics_upscale(&v, 4, 2, &out, &oa);
    assert_int_equal(out[0], 255);           /* far left: pure red */
    assert_int_equal(out[2], 0);
    assert_int_equal(out[3 * 4 + 2], 255);   /* far right: pure blue */
    assert_int_equal(out[(4 + 3) * 4 + 2], 255);
    assert_true(out[1 * 4] > out[2 * 4]);    /* red fades toward the right */
    assert_near(oa[0 * AOV_FLOATS + 3], 1, 0);
    assert_near(oa[3 * AOV_FLOATS + 3], 5, 0);
    assert_near(oa[(4 + 3) * AOV_FLOATS + 4], 9, 0);
    free(out);
    free(oa);
}

static void pareto_front(void **st)
{
    (void)st;
    /* (time, error): B dominates C; A and B and D are on the front; E ties D's time but is worse */
    double t[] = {1, 2, 3, 5, 5}, e[] = {10, 4, 6, 1, 2};
    bool f[5];
    metrics_pareto(t, t, e, 5, f);
    assert_true(f[0] && f[1] && !f[2] && f[3] && !f[4]);
    /* with intervals: B's median is faster than A's but not measurably, and B is worse: off the front
     * (issue 26: shadow_steps 64 came out "faster" than 32 by noise); C is measurably faster: on it */
    double lo[] = {9, 8, 4.5}, hi[] = {11, 10.5, 5.5}, err[] = {5, 6, 7};
    metrics_pareto(lo, hi, err, 3, f);
    assert_true(f[0] && !f[1] && f[2]);
    /* ties, one case a call: the same error and measurably faster leaves the slower off; the same time
     * and a lower error leaves the worse off; the same error and not measurably faster keeps both; a
     * setting measured twice is on twice */
    static const struct { double lo[2], hi[2], err[2]; bool on[2]; } TIES[] = {
        {{1, 3}, {2, 4}, {5, 5}, {true, false}},
        {{3, 3}, {4, 4}, {4, 5}, {true, false}},
        {{1, 1.5}, {2, 2.5}, {5, 5}, {true, true}},
        {{1, 1}, {2, 2}, {3, 3}, {true, true}},
    };
    for (size_t k = 0; k < sizeof TIES / sizeof TIES[0]; k++) {
        bool g[2];
        metrics_pareto(TIES[k].lo, TIES[k].hi, TIES[k].err, 2, g);
        if (g[0] != TIES[k].on[0] || g[1] != TIES[k].on[1])
            fail_msg("ties case %zu: front %d %d", k, g[0], g[1]);
    }
}


/* Every byte value inside a string that gnuplot_string quotes, beside a command substitution, a macro,
 * a quote and a backslash: gnuplot must print each string back as text (control bytes as '?', a newline
 * as a line break) and run nothing. gnuplot's `print` writes to stderr: gnuplot_run's log. */
static void gnuplot_strings_are_text(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-gnuplot-XXXXXX", path[64], ran[80];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/t.gp", dir);
    snprintf(ran, sizeof ran, "%s/RAN", dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    strbuf want = {0};
    fprintf(f, "x = 'MACRO'\n");
    for (int b = 1; b < 256; b++) {
        char s[160];
        snprintf(s, sizeof s, "a%cb'`touch %s`@x\\n\"", (char)b, ran);
        fputs("print ", f);
        gnuplot_string(f, s);
        fputc('\n', f);
        for (const char *c = s; *c; c++)
            sb_printf(&want, "%c", ((unsigned char)*c < 0x20 && *c != '\n') || *c == 0x7f ? '?' : *c);
        sb_append(&want, "\n");
    }
    fclose(f);
    err_t e;
    bool ok = gnuplot_run(dir, "t.gp", &e);
    if (!ok)
        fail_msg("%s", e.msg);
    char log[80], *got = NULL;
    snprintf(log, sizeof log, "%s/%s", dir, GNUPLOT_LOG_NAME);
    assert_true(util_read_file(log, &got, NULL, &e));
    assert_string_equal(got, want.data);
    assert_int_equal(access(ran, F_OK), -1); /* the backquotes ran nothing */
    free(got);
    sb_free(&want);
    unlink(log), unlink(path), rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(identical_images),
        cmocka_unit_test(known_errors),
        cmocka_unit_test(silhouette_iou_and_edge),
        cmocka_unit_test(edge_rmse_counts_silhouettes_only),
        cmocka_unit_test(median_interval_from_order_statistics),
        cmocka_unit_test(upscale_is_exact_on_flat_and_keeps_layout),
        cmocka_unit_test(pareto_front),
        cmocka_unit_test(gnuplot_strings_are_text),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
