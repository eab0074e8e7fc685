/* Water on a DEM (terrain.water, shaders/terrain/terrain.glsl, the glass of common/sdf_main.glsl) against
 * closed forms in double:
 *  - the shoreline: every pixel's first hit is the nearer of the exact ground (tests/lib/terrain_ref.c) and
 *    the level plane where the ground under it lies below the level, from above, grazing, and from a camera
 *    under the water; the water's hits are level (normal (0, 1, 0));
 *  - Beer–Lambert: over a flat bed, the light the water lets through, (c(σ) − c(∞)) / (c(0) − c(∞)), is
 *    e^(−σ d) for d the refracted ray's path to the bed by Snell's law, pixel by pixel;
 *  - only where asked: a scene without water compiles none of it, and one with water at a level below every
 *    height draws what the dry scene draws. */
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
#include <gdal.h>

#include "check.h"
#include "gltest.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "data/geo/terrain.h"
#include "data/geo/water.h"
#include "scene/effect.h"
#include "terrain_ref.h"

static char dir[64], scene_path[256];
static const double LEVEL = 150; /* metres: the synthetic DEM's hills are 0-300 m, its sea flat at 0 */

static int setup(void **st)
{
    if (gl_setup(st))
        return -1;
    snprintf(dir, sizeof dir, "/tmp/fathom-water-XXXXXX");
    if (!mkdtemp(dir))
        return -1;
    synthetic_dem(dir, "hills", 300, 260, false, scene_path, sizeof scene_path);
    /* the same scene with the water's own material, whose absorption the tests set */
    char path[300];
    snprintf(path, sizeof path, "%s/lake.json", dir);
    FILE *f = fopen(path, "w");
    fprintf(f, "{\"program\": \"terrain\", \"materials\": {\"rock\": {}, \"water\": {\"transmission\": 1, \"ior\": 1.333, "
               "\"roughness\": 0, \"absorption\": [0, 0, 0]}}, \"quality\": {\"max_dist\": 1e6}, \"terrain\": "
               "{\"heightmap\": \"hills.exr\", \"spacing\": [30, 30], \"water\": %g}}", LEVEL);
    fclose(f);
    return 0;
}

static int teardown(void **st)
{
    char path[300];
    snprintf(path, sizeof path, "%s/lake.json", dir);
    unlink(path);
    remove_dems(dir, (const char *const[]){"hills", NULL});
    return gl_teardown(st);
}

static heightfield load_hf(const scene *s)
{
    heightfield hf;
    err_t e;
    heightfield_desc d = {.path = s->terrain.heightmap, .spacing = {s->terrain.spacing[0], s->terrain.spacing[1]}};
    if (!heightfield_load(&d, &hf, &e))
        fail_msg("%s", e.msg);
    return hf;
}

/* Where the ray meets the water's surface (the level over ground below it, inside the grid), or −1. */
static double ref_water(const heightfield *hf, const dray *r)
{
    double t = (LEVEL - r->o[1]) / r->d[1];
    if (!(t > 0) || !isfinite(t))
        return -1;
    double cx = (r->o[0] + r->d[0] * t - hf->x0) / hf->dx - 0.5, cz = (r->o[2] + r->d[2] * t - hf->z0) / hf->dz - 0.5;
    if (cx < 0 || cz < 0 || cx > hf->width - 1 || cz > hf->height - 1)
        return -1;
    return height_cell(hf, cx, cz) < LEVEL ? t : -1;
}

/* A texel of the flat sea (height 0) with flat sea for `margin` texels around: world x, z of its centre. */
static void sea_texel(const heightfield *hf, int margin, double *x, double *z)
{
    for (int j = margin; j < hf->height - margin; j++)
        for (int i = margin; i < hf->width - margin; i++) {
            bool flat = true;
            for (int b = -margin; b <= margin && flat; b++)
                for (int a = -margin; a <= margin && flat; a++)
                    flat = texel(hf, i + a, j + b) == 0;
            if (flat) {
                *x = hf->x0 + (i + 0.5) * hf->dx, *z = hf->z0 + (j + 0.5) * hf->dz;
                return;
            }
        }
    fail_msg("the synthetic DEM has no flat sea %d texels wide", 2 * margin + 1);
}

static void shoreline_is_exact(void **st)
{
    (void)st;
    scene s;
    char set[64];
    snprintf(set, sizeof set, "terrain.water=%g", LEVEL);
    load_text_file(scene_path, (const char *const[]){set}, 1, &s);
    heightfield hf = load_hf(&s);
    double sx, sz;
    sea_texel(&hf, 6, &sx, &sz);
    /* the window's probes compile with the water (its flying speed: map() over the sea, 500 m below) */
    float pt[3] = {(float)sx, 500, (float)sz}, d[2];
    err_t e;
    if (!render_set_scene(&s, NULL, &e) || !render_probe(&s, NULL, pt, 1, d, &e))
        fail_msg("%s", e.msg);
    assert_true(d[0] > 0 && d[0] <= 500); /* a bound: the clearance shrunk by the steepest slope */
    const view views[] = {
        {"across the shore, from above", {0, 900, 4000}, {0, 100, -3000}, 60},
        {"grazing the water", {-4000, LEVEL + 15, 3500}, {4000, LEVEL, -3500}, 60},
        {"under the water", {sx, 60, sz}, {sx + 1000, 90, sz - 1000}, 70},
    };
    static float aov[W * H * AOV];
    for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
        camera cam = cam_at(views[v].eye[0], views[v].eye[1], views[v].eye[2], views[v].at[0], views[v].at[1],
                            views[v].at[2], views[v].fov);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int water = 0, ground = 0, ties = 0, bad = 0, shore = 0;
        static signed char kind[W * H]; /* 1 water, 0 ground, -1 sky or a tie */
        for (int row = 0; row < H; row++)
            for (int x = 0; x < W; x++) {
                dray r = pixel_ray(&cam, x, row, W, H);
                double tg = INFINITY, tw = ref_water(&hf, &r);
                if (!ref_terrain(&hf, &r, &tg))
                    tg = INFINITY;
                bool want_water = tw >= 0 && tw < tg;
                double want = want_water ? tw : tg;
                const float *a = aov + (row * W + x) * AOV;
                double tol = 2e-5 * (fabs(want) + hf.hmax) + 0.02 * hf.dx;
                kind[row * W + x] = (signed char)(isinf(want) ? -1 : want_water);
                if (tw >= 0 && isfinite(tg) && fabs(tw - tg) < tol) { /* at the shoreline itself: either */
                    kind[row * W + x] = -1;
                    ties++;
                    continue;
                }
                bool level = a[0] == 0 && a[1] == 1 && a[2] == 0;
                bool ok = isinf(want) ? isinf(a[3]) : fabs(a[3] - want) <= tol && (!want_water || level);
                if (!ok && bad++ < 3)
                    fprintf(stderr, "  %s pixel (%d,%d): depth %.4f normal %.3f %.3f %.3f; exact: %s at %.4f (ground %.4f)\n",
                            views[v].what, x, row, (double)a[3], (double)a[0], (double)a[1], (double)a[2],
                            want_water ? "water" : "ground", want, tg);
                water += want_water;
                ground += !want_water && isfinite(want);
            }
        for (int k = 0; k < W * H; k++) /* pixels whose right or lower neighbour is on the shore's other side */
            shore += kind[k] >= 0 && ((k % W < W - 1 && kind[k + 1] >= 0 && kind[k + 1] != kind[k]) ||
                                      (k + W < W * H && kind[k + W] >= 0 && kind[k + W] != kind[k]));
        fprintf(stderr, "%-30s %4d water, %4d ground, %3d pixels along the shoreline, %3d ties, %d disagree\n",
                views[v].what, water, ground, shore, ties, bad);
        assert_int_equal(bad, 0);
        assert_true(v == 2 ? water > 200 : shore > 30); /* the surface seen from below; shorelines in view */
    }
    heightfield_free(&hf);
    scene_free(&s);
}

/* The lake scene's heightfield and the centre of a texel of its flat sea (12 texels of it around). */
static heightfield lake_sea(double *sx, double *sz)
{
    char lake[300];
    snprintf(lake, sizeof lake, "%s/lake.json", dir);
    scene s;
    load_text_file(lake, NULL, 0, &s);
    heightfield hf = load_hf(&s);
    sea_texel(&hf, 12, sx, sz);
    scene_free(&s);
    return hf;
}

/* The lake scene from cam with each of three overrides (and no jitter): linear RGBA into c[k]. */
static void draw_lake(const camera *cam, const char *const sets[3], float (*c)[W * H * 4])
{
    char lake[300];
    snprintf(lake, sizeof lake, "%s/lake.json", dir);
    for (int k = 0; k < 3; k++) {
        scene s;
        load_text_file(lake, (const char *const[]){sets[k], "effects.aa=off"}, 2, &s);
        draw(&s, cam, W, H, 1, NULL, NULL, c[k]);
        scene_free(&s);
    }
}

static void beer_lambert_through_the_water(void **st)
{
    (void)st;
    double sx, sz;
    heightfield hf = lake_sea(&sx, &sz);
    camera cam = cam_at(sx, 600, sz, sx + 40, 0, sz - 30, 20); /* looking down on the sea's flat bed */
    static float c[3][W * H * 4];
    const double sigma = 0.004;
    draw_lake(&cam, (const char *const[]){"materials.water.absorption=[0, 0, 0]",
                                          "materials.water.absorption=[0.004, 0.004, 0.004]",
                                          "materials.water.absorption=[1000, 1000, 1000]"}, c);
    int checked = 0;
    double worst = 0;
    for (int row = 0; row < H; row++)
        for (int x = 0; x < W; x++) {
            dray r = pixel_ray(&cam, x, row, W, H);
            double t = (LEVEL - r.o[1]) / r.d[1], n = 1.333; /* into the water, refracted by Snell's law */
            double cos_i = -r.d[1], sin_t = sqrt(1 - cos_i * cos_i) / n, cos_t = sqrt(1 - sin_t * sin_t);
            double d = LEVEL / cos_t, h = hypot(r.d[0], r.d[2]);
            double bx = r.o[0] + r.d[0] * t + (h > 0 ? r.d[0] / h : 0) * sin_t * d;
            double bz = r.o[2] + r.d[2] * t + (h > 0 ? r.d[2] / h : 0) * sin_t * d;
            double cx = (bx - hf.x0) / hf.dx - 0.5, cz = (bz - hf.z0) / hf.dz - 0.5;
            int i = (int)floor(cx), j = (int)floor(cz);
            if (i < 1 || j < 1 || i > hf.width - 3 || j > hf.height - 3 || texel(&hf, i, j) != 0 || texel(&hf, i + 1, j) != 0 ||
                texel(&hf, i, j + 1) != 0 || texel(&hf, i + 1, j + 1) != 0)
                continue; /* the bed is flat here */
            for (int ch = 0; ch < 3; ch++) {
                size_t p = (size_t)(row * W + x) * 4 + (size_t)ch;
                double through = (double)c[0][p] - c[2][p], got = ((double)c[1][p] - c[2][p]) / through;
                assert_true(through > 1e-3); /* the bed is lit and seen */
                double want = exp(-sigma * d);
                worst = fmax(worst, fabs(got - want));
                if (fabs(got - want) > 1e-5)
                    fail_msg("pixel (%d,%d) channel %d: %.5f of the bed's light through %.2f m of water, Beer-Lambert "
                             "%.5f", x, row, ch, got, d, want);
            }
            checked++;
        }
    fprintf(stderr, "beer-lambert: %d pixels over the flat bed, worst %.2g from e^(-sigma d)\n", checked, worst);
    assert_true(checked > W * H / 2);
    heightfield_free(&hf);
}

/* A camera under the water looking down at the bed: water that absorbs nothing changes nothing (no surface is
 * crossed: the bed is lit as in the dry scene), and water that does dims each pixel by e^(−σ t), t the ray's
 * length to the bed. */
static void under_the_water(void **st)
{
    (void)st;
    double sx, sz;
    heightfield hf = lake_sea(&sx, &sz);
    camera cam = cam_at(sx, 100, sz, sx + 20, 0, sz - 15, 30);
    static float c[3][W * H * 4];
    draw_lake(&cam, (const char *const[]){"terrain.water=-10", /* dry: water below every height */
                                          "materials.water.absorption=[0, 0, 0]",
                                          "materials.water.absorption=[0.004, 0.004, 0.004]"}, c);
    double worst_clear = 0, worst_beer = 0;
    for (int row = 0; row < H; row++)
        for (int x = 0; x < W; x++) {
            dray r = pixel_ray(&cam, x, row, W, H);
            double t = -r.o[1] / r.d[1]; /* to the flat bed at 0 */
            for (int ch = 0; ch < 3; ch++) {
                size_t p = (size_t)(row * W + x) * 4 + (size_t)ch;
                assert_true(c[0][p] > 1e-3);
                worst_clear = fmax(worst_clear, fabs((double)c[1][p] - c[0][p]) / c[0][p]);
                worst_beer = fmax(worst_beer, fabs((double)c[2][p] / c[1][p] - exp(-0.004 * t)));
            }
        }
    fprintf(stderr, "under the water: clear water differs from none by %.2g, absorbing water from e^(-sigma t) by %.2g\n",
            worst_clear, worst_beer);
    assert_true(worst_clear < 1e-5);
    assert_true(worst_beer < 1e-5);
    heightfield_free(&hf);
}

/* The sun on the bed under the water: through the surface (Fresnel's transmitted share at its angle) and down
 * the refracted path (Beer–Lambert over depth / cos θt); the sky off, so the sun is all the light. Against the
 * dry bed: 1 − F exactly for clear water; absorbing water dims it by e^(−σ (t + depth / cos θt)) more. */
static void sunlight_through_the_water(void **st)
{
    (void)st;
    double sx, sz;
    heightfield hf = lake_sea(&sx, &sz);
    static const char sun[] = "lights=[{\"type\": \"directional\", \"direction\": [0.5, 0.6, 0.3], \"intensity\": 3, "
                              "\"shadow\": \"none\"}]";
    char lake[300];
    snprintf(lake, sizeof lake, "%s/lake.json", dir);
    camera cam = cam_at(sx, 100, sz, sx + 20, 0, sz - 15, 30);
    static float c[3][W * H * 4];
    const char *abs[3] = {"terrain.water=-10", "materials.water.absorption=[0, 0, 0]",
                          "materials.water.absorption=[0.002, 0.004, 0.008]"};
    scene s;
    double l[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        load_text_file(lake, (const char *const[]){abs[k], "effects.aa=off", sun, "environment.intensity=0"}, 4, &s);
        for (int i = 0; i < 3; i++)
            l[i] = s.lights[0].vec[i];
        draw(&s, &cam, W, H, 1, NULL, NULL, c[k]);
        scene_free(&s);
    }
    double n = 1.333, cos_i = l[1], cos_t = sqrt(1 - (1 - cos_i * cos_i) / (n * n));
    double eta = 1 / n, rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t), rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    double T = 1 - 0.5 * (rs * rs + rp * rp), sigma[3] = {0.002, 0.004, 0.008}, worst_t = 0, worst_beer = 0;
    for (int row = 0; row < H; row++)
        for (int x = 0; x < W; x++) {
            dray r = pixel_ray(&cam, x, row, W, H);
            double t = -r.o[1] / r.d[1]; /* to the flat bed at 0, 150 m under the surface */
            for (int ch = 0; ch < 3; ch++) {
                size_t p = (size_t)(row * W + x) * 4 + (size_t)ch;
                assert_true(c[0][p] > 1e-3);
                worst_t = fmax(worst_t, fabs((double)c[1][p] / c[0][p] - T));
                worst_beer = fmax(worst_beer, fabs((double)c[2][p] / c[1][p] - exp(-sigma[ch] * (t + LEVEL / cos_t))));
            }
        }
    fprintf(stderr, "sunlight under the water: 1 - F = %.5f to %.2g, Beer-Lambert down and back to %.2g\n", T, worst_t,
            worst_beer);
    assert_true(worst_t < 1e-5);
    assert_true(worst_beer < 1e-5);
    heightfield_free(&hf);
}

/* terrain.water=fill: the lakes water_grid gives (each flat at its level: a wet corner's level, a dry corner the
 * wet ones' mean) against every pixel's nearer of the exact ground and the plane of the level of the cell the
 * ray crosses it in, in double; the lakes' normals level. */
static void lakes_from_the_dem(void **st)
{
    (void)st;
    scene s;
    load_text_file(scene_path, (const char *const[]){"terrain.water=fill"}, 1, &s);
    heightfield hf = load_hf(&s);
    float *lv = malloc(sizeof(float) * (size_t)hf.width * (size_t)hf.height), top;
    err_t e;
    assert_true(water_grid(hf.h, hf.width, hf.height, hf.dx, hf.dz, NULL, NULL, 1, lv, &top, &e));
    int wet = 0;
    for (int k = 0; k < hf.width * hf.height; k++)
        wet += lv[k] > -1e20f;
    fprintf(stderr, "lakes: %d wet texels, the highest level %.2f\n", wet, (double)top);
    assert_true(wet > 100);
    static float aov[W * H * AOV];
    const view views[] = {{"over the lakes", {0, 900, 4000}, {0, 100, -3000}, 60},
                          {"low over the lakes", {-4000, 420, 3500}, {4000, 100, -3500}, 60}};
    for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
        camera cam = cam_at(views[v].eye[0], views[v].eye[1], views[v].eye[2], views[v].at[0], views[v].at[1],
                            views[v].at[2], views[v].fov);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int water = 0, bad = 0, ties = 0;
        for (int row = 0; row < H; row++)
            for (int x = 0; x < W; x++) {
                dray r = pixel_ray(&cam, x, row, W, H);
                double tg = INFINITY, tw = INFINITY;
                if (!ref_terrain(&hf, &r, &tg))
                    tg = INFINITY;
                bool tie = false;
                for (int k = 0; k < hf.width * hf.height; k++) { /* each lake's plane, where its cells are */
                    if (!(lv[k] > -1e20f) || (k > 0 && lv[k - 1] == lv[k]))
                        continue;
                    double t = (lv[k] - r.o[1]) / r.d[1];
                    if (!(t > 0) || t >= tw)
                        continue;
                    double cx = (r.o[0] + r.d[0] * t - hf.x0) / hf.dx - 0.5, cz = (r.o[2] + r.d[2] * t - hf.z0) / hf.dz - 0.5;
                    int i = (int)floor(cx), j = (int)floor(cz);
                    if (i < 0 || j < 0 || i > hf.width - 2 || j > hf.height - 2)
                        continue;
                    bool here = false;
                    for (int q = 0; q < 4; q++)
                        here |= lv[(j + q / 2) * hf.width + i + q % 2] == lv[k];
                    if (here) {
                        tw = t;
                        tie = fmin(fmin(cx - i, i + 1 - cx), fmin(cz - j, j + 1 - cz)) < 1e-4; /* on a cell's side */
                    }
                }
                bool want_water = tw < tg;
                double want = want_water ? tw : tg, tol = 2e-5 * (fabs(want) + hf.hmax) + 0.02 * hf.dx;
                if (tie || (isfinite(tw) && isfinite(tg) && fabs(tw - tg) < tol)) {
                    ties++;
                    continue;
                }
                const float *a = aov + (row * W + x) * AOV;
                bool level = fabsf(a[1] - 1) < 1e-6f;
                bool ok = isinf(want) ? isinf(a[3]) : fabs(a[3] - want) <= tol && (!want_water || level);
                if (!ok && bad++ < 3)
                    fprintf(stderr, "  %s pixel (%d,%d): depth %.4f normal y %.4f; exact: %s at %.4f (ground %.4f)\n",
                            views[v].what, x, row, (double)a[3], (double)a[1], want_water ? "lake" : "ground", want, tg);
                water += want_water;
            }
        fprintf(stderr, "%-22s %4d on lakes, %3d ties, %d disagree\n", views[v].what, water, ties, bad);
        assert_int_equal(bad, 0);
        assert_true(water > 100);
    }
    free(lv);
    heightfield_free(&hf);
    scene_free(&s);
}

/* terrain.water=RASTER: a flood surface sloping 1 m a texel eastward (100 m at the west edge, 399 m at the east,
 * above the highest hill), a GeoTIFF on the DEM's grid: its bilinear patches are that plane, so every pixel is
 * the nearer of the exact ground and the plane, its normal the plane's; a raster of another size is refused. */
static void flood_raster(void **st)
{
    (void)st;
    scene s;
    load_text_file(scene_path, NULL, 0, &s);
    heightfield hf = load_hf(&s);
    scene_free(&s);
    char tif[300], set[340];
    snprintf(tif, sizeof tif, "%s/flood.tif", dir);
    GDALAllRegister();
    for (int pass = 0; pass < 2; pass++) {
        int fw = pass ? hf.width - 1 : hf.width;
        GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), tif, fw, hf.height, 1, GDT_Float32, NULL);
        float *w = malloc(sizeof(float) * (size_t)fw * (size_t)hf.height);
        for (int k = 0; k < fw * hf.height; k++)
            w[k] = 100.0f + (float)(k % fw);
        assert_true(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, fw, hf.height, w, fw, hf.height, GDT_Float32, 0,
                                 0) == CE_None);
        GDALClose(ds);
        free(w);
        snprintf(set, sizeof set, "terrain.water=%s", tif);
        load_text_file(scene_path, (const char *const[]){set}, 1, &s);
        if (pass) { /* one texel narrower than the DEM */
            err_t e;
            assert_false(render_set_scene(&s, NULL, &e));
            print_message("%s\n", e.msg);
            assert_non_null(strstr(e.msg, "is 299 x 260 texels and the DEM 300 x 260"));
            scene_free(&s);
            break;
        }
        static float aov[W * H * AOV];
        camera cam = cam_at(-3000, 900, 4500, 2000, 150, -2000, 60);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int water = 0, ground = 0, bad = 0;
        double nlen = sqrt(1 + 1 / (hf.dx * hf.dx));
        for (int row = 0; row < H; row++)
            for (int x = 0; x < W; x++) {
                dray r = pixel_ray(&cam, x, row, W, H);
                double tg = INFINITY;
                if (!ref_terrain(&hf, &r, &tg))
                    tg = INFINITY;
                /* y = 100 + cx, cx = (x - x0) / dx - 0.5 along the ray */
                double tw = (100 + (r.o[0] - hf.x0) / hf.dx - 0.5 - r.o[1]) / (r.d[1] - r.d[0] / hf.dx);
                double cx = (r.o[0] + r.d[0] * tw - hf.x0) / hf.dx - 0.5, cz = (r.o[2] + r.d[2] * tw - hf.z0) / hf.dz - 0.5;
                if (!(tw > 0) || cx < 0 || cz < 0 || cx > hf.width - 1 || cz > hf.height - 1)
                    tw = INFINITY;
                bool want_water = tw < tg;
                double want = want_water ? tw : tg, tol = 2e-5 * (fabs(want) + hf.hmax) + 0.02 * hf.dx;
                if (isfinite(tw) && isfinite(tg) && fabs(tw - tg) < tol)
                    continue;
                const float *a = aov + (row * W + x) * AOV;
                bool slope = fabs(a[0] + 1 / hf.dx / nlen) < 1e-4 && fabs(a[1] - 1 / nlen) < 1e-4 && fabs(a[2]) < 1e-4;
                bool ok = isinf(want) ? isinf(a[3]) : fabs(a[3] - want) <= tol && (!want_water || slope);
                if (!ok && bad++ < 3)
                    fprintf(stderr, "  flood pixel (%d,%d): depth %.4f normal %.4f %.4f %.4f; exact: %s at %.4f\n", x, row,
                            (double)a[3], (double)a[0], (double)a[1], (double)a[2], want_water ? "flood" : "ground", want);
                water += want_water;
                ground += !want_water && isfinite(want);
            }
        fprintf(stderr, "flood raster: %d on the flood, %d on the ground, %d disagree\n", water, ground, bad);
        assert_int_equal(bad, 0);
        assert_true(water > 500 && ground > 100);
        scene_free(&s);
    }
    unlink(tif);
    heightfield_free(&hf);
}

static void only_where_asked(void **st)
{
    (void)st;
    scene dry, low;
    load_text_file(scene_path, NULL, 0, &dry);
    load_text_file(scene_path, (const char *const[]){"terrain.water=-10"}, 1, &low); /* below the sea's 0 */
    assert_false(dry.effects & (1u << EFFECT_WATER));
    assert_true(low.effects & (1u << EFFECT_WATER));
    camera cam = cam_at(0, 900, 4000, 0, 100, -3000, 60);
    static float a[W * H * 4], b[W * H * 4];
    draw(&dry, &cam, W, H, 1, NULL, NULL, a);
    draw(&low, &cam, W, H, 1, NULL, NULL, b);
    double worst = 0;
    for (int k = 0; k < W * H * 4; k++)
        worst = fmax(worst, fabs((double)a[k] - b[k]));
    fprintf(stderr, "water below every height: worst difference %.3g from the dry scene\n", worst);
    assert_true(worst < 1e-5);
    scene_free(&dry);
    scene_free(&low);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shoreline_is_exact),
        cmocka_unit_test(beer_lambert_through_the_water),
        cmocka_unit_test(under_the_water),
        cmocka_unit_test(sunlight_through_the_water),
        cmocka_unit_test(lakes_from_the_dem),
        cmocka_unit_test(flood_raster),
        cmocka_unit_test(only_where_asked),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
