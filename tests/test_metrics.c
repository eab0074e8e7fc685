/* Error metrics on synthetic images with answers worked out by hand. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "check.h"
#include "metrics.h"

enum { W = 5, H = 3, N = W * H };

static void fill(uint8_t *srgb, float *aov, uint8_t grey, float depth)
{
    for (int i = 0; i < N; i++) {
        srgb[i * 4] = srgb[i * 4 + 1] = srgb[i * 4 + 2] = grey;
        srgb[i * 4 + 3] = 255;
        for (int k = 0; k < 8; k++)
            aov[i * 8 + k] = 0;
        aov[i * 8 + 3] = depth;
        aov[i * 8 + 4] = 10;
    }
}

static void identical_images(void **st)
{
    (void)st;
    uint8_t a[N * 4];
    float aov[N * 8];
    fill(a, aov, 100, 2.0f);
    image_view v = {W, H, a, aov};
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
    float aa[N * 8], ab[N * 8];
    fill(a, aa, 0, 2.0f);
    fill(b, ab, 0, 2.0f);
    /* one pixel's red channel off by 255: squared error 1 over 3N channel values */
    a[7 * 4] = 255;
    /* depth: one pixel 0.01 m further at t = 2 with pixel angle 0.005 → 1 footprint; another 3 */
    aa[2 * 8 + 3] = 2.01f;
    aa[4 * 8 + 3] = 2.03f;
    /* two pixels flip: a hit that misses, a miss that hits */
    aa[9 * 8 + 3] = INFINITY;
    ab[11 * 8 + 3] = INFINITY;
    aa[0 * 8 + 4] = 25; /* steps: one pixel 25, the rest 10 */
    image_view va = {W, H, a, aa}, vb = {W, H, b, ab};
    metrics m = metrics_compare(&va, &vb, 0.005);
    assert_near(m.rmse, sqrt(1.0 / (3.0 * N)), 1e-12);
    assert_near(m.psnr_db, 20 * log10(1 / sqrt(1.0 / (3.0 * N))), 1e-9);
    assert_int_equal(m.depth_pixels, N - 2);
    assert_near(m.depth_max_fp, 3.0, 1e-4);
    assert_near(m.depth_mean_fp, 4.0 / (N - 2), 1e-4);
    assert_near(m.flip_share, 2.0 / N, 1e-12);
    assert_near(m.mean_steps, (10.0 * (N - 1) + 25) / N, 1e-12);
}

static void upscale_is_exact_on_flat_and_keeps_layout(void **st)
{
    (void)st;
    /* 2×1 → 4×2: left half red, right half blue; depth left 1, right 5 */
    uint8_t in[2 * 4] = {255, 0, 0, 255, 0, 0, 255, 255};
    float aov[2 * 8] = {0, 0, 0, 1, 7, 0, 0, 0, 0, 0, 0, 5, 9, 0, 0, 0};
    image_view v = {2, 1, in, aov};
    uint8_t *out;
    float *oa;
    metrics_upscale(&v, 4, 2, &out, &oa);
    assert_int_equal(out[0], 255);           /* far left: pure red */
    assert_int_equal(out[2], 0);
    assert_int_equal(out[3 * 4 + 2], 255);   /* far right: pure blue */
    assert_int_equal(out[(4 + 3) * 4 + 2], 255);
    assert_true(out[1 * 4] > out[2 * 4]);    /* red fades toward the right */
    assert_near(oa[0 * 8 + 3], 1, 0);
    assert_near(oa[3 * 8 + 3], 5, 0);
    assert_near(oa[(4 + 3) * 8 + 4], 9, 0);
    free(out);
    free(oa);
}

static void pareto_front(void **st)
{
    (void)st;
    /* (time, error): B dominates C; A and B and D are on the front; E ties D's time but is worse */
    double t[] = {1, 2, 3, 5, 5}, e[] = {10, 4, 6, 1, 2};
    bool f[5];
    metrics_pareto(t, e, 5, f);
    assert_true(f[0] && f[1] && !f[2] && f[3] && !f[4]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(identical_images),
        cmocka_unit_test(known_errors),
        cmocka_unit_test(upscale_is_exact_on_flat_and_keeps_layout),
        cmocka_unit_test(pareto_front),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
