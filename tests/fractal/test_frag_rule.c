/* Fragmentarium's hit rule, checked against an independent implementation: for fragments of three
 * families (a Mandelbulb, a Menger sponge, a Mandelbox; tests/frag/rule/, docs/fragments/) this file
 * holds each distance estimate again in C, in double, and traces every pixel as Fragmentarium does —
 * 3D.frag's camera (Eye, Target, Up, FOV) and DE-Raytracer.frag's trace(): steps of DE·FudgeFactor, a
 * hit where a step is below 10^Detail times the distance travelled (then moved back by the difference),
 * background after MaxRaySteps or past MaxDistance — with the preset's values written out here, not read
 * by fathom. fathom opens the same fragments at the same presets; the silhouettes must agree (IoU) and
 * the depths where both hit. The same comparison with fathom's own footprint rule is printed beside it:
 * what the rule changes. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "gltest.h"
#include "gpu/render.h"
#include "scene/formula/frag.h"
#include "view/shot.h"

enum { RW = 128, RH = 96 };

/* ---- the estimates, in double (the fragments' DE() each) ----------------------------------------------- */

static double length3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/* tests/frag/rule/bulb.frag: z -> z^8 + p, 10 iterations, bailout 4; 0.5 ln r · r / dr */
static double bulb_de(const double p[3])
{
    const double power = 8;
    double z[3] = {p[0], p[1], p[2]}, dr = 1, r = length3(z);
    for (int i = 0; i < 10 && r < 4; i++) {
        double theta = acos(fmin(fmax(z[2] / r, -1), 1)) * power, phi = atan2(z[1], z[0]) * power;
        dr = power * pow(r, power - 1) * dr + 1;
        double rp = pow(r, power);
        z[0] = rp * sin(theta) * cos(phi) + p[0];
        z[1] = rp * sin(theta) * sin(phi) + p[1];
        z[2] = rp * cos(theta) + p[2];
        r = length3(z);
    }
    return 0.5 * log(r) * r / dr;
}

static void swap(double *a, double *b)
{
    double t = *a;
    *a = *b;
    *b = t;
}

/* tests/frag/rule/menger.frag: 6 levels of scale 3 */
static double menger_de(const double p[3])
{
    const double scale = 3;
    double z[3] = {p[0], p[1], p[2]}, s = 1;
    for (int i = 0; i < 6; i++) {
        for (int k = 0; k < 3; k++)
            z[k] = fabs(z[k]);
        if (z[0] < z[1])
            swap(&z[0], &z[1]);
        if (z[0] < z[2])
            swap(&z[0], &z[2]);
        if (z[1] < z[2])
            swap(&z[1], &z[2]);
        for (int k = 0; k < 3; k++)
            z[k] = scale * z[k] - (scale - 1);
        if (z[2] < -0.5 * (scale - 1))
            z[2] += scale - 1;
        s *= scale;
    }
    double q[3], out[3];
    for (int k = 0; k < 3; k++)
        q[k] = fabs(z[k]) - 1, out[k] = fmax(q[k], 0);
    return (length3(out) + fmin(fmax(q[0], fmax(q[1], q[2])), 0)) / s;
}

/* docs/fragments/mandelbox.frag at its Default: scale 2.5, MinRad2 0.25, FoldLimit 1, 14 iterations, no turn */
static double mandelbox_de(const double p[3])
{
    const double scale = 2.5, min_r2 = 0.25, fold = 1;
    double z[3] = {p[0], p[1], p[2]}, dr = 1;
    for (int i = 0; i < 14; i++) {
        for (int k = 0; k < 3; k++)
            z[k] = fmin(fmax(z[k], -fold), fold) * 2 - z[k];
        double r2 = z[0] * z[0] + z[1] * z[1] + z[2] * z[2];
        double f = r2 < min_r2 ? 1 / min_r2 : r2 < 1 ? 1 / r2 : 1;
        for (int k = 0; k < 3; k++)
            z[k] = scale * z[k] * f + p[k];
        dr = dr * f * fabs(scale) + 1;
    }
    return length3(z) / fabs(dr);
}

/* ---- Fragmentarium's camera and trace --------------------------------------------------------------- */

typedef struct frag_case {
    const char *file, *preset; /* under the source tree; NULL: the fragment's default */
    double eye[3], target[3], up[3], fov, detail, fudge;
    int max_steps;
    double max_distance;
    double (*de)(const double p[3]);
} frag_case;

/* The preset values as the fragment files have them (DE-Raytracer's defaults where a preset is silent:
 * Detail -2.3, FudgeFactor 1, MaxRaySteps 56, MaxDistance 100000). */
static const frag_case CASES[] = {
    {"tests/frag/rule/bulb.frag", NULL, {0.3, 2.2, -2.1}, {0, 0, 0}, {0, 1, 0}, 0.4, -2.8, 1, 56, 1e5, bulb_de},
    {"tests/frag/rule/bulb.frag", "Near", {0.15, 1.08, -0.45}, {0, 0.9, 0}, {0, 1, 0}, 0.6, -2, 1, 200, 1e5, bulb_de},
    {"tests/frag/rule/menger.frag", NULL, {2.6, 1.9, -3.4}, {0, 0, 0}, {0, 1, 0}, 0.5, -2.3, 1, 56, 1e5, menger_de},
    /* few steps: a ray out of them is background (a third of the sponge's pixels here) */
    {"tests/frag/rule/menger.frag", "Few", {2.6, 1.9, -3.4}, {0, 0, 0}, {0, 1, 0}, 0.5, -3, 0.7, 24, 1e5, menger_de},
    {"docs/fragments/mandelbox.frag", NULL, {7.8, 5.1, -9.2}, {0, 0, 0}, {0, 1, 0}, 0.45, -3.3, 0.9, 300, 1e5,
     mandelbox_de},
};

static void normalize3(double v[3])
{
    double l = length3(v);
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* 3D.frag: coord in [-1, 1] (x times the aspect) times FOV; the ray Dir + x Right + y UpOrtho, with
 * UpOrtho = Up made square to Dir and Right = Dir × UpOrtho. Pixel (x, row), row 0 at the top, its centre. */
static void frag_ray(const frag_case *c, int x, int row, double dir[3])
{
    double d[3], up[3], right[3];
    for (int k = 0; k < 3; k++)
        d[k] = c->target[k] - c->eye[k];
    normalize3(d);
    double along = d[0] * c->up[0] + d[1] * c->up[1] + d[2] * c->up[2];
    for (int k = 0; k < 3; k++)
        up[k] = c->up[k] - along * d[k];
    normalize3(up);
    cross3(d, up, right);
    normalize3(right);
    double cx = (2.0 * (x + 0.5) / RW - 1) * RW / RH * c->fov, cy = (2.0 * ((RH - 1 - row) + 0.5) / RH - 1) * c->fov;
    for (int k = 0; k < 3; k++)
        dir[k] = d[k] + cx * right[k] + cy * up[k];
    normalize3(dir);
}

/* DE-Raytracer.frag's trace(), Dither 0: the distance to the hit, or +inf (background). */
static double frag_trace(const frag_case *c, const double dir[3])
{
    double t = 0, dist = 0, eps = 0, min_dist = pow(10, c->detail);
    for (int steps = 0; steps < c->max_steps; steps++) {
        double p[3] = {c->eye[0] + t * dir[0], c->eye[1] + t * dir[1], c->eye[2] + t * dir[2]};
        dist = c->de(p) * c->fudge;
        t += dist;
        eps = t * min_dist;
        if (dist < eps) {
            t -= eps - dist;
            break;
        }
        if (t > c->max_distance)
            break;
    }
    return dist < eps ? t : INFINITY;
}

/* ---- fathom at the same preset ----------------------------------------------------------------------- */

/* The case's fragment at its preset (its shot) drawn by fathom with `extra` sets after it: the AOVs and
 * the linear colour (either may be NULL), and the sRGB8 image through the display when srgb is not NULL. */
static void fathom_draw(const frag_case *c, const char *extra, float *aov, float *rgba, uint8_t *srgb)
{
    char path[PATH_MAX_LEN];
    snprintf(path, sizeof path, "%s/%s", FATHOM_SOURCE_DIR, c->file);
    strbuf text = {0};
    shot_desc d = {0};
    err_t e;
    if (!frag_preset_shot(path, c->preset, &text, NULL, &e) || !shot_parse(text.data, path, &d, &e))
        fail_msg("%s: %s", c->file, e.msg);
    const char *sets[SHOT_SET_MAX + 4];
    int n = 0;
    for (int i = 0; i < d.set_count; i++)
        sets[n++] = d.sets[i];
    sets[n++] = "quality.spp=1";
    sets[n++] = "effects.aa=off";
    if (extra)
        sets[n++] = extra;
    scene s;
    if (!scene_load("fractal", sets, n, &s, &e))
        fail_msg("%s: %s", c->file, e.msg);
    draw(&s, &d.cam, RW, RH, 1, NULL, aov, rgba);
    if (srgb)
        render_read_srgb8(srgb, 1);
    scene_free(&s);
    shot_free(&d);
    sb_free(&text);
}

/* fathom's depth AOV of the case's fragment at its preset. */
static float *fathom_depths(const frag_case *c, const char *extra)
{
    float *aov = malloc(sizeof(float) * RW * RH * AOV), *depth = malloc(sizeof(float) * RW * RH);
    fathom_draw(c, extra, aov, NULL, NULL);
    for (int i = 0; i < RW * RH; i++)
        depth[i] = aov[i * AOV + AOV_SLOT_DEPTH];
    free(aov);
    return depth;
}

typedef struct agreement {
    double iou, depth_median, depth_p95; /* relative depth errors where both hit */
    int hits_ref, hits_fathom;
} agreement;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static agreement compare(const float *depth, const double *ref)
{
    agreement a = {0};
    int both = 0, either = 0;
    double *rel = malloc(sizeof(double) * RW * RH);
    for (int i = 0; i < RW * RH; i++) {
        bool f = isfinite(depth[i]), r = isfinite(ref[i]);
        a.hits_fathom += f;
        a.hits_ref += r;
        either += f || r;
        if (f && r)
            rel[both++] = fabs(depth[i] - ref[i]) / ref[i];
    }
    a.iou = either ? (double)both / either : 1;
    qsort(rel, (size_t)both, sizeof *rel, cmp_double);
    a.depth_median = both ? rel[both / 2] : 0;
    a.depth_p95 = both ? rel[(int)(0.95 * (both - 1))] : 0;
    free(rel);
    return a;
}

static void fragmentarium_rule(void **st)
{
    (void)st;
    for (size_t k = 0; k < sizeof CASES / sizeof *CASES; k++) {
        const frag_case *c = &CASES[k];
        double *ref = malloc(sizeof(double) * RW * RH);
        for (int row = 0; row < RH; row++)
            for (int x = 0; x < RW; x++) {
                double dir[3];
                frag_ray(c, x, row, dir);
                ref[row * RW + x] = frag_trace(c, dir);
            }
        float *ours = fathom_depths(c, NULL), *footprint = fathom_depths(c, "fractal.hit_rule=footprint");
        agreement a = compare(ours, ref), b = compare(footprint, ref);
        printf("%-32s %-8s Fragmentarium's rule: IoU %.4f, depth off %.4f %% (median) %.4f %% (95th), hits %d/%d; "
               "fathom's footprint rule: IoU %.4f, depth off %.3f %% (median) %.3f %% (95th)\n",
               c->file, c->preset ? c->preset : "default", a.iou, 100 * a.depth_median, 100 * a.depth_p95,
               a.hits_fathom, a.hits_ref, b.iou, 100 * b.depth_median, 100 * b.depth_p95);
        if (a.hits_ref < RW * RH / 20)
            fail_msg("%s: the reference hits only %d pixels: the view shows too little to compare", c->file, a.hits_ref);
        if (a.iou < 0.995 || a.depth_median > 1e-3 || a.depth_p95 > 5e-3)
            fail_msg("%s (%s): fathom's silhouette or depth is not Fragmentarium's: IoU %.4f, depth off %.4f %% "
                     "(median), %.4f %% (95th)",
                     c->file, c->preset ? c->preset : "default", a.iou, 100 * a.depth_median, 100 * a.depth_p95);
        free(ref);
        free(ours);
        free(footprint);
    }
}

/* ---- the look: DE-Raytracer's lighting and 3D.frag's post, on a sphere ------------------------------ */

static double sphere_de(const double p[3]) { return length3(p) - 1.5; }

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* DE-Raytracer's colour of a pixel of tests/frag/sphere.frag at its Default (the renderer's defaults but
 * Specular, and BaseColor 0.8, 0.5, 0.3): the sphere's hit lit by the spot light (0.4, toward SpotLightDir
 * (0.1, 0.1)), its highlight and the camera light (1); no occlusion on a sphere (the estimate grows as
 * the distance along the normal); a miss, BackgroundColor darkened toward the edge (0.3 · |coord|). */
static void look_colour(const frag_case *c, bool phong, int x, int row, double out[3])
{
    double dir[3];
    frag_ray(c, x, row, dir);
    double b = dot3(c->eye, dir), disc = b * b - (dot3(c->eye, c->eye) - 1.5 * 1.5);
    if (disc < 0) {
        const double back[3] = {0.6, 0.6, 0.45};
        double cx = (2.0 * (x + 0.5) / RW - 1) * RW / RH * c->fov, cy = (2.0 * ((RH - 1 - row) + 0.5) / RH - 1) * c->fov;
        for (int k = 0; k < 3; k++)
            out[k] = back[k] * (1 - 0.3 * hypot(cx, cy));
        return;
    }
    double t = -b - sqrt(disc), n[3], l[3], h[3];
    for (int k = 0; k < 3; k++)
        n[k] = (c->eye[k] + t * dir[k]) / 1.5;
    const double pi = 3.1415, ax = 0.1 * pi, ay = 0.1 * pi / 2; /* the renderers' π */
    l[0] = sin(ax) * cos(ay), l[1] = sin(ay) * sin(ax), l[2] = cos(ax);
    normalize3(l);
    for (int k = 0; k < 3; k++)
        h[k] = l[k] - dir[k];
    normalize3(h);
    double n_l = fmax(0, dot3(n, l)), h_n = fmax(0, dot3(n, h)), e = 16;
    double diffuse = n_l * 0.4, ambient = fmax(0, -dot3(n, dir)) * 1;
    double spec = fmin(10, (e + 2) / 8 * pow(h_n, e) * (e + (1 - e) * pow(1 - h_n, 5)) * n_l * 0.4);
    if (phong) { /* Fast-Raytracer: lit toward -L, Phong's highlight of the mirrored light, Specular 4 */
        double r[3], nl = dot3(n, l);
        for (int k = 0; k < 3; k++)
            r[k] = l[k] - 2 * nl * n[k];
        diffuse = fmax(0, -nl) * 0.4;
        spec = pow(fmax(0, -dot3(dir, r)), e) * 4;
    }
    const double base[3] = {0.8, 0.5, 0.3};
    for (int k = 0; k < 3; k++)
        out[k] = (diffuse + ambient + spec) * pow(base[k], 2); /* colours to the power Gamma (2) first */
}

/* One lit sphere's pixels against its renderer's formulas (phong: Fast-Raytracer's, else DE-Raytracer's). */
static void look_against(const frag_case *sphere, bool phong)
{
    float *rgba = malloc(sizeof(float) * RW * RH * 4);
    uint8_t *srgb = malloc((size_t)RW * RH * 4);
    fathom_draw(sphere, "fractal.BaseColor=0.8,0.5,0.3", NULL, rgba, srgb);
    double worst = 0, worst_post = 0;
    int at = 0, hits = 0;
    for (int row = 0; row < RH; row++)
        for (int x = 0; x < RW; x++) {
            double want[3], dir[3];
            look_colour(sphere, phong, x, row, want);
            frag_ray(sphere, x, row, dir);
            double miss = sqrt(fmax(dot3(sphere->eye, sphere->eye) - pow(dot3(sphere->eye, dir), 2), 0));
            if (fabs(miss - 1.5) < 0.05) /* the silhouette's pixels may go either way */
                continue;
            hits += miss < 1.5;
            const float *got = rgba + 4 * (row * RW + x);
            const uint8_t *shown = srgb + 4 * (row * RW + x);
            for (int k = 0; k < 3; k++) {
                double e = fabs(got[k] - want[k]), post = sqrt(got[k] / (1 + got[k])); /* Reinhard, 1/Gamma */
                if (e > worst)
                    worst = e, at = row * RW + x;
                worst_post = fmax(worst_post, fabs(shown[k] - 255 * post)); /* the display's own */
            }
        }
    printf("the look against %s's formulas: worst %.4f (pixel %d), after the post %.2f of 255, %d hits\n",
           phong ? "Fast-Raytracer" : "DE-Raytracer", worst, at, worst_post, hits);
    if (hits < RW * RH / 10 || worst > 0.025 || worst_post > 1.0) /* Phong's highlight: steep */
        fail_msg("fathom's fragment look is not DE-Raytracer's: colour off by %.4f at pixel %d, %.2f of 255 after "
                 "the post", worst, at, worst_post);
    free(rgba);
    free(srgb);
}

static void fragment_look(void **st)
{
    (void)st;
    const frag_case de = {"tests/frag/sphere.frag", NULL, {0, 0, -5}, {0, 0, 0}, {0, 1, 0}, 0.4, -3, 0.8, 300, 1e5,
                          sphere_de};
    const frag_case fast = {"tests/frag/sphere_fast.frag", NULL, {0, 0, -5}, {0, 0, 0}, {0, 1, 0}, 0.4, -3, 0.8, 300,
                            1e5, sphere_de};
    look_against(&de, false);
    look_against(&fast, true);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(fragmentarium_rule), cmocka_unit_test(fragment_look)};
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
