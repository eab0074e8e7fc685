/* The path tracer's lights seen through a BRDF, against quadratures of the model (the closed forms of
 * spheres, fog and droplets: test_pathtrace.c):
 *   - a disc light (radiance Le = E/Ω) reflected by a white metal, against a quadrature of the model's
 *     GGX BRDF over the disc: a near-mirror under a wide disc (found by the path's own sampling), the
 *     same when that sampled direction is never traced (bounces 0: next-event estimation must take
 *     the whole light), and a rough metal under a small disc (found by next-event estimation); the
 *     multiple importance weights must add to one, and each case's noise must be the good strategy's;
 *   - a pane of clear glass over a diffuse floor under a disc sun: shadow rays stop at glass, so the
 *     floor is lit only through the pane by sampled paths (a caustic): ρ/π · Le · ∫ cos θ (1 − R(θ))² dω;
 *   - a diffuse floor under a black cube-map sky with one bright square overhead, of radiance L:
 *     ρ/π · L · ∫ cos θ dω over the square, with the noise of a sky drawn from its own distribution;
 *     and a near-mirror reflecting such a square, against a quadrature of the BRDF over the filtered
 *     face, with the noise of the path's own samples.
 * Each fails when its physics is wrong: next-event estimation alone or the sampled paths alone for a
 * disc, weights that do not add to one, a last vertex weighted as if its direction were traced, a
 * caustic dropped, a sky sampled without the area-to-solid-angle factor, from the wrong faces, or by
 * the sampled paths alone. */
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

/* ---- disc lights: multiple importance sampling ----------------------------------------------------- */

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* A unit vector about n from local coordinates (any orthonormal frame: the integrals below do not
 * depend on it). */
static void about(const double n[3], double x, double y, double z, double out[3])
{
    double t[3] = {fabs(n[0]) < 0.9 ? 1 : 0, fabs(n[0]) < 0.9 ? 0 : 1, 0}, b[3];
    double d = dot3(t, n);
    for (int i = 0; i < 3; i++)
        t[i] -= d * n[i];
    double len = sqrt(dot3(t, t));
    for (int i = 0; i < 3; i++)
        t[i] /= len;
    b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
    for (int i = 0; i < 3; i++)
        out[i] = x * t[i] + y * b[i] + z * n[i];
}

/* The BRDF × cos of a white metal (F = 1, no diffuse) in the model (common/brdf.glsl, written here in
 * double): GGX D with α = r², Smith with Schlick-GGX G1, k = (r + 1)²/8: D G / (4 n·v). */
static double metal_f_cos(const double n[3], const double v[3], const double l[3], double r)
{
    double nl = dot3(n, l), nv = dot3(n, v);
    if (nl <= 0 || nv <= 0)
        return 0;
    double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]}, len = sqrt(dot3(h, h));
    double nh = dot3(n, h) / len, a2 = r * r * r * r, dd = nh * nh * (a2 - 1) + 1, k = (r + 1) * (r + 1) / 8;
    double D = a2 / (GLM_PI * dd * dd), G = nv / (nv * (1 - k) + k) * nl / (nl * (1 - k) + k);
    return D * G / (4 * nv);
}

/* ∫ over the disc (centre c, 1 − cos α = omc) of metal_f_cos dω, by the midpoint rule in (cos θ, φ)
 * about c: for a disc no wider than the BRDF's lobe. */
static double disc_integral(const double n[3], const double v[3], const double c[3], double omc, double r)
{
    enum { NT = 256, NP = 256 };
    double sum = 0;
    for (int i = 0; i < NT; i++)
        for (int j = 0; j < NP; j++) {
            double ct = 1 - (i + 0.5) / NT * omc, sn = sqrt(1 - ct * ct), ph = 2 * GLM_PI * (j + 0.5) / NP, l[3];
            about(c, sn * cos(ph), sn * sin(ph), ct, l);
            sum += metal_f_cos(n, v, l, r);
        }
    return sum * 2 * GLM_PI * omc / (NT * NP);
}

/* Radiance from a direction l: a function of l and its parameters. */
typedef struct sky_fn {
    double (*radiance)(const struct sky_fn *sky, const double l[3]);
    double c[3], omc;   /* a disc: its centre and 1 − cos α (radiance 1 inside) */
    const uint8_t *top; /* a cube map's top face (the others black): FACE × FACE grey texels */
    int face;
} sky_fn;

static double disc_radiance(const sky_fn *sky, const double l[3])
{
    double d[3] = {l[0] - sky->c[0], l[1] - sky->c[1], l[2] - sky->c[2]};
    return dot3(d, d) <= 2 * sky->omc;
}

/* ∫ metal_f_cos(l) · radiance(l) dω for a lobe far narrower than the sky's features: over half-vectors
 * drawn from D(h) (n·h) (u ↦ cos²θ_h = (1 − u)/(1 + (α² − 1)u)), where ∫ f cos L dω_l is the mean of
 * G (v·h) / (n·v n·h) · L(l) over l = reflect(−v, h). */
static double lobe_integral(const double n[3], const double v[3], double r, const sky_fn *sky)
{
    enum { NU = 1024, NP = 256 };
    double a2 = r * r * r * r, k = (r + 1) * (r + 1) / 8, nv = dot3(n, v), sum = 0;
    for (int i = 0; i < NU; i++) {
        double u = (i + 0.5) / NU, c2 = (1 - u) / (1 + (a2 - 1) * u), ch = sqrt(c2), sh = sqrt(1 - c2);
        for (int j = 0; j < NP; j++) {
            double ph = 2 * GLM_PI * (j + 0.5) / NP, h[3], l[3];
            about(n, sh * cos(ph), sh * sin(ph), ch, h);
            double vh = dot3(v, h);
            for (int q = 0; q < 3; q++)
                l[q] = 2 * vh * h[q] - v[q];
            double nl = dot3(n, l);
            if (vh <= 0 || nl <= 0)
                continue;
            double L = sky->radiance(sky, l);
            if (L > 0)
                sum += nv / (nv * (1 - k) + k) * nl / (nl * (1 - k) + k) * vh / (nv * ch) * L;
        }
    }
    return sum / ((double)NU * NP);
}

/* A white metal floor of the given roughness under a soft sun of irradiance E (a disc of angular
 * radius 1/(2k)) in the mirror direction of the view's centre, a black sky; the mean over every
 * third pixel of the rendered radiance against the quadrature, and the pixels' mean relative
 * standard error (from the variance AOV). */
static void metal_under_disc(double roughness, double softness, int bounces, int spp, bool narrow_lobe, double *got,
                             double *expect, double *rel_se, double *se_mean)
{
    const double E = 2, eye[3] = {0, 1, 2}, len = sqrt(5.0);
    const double c[3] = {0, 1 / len, -2 / len}, n[3] = {0, 1, 0};
    const double s = sin(0.25 / softness), omc = 2 * s * s, Le = E / (2 * GLM_PI * omc);
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"color\": [0, 0, 0], \"intensity\": 1},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [%.17g, %.17g, %.17g], \"color\": [1, 1, 1],"
             " \"intensity\": %g, \"shadow\": \"soft\", \"softness\": %g}],"
             " \"quality\": {\"preset\": \"final\", \"spp\": %d, \"integrator\": 1, \"bounces\": %d},"
             " \"materials\": {\"metal\": {\"base_color\": [1, 1, 1], \"metallic\": 1, \"roughness\": %g}},"
             " \"objects\": [{\"shape\": \"plane\", \"normal\": [0, 1, 0], \"material\": \"metal\"}]}",
             c[0], c[1], c[2], E, softness, spp, bounces, roughness);
    scene sc;
    load_text(json, NULL, 0, &sc);
    camera cam = cam_at(eye[0], eye[1], eye[2], 0, 0, 0, 8); /* a narrow view: every pixel's lobe in the disc */
    static float aov[PW * PH * AOV], rgba[PW * PH * 4];
    draw(&sc, &cam, PW, PH, spp, NULL, aov, rgba);
    int count = 0;
    *got = *expect = *rel_se = *se_mean = 0;
    for (int y = 1; y < PH; y += 3)
        for (int x = 1; x < PW; x += 3, count++) {
            dray ray = pixel_ray(&cam, x, y, PW, PH);
            double v[3] = {-ray.d[0], -ray.d[1], -ray.d[2]};
            sky_fn disc = {disc_radiance, {c[0], c[1], c[2]}, omc, NULL, 0};
            double f = narrow_lobe ? lobe_integral(n, v, roughness, &disc) : disc_integral(n, v, c, omc, roughness);
            const float *px = &rgba[(y * PW + x) * 4];
            *expect += Le * f;
            *got += px[0];
            float var = aov[(y * PW + x) * AOV + AOV_SLOT_VARIANCE];
            *rel_se += sqrt(fmax(var, 0)) / (Le * f);
            *se_mean += var;
        }
    *got /= count;
    *expect /= count;
    *rel_se /= count;
    *se_mean = sqrt(*se_mean) / count; /* the pixels are independent: the mean's standard error */
    fprintf(stderr, "metal of roughness %g under a disc of softness %g, bounces %d, %d spp: mean %.5f, expected "
            "%.5f (%+.2f %%, standard error %.5f); a pixel's relative standard error %.4f\n", roughness, softness,
            bounces, spp, *got, *expect, 100 * (*got - *expect) / *expect, *se_mean, *rel_se);
    scene_free(&sc);
}

/* Within five standard errors of the quadrature (which is good to 0.1 %), and a pixel's noise below
 * max_rel_se of its value. */
static void check_disc(double got, double expect, double se_mean, double rel_se, double max_rel_se)
{
    assert_true(fabs(got - expect) < 5 * se_mean + 1e-3 * expect);
    assert_true(rel_se < max_rel_se);
}

/* A near-mirror (roughness 0.1: a lobe about 0.02 rad wide) under a disc 1 rad across: next-event
 * estimation lands in the lobe about once in 2,000 samples (a pixel's relative error about 3 at 64
 * spp alone); the path's own samples land in the disc 9 times in 10 (the mixture's cosine share
 * misses the lobe). Measured: 0.03 % off, a pixel's relative standard error 0.046. */
static void glossy_metal_reflects_a_wide_disc(void **st)
{
    (void)st;
    double got, expect, rel_se, se;
    metal_under_disc(0.1, 1, 1, 64, true, &got, &expect, &rel_se, &se);
    check_disc(got, expect, se, rel_se, 0.1);
}

/* The same at bounces 0: the sampled direction is never traced, so next-event estimation must take
 * the whole light (weight 1), not its multiple-importance share (about 1e-4 here): noisy (a pixel's
 * relative error about 0.4 at 1024 spp), but unbiased. */
static void last_vertex_takes_the_whole_disc(void **st)
{
    (void)st;
    double got, expect, rel_se, se;
    metal_under_disc(0.1, 1, 0, 1024, true, &got, &expect, &rel_se, &se);
    check_disc(got, expect, se, rel_se, 1.0);
    assert_true(se < 0.1 * expect); /* precise enough to tell */
}

/* A rough metal (roughness 0.7) under a small disc (softness 8: 0.0625 rad): the path's own samples
 * land in the disc about once in 100 (a pixel's relative error about 1 at 64 spp alone); next-event
 * estimation finds it every time. Measured: 0.01 % off, relative standard error 0.006. */
static void rough_metal_under_a_small_disc(void **st)
{
    (void)st;
    double got, expect, rel_se, se;
    metal_under_disc(0.7, 8, 1, 64, false, &got, &expect, &rel_se, &se);
    check_disc(got, expect, se, rel_se, 0.1);
}

/* Unpolarized Fresnel reflectance of a dielectric (droplets paper; written afresh in double). */
static double fresnel(double cos_i, double eta)
{
    double s2 = eta * eta * (1 - cos_i * cos_i);
    if (s2 >= 1)
        return 1;
    double ct = sqrt(1 - s2), rs = (eta * cos_i - ct) / (eta * cos_i + ct), rp = (cos_i - eta * ct) / (cos_i + eta * ct);
    return 0.5 * (rs * rs + rp * rp);
}

/* A pane of clear glass (ior 1.5, 2 cm) 1 m over a diffuse floor, a disc sun (softness 4) in a black
 * sky, the camera between them. Shadow rays stop at glass, so the floor is lit only by paths that
 * leave it, cross the pane (its faces are parallel: directions keep) and run into the disc. With
 * bounces 3 a path has just the floor and the two faces: L = ρ/π · Le · ∫_disc cos θ (1 − R(θ))² dω. */
static void glass_pane_lets_the_sun_through(void **st)
{
    (void)st;
    enum { SPP = 256 };
    const double E = 3, softness = 4, len = sqrt(0.09 + 0.64 + 0.2704);
    const double c[3] = {0.3 / len, 0.8 / len, 0.52 / len}, s = sin(0.25 / softness), omc = 2 * s * s;
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"color\": [0, 0, 0], \"intensity\": 1},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [%.17g, %.17g, %.17g], \"color\": [1, 1, 1],"
             " \"intensity\": %g, \"shadow\": \"soft\", \"softness\": %g}],"
             " \"quality\": {\"preset\": \"final\", \"spp\": %d, \"integrator\": 1, \"bounces\": 3},"
             " \"materials\": {\"floor\": {\"base_color\": [%g, %g, %g], \"roughness\": 0.5, \"ior\": 1.0},"
             " \"glass\": {\"transmission\": 1, \"ior\": 1.5, \"roughness\": 0}},"
             " \"objects\": [{\"shape\": \"box\", \"size\": [40, 0.2, 40], \"position\": [0, -0.1, 0], \"material\": \"floor\"},"
             " {\"shape\": \"box\", \"size\": [40, 0.02, 40], \"position\": [0, 1.01, 0], \"material\": \"glass\"}]}",
             c[0], c[1], c[2], E, softness, SPP, RHO, RHO, RHO);
    scene sc;
    load_text(json, NULL, 0, &sc);
    camera cam = cam_at(0, 0.6, 0.8, 0, 0, 0, 40);
    static float rgba[PW * PH * 4];
    draw(&sc, &cam, PW, PH, SPP, NULL, NULL, rgba);
    /* the quadrature over the disc (its radiance Le = E/Ω) */
    enum { NT = 512, NP = 256 };
    double integral = 0;
    for (int i = 0; i < NT; i++)
        for (int j = 0; j < NP; j++) {
            double ct = 1 - (i + 0.5) / NT * omc, sn = sqrt(1 - ct * ct), ph = 2 * GLM_PI * (j + 0.5) / NP, l[3];
            about(c, sn * cos(ph), sn * sin(ph), ct, l);
            double R = fresnel(l[1], 1 / 1.5);
            integral += l[1] * (1 - R) * (1 - R);
        }
    integral *= 2 * GLM_PI * omc / (NT * NP);
    double expect = RHO / GLM_PI * E / (2 * GLM_PI * omc) * integral, got = 0;
    for (int i = 0; i < PW * PH; i++)
        got += rgba[i * 4];
    got /= PW * PH;
    /* a sample is ρ·Le·T or 0, the disc met with probability about cos θ·Ω/π: its standard error */
    double p = c[1] * 2 * omc, se = RHO * E / (2 * GLM_PI * omc) * sqrt(p * (1 - p) / ((double)SPP * PW * PH));
    fprintf(stderr, "glass pane: floor %.5f, expected %.5f (standard error %.5f)\n", got, expect, se);
    assert_true(expect > 0.1);
    assert_true(fabs(got - expect) < 5 * se);
    scene_free(&sc);
}

/* A cube-map sky, black but for a white square of texels [x0, x1) × [y0, y1) (columns, rows from the
 * top) on the top face of FACE × FACE texels; under it a floor of the given material at y = 0; the
 * environment's intensity is the square's radiance. Renders spp samples (bounces 2) from eye toward
 * the origin with the given fov; the square's face is kept in sky->top. */
enum { FACE = 64 };
static void under_sky_square(const char *material, int x0, int x1, int y0, int y1, double intensity, int spp,
                             const double eye[3], double fov, float *aov, float *rgba, uint8_t *top)
{
    char dir[] = "/tmp/fathom-sky-XXXXXX", faces[6][96];
    assert_non_null(mkdtemp(dir));
    static uint8_t px[FACE * FACE * 3];
    static const char *const NAMES[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    for (int f = 0; f < 6; f++) {
        memset(px, 0, sizeof px);
        for (int y = y0; f == 2 && y < y1; y++)
            memset(px + (y * FACE + x0) * 3, 255, (size_t)(x1 - x0) * 3);
        if (f == 2)
            for (int i = 0; i < FACE * FACE; i++)
                top[i] = px[i * 3];
        snprintf(faces[f], sizeof faces[f], "%s/%s.png", dir, NAMES[f]);
        err_t e;
        if (!image_write_u8(faces[f], FACE, FACE, 3, px, &e))
            fail_msg("%s", e.msg);
    }
    char json[2048];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"color\": [1, 1, 1], \"intensity\": %g, \"cubemap\": [\"%s\", "
             "\"%s\", \"%s\", \"%s\", \"%s\", \"%s\"]}, \"lights\": [],"
             " \"quality\": {\"preset\": \"final\", \"spp\": %d, \"integrator\": 1, \"bounces\": 2},"
             " \"materials\": {\"floor\": %s},"
             " \"objects\": [{\"shape\": \"box\", \"size\": [40, 0.2, 40], \"position\": [0, -0.1, 0], \"material\": \"floor\"}]}",
             intensity, faces[0], faces[1], faces[2], faces[3], faces[4], faces[5], spp, material);
    scene sc;
    load_text(json, NULL, 0, &sc);
    camera cam = cam_at(eye[0], eye[1], eye[2], 0, 0, 0, fov);
    draw(&sc, &cam, PW, PH, spp, NULL, aov, rgba);
    for (int f = 0; f < 6; f++)
        unlink(faces[f]);
    rmdir(dir);
    scene_free(&sc);
}

/* The top face's radiance toward world direction l as GL filters it (bilinear between texel centres,
 * clamped at the face's edge; the cube map's axes flip z: common/env.glsl), 0 off the top face. */
static double top_face_radiance(const sky_fn *sky, const double l[3])
{
    if (l[1] <= fabs(l[0]) || l[1] <= fabs(l[2]))
        return 0;
    double s = (l[0] / l[1] + 1) / 2, t = (-l[2] / l[1] + 1) / 2; /* +Y: sc = x, tc = z (cube axes) */
    double u = s * sky->face - 0.5, w = t * sky->face - 0.5;
    int i = (int)floor(u), j = (int)floor(w);
    double fu = u - i, fw = w - j, sum = 0;
    for (int dj = 0; dj <= 1; dj++)
        for (int di = 0; di <= 1; di++) {
            int x = i + di < 0 ? 0 : i + di >= sky->face ? sky->face - 1 : i + di;
            int y = j + dj < 0 ? 0 : j + dj >= sky->face ? sky->face - 1 : j + dj;
            sum += (di ? fu : 1 - fu) * (dj ? fw : 1 - fw) * sky->top[y * sky->face + x] / 255.0;
        }
    return sum;
}

/* A diffuse floor under a square of 8 × 8 texels on the top face, off its centre (face coordinates q
 * in [−1/8, 1/8] × [−3/8, −1/8]: a face turned or flipped would miss it), of radiance L = the intensity. On the top face at distance 1, cos θ dω = dq₁ dq₂ /
 * (1 + |q|²)², so the floor is ρ/π · L · ∫∫ over the square (bilinear filtering spreads each texel but
 * keeps its integral: the weight varies by 1e-4 over a texel). Drawn from the sky's own distribution
 * nearly every sample lands in the square; the floor's cosine samples land there once in 50 (a
 * pixel's relative error 0.36 at 64 spp alone; 0.056 measured with both). */
static void sky_square_over_a_diffuse_floor(void **st)
{
    (void)st;
    enum { SPP = 64 };
    const double intensity = 20, eye[3] = {0, 1, 1.5};
    const int x0 = 28, x1 = 36, y0 = 20, y1 = 28;
    char material[128];
    snprintf(material, sizeof material, "{\"base_color\": [%g, %g, %g], \"roughness\": 0.5, \"ior\": 1.0}", RHO, RHO, RHO);
    static float aov[PW * PH * AOV], rgba[PW * PH * 4];
    static uint8_t top[FACE * FACE];
    under_sky_square(material, x0, x1, y0, y1, intensity, SPP, eye, 40, aov, rgba, top);
    enum { N = 1000 };
    double integral = 0, h = 2.0 / FACE * (x1 - x0) / N; /* a square: the same step both ways */
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            double x = 2.0 * x0 / FACE - 1 + (i + 0.5) * h, y = 2.0 * y0 / FACE - 1 + (j + 0.5) * h, r2 = 1 + x * x + y * y;
            integral += h * h / (r2 * r2);
        }
    double expect = RHO / GLM_PI * intensity * integral, got = 0, var = 0, rel = 0;
    for (int i = 0; i < PW * PH; i++) {
        got += rgba[i * 4];
        var += aov[i * AOV + AOV_SLOT_VARIANCE];
        rel += sqrt(fmax(aov[i * AOV + AOV_SLOT_VARIANCE], 0)) / expect;
    }
    got /= PW * PH;
    rel /= PW * PH;
    double se = sqrt(var) / (PW * PH);
    fprintf(stderr, "sky square over a diffuse floor: %.5f, expected %.5f (%+.2f %%, standard error %.5f); a pixel's "
            "relative standard error %.4f\n", got, expect, 100 * (got - expect) / expect, se, rel);
    assert_true(fabs(got - expect) < 5 * se + 1e-3 * expect);
    assert_true(rel < 0.1);
}

/* A near-mirror metal (roughness 0.1) reflecting a square of 24 × 24 texels off the zenith, seen from
 * 8.5° off the vertical so that the mirror direction falls in it: the path's own GGX samples find it,
 * the sky's distribution mostly does not (its multiple-importance share must stay small), against the
 * GGX quadrature of the filtered face. */
static void sky_square_in_a_glossy_metal(void **st)
{
    (void)st;
    enum { SPP = 64 };
    const double intensity = 2, eye[3] = {0, 2, 0.3}, n[3] = {0, 1, 0};
    static float aov[PW * PH * AOV], rgba[PW * PH * 4];
    static uint8_t top[FACE * FACE];
    under_sky_square("{\"base_color\": [1, 1, 1], \"metallic\": 1, \"roughness\": 0.1}", 20, 44, 26, 50, intensity,
                     SPP, eye, 8, aov, rgba, top);
    camera cam = cam_at(eye[0], eye[1], eye[2], 0, 0, 0, 8);
    sky_fn sky = {top_face_radiance, {0, 0, 0}, 0, top, FACE};
    double got = 0, expect = 0, var = 0, rel = 0;
    int count = 0;
    for (int y = 1; y < PH; y += 3)
        for (int x = 1; x < PW; x += 3, count++) {
            dray ray = pixel_ray(&cam, x, y, PW, PH);
            double v[3] = {-ray.d[0], -ray.d[1], -ray.d[2]};
            double e = intensity * lobe_integral(n, v, 0.1, &sky);
            float pv = aov[(y * PW + x) * AOV + AOV_SLOT_VARIANCE];
            expect += e;
            got += rgba[(y * PW + x) * 4];
            var += pv;
            rel += sqrt(fmax(pv, 0)) / e;
        }
    got /= count;
    expect /= count;
    rel /= count;
    double se = sqrt(var) / count;
    fprintf(stderr, "sky square in a glossy metal: %.5f, expected %.5f (%+.2f %%, standard error %.5f); a pixel's "
            "relative standard error %.4f\n", got, expect, 100 * (got - expect) / expect, se, rel);
    assert_true(fabs(got - expect) < 5 * se + 1e-3 * expect);
    assert_true(rel < 0.1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(glossy_metal_reflects_a_wide_disc),
        cmocka_unit_test(last_vertex_takes_the_whole_disc),
        cmocka_unit_test(rough_metal_under_a_small_disc),
        cmocka_unit_test(glass_pane_lets_the_sun_through),
        cmocka_unit_test(sky_square_over_a_diffuse_floor),
        cmocka_unit_test(sky_square_in_a_glossy_metal),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='glass*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
