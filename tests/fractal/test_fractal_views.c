/* Fractals as a camera meets them: a deep zoom's precision, cameras inside the set, on its surface and
 * far away, a bounding sphere that is never drawn and far corners that are kept, glow without a ring. */
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

/* ---- Deep zoom: double precision against a march in double on the CPU ------------------------- */

enum { DEEP_ITER = 20, DEEP_W = 96, DEEP_H = 54 };
static const double DEEP_BAILOUT = 2, DEEP_POWER = 8, DEEP_BOUND = 1.6, DEEP_MARGIN_BOUND = 0.1;

/* The Mandelbulb's estimate as fractal/iterate.glsl computes it, written here in double with the
 * trigonometric triplex power (the shader's double path uses complex products instead): Mandelbrot
 * mode (julia NULL: c is the point) or Julia mode (c = julia). */
static double bulb_de_mode(const double p[3], const double *julia, double *trap)
{
    double z[3] = {p[0], p[1], p[2]}, dr = 1, r = 0;
    const double *c = julia ? julia : p;
    bool escaped = false;
    *trap = 1e10;
    for (int i = 0; i < DEEP_ITER; i++) {
        r = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
        if ((escaped = r > DEEP_BAILOUT))
            break;
        *trap = fmin(*trap, r);
        double theta = r > 0 ? acos(fmin(fmax(z[1] / r, -1), 1)) * DEEP_POWER : 0;
        double phi = (z[0] != 0 || z[2] != 0) ? atan2(z[2], z[0]) * DEEP_POWER : 0, rn1 = pow(r, DEEP_POWER - 1);
        double rho = sqrt(z[0] * z[0] + z[2] * z[2]);
        double stretch = rho > 1e-6 * r ? fabs(sin(DEEP_POWER * atan2(rho, z[1]))) * r / rho : DEEP_POWER;
        dr = DEEP_POWER * rn1 * fmax(1, stretch) * dr + (julia ? 0 : 1); /* the azimuthal stretch: mandelbulb.glsl */
        z[0] = rn1 * r * sin(theta) * cos(phi) + c[0];
        z[1] = rn1 * r * cos(theta) + c[1];
        z[2] = rn1 * r * sin(theta) * sin(phi) + c[2];
    }
    r = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
    return (escaped || r > DEEP_BAILOUT) && dr > 0 ? 0.5 * log(r) * r / dr : 0;
}

/* The shader's march of a footprint surface (common/march.glsl, fractal/common.glsl) in double: the
 * bounding sphere's distance outside it, a hit once the estimate is below HIT_K pixel footprints.
 * The depth of the hit, or INFINITY. */
static double deep_march(const dray *r, const double *julia, double hit_k, double pixel_angle, double step)
{
    double t = 0, trap;
    for (int k = 0; k < 1000000 && t < 10; k++) {
        double p[3] = {r->o[0] + r->d[0] * t, r->o[1] + r->d[1] * t, r->o[2] + r->d[2] * t};
        double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), d;
        if (len - DEEP_BOUND > DEEP_MARGIN_BOUND) {
            d = len - DEEP_BOUND;
        } else {
            d = bulb_de_mode(p, julia, &trap);
            if (d < hit_k * pixel_angle * t)
                return t;
        }
        t += d * step;
    }
    return INFINITY;
}

/* A point on the set's surface: along the ray from `from` toward the origin, the last point whose
 * orbit escapes (bisected to a double's resolution). */
static void deep_surface_point(const double from[3], const double *julia, double out[3], double dir[3])
{
    double len = sqrt(from[0] * from[0] + from[1] * from[1] + from[2] * from[2]), a = 0, b = 0, trap;
    for (int i = 0; i < 3; i++)
        dir[i] = -from[i] / len;
    for (double t = 0;; t += 0.5 * fmax(bulb_de_mode(out, julia, &trap), 1e-9)) {
        for (int i = 0; i < 3; i++)
            out[i] = from[i] + dir[i] * t;
        if (bulb_de_mode(out, julia, &trap) <= 0) {
            b = t;
            break;
        }
        a = t;
    }
    for (int k = 0; k < 200; k++) {
        double m = 0.5 * (a + b);
        for (int i = 0; i < 3; i++)
            out[i] = from[i] + dir[i] * m;
        if (bulb_de_mode(out, julia, &trap) > 0)
            a = m;
        else
            b = m;
    }
    for (int i = 0; i < 3; i++)
        out[i] = from[i] + dir[i] * a;
}

/* Depths of the GPU image against the CPU march: the share of pixels that agree (both miss, or the
 * depths within a few hit thresholds) and the hit IoU. */
static void deep_compare(const float *aov, const camera *cam, const double *julia, const scene *s, double *agree,
                         double *iou)
{
    double pa = camera_pixel_angle(cam, DEEP_H), hk = s->quality.hit_k, sf = s->quality.step_factor;
    int same = 0, both = 0, either = 0;
    for (int row = 0; row < DEEP_H; row++)
        for (int x = 0; x < DEEP_W; x++) {
            dray r = pixel_ray(cam, x, row, DEEP_W, DEEP_H);
            double ref = deep_march(&r, julia, hk, pa, sf), got = aov[(row * DEEP_W + x) * AOV + AOV_SLOT_DEPTH];
            bool hr = isfinite(ref), hg = isfinite(got);
            both += hr && hg, either += hr || hg;
            same += (!hr && !hg) || (hr && hg && fabs(got - ref) <= 4 * hk * pa * ref + 1e-4 * ref);
        }
    *agree = (double)same / (DEEP_W * DEEP_H);
    *iou = either ? (double)both / either : 1;
}

/* A view 1e-9 and 1e-12 wide at the Mandelbulb's surface and at a Julia set's: with the formula in
 * double (fractal.precision auto switches to it there) every pixel's depth matches a march in double
 * on the CPU; in float the camera itself cannot be placed (its position rounds by ~1e-8) and the
 * image is another place's. */
static void deep_zoom(void **st)
{
    (void)st;
    /* c as the shader has it: the uniform is a float */
    static const double julia_c[3] = {(float)-0.6, (float)0.4, (float)0.2}, from[3] = {0.3, 0.5, 2.2};
    static const double depths[2] = {1e-9, 1e-12};
    static float aov[DEEP_W * DEEP_H * AOV];
    for (int mode = 0; mode < 2; mode++) {
        const double *julia = mode ? julia_c : NULL;
        double p[3], dir[3];
        deep_surface_point(from, julia, p, dir);
        for (int k = 0; k < 2; k++) {
            /* back from the surface along the ray, looking a little across it: near and far in view */
            double eye[3], at[3];
            for (int i = 0; i < 3; i++)
                eye[i] = p[i] - dir[i] * 4 * depths[k], at[i] = p[i] + (i == 1 ? 1.5 * depths[k] : 0);
            camera cam = camera_look_at(eye, at, (float)(40 * DEG2RAD));
            double result[2][2];
            for (int prec = 0; prec < 2; prec++) { /* 0 auto (double here), 1 float */
                char fractal[256];
                snprintf(fractal, sizeof fractal,
                         "{\"iterations\": %d, \"bailout\": %g, \"julia\": %s, \"julia_c\": [%g, %g, %g], \"precision\": \"%s\"}",
                         DEEP_ITER, DEEP_BAILOUT, julia ? "true" : "false", -0.6, 0.4, 0.2,
                         prec ? "float" : "auto");
                scene s;
                load_fractal("mandelbulb", fractal, "{\"preset\": \"final\", \"step_factor\": 0.7}", &s);
                err_t e;
                if (!render_set_scene(&s, NULL, &e) || !render_fit_precision(&s, &cam, DEEP_H, &e))
                    fail_msg("%s", e.msg);
                assert_true(s.fractal.deep_now == (prec == 0)); /* auto takes double where a float cannot resolve */
                draw(&s, &cam, DEEP_W, DEEP_H, 1, NULL, aov, NULL);
                deep_compare(aov, &cam, julia, &s, &result[prec][0], &result[prec][1]);
            if (getenv("DEEP_DEBUG")) {
                double pa = camera_pixel_angle(&cam, DEEP_H);
                for (int q = 0; q < 5; q++) {
                    int x = q * 20, row = q * 10;
                    dray r = pixel_ray(&cam, x, row, DEEP_W, DEEP_H);
                    fprintf(stderr, "  px %d,%d: gpu %.6g cpu %.6g\n", x, row, (double)aov[(row * DEEP_W + x) * AOV + AOV_SLOT_DEPTH],
                            deep_march(&r, julia, s.quality.hit_k, pa, s.quality.step_factor));
                }
            }
                scene_free(&s);
            }
            fprintf(stderr, "deep zoom, %s, view %.0e wide: double: %.4f of pixels agree with the CPU (hit IoU %.4f); "
                    "float: %.4f (IoU %.4f)\n", julia ? "Julia set" : "Mandelbulb", depths[k] * 4 * 0.73,
                    result[0][0], result[0][1], result[1][0], result[1][1]);
            /* the stretch-aware estimate (mandelbulb.glsl) is smaller near the poles, and these views take
             * more, smaller steps than they did: 0.97 of the depths within 4 thresholds at 1e-12 (every
             * hit the same), the Julia set's 0.98 at 1e-9 with some pixels out of llvmpipe's loop budget
             * (flagged; issue 36's item 5). Float draws another place: below 0.9 */
            assert_true(result[0][0] >= (mode == 0 && k == 0 ? 0.99 : 0.96) && result[0][1] >= 0.98);
            assert_true(result[1][0] < 0.9);
        }
    }
}

/* ---- cameras inside the set, 1e-4 from the surface and 1e3 away render without NaN --------------- */

static void extreme_cameras(void **st)
{
    (void)st;
    static const char *const names[] = {"mandelbulb", "menger", "mandelbox"};
    static float aov[W * H * AOV], rgba[W * H * 4];
    for (int k = 0; k < 3; k++) {
        scene s;
        err_t e;
        const char *sets[] = {"quality.spp=1"};
        if (!scene_load(names[k], sets, 1, &s, &e))
            fail_msg("%s", e.msg);
        /* find the surface along a ray from outside, with the shader's own estimate */
        float p[3] = {0.5f, 0.45f, s.fractal.bound_radius + 1.0f}, d[2];
        for (int i = 0; i < 5000 && p[2] > -s.fractal.bound_radius; i++) {
            gl_probe(&s, NULL, p, 1, d);
            if (d[0] < 1e-6f)
                break;
            p[2] -= d[0];
        }
        if (!(d[0] < 1e-5f))
            fail_msg("%s: no surface found along the probe ray (last estimate %g at z %g)", names[k], (double)d[0], (double)p[2]);
        camera cams[] = {
            cam_at(p[0], p[1], p[2] + 1e-4, p[0], p[1], p[2] - 1, 60),  /* 1e-4 from the surface */
            cam_at(p[0], p[1], p[2] - 1e-3, 0, 0, 0, 60),               /* just inside */
            cam_at(0, 0, 0, 1, 0.3, 0.2, 90),                            /* at the centre */
            cam_at(0, 0, 1e3, 0, 0, 0, 1),                               /* 1 km away */
        };
        for (size_t c = 0; c < sizeof cams / sizeof cams[0]; c++) {
            draw(&s, &cams[c], W, H, 1, NULL, aov, rgba);
            char what[64];
            snprintf(what, sizeof what, "%s camera %zu", names[k], c);
            check_finite(what, aov, rgba, W * H);
        }
        scene_free(&s);
    }
}

/* ---- no ray stops on the bounding sphere --------------------------------------------------------------
 * Outside the bounding sphere the programs return its distance (a cheap bound) while it exceeds a
 * margin: 0.1, or four hit thresholds at the point's distance from the eye where that is more
 * (shaders/fractal/common.glsl). From far away the threshold exceeds 0.1, and a ray that stopped on
 * the bound would be drawn on an invisible sphere: its hit point would lie beyond the margin, where
 * no point of the set (which lies inside the sphere) is within reach. */
static void bounding_sphere_is_never_drawn(void **st)
{
    (void)st;
    const double BOUND_MARGIN = 0.1; /* shaders/fractal/common.glsl */
    static const struct { const char *name; double distance; } CASES[] = {{"mandelbulb", 30}, {"mandelbox", 45}};
    static const char *const PRESETS[] = {"draft", "final"};
    static float aov[W * H * AOV];
    for (size_t k = 0; k < sizeof CASES / sizeof CASES[0]; k++)
        for (int p = 0; p < 2; p++) {
            char preset[64];
            snprintf(preset, sizeof preset, "quality.preset=%s", PRESETS[p]);
            const char *sets[] = {preset, "quality.spp=1"};
            scene s;
            err_t e;
            if (!scene_load(CASES[k].name, sets, 2, &s, &e))
                fail_msg("%s", e.msg);
            double d = CASES[k].distance / sqrt(3.0);
            camera cam = cam_at(d, d * 0.8, d * 1.1, 0, 0, 0, 40);
            double eps_at_bound = s.quality.hit_k * (CASES[k].distance - s.fractal.bound_radius) *
                                  camera_pixel_angle(&cam, H);
            assert_true(eps_at_bound > BOUND_MARGIN); /* the case the fixed margin did not cover */
            draw(&s, &cam, W, H, 1, NULL, aov, NULL);
            int hits = 0, on_bound = 0;
            for (int row = 0; row < H; row++)
                for (int x = 0; x < W; x++) {
                    double t = aov[(row * W + x) * AOV + AOV_SLOT_DEPTH];
                    if (isinf(t))
                        continue;
                    hits++;
                    dray r = pixel_ray(&cam, x, row, W, H);
                    double q[3] = {r.o[0] + r.d[0] * t, r.o[1] + r.d[1] * t, r.o[2] + r.d[2] * t};
                    double margin = fmax(BOUND_MARGIN, 4 * s.quality.hit_k * t * camera_pixel_angle(&cam, H));
                    on_bound += sqrt(ref_dot(q, q)) > s.fractal.bound_radius + margin;
                }
            fprintf(stderr, "%s %s from %g: %d hits, %d on the bounding sphere (threshold there %.3g)\n",
                    CASES[k].name, PRESETS[p], CASES[k].distance, hits, on_bound, eps_at_bound);
            assert_true(hits > 20);
            assert_int_equal(on_bound, 0);
            scene_free(&s);
        }
}

/* Far away the hit threshold (the footprint surface) outgrows any fixed margin around the bounding
 * sphere; where the set reaches the sphere (the Mandelbox's corners lie on it) the switch to the bound
 * must wait until the threshold is passed, or the corners are clipped. The far view against the same
 * formula with no bounding sphere in reach (bound_radius 1000): the same pixels hit. */
static void far_corners_are_kept(void **st)
{
    (void)st;
    static float bounded[W * H * AOV], open[W * H * AOV];
    for (int p = 0; p < 2; p++) {
        const char *preset = p ? "quality.preset=final" : "quality.preset=draft";
        scene s, u;
        err_t e;
        if (!scene_load("mandelbox", (const char *const[]){preset, "quality.spp=1"}, 2, &s, &e) ||
            !scene_load("mandelbox", (const char *const[]){preset, "quality.spp=1", "fractal.bound_radius=1000"}, 3, &u, &e))
            fail_msg("%s", e.msg);
        const double distance = 45, d = distance / sqrt(3.0);
        camera cam = cam_at(d, d * 0.8, d * 1.1, 0, 0, 0, 40);
        draw(&s, &cam, W, H, 1, NULL, bounded, NULL);
        draw(&u, &cam, W, H, 1, NULL, open, NULL);
        int both = 0, either = 0, clipped = 0;
        for (int i = 0; i < W * H; i++) {
            bool a = !isinf(bounded[i * AOV + AOV_SLOT_DEPTH]), b = !isinf(open[i * AOV + AOV_SLOT_DEPTH]);
            both += a && b;
            either += a || b;
            clipped += b && !a;
        }
        fprintf(stderr, "  mandelbox %s from %g m: %d px hit without the bound, %d of them clipped by it (IoU %.4f)\n",
                preset + 15, distance, either, clipped, either ? (double)both / either : 1.0);
        assert_true(either > 100);
        /* the two march different step sequences, so a grazing pixel may go either way: 1 of 1757 at
         * draft today; before, 422 (a fixed 0.1 margin) or 53 (twice the threshold) were clipped */
        assert_true(clipped <= either / 500);
        assert_true(either - both <= either / 500);
        scene_free(&s);
        scene_free(&u);
    }
}

/* The glow counts steps near the shape only: background rays that pass just outside the bounding sphere
 * (many steps on the bound, none near the box) are as dark as rays far from it. Before, they drew a
 * faint ring around the sphere's silhouette. */
static void glow_draws_no_ring(void **st)
{
    (void)st;
    enum { GW = 160, GH = 120 };
    const char *sets[] = {"quality.spp=1", "effects.aa=off", "environment.intensity=0", "lights.0.intensity=0"};
    scene s;
    err_t e;
    if (!scene_load("mandelbox", sets, 4, &s, &e))
        fail_msg("%s", e.msg);
    assert_true(s.effects & (1u << EFFECT_GLOW));
    double d = 3.2 * s.fractal.bound_radius / sqrt(3.0);
    camera cam = cam_at(d, d * 0.8, d * 1.1, 0, 0, 0, 50);
    static float aov[GW * GH * AOV], rgba[GW * GH * 4];
    draw(&s, &cam, GW, GH, 1, NULL, aov, rgba);
    double near_sum = 0, far_sum = 0;
    int near_n = 0, far_n = 0;
    for (int row = 0; row < GH; row++)
        for (int x = 0; x < GW; x++) {
            if (!isinf(aov[(row * GW + x) * AOV + AOV_SLOT_DEPTH]))
                continue;
            dray r = pixel_ray(&cam, x, row, GW, GH);
            double b = ref_dot(r.o, r.d), closest = sqrt(ref_dot(r.o, r.o) - b * b);
            double lum = rgba[(row * GW + x) * 4] + rgba[(row * GW + x) * 4 + 1] + rgba[(row * GW + x) * 4 + 2];
            if (closest > s.fractal.bound_radius * 1.001 && closest < s.fractal.bound_radius * 1.05)
                near_sum += lum, near_n++;
            else if (closest > s.fractal.bound_radius * 1.3)
                far_sum += lum, far_n++;
        }
    double near = near_sum / near_n, far = far_sum / far_n;
    fprintf(stderr, "  glow just outside the bounding sphere %.4g (%d px), far from it %.4g (%d px)\n", near, near_n,
            far, far_n);
    assert_true(near_n > 20 && far_n > 20);
    assert_true(near - far < 2e-3); /* without the fix: 0.103 against 0.0065 */
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(deep_zoom),
        cmocka_unit_test(extreme_cameras),
        cmocka_unit_test(bounding_sphere_is_never_drawn),
        cmocka_unit_test(far_corners_are_kept),
        cmocka_unit_test(glow_draws_no_ring),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='far*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
