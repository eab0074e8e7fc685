/* Fractal distance estimates probed in the shader itself (render_probe) against references computed
 * independently in double precision: the Menger sponge's exact distance, the Mandelbulb's estimate never
 * past the set, its hard points (the origin, the axes, the bailout sphere) and over-relaxation. (Views:
 * test_fractal_views.c; every shipped formula: test_formulas.c; check-formula: test_formula_check.c.) */
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

static uint32_t rng = 987654321u;
static double rnd(double lo, double hi)
{
    rng = rng * 1664525u + 1013904223u;
    return lo + (hi - lo) * (double)(rng >> 8) / 16777216.0;
}

/* ---- Menger: the estimate is the exact distance ------------------------------------------------- */

static double box_distance(const double p[3], const double c[3], double half)
{
    double out = 0, in = -INFINITY;
    for (int i = 0; i < 3; i++) {
        double g = fabs(p[i] - c[i]) - half;
        out += g > 0 ? g * g : 0;
        in = fmax(in, g);
    }
    return sqrt(out) + fmin(in, 0.0);
}

/* The level-n sponge as its 20ⁿ cubes: each cube keeps the 20 sub-cubes whose offset in {−1,0,1}³ has
 * at most one zero. */
static int menger_cubes(int level, double (*centres)[3], double *half)
{
    int n = 1;
    centres[0][0] = centres[0][1] = centres[0][2] = 0;
    double h = 1.0;
    for (int l = 0; l < level; l++) {
        double (*next)[3] = malloc(sizeof *next * (size_t)n * 20);
        int m = 0;
        h /= 3;
        for (int i = 0; i < n; i++)
            for (int x = -1; x <= 1; x++)
                for (int y = -1; y <= 1; y++)
                    for (int z = -1; z <= 1; z++) {
                        if ((x == 0) + (y == 0) + (z == 0) > 1)
                            continue;
                        next[m][0] = centres[i][0] + 2 * h * x;
                        next[m][1] = centres[i][1] + 2 * h * y;
                        next[m][2] = centres[i][2] + 2 * h * z;
                        m++;
                    }
        memcpy(centres, next, sizeof *next * (size_t)m);
        free(next);
        n = m;
    }
    *half = h;
    return n;
}

static void menger_exact(void **st)
{
    (void)st;
    enum { LEVEL = 3, RANDOM = 1500, NEAR = 700, N = RANDOM + NEAR };
    scene s;
    char fractal[64];
    snprintf(fractal, sizeof fractal, "{\"iterations\": %d, \"size\": 1}", LEVEL);
    load_fractal("menger", fractal, "{}", &s);
    double (*cubes)[3] = malloc(sizeof *cubes * 8000), half;
    int nc = menger_cubes(LEVEL, cubes, &half);
    assert_int_equal(nc, 8000);
    static float pts[N * 3], de[N * 2];
    for (int i = 0; i < N; i++) {
        if (i < RANDOM) {
            for (int k = 0; k < 3; k++)
                pts[i * 3 + k] = (float)rnd(-1.6, 1.6);
        } else { /* just off a random cube's face: holes and rims are where bounds go wrong */
            const double *c = cubes[(int)rnd(0, nc - 1e-9)];
            int axis = (int)rnd(0, 3 - 1e-9);
            double side = rnd(0, 1) < 0.5 ? -1 : 1;
            for (int k = 0; k < 3; k++)
                pts[i * 3 + k] = (float)(c[k] + rnd(-half, half));
            pts[i * 3 + axis] = (float)(c[axis] + side * (half + rnd(1e-3, 0.08)));
        }
    }
    gl_probe(&s, NULL, pts, N, de);
    int outside = 0, inside = 0;
    double worst = 0;
    for (int i = 0; i < N; i++) {
        double p[3] = {pts[i * 3], pts[i * 3 + 1], pts[i * 3 + 2]}, exact = INFINITY;
        for (int c = 0; c < nc; c++)
            exact = fmin(exact, box_distance(p, cubes[c], half));
        if (exact > 0) {
            double err = fabs(de[2 * i] - exact);
            if (err > 2e-5 + 2e-6 * exact)
                fail_msg("point (%g %g %g): estimate %.7f, exact %.7f", p[0], p[1], p[2], (double)de[2 * i], exact);
            worst = fmax(worst, err);
            outside++;
        } else {
            if (de[2 * i] > 1e-6)
                fail_msg("point (%g %g %g) is inside but the estimate is %g", p[0], p[1], p[2], (double)de[2 * i]);
            inside++;
        }
    }
    fprintf(stderr, "menger level %d: %d outside points agree with the exact distance (worst %.2g), %d inside\n",
            LEVEL, outside, worst, inside);
    assert_true(outside > 1200 && inside > 50);
    free(cubes);
    scene_free(&s);
}

/* ---- Mandelbulb: the estimate, times the step factor, never exceeds the true distance ----------- */

/* The same iteration in double (written from the formula, not from the shader). */
static bool bulb_inside(double cx, double cy, double cz, double power, double bailout, int iterations)
{
    double x = cx, y = cy, z = cz;
    for (int i = 0; i < iterations; i++) {
        double r = sqrt(x * x + y * y + z * z);
        if (r > bailout)
            return false;
        double theta = r > 0 ? acos(y / r) : 0, phi = (x != 0 || z != 0) ? atan2(z, x) : 0;
        double rn = pow(r, power);
        x = rn * sin(power * theta) * cos(power * phi) + cx;
        y = rn * cos(power * theta) + cy;
        z = rn * sin(power * theta) * sin(power * phi) + cz;
    }
    return sqrt(x * x + y * y + z * z) <= bailout;
}

static double bulb_de_double(const double c[3], double power, double bailout, int iterations)
{
    double x = c[0], y = c[1], z = c[2], dr = 1, r = sqrt(x * x + y * y + z * z);
    for (int i = 0; i < iterations; i++) {
        r = sqrt(x * x + y * y + z * z);
        if (r > bailout)
            break;
        double theta = r > 0 ? acos(y / r) : 0, phi = (x != 0 || z != 0) ? atan2(z, x) : 0;
        double rho = sqrt(x * x + z * z), stretch = rho > 1e-6 * r ? fabs(sin(power * atan2(rho, y))) * r / rho : power;
        dr = power * pow(r, power - 1) * fmax(1, stretch) * dr + 1; /* the azimuthal stretch: mandelbulb.glsl */
        double rn = pow(r, power);
        x = rn * sin(power * theta) * cos(power * phi) + c[0];
        y = rn * cos(power * theta) + c[1];
        z = rn * sin(power * theta) * sin(power * phi) + c[2];
    }
    r = sqrt(x * x + y * y + z * z);
    return r > bailout ? 0.5 * log(r) * r / dr : 0; /* an orbit still bounded is inside (fractal/iterate.glsl) */
}

static void mandelbulb_bound(void **st)
{
    (void)st;
    enum { G = 120, SAMPLES = 600 };
    const double lo = -1.3, h = 2.6 / (G - 1), power = 8, bailout = 2;
    const int iterations = 10;
    scene s;
    load_fractal("mandelbulb", "{\"power\": 8, \"iterations\": 10, \"bailout\": 2}",
                 "{\"step_factor\": 0.9}", &s);
    /* the set on a fine grid, in double; keep the inside points that have an outside neighbour */
    uint8_t *in = malloc((size_t)G * G * G);
    for (int i = 0; i < G; i++)
        for (int j = 0; j < G; j++)
            for (int k = 0; k < G; k++)
                in[((size_t)i * G + (size_t)j) * G + (size_t)k] = bulb_inside(lo + i * h, lo + j * h, lo + k * h, power, bailout, iterations);
    float (*edge)[3] = malloc(sizeof *edge * (size_t)G * G * G);
    int ne = 0;
    for (int i = 1; i < G - 1; i++)
        for (int j = 1; j < G - 1; j++)
            for (int k = 1; k < G - 1; k++) {
                size_t id = ((size_t)i * G + (size_t)j) * G + (size_t)k;
                if (in[id] && !(in[id - 1] && in[id + 1] && in[id - G] && in[id + G] && in[id - G * G] && in[id + G * G])) {
                    edge[ne][0] = (float)(lo + i * h), edge[ne][1] = (float)(lo + j * h), edge[ne][2] = (float)(lo + k * h);
                    ne++;
                }
            }
    static float pts[SAMPLES * 3], de[SAMPLES * 2];
    double dgrid[SAMPLES];
    int n = 0;
    while (n < SAMPLES) { /* points outside the set, from touching it to far away */
        double p[3] = {rnd(-1.6, 1.6), rnd(-1.6, 1.6), rnd(-1.6, 1.6)};
        if (bulb_inside(p[0], p[1], p[2], power, bailout, iterations))
            continue;
        double d = INFINITY;
        for (int e = 0; e < ne; e++) {
            double dx = p[0] - edge[e][0], dy = p[1] - edge[e][1], dz = p[2] - edge[e][2];
            d = fmin(d, dx * dx + dy * dy + dz * dz);
        }
        dgrid[n] = sqrt(d); /* an upper bound of the true distance: the grid point is in the set */
        for (int k = 0; k < 3; k++)
            pts[n * 3 + k] = (float)p[k];
        n++;
    }
    gl_probe(&s, NULL, pts, SAMPLES, de);
    double worst_ratio = 0, sf = s.quality.step_factor;
    for (int i = 0; i < SAMPLES; i++) {
        double step = sf * de[2 * i];
        if (step > dgrid[i] + 1e-4)
            fail_msg("point %d: a step of %.5f (estimate %.5f × %.2f) would pass the set at %.5f", i, step,
                     (double)de[2 * i], sf, dgrid[i]);
        if (dgrid[i] > 4 * h)
            worst_ratio = fmax(worst_ratio, de[2 * i] / dgrid[i]);
    }
    fprintf(stderr, "mandelbulb: %d edge voxels (h = %.4f); the estimate reaches at most %.3f of the grid distance; "
            "step factor %.2f\n", ne, h, worst_ratio, sf);
    assert_true(ne > 10000);
    free(in);
    free(edge);
    scene_free(&s);
}

/* ---- Mandelbulb hard cases: the origin, the axes, the bailout sphere, large powers --------------- */

static void mandelbulb_hard_points(void **st)
{
    (void)st;
    static const double powers[] = {3, 5, 8, 16};
    enum { MAXP = 64 };
    for (size_t k = 0; k < sizeof powers / sizeof powers[0]; k++) {
        double pw = powers[k], bailout = 2, escape = bailout; /* mandelbulb.glsl's @escape */
        char fractal[160];
        /* a bound beyond the bailout sphere, so points on that sphere reach the estimate itself */
        snprintf(fractal, sizeof fractal, "{\"power\": %g, \"iterations\": 12, \"bailout\": %g, \"bound_radius\": 3}", pw, bailout);
        scene s;
        load_fractal("mandelbulb", fractal, "{}", &s);
        float pts[MAXP * 3];
        int n = 0;
        const double tiny[] = {0, 1e-30, 1e-20, 1e-7, 1e-3};
        for (size_t t = 0; t < sizeof tiny / sizeof tiny[0]; t++)
            for (int axis = 0; axis < 3; axis++) {
                pts[n * 3] = pts[n * 3 + 1] = pts[n * 3 + 2] = 0;
                pts[n * 3 + axis] = (float)tiny[t];
                n++;
            }
        const double along[] = {-1.5, -0.7, 0.3, 1.1, 2.0};
        for (size_t t = 0; t < sizeof along / sizeof along[0]; t++)
            for (int axis = 0; axis < 3; axis++) {
                pts[n * 3] = pts[n * 3 + 1] = pts[n * 3 + 2] = 0;
                pts[n * 3 + axis] = (float)along[t];
                n++;
            }
        for (int t = 0; t < 12; t++) { /* on the bailout sphere */
            double th = rnd(0, GLM_PI), ph = rnd(0, 2 * GLM_PI);
            pts[n * 3] = (float)(escape * sin(th) * cos(ph));
            pts[n * 3 + 1] = (float)(escape * cos(th));
            pts[n * 3 + 2] = (float)(escape * sin(th) * sin(ph));
            n++;
        }
        float de[MAXP * 2], unguarded[MAXP * 2];
        gl_probe(&s, NULL, pts, n, de);
        for (int i = 0; i < n; i++) {
            double p[3] = {pts[i * 3], pts[i * 3 + 1], pts[i * 3 + 2]};
            double want = bulb_de_double(p, pw, escape, 12);
            if (!isfinite(de[2 * i]))
                fail_msg("power %g, point (%g %g %g): estimate %g", pw, p[0], p[1], p[2], (double)de[2 * i]);
            /* On the bailout sphere the estimate jumps (escape now or one iteration later) and float
             * and double round to different sides: there only finite and outside are checked. */
            if (fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - escape) < 1e-5) {
                assert_true(de[2 * i] > 0);
                continue;
            }
            if (fabs(de[2 * i] - want) > 2e-3 * (1 + fabs(want)))
                fail_msg("power %g, point (%g %g %g): estimate %.6g, double precision %.6g", pw, p[0], p[1], p[2],
                         (double)de[2 * i], want);
        }
        assert_true(de[0] <= 0); /* the origin belongs to the set */
        /* In double precision 0/0 meets no clamp (llvmpipe's float clamp and atan happen to absorb it;
         * GLSL leaves both undefined): there the origin is NaN without the guards, inside with them. */
        scene d;
        snprintf(fractal, sizeof fractal, "{\"power\": %g, \"iterations\": 12, \"bailout\": %g, \"bound_radius\": 3, "
                 "\"precision\": \"double\"}", pw, bailout);
        load_fractal("mandelbulb", fractal, "{}", &d);
        render_set_origin((double[3]){0, 0, 0});
        gl_probe(&d, NULL, pts, n, de);
        assert_true(de[0] <= 0);
        gl_probe(&d, "#define BULB_GUARDS 0\n", pts, n, unguarded);
        assert_true(isnan(unguarded[0])); /* without the guards the origin is NaN */
        scene_free(&d);
        scene_free(&s);
    }
    fprintf(stderr, "mandelbulb: origin, axes and bailout sphere finite and matching double precision for powers "
            "3, 5, 8, 16; the origin is NaN without the guards\n");
}

/* ---- over-relaxation finds the same surfaces (its step counts are a measurement: see fathom bench) */

static void over_relaxation(void **st)
{
    (void)st;
    static float plain[W * H * AOV], relaxed[W * H * AOV];
    static const char *const names[] = {"menger", "mandelbulb"};
    for (int k = 0; k < 2; k++) {
    scene a, b;
    const char *sa[] = {"quality.spp=1"}, *sb[] = {"quality.spp=1", "quality.over_relax=1.6"};
    err_t e;
    assert_true(scene_load(names[k], sa, 1, &a, &e));
    assert_true(scene_load(names[k], sb, 2, &b, &e));
    camera cam = camera_look_at_deg(a.cam_position, a.cam_look_at, a.cam_fov_deg);
    draw(&a, &cam, W, H, 1, NULL, plain, NULL);
    draw(&b, &cam, W, H, 1, NULL, relaxed, NULL);
    double steps_a = 0, steps_b = 0, pa = camera_pixel_angle(&cam, H);
    int both = 0, differ = 0;
    for (int i = 0; i < W * H; i++) {
        steps_a += fabsf(plain[i * AOV + 4]);
        steps_b += fabsf(relaxed[i * AOV + 4]);
        float ta = plain[i * AOV + 3], tb = relaxed[i * AOV + 3];
        if (isinf(ta) != isinf(tb)) {
            differ++;
            continue;
        }
        if (isinf(ta))
            continue;
        both++;
        double eps = a.quality.hit_k * ta * pa;
        if (fabs(ta - tb) > 8 * eps && fabs(ta - tb) > 1e-3 * ta)
            differ++;
    }
    fprintf(stderr, "over-relaxation 1.6 on %s: mean steps %.1f → %.1f; %d of %d hit pixels differ\n",
            names[k], steps_a / (W * H), steps_b / (W * H), differ, both);
    assert_true(both > 1000);
    assert_true(differ <= both / 100);
    scene_free(&a);
    scene_free(&b);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(menger_exact),
        cmocka_unit_test(mandelbulb_bound),
        cmocka_unit_test(mandelbulb_hard_points),
        cmocka_unit_test(over_relaxation),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='far*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
