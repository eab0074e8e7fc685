/* Shading against closed forms in double: a point light's radiance albedo/π · I · cos θ / d², the
 * specular lobe against the PBR lecture's D · G · F / (4 cos θ), the constant ambient as the sky's mean,
 * a glass sphere's refraction by Snell's law and its radiance, Fresnel on mirrors, and a lit plane
 * without self-shadowing acne. */
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
#include <epoxy/gl.h>

#include "check.h"
#include "cli/cli.h"
#include "gpu/gpu.h"
#include "data/media/image_io.h"
#include "jobs/capture/offline.h"
#include "reference.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "gpu/render_resource.h"
#include "scene/scene.h"

#include "gltest.h"

/* ---- refraction: a ray through a glass sphere leaves where Snell's law says --------------------- */

static void glass_sphere_snell(void **st)
{
    (void)st;
    static const char json[] =
        "{\"program\": \"csg\", \"environment\": {\"color\": [0.5, 0.5, 0.5]},"
        " \"quality\": {\"preset\": \"reference\", \"spp\": 1, \"hit_k\": 0.02},"
        " \"materials\": {\"glass\": {\"transmission\": 1, \"ior\": 1.5, \"roughness\": 0}},"
        " \"objects\": [{\"shape\": \"sphere\", \"radius\": 1, \"material\": \"glass\"}]}";
    scene s;
    load_text(json, NULL, 0, &s);
    camera cam = cam_at(0.3, 0.2, 4.0, 0, 0, 0, 40);
    static float aov[W * H * AOV];
    draw(&s, &cam, W, H, 1, NULL, aov, NULL);
    const double c[3] = {0, 0, 0}, ior = 1.5, pixel_angle = camera_pixel_angle(&cam, H);
    int checked = 0, straight = 0;
    double worst = 0, max_bend = 0;
    for (int row = 0; row < H; row++)
        for (int x = 0; x < W; x++) {
            dray r = pixel_ray(&cam, x, row, W, H);
            const float *a = &aov[(row * W + x) * AOV];
            double exit_dir[3] = {a[5], a[6], a[7]};
            dinterval in = ref_sphere(&r, c, 1.0);
            if (!in.hit) {
                /* a miss leaves along the camera ray itself */
                bool far = true;
                double oc = -ref_dot(r.o, r.d), d2 = ref_dot(r.o, r.o) - oc * oc;
                far = sqrt(d2) > 1.0 + 3 * 4.0 * pixel_angle;
                if (far) {
                    assert_near(ref_dot(exit_dir, r.d), 1.0, 1e-5);
                    straight++;
                }
                continue;
            }
            double cosv = -ref_dot(r.d, in.n0);
            if (cosv < 0.3)
                continue;
            /* enter: air → glass; cross; leave: glass → air, the normal turned to face the ray */
            dray inside;
            for (int i = 0; i < 3; i++)
                inside.o[i] = r.o[i] + r.d[i] * in.t0;
            assert_true(ref_refract(r.d, in.n0, 1.0 / ior, inside.d));
            dinterval out = ref_sphere(&inside, c, 1.0);
            double n_exit[3] = {-out.n1[0], -out.n1[1], -out.n1[2]}, want[3];
            assert_true(ref_refract(inside.d, n_exit, ior, want)); /* a sphere never traps light by TIR */
            double angle = acos(fmin(1.0, ref_dot(exit_dir, want) / sqrt(ref_dot(exit_dir, exit_dir))));
            double eps = s.quality.hit_k * in.t0 * pixel_angle;
            double tol = 2e-3 + 8.0 * eps / cosv; /* the entry point is off by up to eps/cos */
            if (angle > tol)
                fail_msg("pixel (%d,%d): leaves %.4f rad off Snell's direction (> %.4f)", x, row, angle, tol);
            worst = fmax(worst, angle);
            max_bend = fmax(max_bend, acos(fmin(1.0, ref_dot(want, r.d))));
            checked++;
        }
    fprintf(stderr, "snell: %d px through glass (worst %.5f rad, paths bend up to %.3f rad), %d px straight\n",
            checked, worst, max_bend, straight);
    assert_true(checked > 300 && straight > 1000);
    assert_true(max_bend > 0.2); /* the test looks at paths that really bend */
    scene_free(&s);
}

/* Fresnel's equations for unpolarised light from a medium into one eta times denser... as the
 * renderer's fresnelDielectric takes them: eta = n_from / n_to; 1 under total internal reflection. */
static double fresnel_exact(double cos_i, double eta)
{
    double sin2t = eta * eta * (1 - cos_i * cos_i);
    if (sin2t >= 1)
        return 1;
    double cos_t = sqrt(1 - sin2t);
    double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t), rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

/* Glass radiance in closed form: a clear sphere (radius 1, ior 1.5, absorption σ per channel) in a
 * uniform environment L and no lights. A ray that meets it at incidence θ sends F(θ) of its light to
 * the environment; (1 − F) goes in, crosses the chord 2 cos θt (θt: Snell's refraction angle) losing
 * e^(−σ · chord), and meets the far face at θt, where by the sphere's symmetry (and Fresnel's
 * reciprocity) it loses F(θ) again; the internally reflected part is not followed. So every pixel on
 * the sphere is L · (F + (1 − F)² e^(−σ · 2 cos θt)), in double here. Beer's path halved (σ l / 2)
 * gives e^(−0.2) for e^(−0.4) in red, one Fresnel face dropped 4 % more: both far beyond the tolerance. */
static void glass_radiance_closed_form(void **st)
{
    (void)st;
    const double L = 0.5, ior = 1.5, sigma[3] = {0.2, 0.5, 1.0};
    char json[768];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"color\": [%g, %g, %g]},"
             " \"quality\": {\"preset\": \"reference\", \"spp\": 1, \"hit_k\": 0.02},"
             " \"materials\": {\"glass\": {\"transmission\": 1, \"ior\": %g, \"roughness\": 0,"
             " \"absorption\": [%g, %g, %g]}},"
             " \"objects\": [{\"shape\": \"sphere\", \"radius\": 1, \"material\": \"glass\"}]}",
             L, L, L, ior, sigma[0], sigma[1], sigma[2]);
    scene s;
    load_text(json, NULL, 0, &s);
    camera cam = cam_at(0, 0, 4.0, 0, 0, 0, 40);
    static float rgba[W * H * 4];
    draw(&s, &cam, W, H, 1, NULL, NULL, rgba);
    const double c[3] = {0, 0, 0}, pixel_angle = camera_pixel_angle(&cam, H);
    int checked = 0;
    double worst = 0, centre[3] = {0, 0, 0};
    for (int row = 0; row < H; row++)
        for (int x = 0; x < W; x++) {
            dray r = pixel_ray(&cam, x, row, W, H);
            dinterval in = ref_sphere(&r, c, 1.0);
            if (!in.hit)
                continue;
            double cos_i = -ref_dot(r.d, in.n0);
            if (cos_i < 0.5) /* near the rim a pixel's footprint spans a fast-changing Fresnel term */
                continue;
            double F = fresnel_exact(cos_i, 1.0 / ior);
            double sin_t = sqrt(1 - cos_i * cos_i) / ior, chord = 2 * sqrt(1 - sin_t * sin_t);
            for (int k = 0; k < 3; k++) {
                double want = L * (F + (1 - F) * (1 - F) * exp(-sigma[k] * chord));
                double got = rgba[(row * W + x) * 4 + k], err = fabs(got - want) / want;
                /* the march finds each face within its threshold eps: the chord is that much off, Beer's
                 * term σ·δ relatively (Beer's length runs from surface to surface, not from the offset
                 * start: the centre pixel matches the closed form to 5 digits) */
                double eps = s.quality.hit_k * in.t0 * pixel_angle, tol = 5e-4 + sigma[k] * 8 * eps / cos_i;
                if (err > tol)
                    fail_msg("pixel (%d,%d) channel %d: %.6f, the closed form says %.6f (F %.4f, chord %.4f; off %.2g > %.2g)",
                             x, row, k, got, want, F, chord, err, tol);
                worst = fmax(worst, err);
                if (x == W / 2 && row == H / 2)
                    centre[k] = got;
            }
            checked++;
        }
    double F0 = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
    fprintf(stderr, "  glass: %d px against L(F + (1-F)^2 e^(-sigma chord)), worst %.2g relative; centre %.5f %.5f %.5f "
            "(closed form %.5f %.5f %.5f)\n", checked, worst, centre[0], centre[1], centre[2],
            L * (F0 + (1 - F0) * (1 - F0) * exp(-2 * sigma[0])), L * (F0 + (1 - F0) * (1 - F0) * exp(-2 * sigma[1])),
            L * (F0 + (1 - F0) * (1 - F0) * exp(-2 * sigma[2])));
    assert_true(checked > 500);
    scene_free(&s);
}

/* A smooth opaque surface in a uniform environment L: the traced mirror image carries Schlick's
 * F(θ) = F0 + (1 − F0)(1 − cos θ)⁵, F0 = ((ior − 1)/(ior + 1))² for a black dielectric and the base
 * colour for a metal; nothing else lights it. Every pixel of the plane against that, in double. A
 * metal taking the dielectric's F0 (0.04 for gold's 1.0, 0.71, 0.29) or exponent 3 fails. */
static void fresnel_on_mirrors(void **st)
{
    (void)st;
    const double L = 0.8, gold[3] = {1.0, 0.71, 0.29};
    for (int metal = 0; metal < 2; metal++) {
        char json[768];
        snprintf(json, sizeof json,
                 "{\"program\": \"csg\", \"environment\": {\"color\": [%g, %g, %g]},"
                 " \"materials\": {\"m\": {\"base_color\": [%g, %g, %g], \"metallic\": %d, \"roughness\": 0, \"ior\": 1.5}},"
                 " \"objects\": [{\"shape\": \"plane\", \"material\": \"m\"}],"
                 " \"effects\": {\"ao\": \"off\"}, \"quality\": {\"preset\": \"final\", \"spp\": 1}}",
                 L, L, L, metal ? gold[0] : 0, metal ? gold[1] : 0, metal ? gold[2] : 0, metal);
        scene s;
        load_text(json, NULL, 0, &s);
        camera cam = cam_at(0, 1.0, 0, 0, 0, -1.6, 80);
        static float rgba[W * H * 4];
        draw(&s, &cam, W, H, 1, NULL, NULL, rgba);
        int checked = 0;
        double worst = 0, lo = 1, hi = 0;
        for (int row = 0; row < H; row++)
            for (int x = 0; x < W; x++) {
                dray r = pixel_ray(&cam, x, row, W, H);
                double cos_t = -r.d[1];
                if (cos_t < 0.05 || r.o[1] / cos_t > 50) /* the plane, not its far horizon */
                    continue;
                for (int k = 0; k < 3; k++) {
                    double F0 = metal ? gold[k] : 0.04, m = 1 - cos_t;
                    double want = L * (F0 + (1 - F0) * m * m * m * m * m);
                    double got = rgba[(row * W + x) * 4 + k], err = fabs(got - want) / want;
                    if (err > 2e-3)
                        fail_msg("%s, pixel (%d,%d) channel %d at %.1f deg: %.6f, Schlick says %.6f", metal ? "gold" : "black glass",
                                 x, row, k, acos(cos_t) * 180 / 3.14159265358979, got, want);
                    worst = fmax(worst, err);
                }
                lo = fmin(lo, cos_t), hi = fmax(hi, cos_t);
                checked++;
            }
        fprintf(stderr, "  %s mirror: %d px from %.0f to %.0f deg, worst %.2g relative to Schlick\n", metal ? "gold" : "black dielectric",
                checked, acos(hi) * 180 / 3.14159265358979, acos(lo) * 180 / 3.14159265358979, worst);
        assert_true(checked > 1000 && acos(lo) > 80 * 3.14159265358979 / 180); /* grazing angles, where F grows */
        scene_free(&s);
    }
}

/* ---- shadows: a lit plane shows no self-shadowing acne ------------------------------------------ */

/* Share of ground pixels whose colour differs from the unshadowed render by more than 0.1 %.
 * light_pos: a point light's position (NULL: directional). Soft shadows estimate a light of angular
 * radius ~1/k: within that angle of the plane's own horizon the plane does hide part of it, so those
 * pixels (k sin(elevation) < 2) are left out. */
static double acne_share(const char *light, const double *light_pos, double k, const char *extra)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"intensity\": 0}, \"lights\": [%s],"
             " \"quality\": {\"preset\": \"interactive\", \"spp\": 1},"
             " \"materials\": {\"floor\": {\"base_color\": [0.8, 0.8, 0.8], \"roughness\": 0.7}},"
             " \"objects\": [{\"shape\": \"plane\", \"material\": \"floor\"}]}", light);
    static float lit[W * H * 4], unshadowed[W * H * 4], aov[W * H * AOV];
    scene s, s_off;
    load_text(json, NULL, 0, &s);
    const char *off[] = {"effects.shadows=off"};
    load_text(json, off, 1, &s_off);
    camera cam = cam_at(0.0, 1.2, 4.0, 0.0, 0.0, -2.0, 50);
    draw(&s, &cam, W, H, 1, extra, aov, lit);
    draw(&s_off, &cam, W, H, 1, NULL, NULL, unshadowed);
    int ground = 0, acne = 0;
    for (int i = 0; i < W * H; i++) {
        if (isinf(aov[i * AOV + 3]))
            continue;
        if (light_pos) {
            dray r = pixel_ray(&cam, i % W, i / W, W, H);
            double l[3];
            for (int c = 0; c < 3; c++)
                l[c] = light_pos[c] - (r.o[c] + r.d[c] * (double)aov[i * AOV + 3]);
            if (k * l[1] / sqrt(ref_dot(l, l)) < 2.0)
                continue;
        }
        ground++;
        double a = lit[i * 4], b = unshadowed[i * 4];
        acne += fabs(a - b) > 1e-3 * fmax(b, 1e-6);
    }
    assert_true(ground > W * H / 3);
    scene_free(&s);
    scene_free(&s_off);
    return (double)acne / ground;
}

static void no_self_shadowing(void **st)
{
    (void)st;
    static const char *const lights[] = {
        "{\"type\": \"directional\", \"direction\": [0.3, 0.35, 0.2], \"shadow\": \"hard\", \"intensity\": 2}",
        "{\"type\": \"point\", \"position\": [1, 1.5, -1], \"shadow\": \"soft\", \"intensity\": 10}",
    };
    static const double point[3] = {1, 1.5, -1};
    for (int i = 0; i < 2; i++) {
        const double *pos = i == 1 ? point : NULL;
        double with_offset = acne_share(lights[i], pos, 16, NULL);
        double without = acne_share(lights[i], pos, 16, "#define SURFACE_OFFSET_K 0.0\n");
        fprintf(stderr, "acne, light %d: %.1f %% of ground pixels with the offset, %.1f %% without\n", i,
                100 * with_offset, 100 * without);
        assert_true(with_offset == 0.0);
        assert_true(without > 0.5); /* the check sees acne when the guard is off */
    }
}

/* Point-light radiometry against the formula: a point light of intensity I at distance d makes the
 * radiance of a diffuse plane proportional to I · cos θ / d² (the course task's falloff). The camera
 * and the lit point stay fixed, so every angular term but the light's cancels in a ratio:
 *   - the light straight above at heights 1 and 3: radiance ratio 9 (1/d would give 3);
 *   - the light at distance 2, straight above and 60° off the normal: ratio 2 (no cosine: 1).
 * The material has ior 1 (F0 = 0: no specular at these angles beyond 1e-3) and the sky is off. */
static double centre_radiance(const float light[3])
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"environment\": {\"intensity\": 0},"
             " \"lights\": [{\"type\": \"point\", \"position\": [%.9g, %.9g, %.9g], \"intensity\": 10, \"shadow\": \"none\"}],"
             " \"materials\": {\"ground\": {\"base_color\": [0.5, 0.5, 0.5], \"roughness\": 1, \"ior\": 1}},"
             " \"objects\": [{\"shape\": \"plane\", \"material\": \"ground\"}],"
             " \"effects\": {\"ao\": \"off\"}, \"quality\": {\"preset\": \"final\", \"spp\": 1}}",
             (double)light[0], (double)light[1], (double)light[2]);
    scene s;
    load_text(json, NULL, 0, &s);
    static float rgba[W * H * 4];
    camera cam = cam_at(0, 1, 3, 0, 0, 0, 40);
    draw(&s, &cam, W, H, 1, NULL, NULL, rgba);
    scene_free(&s);
    return rgba[((H / 2) * W + W / 2) * 4 + 1];
}

static void point_light_radiometry(void **st)
{
    (void)st;
    double near = centre_radiance((const float[]){0, 1, 0}), far = centre_radiance((const float[]){0, 3, 0});
    fprintf(stderr, "  radiance below a point light at 1 m %.6g, at 3 m %.6g: ratio %.4f (1/d²: 9)\n", near, far,
            near / far);
    assert_true(far > 0);
    assert_near(near / far, 9.0, 9.0 * 1e-3);
    /* and the value itself: Lambert's albedo / π · I / d² (albedo 0.5, I = 10, d = 1, F0 = 0) */
    assert_near(near, 0.5 / 3.14159265358979 * 10, 2e-3);
    const double deg60 = 60 * 3.14159265358979 / 180;
    double above = centre_radiance((const float[]){0, 2, 0});
    double slant = centre_radiance((const float[]){(float)(2 * sin(deg60)), (float)(2 * cos(deg60)), 0});
    fprintf(stderr, "  at 2 m straight above %.6g, 60 deg off the normal %.6g: ratio %.4f (cos: 2)\n", above, slant,
            above / slant);
    assert_near(above / slant, 2.0, 2.0 * 1e-2);
}

/* Cook–Torrance against the PBR lecture's formulas, computed here in double: a black dielectric
 * (ior 1.5: F0 = 0.04, no diffuse) of roughness 0.5 seen at angle θ with a point light at the mirror
 * angle, so the half vector is the normal: L = D(1) · G1(cos θ)² · F(cos θ) / (4 cos θ) · I / d², with
 * D(1) = 1 / (π α²), α = r², G1(c) = c / (c(1 − k) + k), k = (r + 1)² / 8, and Schlick's
 * F(c) = F0 + (1 − F0)(1 − c)⁵. At 75° Schlick's exponent 3 instead of 5 gives 70 % more. */
static void specular_against_the_lecture(void **st)
{
    (void)st;
    const double d = 2, I = 10, r = 0.5, F0 = 0.04, PI_D = 3.14159265358979;
    const double angles[] = {30, 60, 75};
    for (size_t k = 0; k < sizeof angles / sizeof angles[0]; k++) {
        double th = angles[k] * PI_D / 180, c = cos(th);
        char json[1024];
        snprintf(json, sizeof json,
                 "{\"program\": \"csg\", \"environment\": {\"intensity\": 0},"
                 " \"lights\": [{\"type\": \"point\", \"position\": [0, %.9g, %.9g], \"intensity\": %g, \"shadow\": \"none\"}],"
                 " \"materials\": {\"black\": {\"base_color\": [0, 0, 0], \"roughness\": %g, \"ior\": 1.5}},"
                 " \"objects\": [{\"shape\": \"plane\", \"material\": \"black\"}],"
                 " \"effects\": {\"ao\": \"off\"}, \"quality\": {\"preset\": \"final\", \"spp\": 1}}",
                 d * c, -d * sin(th), I, r);
        scene s;
        load_text(json, NULL, 0, &s);
        static float rgba[W * H * 4];
        camera cam = cam_at(0, d * c, d * sin(th), 0, 0, 0, 30);
        draw(&s, &cam, W, H, 1, NULL, NULL, rgba);
        scene_free(&s);
        double got = rgba[((H / 2) * W + W / 2) * 4 + 1];
        double alpha = r * r, kk = (r + 1) * (r + 1) / 8, G1 = c / (c * (1 - kk) + kk);
        double D = 1 / (PI_D * alpha * alpha), F = F0 + (1 - F0) * pow(1 - c, 5);
        double want = D * G1 * G1 * F / (4 * c) * I / (d * d);
        fprintf(stderr, "  specular at %2.0f deg: %.6g, the lecture's formula %.6g (F = %.4f)\n", angles[k], got, want, F);
        assert_near(got, want, want * 2e-3);
    }
}

/* ---- the ambient term: the sky around the normal, or its mean ------------------------------------------
 * A white diffuse sphere (roughness 1, ior 1: no Fresnel, so the shade is albedo × ambient alone; no
 * lights, no AO) under a cube map whose six faces are each one colour. With quality.ambient 0 the
 * ambient is the mean of the six faces (equal solid angles), the same at every pixel: ρ · Σ c_f / 6 in
 * linear terms. With 1 it follows the normal: the top of the sphere sees the bright top face more. */
static void constant_ambient_is_the_sky_mean(void **st)
{
    (void)st;
    enum { FACE = 16 };
    static const uint8_t GREY[6] = {40, 80, 250, 10, 120, 160}; /* +X −X +Y −Y +Z −Z, sRGB */
    char dir[] = "/tmp/fathom-ambient-XXXXXX", faces[6][96];
    assert_non_null(mkdtemp(dir));
    double mean = 0;
    for (int f = 0; f < 6; f++) {
        static uint8_t px[FACE * FACE * 3];
        memset(px, GREY[f], sizeof px);
        snprintf(faces[f], sizeof faces[f], "%s/%d.png", dir, f);
        err_t e;
        if (!image_write_u8(faces[f], FACE, FACE, 3, px, &e))
            fail_msg("%s", e.msg);
        double c = GREY[f] / 255.0;
        mean += (c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4)) / 6;
    }
    double rho = 0.5, top = 0, bottom = 0;
    for (int ambient = 0; ambient <= 1; ambient++) {
        char json[1024];
        snprintf(json, sizeof json,
                 "{\"program\": \"csg\", \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1, \"cubemap\": "
                 "[\"%s\", \"%s\", \"%s\", \"%s\", \"%s\", \"%s\"]}, \"lights\": [],"
                 " \"materials\": {\"white\": {\"base_color\": [%g, %g, %g], \"roughness\": 1, \"ior\": 1}},"
                 " \"objects\": [{\"shape\": \"sphere\", \"radius\": 1, \"material\": \"white\"}],"
                 " \"effects\": {\"ao\": \"off\"}, \"quality\": {\"preset\": \"final\", \"spp\": 1, \"ambient\": %d}}",
                 faces[0], faces[1], faces[2], faces[3], faces[4], faces[5], rho, rho, rho, ambient);
        scene s;
        load_text(json, NULL, 0, &s);
        static float rgba[W * H * 4], aov[W * H * AOV];
        camera cam = cam_at(0, 0, 4, 0, 0, 0, 40);
        draw(&s, &cam, W, H, 1, NULL, aov, rgba);
        scene_free(&s);
        double worst = 0;
        int n = 0;
        for (int i = 0; i < W * H; i++) {
            if (isinf(aov[i * AOV + AOV_SLOT_DEPTH]))
                continue;
            n++;
            worst = fmax(worst, fabs(rgba[i * 4] - rho * mean));
            if (aov[i * AOV + 1] > 0.9) /* the normal's y: the top of the sphere */
                top = rgba[i * 4];
            if (aov[i * AOV + 1] < -0.9)
                bottom = rgba[i * 4];
        }
        if (ambient == 0) {
            fprintf(stderr, "  constant ambient: %d sphere pixels, worst |L - rho * mean| %.2g (rho * mean %.5f)\n", n,
                    worst, rho * mean);
            assert_true(n > 1000);
            assert_true(worst < 2e-3 * rho * mean); /* the 1x1 levels are 8-bit sRGB */
        } else {
            fprintf(stderr, "  sky ambient: top of the sphere %.4f, bottom %.4f\n", top, bottom);
            assert_true(top > 2 * rho * mean && bottom < rho * mean); /* the bright top face, the dark bottom one */
        }
    }
    for (int f = 0; f < 6; f++)
        unlink(faces[f]);
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(point_light_radiometry),
        cmocka_unit_test(specular_against_the_lecture),
        cmocka_unit_test(constant_ambient_is_the_sky_mean),
        cmocka_unit_test(glass_sphere_snell),
        cmocka_unit_test(glass_radiance_closed_form),
        cmocka_unit_test(fresnel_on_mirrors),
        cmocka_unit_test(no_self_shadowing),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='glass*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
