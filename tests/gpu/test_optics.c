/* The camera's optics against closed forms (view/camera.h): a rolled image is the level one turned,
 * an orthographic sphere keeps its size at any distance and has the depths of parallel rays, an
 * equirectangular and a fisheye panorama put a ground plane and a sphere where their angles say, the
 * stereo eyes see a sphere with the disparity a pair of off-axis eyes gives, and the thin lens
 * spreads a sphere off the focal plane by its circle of confusion (in the model and in the path
 * tracer) while one on it stays sharp. Every reference here computes its own directions from the
 * stated formulas: none calls camera_ray. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "cli/cli.h"
#include "data/media/image_io.h"
#include "gltest.h"
#include "jobs/capture/offline.h"

static const char *const ONE_SAMPLE[] = {"quality.spp=1", "effects.aa=off"};

/* A csg scene of spheres (x, y, z, r each) and, with `ground`, the plane y = -1; a grey sky. */
static void spheres_scene(const double (*sp)[4], int n, bool ground, const char *material, scene *s)
{
    strbuf j = {0};
    sb_printf(&j, "{\"program\": \"csg\", \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1},"
                  " \"materials\": {\"m\": %s}, \"objects\": [",
              material ? material : "{\"base_color\": [0.6, 0.6, 0.6]}");
    for (int i = 0; i < n; i++)
        sb_printf(&j, "%s{\"shape\": \"sphere\", \"position\": [%.17g, %.17g, %.17g], \"radius\": %.17g, \"material\": \"m\"}",
                  i ? ", " : "", sp[i][0], sp[i][1], sp[i][2], sp[i][3]);
    if (ground)
        sb_printf(&j, "%s{\"shape\": \"plane\", \"position\": [0, -1, 0], \"normal\": [0, 1, 0], \"material\": \"m\"}",
                  n ? ", " : "");
    sb_append(&j, "]}");
    load_text(j.data, ONE_SAMPLE, 2, s);
    sb_free(&j);
}

/* The first hit of the ray o + t d (unit d) with a sphere, +inf on a miss. */
static double sphere_hit(const double o[3], const double d[3], const double *sp)
{
    double oc[3] = {o[0] - sp[0], o[1] - sp[1], o[2] - sp[2]};
    double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2], c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - sp[3] * sp[3];
    double disc = b * b - c;
    if (disc < 0)
        return INFINITY;
    double t = -b - sqrt(disc);
    return t > 0 ? t : INFINITY;
}

static double depth(const float *aov, int w, int x, int row) { return aov[(row * w + x) * AOV + AOV_SLOT_DEPTH]; }

/* Pixels where hit and miss disagree with the reference, and the largest depth error where both hit,
 * in units of `scale` (a pixel's footprint at the depth). */
typedef struct agreement {
    int wrong, hits;
    double worst;
} agreement;

static void agree(agreement *a, double got, double want, double scale)
{
    if (isinf(got) != isinf(want)) {
        a->wrong++;
        return;
    }
    if (isinf(want))
        return;
    a->hits++;
    a->worst = fmax(a->worst, fabs(got - want) / scale);
}

/* ---- roll -------------------------------------------------------------------------------------------- */

/* Rolled by 90° a square image is the level one turned clockwise (camera.h: roll > 0 turns the
 * camera's right toward its up), pixel for pixel: rolled (x, row) sees what level (row, n-1-x) sees
 * (rows top first). Rolled by −90° the other way, by 180° upside down. */
static void roll_turns_the_image(void **st)
{
    (void)st;
    enum { N = 63 };
    static const double SP[][4] = {{0.9, 0.5, 0, 0.8}, {-0.6, -0.6, 0.3, 0.55}, {0.2, 1.1, -1, 0.45}, {-1.3, 0.9, -0.5, 0.4}};
    scene s;
    spheres_scene(SP, 4, false, NULL, &s);
    static float level[N * N * AOV], rolled[N * N * AOV];
    camera cam = cam_at(0.3, 0.4, 6, 0, 0.2, 0, 40);
    draw(&s, &cam, N, N, 1, NULL, level, NULL);
    const float rolls[] = {90, -90, 180};
    for (int k = 0; k < 3; k++) {
        camera r = cam;
        r.roll = (float)(rolls[k] * DEG2RAD);
        draw(&s, &r, N, N, 1, NULL, rolled, NULL);
        int wrong = 0, hits = 0;
        for (int row = 0; row < N; row++)
            for (int x = 0; x < N; x++) {
                int lx = k == 0 ? row : k == 1 ? N - 1 - row : N - 1 - x, lrow = k == 0 ? N - 1 - x : k == 1 ? x : N - 1 - row;
                double a = depth(rolled, N, x, row), b = depth(level, N, lx, lrow);
                hits += !isinf(b);
                wrong += isinf(a) != isinf(b) || (!isinf(a) && fabs(a - b) > 1e-3 * b);
            }
        print_message("roll %+.0f°: %d of %d pixels differ from the level image turned (%d hits)\n", (double)rolls[k],
                      wrong, N * N, hits);
        assert_true(hits > N * N / 8);
        assert_true(wrong <= N / 4); /* a pixel whose centre grazes a silhouette may round either way */
    }
    scene_free(&s);
}

/* ---- orthographic ---------------------------------------------------------------------------------- */

/* Parallel rays from the plane through the eye: a sphere is a disc of its own radius (in units of the
 * view's height 2 · focus · tan(fov/2)) wherever it is, and its depth is its distance from that plane
 * less the sphere's height over the ray. Two equal spheres, one 3 times as far, are equal discs. */
static void orthographic_sphere(void **st)
{
    (void)st;
    enum { OW = 121, OH = 81 };
    static const double SP[][4] = {{-1.0, 0, 0, 0.6}, {1.2, 0, -12, 0.6}};
    scene s;
    spheres_scene(SP, 2, false, NULL, &s);
    camera cam = cam_at(0, 0, 6, 0, 0, 0, 40);
    cam.lens = (camera_lens){.projection = PROJECTION_ORTHOGRAPHIC, .focus = 6};
    static float aov[OW * OH * AOV];
    draw(&s, &cam, OW, OH, 1, NULL, aov, NULL);
    scene_free(&s);
    double half = 6 * tan(20 * DEG2RAD), pixel = 2 * half / OH; /* world units a pixel spans */
    agreement a = {0};
    int disc[2] = {0, 0};
    for (int row = 0; row < OH; row++)
        for (int x = 0; x < OW; x++) {
            double sx = (2.0 * (x + 0.5) / OW - 1.0) * half * OW / OH, sy = (2.0 * (OH - 1 - row + 0.5) / OH - 1.0) * half;
            double o[3] = {sx, sy, 6}, d[3] = {0, 0, -1};
            double t0 = sphere_hit(o, d, SP[0]), t1 = sphere_hit(o, d, SP[1]);
            disc[0] += !isinf(t0);
            disc[1] += !isinf(t1);
            agree(&a, depth(aov, OW, x, row), fmin(t0, t1), pixel);
        }
    print_message("orthographic: %d pixels off the closed form, depth within %.3f pixels; discs %d and %d pixels "
                  "(pi r^2 = %.0f)\n", a.wrong, a.worst, disc[0], disc[1], GLM_PI * pow(0.6 / pixel, 2));
    assert_true(abs(disc[0] - disc[1]) < 0.03 * disc[0]); /* the far one is as big (perspective: 1/9) */
    assert_true(fabs(disc[0] - GLM_PI * pow(0.6 / pixel, 2)) < 0.03 * disc[0]);
    assert_true(a.wrong <= 4);
    assert_true(a.worst < 1.0);
}

/* ---- panoramas ------------------------------------------------------------------------------------- */

/* Equirectangular from (0, 0, 0) looking down −Z: longitude λ = π sx (> 0 right), latitude φ = π sy / 2.
 * The plane y = −1 fills the lower half at depth 1 / sin(−φ); a sphere to the right (+X) sits at
 * λ = 90°, three quarters across. */
static void equirectangular_panorama(void **st)
{
    (void)st;
    enum { EW = 128, EH = 64 };
    static const double SP[][4] = {{3, 0.5, 0, 0.8}};
    scene s;
    spheres_scene(SP, 1, true, NULL, &s);
    camera cam = cam_at(0, 0, 0, 0, 0, -1, 50);
    cam.lens.projection = PROJECTION_EQUIRECTANGULAR;
    static float aov[EW * EH * AOV];
    draw(&s, &cam, EW, EH, 1, NULL, aov, NULL);
    scene_free(&s);
    agreement a = {0};
    double sum_x = 0;
    int n = 0;
    for (int row = 0; row < EH; row++)
        for (int x = 0; x < EW; x++) {
            double lon = GLM_PI * (2.0 * (x + 0.5) / EW - 1.0), lat = 0.5 * GLM_PI * (2.0 * (EH - 1 - row + 0.5) / EH - 1.0);
            double o[3] = {0, 0, 0}, d[3] = {cos(lat) * sin(lon), sin(lat), -cos(lat) * cos(lon)};
            double ts = sphere_hit(o, d, SP[0]), tg = d[1] < 0 ? -1.0 / d[1] : INFINITY;
            double want = fmin(ts, tg);
            if (!isinf(ts) && ts < tg) {
                sum_x += x;
                n++;
            }
            if (!(want > 60)) /* the far ground is a few pixels below the horizon's own thresholds */
                agree(&a, depth(aov, EW, x, row), want, want * GLM_PI / EH);
        }
    print_message("equirectangular: %d pixels off, depth within %.3f footprints; the sphere's centre at column %.2f "
                  "(expected %.2f)\n", a.wrong, a.worst, sum_x / n, 0.75 * EW - 0.5);
    assert_true(fabs(sum_x / n - (0.75 * EW - 0.5)) < 0.5);
    assert_true(a.wrong <= EW / 16);
    assert_true(a.worst < 0.5);
}

/* Fisheye (equidistant, 180° across the height): a ray at image radius r (of the half-height) is
 * θ = 90° r off the axis. Straight down at the ground: a sphere 60° to the right of the axis lies at
 * radius 2/3, and outside the circle there is nothing (black, a miss). */
static void fisheye_dome(void **st)
{
    (void)st;
    enum { FN = 91 };
    double sp[4] = {2 * sin(60 * DEG2RAD), 2 - 2 * cos(60 * DEG2RAD), 0, 0.3}; /* 2 m from the eye, 60° off down */
    const double eye[3] = {0, 2, 0};
    double spheres[1][4] = {{sp[0], sp[1], sp[2], sp[3]}};
    scene s;
    spheres_scene((const double(*)[4])spheres, 1, true, NULL, &s);
    camera cam = camera_look_at_up(eye, (double[3]){0, 0, 0}, (double[3]){0, 0, -1}, (float)(50 * DEG2RAD));
    cam.lens.projection = PROJECTION_FISHEYE;
    static float aov[FN * FN * AOV], rgba[FN * FN * 4];
    draw(&s, &cam, FN, FN, 1, NULL, aov, rgba);
    scene_free(&s);
    camera_basis b = camera_get_basis(&cam);
    agreement a = {0};
    int outside_lit = 0;
    for (int row = 0; row < FN; row++)
        for (int x = 0; x < FN; x++) {
            double px = 2.0 * (x + 0.5) / FN - 1.0, py = 2.0 * (FN - 1 - row + 0.5) / FN - 1.0, r = hypot(px, py);
            double got = depth(aov, FN, x, row);
            if (r > 1) {
                outside_lit += !isinf(got) || rgba[(row * FN + x) * 4] != 0;
                continue;
            }
            double th = 0.5 * GLM_PI * r, k = r > 0 ? sin(th) / r : 0, d[3];
            for (int i = 0; i < 3; i++)
                d[i] = cos(th) * b.forward[i] + k * (px * b.right[i] + py * b.up[i]);
            double ts = sphere_hit(eye, d, sp), tg = d[1] < 0 ? -3.0 / d[1] : INFINITY, want = fmin(ts, tg);
            if (!(want > 40))
                agree(&a, got, want, want * GLM_PI / FN);
        }
    print_message("fisheye: %d pixels off, depth within %.3f footprints, %d pixels outside the circle not black\n",
                  a.wrong, a.worst, outside_lit);
    assert_int_equal(outside_lit, 0);
    assert_true(a.wrong <= FN / 10);
    assert_true(a.worst < 0.5);
}

/* ---- stereo ---------------------------------------------------------------------------------------- */

/* The centroid of the hit pixels of columns [x0, x1) (rows top first), in pixels from x0. */
static double hit_centroid(const float *aov, int w, int h, int x0, int x1, int y0, int y1)
{
    double sum = 0;
    int n = 0;
    for (int row = y0; row < y1; row++)
        for (int x = x0; x < x1 && x < w && row < h; x++)
            if (!isinf(depth(aov, w, x, row))) {
                sum += x - x0;
                n++;
            }
    return n ? sum / n : NAN;
}

/* The reference: eye e (−1 left, +1 right) at (e s/2, 0, 6) looking down −Z, its ray through pixel
 * (x, row) aimed at where the centre's pinhole ray meets the focal plane z = 6 − F; the centroid of
 * the pixels whose ray meets the sphere. */
static double reference_centroid(double e, double s, double F, double fov, const double *sp, int w, int h)
{
    double t = tan(fov / 2 * DEG2RAD), sum = 0;
    int n = 0;
    for (int row = 0; row < h; row++)
        for (int x = 0; x < w; x++) {
            double u = (2.0 * (x + 0.5) / w - 1.0) * t * w / h, v = (2.0 * (h - 1 - row + 0.5) / h - 1.0) * t;
            double o[3] = {e * s / 2, 0, 6}, d[3] = {u * F - o[0], v * F, -F}, l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (int i = 0; i < 3; i++)
                d[i] /= l;
            if (!isinf(sphere_hit(o, d, sp))) {
                sum += x;
                n++;
            }
        }
    return sum / n;
}

/* Off-axis eyes ∓s/2 along right, aimed at the focal plane: a point straight ahead at distance Z
 * appears at ±(s/2)(1/Z − 1/F) (tangent units), so its disparity between the eyes is about
 * s (1/Z − 1/F) · H / (2 tan(fov/2)) pixels (a sphere's image is a little wider off the axis): 0 on
 * the focal plane, crossed (left eye to the right) nearer. Side by side the left eye is the left
 * half; top-bottom the top half. Each eye's centroid is checked against the reference's. */
static void stereo_disparity(void **st)
{
    (void)st;
    enum { EW = 80, EH = 60 };
    const double F = 6, S = 0.4, fov = 40;
    /* on the axis at the focal distance, nearer and farther; off the axis in the focal plane (no
     * disparity there either: the eyes converge on a plane, not on a sphere around the eye) */
    const double Z[] = {6, 3, 12, 6}, X[] = {0, 0, 0, 1.8};
    for (int k = 0; k < 4; k++) {
        double sp[1][4] = {{X[k], 0, 6 - Z[k], 0.25 * Z[k] / 3}};
        scene s;
        spheres_scene((const double(*)[4])sp, 1, false, NULL, &s);
        double want_left = reference_centroid(-1, S, F, fov, sp[0], EW, EH), want_right = reference_centroid(1, S, F, fov, sp[0], EW, EH);
        for (int layout = STEREO_SIDE_BY_SIDE; layout <= STEREO_TOP_BOTTOM; layout++) {
            camera cam = cam_at(0, 0, 6, 0, 0, 0, fov);
            cam.lens = (camera_lens){.stereo = (camera_stereo)layout, .eye_separation = (float)S, .focus = (float)F};
            bool sbs = layout == STEREO_SIDE_BY_SIDE;
            int w = sbs ? 2 * EW : EW, h = sbs ? EH : 2 * EH;
            static float aov[4 * EW * EH * AOV];
            draw(&s, &cam, w, h, 1, NULL, aov, NULL);
            /* rows top first: top-bottom's left eye has rows 0 … EH−1 */
            double left = hit_centroid(aov, w, h, 0, EW, 0, EH);
            double right = sbs ? hit_centroid(aov, w, h, EW, 2 * EW, 0, EH) : hit_centroid(aov, w, h, 0, EW, EH, 2 * EH);
            double thin = S * (1 / Z[k] - 1 / F) * EH / (2 * tan(fov / 2 * DEG2RAD));
            print_message("stereo %s, sphere at %.1f, %.0f (focus %.0f): disparity %.3f pixels (reference %.3f; a point's %.3f)\n",
                          CAMERA_STEREOS[layout], X[k], Z[k], F, left - right, want_left - want_right, thin);
            assert_true(fabs(left - want_left) < 0.1 && fabs(right - want_right) < 0.1);
            assert_true(fabs(left - right - thin) < 0.1 * fabs(thin) + 0.1);
        }
        scene_free(&s);
    }
}

/* ---- depth of field -------------------------------------------------------------------------------- */

/* A dark sphere against a white sky: its darkness D(x, y) = 1 − luminance is the sharp disc convolved
 * with the lens's circle of confusion. Second moments add under convolution and a uniform disc of
 * radius R has E[x² + y²] = R²/2, so the circle's radius in pixels is sqrt(2 (M_blurred − M_sharp)).
 * The thin lens predicts aperture · |d − F| / d on the focal plane, F · pixel angle a pixel there. */
static double darkness_moment(const float *rgba, int n, double *mass)
{
    double m = 0, sx = 0, sy = 0, sxx = 0;
    for (int row = 0; row < n; row++)
        for (int x = 0; x < n; x++) {
            const float *p = rgba + (row * n + x) * 4;
            double w = fmax(0.0, 1.0 - (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]));
            m += w;
            sx += w * x;
            sy += w * row;
            sxx += w * ((double)x * x + (double)row * row);
        }
    *mass = m;
    return sxx / m - (sx * sx + sy * sy) / (m * m);
}

static void lens_circle_of_confusion(void **st)
{
    (void)st;
    enum { N = 61, SPP = 96 };
    const double F = 6, A = 0.4, fov = 30;
    const char *const integrators[] = {"quality.integrator=0", "quality.integrator=1"};
    const double distances[] = {6, 4, 9};
    static float rgba[N * N * 4];
    for (int ig = 0; ig < 2; ig++)
        for (int k = 0; k < 3; k++) {
            double d = distances[k], sp[1][4] = {{0, 0, 6 - d, 0.15 * d / 6}};
            strbuf j = {0};
            sb_printf(&j, "{\"program\": \"csg\", \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1},"
                          " \"materials\": {\"m\": {\"base_color\": [0, 0, 0], \"roughness\": 1}}, \"objects\": ["
                          "{\"shape\": \"sphere\", \"position\": [0, 0, %.17g], \"radius\": %.17g, \"material\": \"m\"}]}",
                      sp[0][2], sp[0][3]);
            const char *sets[] = {"effects.aa=on", integrators[ig], "quality.bounces=1"};
            scene s;
            load_text(j.data, sets, 3, &s);
            sb_free(&j);
            camera cam = cam_at(0, 0, 6, 0, 0, 0, fov);
            cam.lens.focus = (float)F;
            double mass0, mass1;
            draw(&s, &cam, N, N, SPP, NULL, NULL, rgba);
            double sharp = darkness_moment(rgba, N, &mass0);
            cam.lens.aperture = (float)A;
            draw(&s, &cam, N, N, SPP, NULL, NULL, rgba);
            double blurred = darkness_moment(rgba, N, &mass1);
            scene_free(&s);
            double pa = 2 * tan(fov / 2 * DEG2RAD) / N, want = A * fabs(d - F) / d / (F * pa);
            double got = sqrt(fmax(0.0, 2 * (blurred - sharp)));
            print_message("%s: sphere at %.0f, focus %.0f: circle of confusion %.2f pixels (thin lens: %.2f); "
                          "darkness kept %.3f\n", ig ? "path tracer" : "model", d, F, got, want, mass1 / mass0);
            assert_true(fabs(got - want) < 0.08 * want + 0.35);
            assert_true(fabs(mass1 / mass0 - 1) < 0.03); /* a blur moves darkness, it does not make it */
        }
}

/* ---- for compositors ------------------------------------------------------------------------------- */

/* 16 numbers from an attribute's text (OpenImageIO prints a matrix with commas). */
static void matrix_of(const char *path, const char *key, double m[16])
{
    char *text;
    err_t e = {{0}};
    if (!image_read_text(path, key, &text, &e))
        fail_msg("%s: %s", key, e.msg);
    const char *p = text;
    for (int i = 0; i < 16; i++) {
        while (*p == ',' || *p == ' ')
            p++;
        char *end;
        m[i] = strtod(p, &end);
        if (end == p)
            fail_msg("%s: '%s' is not 16 numbers", key, text);
        p = end;
    }
    free(text);
}

/* An EXR with the position and albedo AOVs and the camera's matrices, from a rolled camera (and orthographic): every
 * hit pixel's P lies on the sphere (the scene's own geometry), P through worldToNDC lands in that
 * pixel's centre, and worldToCamera puts P at its depth along the view (+z, left-handed). Stereo, side by side
 * and top-bottom (issue 58 item 10: the centre's matrix put left-eye points ~156 px off): each half's P through
 * its eye's matrices (worldToNDC, rightWorldToNDC) lands in its pixel's centre. */
static void exr_position_and_camera(void **st)
{
    (void)st;
    enum { XW = 81, XH = 51 };
    static const double SP[][4] = {{0.3, 0.2, 0, 1.1}};
    scene s;
    spheres_scene(SP, 1, false, NULL, &s);
    for (int run = 0; run < 6; run++) {
        int ortho = run % 2, stereo = run / 2; /* STEREO_NONE, _SIDE_BY_SIDE, _TOP_BOTTOM */
        camera cam = cam_at(1.5, 1, 5, 0, 0, 0, 40);
        cam.roll = 0.4f;
        cam.lens = (camera_lens){.projection = ortho ? PROJECTION_ORTHOGRAPHIC : PROJECTION_PERSPECTIVE, .focus = 5,
                                 .stereo = (camera_stereo)stereo, .eye_separation = 0.3f};
        const char *out = "fathom-test-optics.exr";
        offline_desc d = {.scene = &s, .cam = cam, .width = stereo == 1 ? 2 * XW : XW,
                          .height = stereo == 2 ? 2 * XH : XH, .spp = 1, .output = out,
                          .aovs = AOV_DEPTH | AOV_POSITION | AOV_ALBEDO, .quiet = true};
        err_t e = {{0}};
        if (!offline_render_current(&d, &e))
            fail_msg("%s", e.msg);
        double w2c[16], w2n[16], right_w2c[16], right_w2n[16];
        matrix_of(out, "worldtocamera", w2c);
        matrix_of(out, "worldtoNDC", w2n);
        if (stereo) {
            matrix_of(out, "rightWorldToCamera", right_w2c);
            matrix_of(out, "rightWorldToNDC", right_w2n);
        }
        float *px;
        int w, h, nc;
        if (!image_read_f32(out, 0, 16384, &w, &h, &nc, &px, &e))
            fail_msg("%s", e.msg);
        unlink(out);
        assert_int_equal(nc, 11); /* R G B A Z P.X P.Y P.Z albedo.R albedo.G albedo.B */
        double worst_surface = 0, worst_pixel = 0, worst_depth = 0, worst_albedo = 0;
        int hits = 0;
        camera_basis b = camera_get_basis(&cam);
        for (int row = 0; row < h; row++)
            for (int x = 0; x < w; x++) {
                const float *q = px + ((size_t)row * (size_t)w + (size_t)x) * (size_t)nc;
                for (int k = 8; k < 11; k++) /* the material's base colour on a hit, 0 on a miss */
                    worst_albedo = fmax(worst_albedo, fabs(q[k] - (isinf(q[4]) ? 0.0 : 0.6)));
                if (isinf(q[4]))
                    continue;
                hits++;
                double P[4] = {q[5], q[6], q[7], 1}, ndc[4] = {0}, c[4] = {0};
                bool right = (stereo == 1 && x >= w / 2) || (stereo == 2 && row >= h / 2); /* top: the left eye */
                const double *M = right ? right_w2n : w2n, *C = right ? right_w2c : w2c;
                worst_surface = fmax(worst_surface, fabs(sqrt(pow(P[0] - SP[0][0], 2) + pow(P[1] - SP[0][1], 2) +
                                                              pow(P[2] - SP[0][2], 2)) - SP[0][3]));
                for (int k = 0; k < 4; k++)
                    for (int j = 0; j < 4; j++) {
                        ndc[k] += P[j] * M[4 * j + k];
                        c[k] += P[j] * C[4 * j + k];
                    }
                worst_pixel = fmax(worst_pixel, hypot(ndc[0] / ndc[3] * w - (x + 0.5), ndc[1] / ndc[3] * h - (row + 0.5)));
                double along = 0; /* the depth along the view, from the eye (orthographic: its plane) */
                for (int i = 0; i < 3; i++)
                    along += (P[i] - cam.position[i]) * b.forward[i];
                worst_depth = fmax(worst_depth, fabs(c[2] - along));
            }
        free(px);
        print_message("%s%s, rolled: %d hits; P off the sphere by %.2g at most, P through worldToNDC %.3f pixels from "
                      "its pixel, worldToCamera z off by %.2g\n", ortho ? "orthographic" : "perspective",
                      (const char *[]){"", " side by side", " top-bottom"}[stereo], hits, worst_surface, worst_pixel,
                      worst_depth);
        assert_true(hits > XW * XH / 8);
        assert_true(worst_surface < 2e-3);
        assert_true(worst_pixel < 0.02);
        assert_true(worst_depth < 1e-4);
        assert_true(worst_albedo < 1e-6);
    }
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(roll_turns_the_image),       cmocka_unit_test(orthographic_sphere),
        cmocka_unit_test(equirectangular_panorama),   cmocka_unit_test(fisheye_dome),
        cmocka_unit_test(stereo_disparity),           cmocka_unit_test(lens_circle_of_confusion),
        cmocka_unit_test(exr_position_and_camera),
    };
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
