/* GIS layers in (data/geo/geo.h), each checked with GDAL and OGR called here directly:
 *  - imagery in another CRS (a WGS 84 checkerboard on a UTM DEM) lands where its squares are: every
 *    drape pixel away from a square's edge has its square's colour, and each edge crossed by the middle
 *    row lies within half a drape pixel of its longitude; where the imagery does not reach, alpha is 0;
 *    vectors keep the imagery's resolution and are as wide as their metres say;
 *  - the sun block points by true north on a projected grid and at the poles; a south-up DEM is the
 *    same place. (The GIS jobs' files: test_gis_jobs.c.) */
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
#include <cpl_conv.h>
#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "data/geo/dem.h"
#include "data/geo/geo.h"
#include "data/sky/sun.h"
#include "data/geo/viewshed.h"
#include "jobs/gis/gis_job.h"
#include "scene/scene.h"
#include "view/path.h"

#include "geo_fixture.h"

enum { SQ_PX = 10 };          /* imagery pixels a checker square */
static const double PX = 0.005; /* degrees an imagery pixel */
static const double LON0 = 13.5, LAT0 = 48.2; /* the imagery's north-west corner */

/* A WGS 84 checkerboard, red and blue squares of 0.05°, reaching only 0.55° east of LON0. */
static void write_checker(const char *file, int iw, int ih)
{
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), file, iw, ih, 3, GDT_Byte, NULL);
    double gt[6] = {LON0, PX, 0, LAT0, 0, -PX};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH s = fixture_srs(4326);
    GDALSetSpatialRef(ds, s);
    OSRDestroySpatialReference(s);
    unsigned char *b = malloc((size_t)iw * (size_t)ih);
    for (int c = 0; c < 3; c++) {
        for (int j = 0; j < ih; j++)
            for (int i = 0; i < iw; i++) {
                bool red = ((i / SQ_PX) + (j / SQ_PX)) % 2 == 0;
                b[(size_t)j * (size_t)iw + (size_t)i] = (unsigned char)(c == 0 ? (red ? 255 : 0) : c == 2 ? (red ? 0 : 255) : 0);
            }
        assert_true(GDALRasterIO(GDALGetRasterBand(ds, c + 1), GF_Write, 0, 0, iw, ih, b, iw, ih, GDT_Byte, 0, 0) == CE_None);
    }
    free(b);
    GDALClose(ds);
}

static void drape_lands_on_the_right_texels(void **st)
{
    (void)st;
    double lon_w, lat_n, lon_e, lat_s;
    fixture_utm_to_lonlat(DEM_GT[0], DEM_GT[3], &lon_w, &lat_n);
    fixture_utm_to_lonlat(DEM_GT[0] + W * 1000, DEM_GT[3] - H * 1000, &lon_e, &lat_s);
    assert_true(lon_w > LON0 + 0.05 && lat_n < LAT0 - 0.05); /* the board covers the DEM's north-west */
    int iw = 110, ih = (int)ceil((LAT0 - lat_s + 0.1) / PX); /* 0.55° wide: ends inside the DEM */
    assert_true(LON0 + iw * PX < lon_e - 0.05);
    write_checker(fixture_path("checker.tif"), iw, ih);
    unsigned char *rgba;
    int w = 0, h = 0;
    err_t e;
    if (!geo_drape(fixture_path("dem.tif"), fixture_path("checker.tif"), 4096, &rgba, &w, &h, &e))
        fail_msg("%s", e.msg);
    print_message("drape: %d x %d\n", w, h);
    assert_true(w > 80 && h > 60);
    int checked = 0, wrong = 0, bare = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const unsigned char *p = rgba + 4 * ((size_t)j * (size_t)w + (size_t)i);
            double lon, lat;
            fixture_utm_to_lonlat(DEM_GT[0] + (i + 0.5) * W * 1000.0 / w, DEM_GT[3] - (j + 0.5) * H * 1000.0 / h, &lon, &lat);
            double u = (lon - LON0) / PX, v = (LAT0 - lat) / PX; /* imagery pixels from its corner */
            if (u > iw + 1.5) { /* past the imagery's eastern edge: no coverage */
                bare += p[3] == 0;
                continue;
            }
            double du = fabs(u / SQ_PX - round(u / SQ_PX)) * SQ_PX, dv = fabs(v / SQ_PX - round(v / SQ_PX)) * SQ_PX;
            if (du < 1.5 || dv < 1.5 || u > iw - 1.5)
                continue; /* an edge's blend */
            bool red = ((int)floor(u / SQ_PX) + (int)floor(v / SQ_PX)) % 2 == 0;
            checked++;
            wrong += p[3] != 255 || (red ? p[0] < 200 || p[2] > 55 : p[2] < 200 || p[0] > 55);
        }
    print_message("drape: %d pixels checked, %d wrong, %d past the imagery with alpha 0\n", checked, wrong, bare);
    assert_int_equal(wrong, 0);
    assert_true(checked > 2000 && bare > 500);
    /* the middle row: where red turns blue, against the squares' longitudes */
    int j = h / 2, edges = 0;
    double worst = 0;
    for (int i = 0; i + 1 < w; i++) {
        const unsigned char *a = rgba + 4 * ((size_t)j * (size_t)w + (size_t)i), *b = a + 4;
        if (a[3] != 255 || b[3] != 255)
            continue;
        double fa = a[0] / (double)(a[0] + a[2] + 1), fb = b[0] / (double)(b[0] + b[2] + 1);
        if ((fa - 0.5) * (fb - 0.5) >= 0)
            continue;
        double x = i + (0.5 - fa) / (fb - fa); /* the crossing, in drape pixels from pixel i's centre */
        double lon, lat, lon1, lat1;
        fixture_utm_to_lonlat(DEM_GT[0] + (x + 0.5) * W * 1000.0 / w, DEM_GT[3] - (j + 0.5) * H * 1000.0 / h, &lon, &lat);
        fixture_utm_to_lonlat(DEM_GT[0] + (x + 1.5) * W * 1000.0 / w, DEM_GT[3] - (j + 0.5) * H * 1000.0 / h, &lon1, &lat1);
        double edge = LON0 + round((lon - LON0) / (SQ_PX * PX)) * SQ_PX * PX;
        worst = fmax(worst, fabs(lon - edge) / fabs(lon1 - lon)); /* in drape pixels */
        edges++;
    }
    print_message("drape: %d square edges on the middle row, the worst %.3f drape pixels off its longitude\n", edges,
                  worst);
    assert_true(edges >= 5);
    assert_true(worst < 0.5);
    free(rgba);
}

/* Issue 58, item 1: a vector layer never coarsens the imagery under it. The checkerboard's own drape size
 * stands when the vectors ask for less (a 5 km line), and gives way to theirs when they ask for more. */
static void vectors_keep_the_imagery_resolution(void **st)
{
    (void)st;
    write_checker(fixture_path("layers.tif"), 400, 300);
    unsigned char *rgba;
    int w = 0, h = 0, lw, lh;
    err_t e;
    if (!geo_drape(fixture_path("dem.tif"), fixture_path("layers.tif"), 4096, &rgba, &w, &h, &e))
        fail_msg("%s", e.msg);
    free(rgba);
    const float coarse[] = {5000, 0}, fine[] = {5000, 100};
    assert_true(geo_layers_size(fixture_path("dem.tif"), fixture_path("layers.tif"), coarse, 2, 4096, &lw, &lh, &e));
    print_message("layers: the imagery's own %d x %d; with 5 km and DEM-texel lines %d x %d\n", w, h, lw, lh);
    assert_true(w > 2 * W && lw == w && lh == h);
    assert_true(geo_layers_size(fixture_path("dem.tif"), fixture_path("layers.tif"), fine, 2, 4096, &lw, &lh, &e));
    print_message("layers: with a 100 m line %d x %d (two texels across it)\n", lw, lh);
    assert_true(lw >= W * 1000 / 50 - 1 && lw > w);
    assert_true(geo_layers_size(fixture_path("dem.tif"), NULL, coarse, 1, 4096, &lw, &lh, &e) && lw == W && lh == H);
}

/* Burns a north-south line `width` metres wide at longitude 10.5 on a WGS 84 DEM at 49.5–50.1° N drawn at
 * w × h; returns its width in metres on the middle row, alpha summed (coverage) times the texel's width. */
static double drawn_width(double width, int w, int h)
{
    FILE *f = fopen(fixture_path("ns.geojson"), "w");
    fprintf(f, "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Feature\", \"properties\": {},"
               " \"geometry\": {\"type\": \"LineString\", \"coordinates\": [[10.5, 49.4], [10.5, 50.2]]}}]}\n");
    fclose(f);
    unsigned char *rgba = malloc(4 * (size_t)w * (size_t)h);
    err_t e;
    if (!geo_vectors(fixture_path("geo.tif"), fixture_path("ns.geojson"), width, (const float[4]){1, 0, 0, 1}, w, h, rgba, &e))
        fail_msg("%s", e.msg);
    double covered = 0, lat = 50.1 - 0.6 * (h / 2 + 0.5) / h;
    for (int i = 0; i < w; i++)
        covered += rgba[4 * ((size_t)(h / 2) * (size_t)w + (size_t)i) + 3] / 255.0;
    free(rgba);
    /* a texel's east-west metres on the WGS 84 ellipsoid: the parallel's radius, N(φ) cos φ */
    double a = 6378137, e2 = 0.00669437999014, phi = lat * M_PI / 180;
    double east = M_PI / 180 * a * cos(phi) / sqrt(1 - e2 * sin(phi) * sin(phi)) * 1.0 / w;
    return covered * east;
}

/* Issue 58, item 4: a line's width is metres on the ground in every direction, on a geographic DEM too (an
 * 8 km line was 5.5 km wide east–west at 49.8° N: the width was taken in degrees of latitude), and not
 * quantised to drape texels (a line two texels wide was drawn one to three wide). */
static void vector_widths_in_metres(void **st)
{
    (void)st;
    enum { GW = 100, GH = 60 };
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), fixture_path("geo.tif"), GW, GH, 1, GDT_Float32, NULL);
    double gt[6] = {10, 0.01, 0, 50.1, 0, -0.01};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH s = fixture_srs(4326);
    GDALSetSpatialRef(ds, s);
    OSRDestroySpatialReference(s);
    float v[GW * GH] = {0};
    assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, GW, GH, v, GW, GH, GDT_Float32, 0, 0),
                     CE_None);
    GDALClose(ds);
    double wide = drawn_width(8000, 400, 240), worst = 0;
    print_message("widths: an 8 km line drawn %.0f m wide east-west at 49.8 N\n", wide);
    assert_true(fabs(wide / 8000 - 1) < 0.01);
    for (int k = 0; k < 7; k++) { /* a 2.2-texel line (texels of 180 m), at seven offsets from the grid */
        double width = 400 + 20 * k, got = drawn_width(width, 400, 240);
        worst = fmax(worst, fabs(got / width - 1));
    }
    print_message("widths: 400-520 m lines (2.2-2.9 texels) drawn within %.1f %% of their width\n", 100 * worst);
    assert_true(worst < 0.06); /* a sub-texel of 8 across: 1/17.6 of a 2.2-texel line */
}

/* Issue 58, item 17: a south-up DEM (positive y pixel size, its first row the southernmost) is the same place as
 * its north-up twin: the viewshed from the same longitude and latitude is the same, written north-up on the
 * same grid (a wrong south-up origin survived the tests). */
static void south_up_dem_is_the_same_place(void **st)
{
    (void)st;
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), fixture_path("south.tif"), W, H, 1, GDT_Float32, NULL);
    const double gt[6] = {DEM_GT[0], 1000, 0, DEM_GT[3] - H * 1000, 0, 1000};
    GDALSetGeoTransform(ds, (double *)gt);
    OGRSpatialReferenceH s = fixture_srs(32633);
    GDALSetSpatialRef(ds, s);
    OSRDestroySpatialReference(s);
    float v[W * H];
    for (int j = 0; j < H; j++) /* file row j is the north-up row H − 1 − j */
        for (int i = 0; i < W; i++)
            v[j * W + i] = (float)fixture_hill(i, H - 1 - j);
    assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, W, H, v, W, H, GDT_Float32, 0, 0), CE_None);
    GDALClose(ds);
    double lon, lat;
    fixture_utm_to_lonlat(DEM_GT[0] + 20.5 * 1000, DEM_GT[3] - 30.5 * 1000, &lon, &lat);
    err_t e;
    const char *dems[2] = {fixture_path("dem.tif"), fixture_path("south.tif")}, *outs[2] = {fixture_path("vs-n.tif"), fixture_path("vs-s.tif")};
    unsigned char got[2][W * H];
    for (int radius = 0; radius <= 7500; radius += 7500) { /* the whole DEM, and a window of it read from disk */
        double g[2][6];
        int size[2][2];
        for (int k = 0; k < 2; k++) {
            gis_options o = {.command = GIS_VIEWSHED, .dem = dems[k], .output = outs[k], .lon = lon, .lat = lat,
                             .observer_height = 10, .refraction = 0.13, .radius = radius};
            if (!gis_viewshed_run(&o, &e))
                fail_msg("%s", e.msg);
            GDALDatasetH r = GDALOpen(outs[k], GA_ReadOnly);
            assert_true(GDALGetGeoTransform(r, g[k]) == CE_None);
            size[k][0] = GDALGetRasterXSize(r), size[k][1] = GDALGetRasterYSize(r);
            assert_true(GDALRasterIO(GDALGetRasterBand(r, 1), GF_Read, 0, 0, size[k][0], size[k][1], got[k], size[k][0],
                                     size[k][1], GDT_Byte, 0, 0) == CE_None);
            GDALClose(r);
        }
        for (int i = 0; i < 6; i++)
            assert_true(g[0][i] == g[1][i] && (radius || g[0][i] == DEM_GT[i]));
        assert_true(size[0][0] == size[1][0] && size[0][1] == size[1][1]);
        assert_memory_equal(got[0], got[1], (size_t)size[0][0] * (size_t)size[0][1]);
    }
}

/* Issue 58, item 2: on a polar stereographic DEM (EPSG:3413, the projection fathom recommends near the poles;
 * central meridian 45° W) grid north is the central meridian's: at 0° E true north lies 45° west of it
 * (γ = −(λ − λ0) on the polar stereographic), so the sun's light is turned by −45° on the grid (shadows were
 * 45° off; 25° on the DEM). */
static void sun_on_a_polar_grid(void **st)
{
    (void)st;
    enum { PW = 40, PH = 30 };
    OGRSpatialReferenceH polar = fixture_srs(3413), g = fixture_srs(4326);
    OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(g, polar);
    double x = 0, y = 75, z = 0; /* the DEM's centre: 75° N, 0° E */
    assert_true(OCTTransform(t, 1, &x, &y, &z));
    OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(g);
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), fixture_path("polar.tif"), PW, PH, 1, GDT_Float32, NULL);
    double gt[6] = {x - PW / 2.0 * 500, 500, 0, y + PH / 2.0 * 500, 0, -500};
    GDALSetGeoTransform(ds, gt);
    GDALSetSpatialRef(ds, polar);
    OSRDestroySpatialReference(polar);
    float v[PW * PH];
    for (int k = 0; k < PW * PH; k++)
        v[k] = (float)(100 + k % 7);
    assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, PW, PH, v, PW, PH, GDT_Float32, 0, 0),
                     CE_None);
    GDALClose(ds);
    char text[1024];
    snprintf(text, sizeof text,
             "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"lights\": [{\"type\": \"directional\","
             " \"direction\": [0, 1, 0]}], \"terrain\": {\"heightmap\": \"%s\"},"
             " \"sun\": {\"date\": \"2026-06-21\", \"hour\": 15, \"utc_offset\": 0}}", fixture_path("polar.tif"));
    scene s;
    err_t e;
    if (!scene_load_text(text, fixture_path("polar.json"), NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    const float *l = s.lights[0].vec;
    double grid_az = atan2(l[0], -l[2]) * 180 / M_PI, want = s.sun.azimuth - 45;
    print_message("polar: the sun at azimuth %.2f° true, %.2f° on the grid (want %.2f°), convergence %.3f°\n",
                  s.sun.azimuth, grid_az, want, s.sun.convergence);
    assert_true(fabs(s.sun.latitude - 75) < 1e-3 && fabs(s.sun.longitude) < 1e-3);
    assert_true(fabs(s.sun.convergence + 45) < 1e-3);
    assert_true(fabs(remainder(grid_az - want, 360)) < 1e-3);
    scene_free(&s);
}

/* Issue 58, item 8: imagery wholly off the DEM is refused by name (it drew as nothing, silently): geo.tif lies
 * at 10-11° E, 49.5-50.1° N, the DEM near 14° E, 47.5° N. */
static void imagery_off_the_dem_refused(void **st)
{
    (void)st;
    unsigned char *rgba = NULL;
    int w = 0, h = 0;
    err_t e;
    assert_false(geo_drape(fixture_path("dem.tif"), fixture_path("geo.tif"), 4096, &rgba, &w, &h, &e));
    print_message("%s\n", e.msg);
    assert_non_null(strstr(e.msg, "wholly off the DEM"));
}

/* Issue 58, item 8 (after the tests above, which wrote ns.geojson and layers.tif): a layer's file given on the
 * command line in the object form is the user's folder's, as the
 * plain form is (it was looked for beside the scene file: under scenes/ for a named scene). */
static void set_layers_from_the_users_folder(void **st)
{
    (void)st;
    char here[PATH_MAX_LEN], want[PATH_MAX_LEN * 2];
    assert_non_null(getcwd(here, sizeof here));
    assert_int_equal(chdir(fixture_dir), 0);
    const char *text = "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"terrain\": {\"heightmap\": "
                       "\"/nonexistent/dem.tif\"}}";
    const char *sets[] = {"terrain.heightmap=dem.tif", "terrain.imagery={\"file\": \"layers.tif\", \"opacity\": 0.5}",
                          "terrain.vectors=[{\"file\": \"ns.geojson\", \"width\": 30}, \"ns.geojson\"]"};
    scene s;
    err_t e;
    bool ok = scene_load_text(text, "/nonexistent/scene.json", sets, 3, &s, &e);
    assert_int_equal(chdir(here), 0);
    if (!ok)
        fail_msg("%s", e.msg);
    snprintf(want, sizeof want, "%s/ns.geojson", fixture_dir);
    assert_string_equal(s.terrain.vectors[0], want);
    assert_string_equal(s.terrain.vectors[1], want);
    snprintf(want, sizeof want, "%s/layers.tif", fixture_dir);
    assert_string_equal(s.terrain.imagery[0], want);
    scene_free(&s);
}

/* The "sun" block on the UTM DEM: the light points where NOAA's sun stands over the DEM's centre (its
 * longitude and latitude found here by OSR), coloured by the beam; night leaves it black; mistakes are
 * named. */
static void sun_block_moves_the_light(void **st)
{
    (void)st;
    char text[1024];
    const char *fmt = "{\"program\": \"terrain\", \"materials\": {\"rock\": {}},"
                      " \"lights\": [{\"type\": \"%s\", \"%s\": [0, 1, 0], \"color\": [1, 1, 1]}],"
                      " \"terrain\": {\"heightmap\": \"%s\"},"
                      " \"sun\": {\"date\": \"%s\", \"hour\": %g, \"utc_offset\": 2}}";
    snprintf(text, sizeof text, fmt, "directional", "direction", fixture_path("dem.tif"), "2026-06-21", 9.5);
    scene s;
    err_t e;
    if (!scene_load_text(text, fixture_path("sun.json"), NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    double lon, lat, t;
    fixture_utm_to_lonlat(DEM_GT[0] + W / 2.0 * 1000, DEM_GT[3] - H / 2.0 * 1000, &lon, &lat); /* the centre */
    assert_true(sun_time("2026-06-21", 9.5, 2, &t));
    sun_position p = sun_at(t, lat, lon);
    /* the grid's north is not true north: in UTM 33N (central meridian 15° E) true north lies
     * atan(tan(λ − λ0) sin φ) east of grid north's west, the transverse Mercator's convergence (the ellipsoid's
     * terms are below 1e-6° here) (issue 58 item 2) */
    double gamma = -atan(tan((lon - 15) * M_PI / 180) * sin(lat * M_PI / 180));
    double az = p.azimuth * M_PI / 180 + gamma, el = p.elevation * M_PI / 180;
    const float *v = s.lights[0].vec;
    print_message("sun over %.4f, %.4f at 09:30 UTC+2: azimuth %.2f, elevation %.2f; true north %+.3f° from the grid's "
                  "(fathom: %+.3f°)\n", lon, lat, p.azimuth, p.elevation, gamma * 180 / M_PI, s.sun.convergence);
    assert_true(fabs(s.sun.convergence - gamma * 180 / M_PI) < 1e-3 && fabs(gamma) > 0.005);
    assert_true(fabs(v[0] - cos(el) * sin(az)) < 1e-5 && fabs(v[1] - sin(el)) < 1e-5 &&
                fabs(v[2] + cos(el) * cos(az)) < 1e-5); /* east +X, north −Z */
    assert_true(fabs(s.sun.azimuth - p.azimuth) < 1e-6 && p.azimuth > 90 && p.azimuth < 180); /* south-east */
    float beam[3];
    sun_color(p.elevation, beam);
    assert_true(fabsf(s.lights[0].color[2] - beam[2]) < 1e-6f);
    scene_free(&s);
    snprintf(text, sizeof text, fmt, "directional", "direction", fixture_path("dem.tif"), "2026-12-21", 1.0);
    assert_true(scene_load_text(text, fixture_path("sun.json"), NULL, 0, &s, &e));
    assert_true(s.lights[0].color[0] == 0 && s.sun.elevation < -30); /* a winter's night */
    scene_free(&s);
    snprintf(text, sizeof text, fmt, "point", "position", fixture_path("dem.tif"), "2026-06-21", 9.5);
    assert_false(scene_load_text(text, fixture_path("sun.json"), NULL, 0, &s, &e));
    assert_non_null(strstr(e.msg, "not a directional light"));
    snprintf(text, sizeof text, fmt, "directional", "direction", fixture_path("dem.tif"), "2026-02-30", 9.5);
    assert_false(scene_load_text(text, fixture_path("sun.json"), NULL, 0, &s, &e));
    assert_non_null(strstr(e.msg, "sun.date"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(drape_lands_on_the_right_texels),
        cmocka_unit_test(sun_block_moves_the_light),
        cmocka_unit_test(vectors_keep_the_imagery_resolution),
        cmocka_unit_test(vector_widths_in_metres),
        cmocka_unit_test(sun_on_a_polar_grid),
        cmocka_unit_test(set_layers_from_the_users_folder),
        cmocka_unit_test(imagery_off_the_dem_refused),
        cmocka_unit_test(south_up_dem_is_the_same_place),
    };
    return cmocka_run_group_tests(tests, fixture_setup, fixture_teardown);
}
