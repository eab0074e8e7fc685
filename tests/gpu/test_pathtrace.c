/* The path tracer (quality.integrator = 1, shaders/common/pathtrace.glsl) against closed forms, for lights
 * and media (discs and skies through a BRDF: test_pathtrace_lights.c):
 *   - the white furnace: a diffuse sphere of albedo ρ (ior 1: no specular) under a uniform sky of
 *     radiance L is ρL at every pixel, exactly, however it is sampled;
 *   - Lambert: the same sphere under a sun of irradiance E in a black sky is ρ/π · E · max(0, n·l);
 *   - a point light of intensity I at distance d: ρ/π · I/d² · max(0, n·l);
 *   - a glass slab (ior 1.5, Beer absorption e^(−σ d) = 1/2) seen at normal incidence under a uniform
 *     sky: R + (1−R)² R a² / (1 − R² a²) + (1−R)² a / (1 − R² a²), all its internal reflections;
 *   - the slab's Monte Carlo error falls as 1/√spp (16 against 256 samples: 4×), and the variance AOV
 *     predicts it (its mean over the image against the measured squared error);
 *   - a diffuse floor under an emissive sphere: ρ · Le · (r/d)² · cos θ, reached only by sampling.
 *   - a soft sun (a disc of angular radius α = 1/(2k)) on the sphere, where all the disc is above the
 *     horizon: ρ/π · E · cos θ · (1 + cos α)/2 (the mean of n·ω over the disc's cone);
 *   - height fog as a pure absorber (albedo 0) under a uniform sky: L · e^(−τ) along each pixel's
 *     ray, τ the closed-form optical depth;
 *   - height fog's single scattering of a sun (bounces 0, black sky), against a quadrature of
 *     ∫ σ(t) e^(−τ(0,t)) · ρ E/(4π) · e^(−τ_sun(t)) dt along the pixel's ray.
 *   - droplets: a clear droplet under a uniform sky loses and gains nothing (every pixel is the sky,
 *     however its paths split), and an absorbing one seen through its centre is C (R + (1−R)² a / (1 − R a)
 *     ...) with a = e^(−σ 2r), all its internal reflections, as the slab.
 * Each fails when its physics is wrong: no Beer, no Fresnel split, a 1/d falloff, a BRDF without 1/π,
 * a point sun for a soft one, a free flight that ignores the fog's height (c = 0), an unshadowed or
 * 1/(2π) phase. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "data/media/image_io.h"
#include "gltest.h"

enum { PW = 48, PH = 27 };

static const double RHO = 0.6;

/* a sphere of albedo RHO and ior 1 (no specular) at the origin, with the given sky and lights */
static void sphere_scene(const char *env, const char *lights, int spp, scene *s)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"color\": [%s], \"intensity\": 1}, \"lights\": [%s],"
             " \"quality\": {\"preset\": \"final\", \"spp\": %d, \"integrator\": 1, \"bounces\": 8},"
             " \"materials\": {\"white\": {\"base_color\": [%g, %g, %g], \"roughness\": 0.5, \"ior\": 1.0}},"
             " \"objects\": [{\"shape\": \"sphere\", \"radius\": 1, \"material\": \"white\"}]}",
             env, lights, spp, RHO, RHO, RHO);
    load_text(json, NULL, 0, s);
}

/* Pixels whose 3x3 block all hit: their centre sample's normal is the whole pixel's. */
static bool inside(const float *aov, int x, int y)
{
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= PW || yy >= PH || !isfinite(aov[(yy * PW + xx) * AOV + AOV_SLOT_DEPTH]))
                return false;
        }
    return true;
}

static void white_furnace(void **st)
{
    (void)st;
    scene s;
    sphere_scene("1, 1, 1", "", 4, &s);
    camera cam = cam_at(0, 0, 4, 0, 0, 0, 40);
    static float aov[PW * PH * AOV], rgba[PW * PH * 4];
    draw(&s, &cam, PW, PH, 4, NULL, aov, rgba);
    int n = 0;
    double worst = 0;
    for (int y = 0; y < PH; y++)
        for (int x = 0; x < PW; x++)
            if (inside(aov, x, y)) {
                for (int c = 0; c < 3; c++)
                    worst = fmax(worst, fabs(rgba[(y * PW + x) * 4 + c] - RHO));
                n++;
            }
    fprintf(stderr, "white furnace: %d pixels, worst |L - rho L| %.2g\n", n, worst);
    assert_true(n > 200);
    assert_true(worst < 1e-5);
    scene_free(&s);
}

/* Every lit pixel against its closed form, from its own normal (and position, for a point light). */
static void lambert_check(const char *lights, const double *light, bool point, double power, int spp,
                          double min_cos, double tolerance)
{
    scene s;
    sphere_scene("0, 0, 0", lights, spp, &s);
    camera cam = cam_at(0.5, 0.8, 4, 0, 0, 0, 40);
    static float aov[PW * PH * AOV], rgba[PW * PH * 4];
    draw(&s, &cam, PW, PH, spp, NULL, aov, rgba);
    int n = 0;
    double worst = 0, mean = 0;
    for (int y = 0; y < PH; y++)
        for (int x = 0; x < PW; x++) {
            const float *a = &aov[(y * PW + x) * AOV];
            if (spp == 1 ? !isfinite(a[AOV_SLOT_DEPTH]) : !inside(aov, x, y)) /* jittered: not on the outline */
                continue;
            dray r = pixel_ray(&cam, x, y, PW, PH);
            double p[3], l[3], d2 = 1, len = 0;
            for (int i = 0; i < 3; i++) {
                p[i] = r.o[i] + r.d[i] * a[AOV_SLOT_DEPTH];
                l[i] = point ? light[i] - p[i] : light[i];
                len += l[i] * l[i];
            }
            if (point)
                d2 = len;
            len = sqrt(len);
            double cosl = (a[0] * l[0] + a[1] * l[1] + a[2] * l[2]) / len;
            if (cosl < min_cos) /* the terminator: shadow rays start off the surface there */
                continue;
            double expect = RHO / GLM_PI * power / d2 * cosl, got = rgba[(y * PW + x) * 4];
            worst = fmax(worst, fabs(got - expect) / expect);
            mean += (got - expect) / expect;
            n++;
        }
    mean /= n > 0 ? n : 1;
    fprintf(stderr, "%s: %d lit pixels, worst relative error %.2g, mean %.2g\n", point ? "point light" : "sun", n,
            worst, mean);
    assert_true(n > 100);
    assert_true(worst < tolerance);
    assert_true(fabs(mean) < tolerance / 4); /* a bias, not noise: a point sun for a soft one is 6.5 % */
    scene_free(&s);
}

static void lambert_sun(void **st)
{
    (void)st;
    double d[3] = {0.3, 0.8, 0.52}, len = sqrt(0.09 + 0.64 + 0.2704);
    for (int i = 0; i < 3; i++)
        d[i] /= len;
    char lights[256];
    snprintf(lights, sizeof lights,
             "{\"type\": \"directional\", \"direction\": [%.17g, %.17g, %.17g], \"color\": [1, 1, 1], "
             "\"intensity\": 3, \"shadow\": \"hard\"}", d[0], d[1], d[2]);
    lambert_check(lights, d, false, 3, 1, 0.1, 2e-3);
}

/* softness k = 1: a disc of angular radius 0.5 rad, whose whole cone is above the horizon where
 * cos θ > sin 0.5; the pixel's mean over 1024 directions (a cosine's spread over the cone is < 0.5 of
 * its mean there: standard error < 1.6 %, the mean of many pixels far less) */
static void soft_sun_is_a_disc(void **st)
{
    (void)st;
    double d[3] = {0.3, 0.8, 0.52}, len = sqrt(0.09 + 0.64 + 0.2704), alpha = 0.5;
    for (int i = 0; i < 3; i++)
        d[i] /= len;
    char lights[256];
    snprintf(lights, sizeof lights,
             "{\"type\": \"directional\", \"direction\": [%.17g, %.17g, %.17g], \"color\": [1, 1, 1], "
             "\"intensity\": 3, \"shadow\": \"soft\", \"softness\": 1}", d[0], d[1], d[2]);
    lambert_check(lights, d, false, 3 * (1 + cos(alpha)) / 2, 1024, sin(alpha) + 0.05, 0.06);
}

static void point_light_falloff(void **st)
{
    (void)st;
    const double q[3] = {1.5, 2.0, 2.5};
    lambert_check("{\"type\": \"point\", \"position\": [1.5, 2.0, 2.5], \"color\": [1, 1, 1], \"intensity\": 20, "
                  "\"shadow\": \"hard\"}", q, true, 20, 1, 0.1, 2e-3);
}

/* The slab's pixels at spp samples: their mean and their RMSE against the closed form. */
static void slab(int spp, double expect, double *mean, double *rmse, double *variance)
{
    const double thick = 0.1, sigma = log(2.0) / thick;
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1}, \"lights\": [],"
             " \"quality\": {\"preset\": \"final\", \"spp\": %d, \"integrator\": 1, \"bounces\": 16},"
             " \"materials\": {\"glass\": {\"transmission\": 1, \"ior\": 1.5, \"roughness\": 0,"
             " \"absorption\": [%.17g, %.17g, %.17g]}},"
             " \"objects\": [{\"shape\": \"box\", \"size\": [20, 20, %g], \"material\": \"glass\"}]}",
             spp, sigma, sigma, sigma, thick);
    scene s;
    load_text(json, NULL, 0, &s);
    camera cam = cam_at(0, 0, 3, 0, 0, 0, 4); /* a narrow view: every ray within 2.3° of the normal */
    static float rgba[PW * PH * 4], aov[PW * PH * AOV];
    draw(&s, &cam, PW, PH, spp, NULL, aov, rgba);
    double sum = 0, sq = 0, var = 0;
    for (int i = 0; i < PW * PH; i++) {
        sum += rgba[i * 4];
        sq += (rgba[i * 4] - expect) * (rgba[i * 4] - expect);
        var += aov[i * AOV + AOV_SLOT_VARIANCE];
        assert_int_equal((int)aov[i * AOV + AOV_SLOT_SAMPLES], spp);
    }
    *mean = sum / (PW * PH);
    *rmse = sqrt(sq / (PW * PH));
    *variance = var / (PW * PH);
    scene_free(&s);
}

static void glass_slab_and_convergence(void **st)
{
    (void)st;
    const double R = 0.04, a = 0.5, k = 1 - R * R * a * a; /* ((1.5 - 1) / (1.5 + 1))² */
    const double expect = R + (1 - R) * (1 - R) * R * a * a / k + (1 - R) * (1 - R) * a / k;
    double m16, e16, m256, e256, v16, v256;
    slab(16, expect, &m16, &e16, &v16);
    slab(256, expect, &m256, &e256, &v256);
    /* a path's value is 1, a, a^3...: its standard deviation is below 0.5, and 1296 pixels average */
    double se = 0.5 / sqrt(256.0 * PW * PH);
    fprintf(stderr, "glass slab: expected %.5f, mean %.5f at 256 spp (standard error < %.5f); pixel RMSE %.4f at 16 "
            "spp, %.4f at 256: ratio %.2f (1/sqrt(spp): 4)\n", expect, m256, se, e16, e256, e16 / e256);
    assert_true(fabs(m256 - expect) < 5 * se);
    assert_true(e16 / e256 > 3.0 && e16 / e256 < 5.3);
    /* the variance AOV is each pixel's own estimate of its mean's squared error: over the image it
     * must agree with the error measured against the closed form (the estimate is unbiased) */
    fprintf(stderr, "variance AOV: mean %.3g at 16 spp (measured squared error %.3g), %.3g at 256 (%.3g)\n", v16,
            e16 * e16, v256, e256 * e256);
    assert_true(v16 / (e16 * e16) > 0.85 && v16 / (e16 * e16) < 1.15);
    assert_true(v256 / (e256 * e256) > 0.85 && v256 / (e256 * e256) < 1.15);
}

/* A diffuse floor below an emissive sphere (radiance Le, radius r, centre c) in a black sky: the
 * floor's light comes only through the sampled directions, so this checks the sampling's density, which
 * the furnace cannot (there every direction weighs the same). A sphere subtends a cap of sin²α = r²/d²
 * of the projected hemisphere: L = ρ · Le · (r/d)² · cos θ, θ the centre's angle from the normal. */
static void emitter_through_sampling(void **st)
{
    (void)st;
    const double Le = 4, r = 0.5, c[3] = {0, 1.2, 0};
    /* a secondary ray hits within hit_k footprints of its whole path's length, which grows the lamp
     * (hit_k 1 at 4 m: 5 cm on a 50 cm radius, 10 % more light): a tight threshold keeps that small */
    const double hit_k = 0.01;
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"color\": [0, 0, 0], \"intensity\": 1}, \"lights\": [],"
             " \"quality\": {\"preset\": \"reference\", \"spp\": 1, \"integrator\": 1, \"bounces\": 4, \"hit_k\": %g},"
             " \"materials\": {\"floor\": {\"base_color\": [%g, %g, %g], \"roughness\": 0.5, \"ior\": 1.0},"
             " \"lamp\": {\"base_color\": [0, 0, 0], \"ior\": 1.0, \"emission\": [%g, %g, %g]}},"
             " \"objects\": [{\"shape\": \"box\", \"size\": [40, 0.2, 40], \"position\": [0, -0.1, 0], \"material\": \"floor\"},"
             " {\"shape\": \"sphere\", \"radius\": %g, \"position\": [%g, %g, %g], \"material\": \"lamp\"}]}",
             hit_k, RHO, RHO, RHO, Le, Le, Le, r, c[0], c[1], c[2]);
    scene s;
    load_text(json, NULL, 0, &s);
    camera cam = cam_at(0, 2.5, 3.5, 0, 0, 0.3, 40);
    enum { SPP = 256 };
    static float aov[PW * PH * AOV], rgba[PW * PH * 4];
    draw(&s, &cam, PW, PH, SPP, NULL, aov, rgba);
    double got = 0, expect = 0;
    int n = 0;
    for (int y = 0; y < PH; y++)
        for (int x = 0; x < PW; x++) {
            const float *a = &aov[(y * PW + x) * AOV];
            if (!inside(aov, x, y) || a[1] < 0.999) /* the floor's pixels, away from the lamp's outline */
                continue;
            dray ray = pixel_ray(&cam, x, y, PW, PH);
            double p[3], d2 = 0;
            for (int i = 0; i < 3; i++) {
                p[i] = ray.o[i] + ray.d[i] * a[AOV_SLOT_DEPTH];
                d2 += (c[i] - p[i]) * (c[i] - p[i]);
            }
            expect += RHO * Le * r * r / d2 * (c[1] - p[1]) / sqrt(d2);
            got += rgba[(y * PW + x) * 4];
            n++;
        }
    /* each sample is 0 or ρ·Le: a Bernoulli of mean expect/(ρ Le); the sum's standard error */
    double q = expect / n / (RHO * Le), se = RHO * Le * sqrt(q * (1 - q) / ((double)SPP * n));
    fprintf(stderr, "lamp over a floor: %d pixels, mean %.5f, expected %.5f (standard error %.5f)\n", n, got / n,
            expect / n, se);
    assert_true(n > 300);
    assert_true(fabs(got / n - expect / n) < 5 * se);
    scene_free(&s);
}

/* Height fog σ(y) = σ0 e^(−b y) (fog height 0): the optical depth from height oy along direction dy
 * over s, in closed form (the integral of the definition, written here afresh). */
static const double FOG_S0 = 0.05, FOG_B = 0.1, FOG_MAX = 2000;

static double fog_tau(double oy, double dy, double s)
{
    double c = FOG_B * dy;
    return fabs(c) < 1e-12 ? FOG_S0 * exp(-FOG_B * oy) * s : FOG_S0 * exp(-FOG_B * oy) * (1 - exp(-c * s)) / c;
}

/* fog of the given albedo, a sky, lights, no object in view (a small sphere far below) */
static void fog_scene(const char *albedo, const char *sky, const char *lights, int spp, int bounces, scene *s)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"color\": [%s], \"intensity\": 1}, \"lights\": [%s],"
             " \"fog\": {\"color\": [%s], \"density\": %g, \"falloff\": %g, \"height\": 0},"
             " \"quality\": {\"preset\": \"final\", \"spp\": %d, \"integrator\": 1, \"bounces\": %d, \"max_dist\": %g},"
             " \"materials\": {\"white\": {\"base_color\": [0.5, 0.5, 0.5]}},"
             " \"objects\": [{\"shape\": \"sphere\", \"radius\": 1, \"position\": [0, -500, 0], \"material\": \"white\"}]}",
             sky, lights, albedo, FOG_S0, FOG_B, spp, bounces, FOG_MAX);
    load_text(json, NULL, 0, s);
}

/* A pure absorber: each sample is 1 (escaped) or 0 (absorbed), so the image's mean has a binomial
 * standard error; the expected mean is each pixel's e^(−τ) to the end of the march. */
static void fog_absorbs_by_its_optical_depth(void **st)
{
    (void)st;
    enum { SPP = 16 };
    scene s;
    fog_scene("0, 0, 0", "1, 1, 1", "", SPP, 4, &s);
    camera cam = cam_at(0, 0, 0, 0, 0.5, -0.8660254037844386, 20); /* 30° up: τ ≈ σ0 / (b sin 30°) = 1 */
    static float rgba[PW * PH * 4];
    draw(&s, &cam, PW, PH, SPP, NULL, NULL, rgba);
    double got = 0, expect = 0;
    for (int y = 0; y < PH; y++)
        for (int x = 0; x < PW; x++) {
            dray r = pixel_ray(&cam, x, y, PW, PH);
            expect += exp(-fog_tau(r.o[1], r.d[1], FOG_MAX));
            got += rgba[(y * PW + x) * 4 + 1];
        }
    int n = PW * PH;
    double q = expect / n, se = sqrt(q * (1 - q) / ((double)SPP * n));
    fprintf(stderr, "fog as an absorber: mean %.5f, expected %.5f (standard error %.5f)\n", got / n, q, se);
    assert_true(fabs(got / n - q) < 5 * se);
    scene_free(&s);
}

/* Single scattering of a sun of irradiance E (bounces 0: the path ends at its first event, lit by
 * next-event estimation only) against a quadrature along each of a few pixels' rays. */
static void fog_single_scattering_of_a_sun(void **st)
{
    (void)st;
    enum { SPP = 256 };
    const double rho = 0.8, E = 5, l[3] = {0, 0.6, 0.8};
    char lights[256];
    snprintf(lights, sizeof lights, "{\"type\": \"directional\", \"direction\": [%g, %g, %g], \"color\": [1, 1, 1], "
             "\"intensity\": %g, \"shadow\": \"hard\"}", l[0], l[1], l[2], E);
    scene s;
    fog_scene("0.8, 0.8, 0.8", "0, 0, 0", lights, SPP, 0, &s);
    camera cam = cam_at(0, 2, 0, 10, 1, 0, 30); /* a little downhill, into denser fog */
    static float rgba[PW * PH * 4];
    draw(&s, &cam, PW, PH, SPP, NULL, NULL, rgba);
    double got = 0, expect = 0;
    int n = 0;
    for (int y = 0; y < PH; y += 3)
        for (int x = 0; x < PW; x += 3, n++) {
            dray r = pixel_ray(&cam, x, y, PW, PH);
            /* the midpoint rule in t, 20000 steps over the march's 2000 m (the integrand's scale is 1/σ ≈ 20 m) */
            const int N = 20000;
            double h = FOG_MAX / N, sum = 0;
            for (int i = 0; i < N; i++) {
                double t = (i + 0.5) * h, y1 = r.o[1] + r.d[1] * t;
                double sigma = FOG_S0 * exp(-FOG_B * y1);
                sum += sigma * exp(-fog_tau(r.o[1], r.d[1], t)) * exp(-fog_tau(y1, l[1], FOG_MAX)) * h;
            }
            expect += rho * E / (4 * GLM_PI) * sum;
            got += rgba[(y * PW + x) * 4];
        }
    /* each sample's value varies with where it scatters; the mean of n pixels of 256 samples each is
     * within 1 % (measured spread: 0.1 %) */
    fprintf(stderr, "fog single scattering: mean %.5f, expected %.5f\n", got / n, expect / n);
    assert_true(expect / n > 0.01);
    assert_true(fabs(got - expect) / expect < 0.01);
    scene_free(&s);
}

/* One droplet (x, y, z, r) in a csg scene under a uniform sky of colour sky, the liquid absorbing
 * `absorption` per metre; an object past max_dist (100 m: a csg scene needs one, no path may meet it). */
static char drop_csv[64];
static void droplet_under_sky(const double drop[4], const char *absorption, const char *sky, int spp, scene *s)
{
    snprintf(drop_csv, sizeof drop_csv, "/tmp/fathom-pt-drop-XXXXXX");
    int fd = mkstemp(drop_csv);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fprintf(f, "x,y,z,r\n%.9g,%.9g,%.9g,%.9g\n", drop[0], drop[1], drop[2], drop[3]);
    fclose(f);
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"color\": [%s], \"intensity\": 1}, \"lights\": [],"
             " \"quality\": {\"preset\": \"reference\", \"spp\": %d, \"integrator\": 1, \"bounces\": 8},"
             " \"materials\": {\"a\": {}}, \"objects\": [{\"shape\": \"sphere\", \"radius\": 0.1, \"position\": [0, 500, 0],"
             " \"material\": \"a\"}], \"droplets\": {\"file\": \"%s\", \"absorption\": [%s]}}",
             sky, spp, drop_csv, absorption);
    load_text(json, NULL, 0, s);
}

/* A clear droplet under a white sky: every path ends in the sky with its weight whole (reflect or
 * refract is drawn by the Fresnel split, not weighted by it), so every pixel is 1, droplet or not. */
static void clear_droplet_under_a_white_sky(void **st)
{
    (void)st;
    const double drop[4] = {0, 1, 0, 0.25};
    scene s;
    droplet_under_sky(drop, "0, 0, 0", "1, 1, 1", 8, &s);
    camera cam = cam_at(0, 1, -0.6, 0, 1, 0, 50);
    static float aov[PW * PH * AOV], rgba[PW * PH * 4];
    draw(&s, &cam, PW, PH, 8, NULL, aov, rgba);
    unlink(drop_csv);
    int on = 0;
    double worst = 0;
    for (int i = 0; i < PW * PH; i++) {
        on += isfinite(aov[i * AOV + AOV_SLOT_DEPTH]);
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fabs(rgba[i * 4 + c] - 1));
    }
    fprintf(stderr, "clear droplet under a white sky: %d of %d pixels on the droplet, worst |L - 1| %.2g\n", on,
            PW * PH, worst);
    assert_true(on > PW * PH / 4);
    assert_true(worst < 1e-5);
    scene_free(&s);
}

/* An absorbing droplet (radius r, σ per metre) under a sky of colour C, through its centre at normal
 * incidence: every internal reflection runs along the diameter, so as for the slab
 * L = C (R + (1−R)² R a² / (1 − R² a²) + (1−R)² a / (1 − R² a²)), a = e^(−σ 2r), R = ((n−1)/(n+1))². */
static void droplet_centre_against_the_closed_form(void **st)
{
    (void)st;
    enum { SPP = 1024, S = 9 };
    const double drop[4] = {0, 1, 0, 0.25}, sigma[3] = {0.5, 2, 8}, C[3] = {0.8, 0.6, 0.4};
    scene s;
    droplet_under_sky(drop, "0.5, 2, 8", "0.8, 0.6, 0.4", SPP, &s);
    camera cam = cam_at(0, 1, -2, 0, 1, 0, 0.5); /* a narrow view: every ray within 0.25° of the axis */
    static float aov[S * S * AOV], rgba[S * S * 4];
    draw(&s, &cam, S, S, SPP, NULL, aov, rgba);
    unlink(drop_csv);
    double n = s.droplets.ior, R = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
    for (int c = 0; c < 3; c++) {
        double a = exp(-sigma[c] * 2 * drop[3]), k = 1 - R * R * a * a;
        double want = C[c] * (R + (1 - R) * (1 - R) * R * a * a / k + (1 - R) * (1 - R) * a / k), got = 0, var = 0;
        for (int i = 0; i < S * S; i++) {
            got += rgba[i * 4 + c];
            var += aov[i * AOV + AOV_SLOT_VARIANCE + c];
        }
        got /= S * S;
        double se = sqrt(var) / (S * S);
        fprintf(stderr, "droplet centre, channel %d: %.5f, closed form %.5f (standard error %.5f)\n", c, got, want, se);
        assert_true(fabs(got - want) < 5 * se + 1e-4);
    }
    assert_true(fabs(aov[(S / 2 * S + S / 2) * AOV + AOV_SLOT_DEPTH] - (2 - drop[3])) < 1e-4); /* the droplet's front */
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(white_furnace),
        cmocka_unit_test(lambert_sun),
        cmocka_unit_test(point_light_falloff),
        cmocka_unit_test(soft_sun_is_a_disc),
        cmocka_unit_test(fog_absorbs_by_its_optical_depth),
        cmocka_unit_test(fog_single_scattering_of_a_sun),
        cmocka_unit_test(glass_slab_and_convergence),
        cmocka_unit_test(emitter_through_sampling),
        cmocka_unit_test(clear_droplet_under_a_white_sky),
        cmocka_unit_test(droplet_centre_against_the_closed_form),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='glass*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
