/* Adaptive sampling against every pixel sampled: in the window, pixels off the edge mask keep their
 * centre sample; by the standard error, fewer samples a pixel for nearly the same image; and no pixel
 * left far off by the stop rule (shaders/errormask.frag), judged on the worst pixel of the shot as a user
 * sees it, not on the RMSE. */
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

#include "data/media/image_io.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "jobs/capture/offline.h"
#include "scene/scene.h"

#include "gltest.h"

/* Adaptive sampling (the window's still images): after the centre sample, only pixels on the edge
 * mask take further samples. Every other pixel must keep exactly its centre value (each pixel's alpha
 * counts its own samples), and the image must come near the one where every pixel took all its
 * samples: the reference, independent of the mask. */
static void adaptive_sampling(void **st)
{
    (void)st;
    enum { AW = 320, AH = 180, SPP = RENDER_ADAPTIVE_MIN };
    size_t n = (size_t)AW * AH;
    float *full = malloc(sizeof(float) * 4 * n), *one = malloc(sizeof(float) * 4 * n), *ad = malloc(sizeof(float) * 4 * n);
    scene s;
    err_t e;
    if (!scene_load("csg", NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    camera cam = camera_look_at_deg(s.cam_position, s.cam_look_at, s.cam_fov_deg);
    s.quality.tolerance = 0; /* the reference: every pixel takes every sample */
    draw(&s, &cam, AW, AH, SPP, NULL, NULL, full);
    draw(&s, &cam, AW, AH, 1, NULL, NULL, one);
    s.quality.tolerance = 0.008f; /* a pixel's standard error stops it after RENDER_ADAPTIVE_MIN */
    render_set_adaptive(true);
    draw(&s, &cam, AW, AH, SPP, NULL, NULL, ad);
    render_set_adaptive(false);
    int kept = render_adaptive_pixels();
    size_t same = 0;
    double e_one = 0, e_ad = 0;
    for (size_t i = 0; i < n; i++) {
        same += !memcmp(ad + 4 * i, one + 4 * i, sizeof(float) * 3);
        for (int c = 0; c < 3; c++) {
            double a = full[4 * i + (size_t)c];
            e_one += (one[4 * i + (size_t)c] - a) * (one[4 * i + (size_t)c] - a);
            e_ad += (ad[4 * i + (size_t)c] - a) * (ad[4 * i + (size_t)c] - a);
        }
    }
    e_one = sqrt(e_one / (3.0 * (double)n)), e_ad = sqrt(e_ad / (3.0 * (double)n));
    fprintf(stderr, "adaptive: %d of %zu pixels kept by the last mask; %zu keep their centre sample; RMSE to %d spp "
            "everywhere: %.5f (1 spp: %.5f)\n", kept, n, same, SPP, e_ad, e_one);
    assert_true((size_t)kept < 3 * n / 4); /* a small image: many of its pixels are on edges */
    assert_true(same >= n - (size_t)kept);       /* off the mask: exactly the centre sample */
    assert_true(same < n - (size_t)kept + n / 50); /* on it: the samples were taken */
    assert_true(e_ad < 0.5 * e_one);
    scene_free(&s);
    free(full);
    free(one);
    free(ad);
}

/* Adaptive sampling by the standard error (quality.tolerance; every shot, not only the window's): at
 * tolerance 0 every pixel takes every sample; at the final preset's the Mandelbulb's pixels take far
 * fewer on average, and the image stays near every pixel's 16 samples: much nearer than the
 * RENDER_ADAPTIVE_MIN samples everywhere that every pixel takes before the tolerance may stop it. (Without the 3x3 block in
 * shaders/errormask.frag a pixel whose four samples agree stops before a thread thinner than the pixel
 * shows: RMSE 0.69 of the 2-sample image's; with it, 0.04.) */
static void adaptive_standard_error(void **st)
{
    (void)st;
    enum { AW = 240, AH = 135, SPP = 16 };
    size_t n = (size_t)AW * AH;
    float *full = malloc(sizeof(float) * 4 * n), *four = malloc(sizeof(float) * 4 * n), *ad = malloc(sizeof(float) * 4 * n);
    scene s;
    err_t e;
    if (!scene_load("mandelbulb", (const char *[]){"quality.preset=final"}, 1, &s, &e))
        fail_msg("%s", e.msg);
    camera cam = camera_look_at_deg(s.cam_position, s.cam_look_at, s.cam_fov_deg);
    float tolerance = s.quality.tolerance;
    assert_true(tolerance > 0);
    s.quality.tolerance = 0;
    draw(&s, &cam, AW, AH, SPP, NULL, NULL, full);
    assert_true(fabs(render_mean_samples() - SPP) < 1e-9);
    draw(&s, &cam, AW, AH, RENDER_ADAPTIVE_MIN, NULL, NULL, four);
    s.quality.tolerance = tolerance;
    draw(&s, &cam, AW, AH, SPP, NULL, NULL, ad);
    double mean = render_mean_samples(), e4 = 0, ead = 0;
    for (size_t i = 0; i < 4 * n; i++)
        if (i % 4 != 3) {
            e4 += (four[i] - full[i]) * (four[i] - full[i]);
            ead += (ad[i] - full[i]) * (ad[i] - full[i]);
        }
    e4 = sqrt(e4 / (3.0 * (double)n)), ead = sqrt(ead / (3.0 * (double)n));
    fprintf(stderr, "adaptive by standard error (tolerance %g): %.2f samples a pixel of %d; RMSE to every pixel's "
            "%d: %.5f (%d everywhere: %.5f)\n", (double)tolerance, mean, SPP, SPP, ead, RENDER_ADAPTIVE_MIN, e4);
    assert_true(mean > RENDER_ADAPTIVE_MIN && mean < 0.75 * SPP);
    assert_true(ead < 0.2 * e4);
    scene_free(&s);
    free(full);
    free(four);
    free(ad);
}

/* A thread between the first samples: a white rod a tenth of a pixel thick lies along a pixel row, 0.17
 * to 0.22 pixels above its centre, so neither of the two samples every pixel takes (Halton rows 0.5 and
 * 0.33 of the pixel) meets it, and the image after them is black everywhere: no error, no edge. Only the
 * rays' pass-bys (common/hit.glsl) say the row is hiding something; its pixels must then take every
 * sample and equal every pixel sampled (without pass-bys the row stays black). */
static void thread_between_samples(void **st)
{
    (void)st;
    enum { TW = 64, TH = 60, ROW = 30, SPP = 16 }; /* the rod in GL row ROW (from the bottom) */
    const double dist = 5, fov = 40, tan_half = tan(0.5 * fov * DEG2RAD), pixel = 2 * dist * tan_half / TH;
    double centre = (2.0 * (ROW + 0.67) / TH - 1.0) * dist * tan_half, thick = 0.1 * pixel;
    char json[768];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"intensity\": 0},"
             " \"quality\": {\"preset\": \"final\", \"spp\": %d},"
             " \"materials\": {\"white\": {\"base_color\": [0, 0, 0], \"emission\": [4, 4, 4]}},"
             " \"objects\": [{\"shape\": \"box\", \"size\": [20, %.9g, %.9g], \"position\": [0, %.9g, 0],"
             " \"material\": \"white\"}]}", SPP, thick, thick, centre);
    scene s;
    load_text(json, NULL, 0, &s);
    assert_true(s.quality.tolerance > 0);
    camera cam = cam_at(0, 0, dist, 0, 0, 0, fov);
    size_t n = (size_t)TW * TH;
    float *full = malloc(sizeof(float) * 4 * n), *ad = malloc(sizeof(float) * 4 * n);
    float tolerance = s.quality.tolerance;
    s.quality.tolerance = 0;
    draw(&s, &cam, TW, TH, SPP, NULL, NULL, full);
    s.quality.tolerance = tolerance;
    draw(&s, &cam, TW, TH, SPP, NULL, NULL, ad);
    double mean = render_mean_samples(), worst = 0, least = 1e9;
    int row = TH - 1 - ROW; /* draw's rows count from the top */
    for (int x = 0; x < TW; x++) {
        const float *r = full + 4 * ((size_t)row * TW + (size_t)x), *a = ad + 4 * ((size_t)row * TW + (size_t)x);
        least = fmin(least, r[0]);
        worst = fmax(worst, fabs((double)a[0] - r[0]));
    }
    fprintf(stderr, "thread between samples: %.2f samples a pixel of %d; the rod's row %.4f in every pixel sampled, "
            "adaptive off it by %.4f at worst\n", mean, SPP, least, worst);
    assert_true(least > 0.05);         /* every pixel's 16 samples see the rod (2 of 16 meet it) */
    assert_true(worst < 1e-6);         /* and so do the adaptive ones: all 16 taken */
    assert_true(mean < 0.5 * SPP);     /* the empty rest stops at 2 */
    scene_free(&s);
    free(full);
    free(ad);
}

/* ---- the stopping rule itself, on sums made here (render_probe_error_mask) ------------------------ */

enum { MW = 7, MH = 5 };

/* display.frag's curve (the ACES fit, then sRGB's encoding), written again from the published formulas
 * (Narkowicz 2015; IEC 61966-2-1). */
static double shown(double x)
{
    x = fmax(x, 0);
    double t = fmin(fmax((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0), 1);
    return t <= 0.0031308 ? 12.92 * t : 1.055 * pow(t, 1 / 2.4) - 0.055;
}

typedef struct sums {
    float sum[MW * MH * 4], sq[MW * MH * 4];
} sums;

/* Pixel (x, y) (y from the bottom) as n samples of mean m with standard deviation sd in every channel. */
static void set_pixel(sums *S, int x, int y, int n, double m, double sd, float passed)
{
    float *a = S->sum + 4 * (y * MW + x), *b = S->sq + 4 * (y * MW + x);
    for (int c = 0; c < 3; c++) {
        a[c] = (float)(n * m);
        b[c] = (float)(n * m * m + (n - 1) * sd * sd); /* Σx² = n·m² + (n − 1)·s² */
    }
    a[3] = (float)n;
    b[3] = passed;
}

static void uniform(sums *S, int n, double m)
{
    for (int y = 0; y < MH; y++)
        for (int x = 0; x < MW; x++)
            set_pixel(S, x, y, n, m, 0, 0);
}

/* The sample standard deviation whose mean's error over n samples shows as `shown_error` at mean m. */
static double sd_for(double m, int n, double shown_error)
{
    double lo = 0, hi = m;
    for (int i = 0; i < 60; i++) {
        double sd = 0.5 * (lo + hi), e = sd / sqrt(n);
        *(0.5 * (shown(m + e) - shown(m - e)) > shown_error ? &hi : &lo) = sd;
    }
    return lo;
}

/* The pixels the mask keeps, as a string of '1' and '.' from the top row down. */
static void mask_of(const sums *S, float tolerance, char *out)
{
    uint8_t mask[MW * MH];
    err_t e;
    if (!render_probe_error_mask(S->sum, S->sq, MW, MH, tolerance, mask, &e))
        fail_msg("%s", e.msg);
    char *o = out;
    for (int y = MH - 1; y >= 0; y--) {
        for (int x = 0; x < MW; x++)
            *o++ = mask[y * MW + x] ? '1' : '.';
        *o++ = y ? '/' : '\0';
    }
}

/* Each of the rule's parts on a 7×5 image of 0.18 grey: the mean's standard error (not the samples'
 * spread) against the tolerance over the 3×3 block, a pass-by keeping its own pixel, an edge keeping its
 * block until it has contrast / 2.5 tolerances samples, and a pixel of one sample (the window's centre)
 * never going on. */
static void stopping_rule(void **st)
{
    (void)st;
    const float tol = 0.008f;
    const double m = 0.18;
    static sums S;
    char got[MW * MH + MH];
    uniform(&S, 16, m);
    mask_of(&S, tol, got);
    assert_string_equal(got, "......./......./......./......./.......");
    set_pixel(&S, 3, 2, 16, m, sd_for(m, 16, 0.8 * tol), 0); /* its mean's error 0.8 tolerances (its spread 3.2) */
    mask_of(&S, tol, got);
    assert_string_equal(got, "......./......./......./......./.......");
    set_pixel(&S, 3, 2, 16, m, sd_for(m, 16, 1.25 * tol), 0); /* 1.25 tolerances: its block goes on */
    mask_of(&S, tol, got);
    assert_string_equal(got, "......./..111../..111../..111../.......");
    uniform(&S, 16, m);
    set_pixel(&S, 1, 1, 16, m, 0, 1); /* a pass-by: that pixel alone */
    mask_of(&S, tol, got);
    assert_string_equal(got, "......./......./......./.1...../.......");
    /* an edge: pixel (5, 2) brighter by 0.2 as displayed, so its block needs 0.2 / 0.02 = 10 samples */
    double lo = m, hi = 1;
    for (int i = 0; i < 60; i++)
        *(shown(0.5 * (lo + hi)) - shown(m) > 0.2 ? &hi : &lo) = 0.5 * (lo + hi);
    for (int n = 8; n <= 12; n += 4) {
        uniform(&S, n, m);
        set_pixel(&S, 5, 2, n, 1.001 * hi, 0, 0);
        mask_of(&S, tol, got);
        assert_string_equal(got, n < 10 ? "......./....111/....111/....111/......." : "......./......./......./......./.......");
    }
    set_pixel(&S, 4, 2, 1, m, 0, 0); /* one sample (the window's centre, off its edge mask): stays */
    set_pixel(&S, 5, 2, 8, 1.001 * hi, 0, 0);
    for (int y = 1; y <= 3; y++)
        for (int x = 4; x <= 6; x++)
            if (x != 4 || y != 2)
                set_pixel(&S, x, y, 8, x == 5 && y == 2 ? 1.001 * hi : m, 0, 0);
    mask_of(&S, tol, got);
    assert_string_equal(got, "......./....111/.....11/....111/.......");
}

/* The shot as a user takes it (fathom --scene S --quality final --size 640x360), 8-bit sRGB, at the
 * final preset's tolerance or at tolerance 0 (every pixel, every sample). */
static uint8_t *final_shot(const char *name, const char *set, bool every_pixel, const char *path, double *mean)
{
    enum { SW = 640, SH = 360 };
    scene s;
    err_t e;
    const char *sets[] = {"quality.preset=final", set ? set : "quality.preset=final", "quality.tolerance=0"};
    if (!scene_load(name, sets, every_pixel ? 3 : 2, &s, &e))
        fail_msg("%s", e.msg);
    offline_desc d = {.scene = &s, .cam = scene_camera(&s, s.cam_position, s.cam_look_at, s.cam_fov_deg),
                      .width = SW, .height = SH, .spp = s.quality.spp, .output = path, .quiet = true};
    if (!offline_render_current(&d, &e))
        fail_msg("%s", e.msg);
    *mean = render_mean_samples();
    int w, h;
    uint8_t *px;
    if (!image_read_u8(path, 3, IMAGE_MAX_SIDE, &w, &h, &px, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(w, SW);
    assert_int_equal(h, SH);
    unlink(path);
    scene_free(&s);
    return px;
}

/* Item 16 of the independent checks: the error alone stopped pixels whose two samples agreed while a
 * feature lay between them, 138–150 levels off every pixel's 16 samples (csg: the thin mirror's frame
 * and the horizon; spray: glints on droplets, found by the grid's walk and the BVH's; menger: holes in the
 * faces). The worst pixel must be
 * within 32 levels and the 99.99th percentile within 8 (issue 57's goal), with fewer samples than
 * every pixel's. (The rules one at a time: without pass-bys spray is 61 levels off; without the edge rule,
 * csg 74.) */
static void worst_pixel(void **st)
{
    (void)st;
    const char *names[] = {"csg", "spray", "spray", "menger"}, *sets[] = {NULL, NULL, "droplets.structure=bvh", NULL};
    char dir[] = "/tmp/fathom-adaptive-XXXXXX", path[64];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/shot.png", dir);
    for (int k = 0; k < 4; k++) {
        double every, mean;
        uint8_t *ref = final_shot(names[k], sets[k], true, path, &every), *ad = final_shot(names[k], sets[k], false, path, &mean);
        enum { N = 640 * 360 };
        static int hist[256];
        memset(hist, 0, sizeof hist);
        int worst = 0, at = 0;
        for (int i = 0; i < N; i++) {
            int d = 0;
            for (int c = 0; c < 3; c++)
                d = abs(ref[3 * i + c] - ad[3 * i + c]) > d ? abs(ref[3 * i + c] - ad[3 * i + c]) : d;
            hist[d]++;
            if (d > worst)
                worst = d, at = i;
        }
        int p9999 = 0;
        for (int above = N; p9999 < 255 && (above -= hist[p9999]) > N / 10000;)
            p9999++;
        fprintf(stderr, "%s%s%s at 640x360 final: %.2f samples a pixel of %.0f; worst pixel %d levels off at (%d, %d), "
                "99.99th percentile %d\n", names[k], sets[k] ? " " : "", sets[k] ? sets[k] : "", mean, every, worst,
                at % 640, at / 640, p9999);
        assert_true(mean < 0.75 * every);
        assert_true(worst <= 32);
        assert_true(p9999 <= 8);
        free(ref);
        free(ad);
    }
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(adaptive_sampling),
        cmocka_unit_test(adaptive_standard_error),
        cmocka_unit_test(stopping_rule),
        cmocka_unit_test(thread_between_samples),
        cmocka_unit_test(worst_pixel),
    };
    if (getenv("FATHOM_TEST_FILTER"))
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
