/* Terrain on DEMs the tests were not written on, generated here, every pixel against the exact
 * ray–bilinear-heightfield intersection in double (tests/lib/terrain_ref.c): a 4096² DEM far and grazing,
 * a 1000×150 strip, nodata holes, the same in tiles (seams in the heights and the pyramid), patch normals
 * that are each patch's own gradient, and a plain on the Earth's curvature against its closed form. */
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
#include <ogr_srs_api.h>

#include "check.h"
#include "gltest.h"
#include "data/media/image_io.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "data/geo/terrain.h"
#include "terrain_ref.h"


/* The exact traversal on DEMs it was not written on. Each fails without one fix:
 *  - 4096², far rays: the nudge past a node's face must exceed the rounding of a position recomputed
 *    from an origin thousands of cells away, or the walk stalls and reports a miss (9 pixels);
 *  - a 1000 × 150 strip: the max pyramid's upper levels need a side of at least 1 on the short axis,
 *    or they are all −inf and nothing is drawn (every pixel);
 *  - the sea exactly at the minimum height: the slab of a descending ray reaches a little below hmin,
 *    or float rounding at the slab's exit decides hit or miss (16 pixels). */
static void big_and_odd_grids(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-dems-XXXXXX", big[300], strip[300];
    assert_non_null(mkdtemp(dir));
    synthetic_dem(dir, "big", 4096, 4096, false, big, sizeof big);     /* 123 km square */
    synthetic_dem(dir, "strip", 1000, 150, false, strip, sizeof strip); /* 30 × 4.5 km: 6.7:1 */
    const char *sets[] = {"terrain.method=maxmip", "quality.spp=1", "quality.preset=final"};
    /* over the big DEM: oblique from a corner across thousands of cells, grazing, and straight down on
     * the flat sea (heights exactly the minimum) */
    const view big_views[] = {
        {"4096²: oblique, far", {-55000, 2500, -55000}, {20000, 0, 15000}, 50},
        {"4096²: grazing", {-30000, 310, 40000}, {30000, 250, -40000}, 20},
        {"4096²: down on the sea", {10000, 3000, 10000}, {10100, 0, 10050}, 60},
    };
    const view strip_views[] = {
        {"1000×150: along the strip", {-16000, 900, 0}, {10000, 100, 0}, 40},
        {"1000×150: across it", {0, 1500, 9000}, {0, 100, 0}, 60},
    };
    check_views_in(strip, "maxmip", sets, 3, true, strip_views, 2);
    check_views_in(big, "maxmip", sets, 3, true, big_views, 3);
    remove_dems(dir, (const char *const[]){"strip", "big", NULL});
}

/* Nodata holes (NaN in the file): rays pass through a hole's cells and meet its walls where the
 * column goes on, against the same reference with no surface in cells that touch a hole. Both
 * methods: maxmip exactly, the linear search within its step (its walls are found by bisection). */
static void nodata_holes(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-holes-XXXXXX", scene_path[300];
    assert_non_null(mkdtemp(dir));
    synthetic_dem(dir, "holes", 256, 192, true, scene_path, sizeof scene_path);
    const view views[] = {
        {"holes: oblique", {-5000, 1500, -4000}, {0, 50, 0}, 50},
        {"holes: down into the round hole", {300, 2500, 200}, {0, 0, 0}, 40},
        {"holes: grazing the line", {-2000, 200, -3500}, {-2000, 150, 3000}, 30},
    };
    const char *maxmip[] = {"terrain.method=maxmip", "quality.spp=1", "quality.preset=final"};
    check_views_in(scene_path, "maxmip", maxmip, 3, true, views, 3);
    const char *linear[] = {"terrain.method=linear", "quality.preset=reference", "quality.spp=1", "quality.max_steps=4096"};
    check_views_in(scene_path, "linear", linear, 4, false, views, 2);
    remove_dems(dir, (const char *const[]){"holes", NULL});
}

/* DEMs in tiles: with tiles of 64 texels (FATHOM_TERRAIN_TILE) the long strip and the holes DEM cross
 * dozens of tile seams, in the heights and in every pyramid level; every pixel still agrees with the
 * reference. Then a 16-bit GeoTIFF wider than the GL texture limit (16384 on llvmpipe), tiled by
 * default: before tiling it could not be drawn at all. */
static void tiled_grids(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-tiles-XXXXXX", strip[300], holes[300], wide[300], file[320];
    assert_non_null(mkdtemp(dir));
    synthetic_dem(dir, "strip", 1000, 150, false, strip, sizeof strip);
    synthetic_dem(dir, "holes", 256, 192, true, holes, sizeof holes);
    setenv("FATHOM_TERRAIN_TILE", "64", 1);
    const char *maxmip[] = {"terrain.method=maxmip", "quality.spp=1", "quality.preset=final"};
    const view strip_views[] = {
        {"tiles of 64: along the strip", {-16000, 900, 0}, {10000, 100, 0}, 40},
        {"tiles of 64: across it", {0, 1500, 9000}, {0, 100, 0}, 60},
    };
    const view hole_views[] = {
        {"tiles of 64: holes, oblique", {-5000, 1500, -4000}, {0, 50, 0}, 50},
        {"tiles of 64: holes, grazing", {-2000, 200, -3500}, {-2000, 150, 3000}, 30},
    };
    check_views_in(strip, "maxmip", maxmip, 3, true, strip_views, 2);
    int tx = 0, ty = 0;
    assert_true(render_terrain_tiles(&tx, &ty));
    assert_int_equal(tx, 16); /* 1000 / 64 */
    assert_int_equal(ty, 3);
    check_views_in(holes, "maxmip", maxmip, 3, true, hole_views, 2);
    const char *linear[] = {"terrain.method=linear", "quality.preset=reference", "quality.spp=1", "quality.max_steps=4096"};
    check_views_in(holes, "linear", linear, 4, false, hole_views, 1);
    unsetenv("FATHOM_TERRAIN_TILE");

    /* 16,500 x 48 Int16 metres, UTM 30 m: wider than one texture */
    enum { WW = 16500, WH = 48 };
    int16_t *v = malloc(sizeof(int16_t) * WW * WH);
    for (int j = 0; j < WH; j++)
        for (int i = 0; i < WW; i++)
            v[j * WW + i] = (int16_t)(200 + 150 * sin(i * 0.021) * cos(j * 0.3) + 80 * sin(i * 0.0037));
    snprintf(file, sizeof file, "%s/wide.tif", dir);
    GDALAllRegister();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), file, WW, WH, 1, GDT_Int16, NULL);
    double gt[6] = {400000, 30, 0, 5000000, 0, -30};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(NULL);
    OSRImportFromEPSG(srs, 32632);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
    assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, WW, WH, v, WW, WH, GDT_Int16, 0, 0), CE_None);
    GDALClose(ds);
    free(v);
    snprintf(wide, sizeof wide, "%s/wide.json", dir);
    FILE *f = fopen(wide, "w");
    fprintf(f, "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"quality\": {\"max_dist\": 1e6}, "
               "\"terrain\": {\"heightmap\": \"wide.tif\"}}");
    fclose(f);
    const view wide_views[] = {
        {"16500x48: along, across 4 seams", {-250000, 3000, 0}, {100000, 0, 0}, 30},
        {"16500x48: over a seam", {-122000 + 30 * 4096 - 247500, 2500, -900}, {30 * 4096 - 247500, 200, 0}, 50},
    };
    check_views_in(wide, "maxmip", maxmip, 3, true, wide_views, 2);
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    assert_true(render_terrain_tiles(&tx, &ty));
    fprintf(stderr, "16500x48 on a GPU whose textures reach %d: %d x %d tiles\n", max_side, tx, ty);
    if (max_side < WW)
        assert_true(tx > 1);
    unlink(file);
    remove_dems(dir, (const char *const[]){"strip", "holes", "wide", NULL});
}

/* terrain.normals=patch: the normal at each hit is the hit bilinear patch's own, against its gradient
 * in double at the reference's hit point (pixels whose hit lies within 0.01 cell of a cell edge are
 * left out: the surface has a crease there). The smooth default differs: the test can fail. */
static void patch_normals_are_exact(void **st)
{
    (void)st;
    static float aov[W * H * AOV];
    double worst[2] = {0, 0};
    for (int mode = 0; mode < 2; mode++) {
        scene s;
        err_t e;
        const char *sets[] = {"quality.spp=1", mode ? "terrain.normals=smooth" : "terrain.normals=patch"};
        if (!scene_load("jacksboro", sets, 2, &s, &e))
            fail_msg("%s", e.msg);
        heightfield hf;
        heightfield_desc d = {.path = s.terrain.heightmap, .height_min = s.terrain.height_min,
                              .height_max = s.terrain.height_max, .exaggeration = s.terrain.exaggeration};
        if (!heightfield_load(&d, &hf, &e))
            fail_msg("%s", e.msg);
        int checked = 0;
        for (int v = 0; v < 2; v++) {
            const view *vw = &VIEWS[v + 1]; /* inside the slab; below the surface (looking up at it) */
            camera cam = cam_at(vw->eye[0], vw->eye[1], vw->eye[2], vw->at[0], vw->at[1], vw->at[2], vw->fov);
            draw(&s, &cam, W, H, 1, NULL, aov, NULL);
            for (int row = 0; row < H; row++)
                for (int x = 0; x < W; x++) {
                    dray r = pixel_ray(&cam, x, row, W, H);
                    double t;
                    if (!ref_terrain(&hf, &r, &t) || t == 0)
                        continue;
                    double cx = (r.o[0] + r.d[0] * t - hf.x0) / hf.dx - 0.5, cz = (r.o[2] + r.d[2] * t - hf.z0) / hf.dz - 0.5;
                    int i = (int)floor(cx), j = (int)floor(cz);
                    double u = cx - i, w = cz - j;
                    if (fmin(fmin(u, 1 - u), fmin(w, 1 - w)) < 0.01 || i < 0 || j < 0 || i > hf.width - 2 || j > hf.height - 2)
                        continue;
                    if (r.o[1] + r.d[1] * t < height_cell(&hf, cx, cz) - 0.01) /* the column's floor or side */
                        continue;
                    double h00 = texel(&hf, i, j), h10 = texel(&hf, i + 1, j), h01 = texel(&hf, i, j + 1),
                           h11 = texel(&hf, i + 1, j + 1), k = h00 - h10 - h01 + h11;
                    double gx = (h10 - h00 + k * w) / hf.dx, gz = (h01 - h00 + k * u) / hf.dz;
                    double n[3] = {-gx, 1, -gz}, len = sqrt(gx * gx + 1 + gz * gz);
                    const float *a = &aov[(row * W + x) * AOV + AOV_SLOT_NORMAL];
                    double c = (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / len;
                    worst[mode] = fmax(worst[mode], acos(fmin(c, 1.0)) * 57.29577951308232);
                    checked++;
                }
        }
        fprintf(stderr, "%s normals: %d hits checked, worst angle to the patch's normal %.4f°\n", mode ? "smooth" : "patch",
                checked, worst[mode]);
        assert_true(checked > W * H / 4);
        heightfield_free(&hf);
        scene_free(&s);
    }
    assert_true(worst[0] < 0.05); /* float rounding of the hit point and the normal */
    assert_true(worst[1] > 1.0);  /* the smooth normal is not the patch's */
}

/* The Earth's curvature (terrain.curvature): over a sea-level plain 200 km across, from 100 m up, every pixel
 * against the closed form in double: the ground d from the camera lies (1 − k) d² / 2R lower (times the
 * exaggeration), so a ray of direction r meets it where 100 + r_y t + c |r_xz|² t² = 0, and misses above the
 * horizon (the dip 2√(100 c)); water 2 cm over the plain curves with it. Rays within 1e-4 of grazing the
 * curve are skipped (a float's direction moves their root by metres). */
static void earth_curvature(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-curve-XXXXXX", exr[300], json[300];
    assert_non_null(mkdtemp(dir));
    enum { N = 2001 };
    float *zero = calloc((size_t)N * N, sizeof *zero);
    zero[0] = 50; /* one texel in a far corner: the slab's top above the plain, so the walk (not the slab) finds it */
    snprintf(exr, sizeof exr, "%s/plain.exr", dir);
    err_t e;
    if (!image_write_f32(exr, N, N, 1, (const char *const[]){"Y"}, zero, &e))
        fail_msg("%s", e.msg);
    free(zero);
    snprintf(json, sizeof json, "%s/plain.json", dir);
    static float aov[W * H * AOV];
    /* 100 m texels at true scale; then 1 km texels exaggerated 100 times, where the drop within one cell (7 m)
     * is more than the tolerance: each cell's intersection must carry the curve too, not only the walk */
    const struct { double spacing, ex; } passes[2] = {{100, 1}, {1000, 100}};
    for (int pass = 0; pass < 4; pass++) {
        int water = pass & 1;
        double spacing = passes[pass / 2].spacing, ex = passes[pass / 2].ex;
        FILE *f = fopen(json, "w");
        fprintf(f, "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"quality\": {\"max_dist\": 1e7}, "
                   "\"terrain\": {\"heightmap\": \"plain.exr\", \"spacing\": [%g, %g], \"curvature\": true, "
                   "\"exaggeration\": %g}}", spacing, spacing, ex);
        fclose(f);
        const double c = ex * (1 - 0.13) / (2 * 6371000.0), EYE = 100, dip = 2 * sqrt(EYE * c);
        scene s;
        load_text_file(json, (const char *const[]){water ? "terrain.water=0.02" : "terrain.curvature=true"}, 1, &s);
        camera cam = cam_at(0, EYE, 0, 0, EYE - 3000 * tan(dip), -3000, 4 * dip / DEG2RAD); /* the horizon mid-image */
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int hits = 0, misses = 0, grazing = 0, bad = 0;
        double worst = 0;
        for (int row = 0; row < H; row++)
            for (int x = 0; x < W; x++) {
                dray r = pixel_ray(&cam, x, row, W, H);
                double A = c * (r.d[0] * r.d[0] + r.d[2] * r.d[2]), B = r.d[1], C = EYE - (water ? 0.02 * ex : 0);
                double disc = B * B - 4 * A * C, t = disc >= 0 && B < 0 ? (-B - sqrt(disc)) / (2 * A) : INFINITY;
                if (fabs(disc) < 1e-4 * B * B) {
                    grazing++;
                    continue;
                }
                float got = aov[(row * W + x) * AOV + 3];
                double tol = 2e-5 * (isinf(t) ? 0 : t) + 0.5;
                bool ok = isinf(t) ? isinf(got) : fabs(got - t) <= tol;
                if (isfinite(t) && isfinite(got))
                    worst = fmax(worst, fabs(got - t));
                if (!ok && bad++ < 3)
                    fprintf(stderr, "  %s pixel (%d,%d): depth %.2f, the curved ground's %.2f\n", water ? "water" : "plain", x,
                            row, (double)got, t);
                hits += isfinite(t), misses += isinf(t);
            }
        fprintf(stderr, "curvature (%g m texels, x%g)%s: %d hits (worst %.3f m), %d misses above the horizon, %d grazing, "
                "%d disagree\n", spacing, ex, water ? " with water" : "", hits, worst, misses, grazing, bad);
        assert_int_equal(bad, 0);
        assert_true(hits > 500 && misses > 500);
        scene_free(&s);
    }
    unlink(exr);
    unlink(json);
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(big_and_odd_grids),
        cmocka_unit_test(nodata_holes),
        cmocka_unit_test(patch_normals_are_exact),
        cmocka_unit_test(tiled_grids),
        cmocka_unit_test(earth_curvature),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='far*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
