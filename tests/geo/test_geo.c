/* GIS in and out (data/geo/geo.h, jobs/gis/gis_job.h), each checked with GDAL and OGR called here directly:
 *  - imagery in another CRS (a WGS 84 checkerboard on a UTM DEM) lands where its squares are: every
 *    drape pixel away from a square's edge has its square's colour, and each edge crossed by the middle
 *    row lies within half a drape pixel of its longitude; where the imagery does not reach, alpha is 0;
 *  - the viewshed GeoTIFF has the DEM's grid, CRS, nodata and the values computed, and the observer
 *    lands on the texel its longitude and latitude name;
 *  - GPX and KML written are read back by OGR with the same points, heights and times (a hostile track
 *    name is escaped), and read back by fathom too;
 *  - a flight becomes a track and the track a flight again: its keys lie within a texel of the first
 *    flight's path and `height` above the ground. */
#define _XOPEN_SOURCE 700 /* M_PI, mkdtemp */
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

static char dir[] = "/tmp/fathom-geo-XXXXXX";
enum { W = 64, H = 48 };
static const double DEM_GT[6] = {400000, 1000, 0, 5300000, 0, -1000}; /* UTM 33N, 1 km texels */

static const char *in_dir(const char *name)
{
    static char full[16][256];
    static int k;
    k = (k + 1) % 16;
    snprintf(full[k], sizeof full[k], "%s/%s", dir, name);
    return full[k];
}

static double hill(int i, int j) { return 300 + 250 * sin(0.2 * i) * cos(0.15 * j) + 4 * i; }

static OGRSpatialReferenceH srs_of(int epsg)
{
    OGRSpatialReferenceH s = OSRNewSpatialReference(NULL);
    OSRImportFromEPSG(s, epsg);
    OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER);
    return s;
}

static int setup(void **st)
{
    (void)st;
    if (!mkdtemp(dir))
        return -1;
    GDALAllRegister();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), in_dir("dem.tif"), W, H, 1, GDT_Float32, NULL);
    GDALSetGeoTransform(ds, (double *)DEM_GT);
    OGRSpatialReferenceH s = srs_of(32633);
    GDALSetSpatialRef(ds, s);
    OSRDestroySpatialReference(s);
    float v[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            v[j * W + i] = (float)hill(i, j);
    int ok = GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, W, H, v, W, H, GDT_Float32, 0, 0) == CE_None;
    GDALClose(ds);
    return ok ? 0 : -1;
}

static int teardown(void **st)
{
    (void)st;
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* UTM 33N x, y to longitude and latitude, by OSR here. */
static void utm_to_lonlat(double x, double y, double *lon, double *lat)
{
    OGRSpatialReferenceH u = srs_of(32633), g = srs_of(4326);
    OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(u, g);
    double z = 0;
    assert_true(OCTTransform(t, 1, &x, &y, &z));
    *lon = x, *lat = y;
    OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(u);
    OSRDestroySpatialReference(g);
}

enum { SQ_PX = 10 };          /* imagery pixels a checker square */
static const double PX = 0.005; /* degrees an imagery pixel */
static const double LON0 = 13.5, LAT0 = 48.2; /* the imagery's north-west corner */

/* A WGS 84 checkerboard, red and blue squares of 0.05°, reaching only 0.55° east of LON0. */
static void write_checker(const char *file, int iw, int ih)
{
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), file, iw, ih, 3, GDT_Byte, NULL);
    double gt[6] = {LON0, PX, 0, LAT0, 0, -PX};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH s = srs_of(4326);
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
    utm_to_lonlat(DEM_GT[0], DEM_GT[3], &lon_w, &lat_n);
    utm_to_lonlat(DEM_GT[0] + W * 1000, DEM_GT[3] - H * 1000, &lon_e, &lat_s);
    assert_true(lon_w > LON0 + 0.05 && lat_n < LAT0 - 0.05); /* the board covers the DEM's north-west */
    int iw = 110, ih = (int)ceil((LAT0 - lat_s + 0.1) / PX); /* 0.55° wide: ends inside the DEM */
    assert_true(LON0 + iw * PX < lon_e - 0.05);
    write_checker(in_dir("checker.tif"), iw, ih);
    unsigned char *rgba;
    int w = 0, h = 0;
    err_t e;
    if (!geo_drape(in_dir("dem.tif"), in_dir("checker.tif"), 4096, &rgba, &w, &h, &e))
        fail_msg("%s", e.msg);
    print_message("drape: %d x %d\n", w, h);
    assert_true(w > 80 && h > 60);
    int checked = 0, wrong = 0, bare = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const unsigned char *p = rgba + 4 * ((size_t)j * (size_t)w + (size_t)i);
            double lon, lat;
            utm_to_lonlat(DEM_GT[0] + (i + 0.5) * W * 1000.0 / w, DEM_GT[3] - (j + 0.5) * H * 1000.0 / h, &lon, &lat);
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
        utm_to_lonlat(DEM_GT[0] + (x + 0.5) * W * 1000.0 / w, DEM_GT[3] - (j + 0.5) * H * 1000.0 / h, &lon, &lat);
        utm_to_lonlat(DEM_GT[0] + (x + 1.5) * W * 1000.0 / w, DEM_GT[3] - (j + 0.5) * H * 1000.0 / h, &lon1, &lat1);
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
    write_checker(in_dir("layers.tif"), 400, 300);
    unsigned char *rgba;
    int w = 0, h = 0, lw, lh;
    err_t e;
    if (!geo_drape(in_dir("dem.tif"), in_dir("layers.tif"), 4096, &rgba, &w, &h, &e))
        fail_msg("%s", e.msg);
    free(rgba);
    const float coarse[] = {5000, 0}, fine[] = {5000, 100};
    assert_true(geo_layers_size(in_dir("dem.tif"), in_dir("layers.tif"), coarse, 2, 4096, &lw, &lh, &e));
    print_message("layers: the imagery's own %d x %d; with 5 km and DEM-texel lines %d x %d\n", w, h, lw, lh);
    assert_true(w > 2 * W && lw == w && lh == h);
    assert_true(geo_layers_size(in_dir("dem.tif"), in_dir("layers.tif"), fine, 2, 4096, &lw, &lh, &e));
    print_message("layers: with a 100 m line %d x %d (two texels across it)\n", lw, lh);
    assert_true(lw >= W * 1000 / 50 - 1 && lw > w);
    assert_true(geo_layers_size(in_dir("dem.tif"), NULL, coarse, 1, 4096, &lw, &lh, &e) && lw == W && lh == H);
}

/* Burns a north-south line `width` metres wide at longitude 10.5 on a WGS 84 DEM at 49.5–50.1° N drawn at
 * w × h; returns its width in metres on the middle row, alpha summed (coverage) times the texel's width. */
static double drawn_width(double width, int w, int h)
{
    FILE *f = fopen(in_dir("ns.geojson"), "w");
    fprintf(f, "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Feature\", \"properties\": {},"
               " \"geometry\": {\"type\": \"LineString\", \"coordinates\": [[10.5, 49.4], [10.5, 50.2]]}}]}\n");
    fclose(f);
    unsigned char *rgba = malloc(4 * (size_t)w * (size_t)h);
    err_t e;
    if (!geo_vectors(in_dir("geo.tif"), in_dir("ns.geojson"), width, (const float[4]){1, 0, 0, 1}, w, h, rgba, &e))
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
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), in_dir("geo.tif"), GW, GH, 1, GDT_Float32, NULL);
    double gt[6] = {10, 0.01, 0, 50.1, 0, -0.01};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH s = srs_of(4326);
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

static void viewshed_geotiff(void **st)
{
    (void)st;
    double lon, lat;
    utm_to_lonlat(DEM_GT[0] + 20.5 * 1000, DEM_GT[3] - 30.5 * 1000, &lon, &lat); /* texel (20, 30)'s centre */
    gis_options o = {.command = GIS_VIEWSHED, .dem = in_dir("dem.tif"), .output = in_dir("vs.tif"), .lon = lon,
                     .lat = lat, .observer_height = 10, .refraction = 0.13};
    err_t e;
    if (!gis_viewshed_run(&o, &e))
        fail_msg("%s", e.msg);
    double col, row;
    assert_true(geo_convert(in_dir("dem.tif"), true, 1, &lon, &lat, &col, &row, &e));
    assert_true(fabs(col - 20) < 1e-6 && fabs(row - 30) < 1e-6);
    /* the same computation here, then the file against it */
    float hts[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            hts[j * W + i] = (float)hill(i, j);
    unsigned char want[W * H], got[W * H];
    viewshed_desc d = {.heights = hts, .w = W, .h = H, .dx = 1000, .dz = 1000, .col = 20, .row = 30,
                       .observer_height = 10, .refraction = 0.13, .curvature = true};
    assert_true(viewshed_compute(&d, want, NULL, &e));
    GDALDatasetH ds = GDALOpen(in_dir("vs.tif"), GA_ReadOnly);
    assert_non_null(ds);
    double gt[6];
    assert_true(GDALGetGeoTransform(ds, gt) == CE_None);
    for (int k = 0; k < 6; k++)
        assert_true(gt[k] == DEM_GT[k]);
    OGRSpatialReferenceH utm = srs_of(32633);
    assert_true(OSRIsSame(GDALGetSpatialRef(ds), utm));
    OSRDestroySpatialReference(utm);
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    int has;
    assert_true(GDALGetRasterNoDataValue(b, &has) == 255 && has);
    assert_non_null(GDALGetRasterColorTable(b));
    assert_non_null(strstr(GDALGetDescription(b), "refraction coefficient 0.130"));
    assert_true(GDALRasterIO(b, GF_Read, 0, 0, W, H, got, W, H, GDT_Byte, 0, 0) == CE_None);
    GDALClose(ds);
    assert_memory_equal(got, want, sizeof got);
    size_t vis = 0;
    for (int k = 0; k < W * H; k++)
        vis += got[k] == VIEWSHED_VISIBLE;
    assert_true(vis > 50 && vis < W * H - 50);
    /* an observer off the DEM: an error, and no file */
    o.output = in_dir("off.tif");
    o.lon = lon + 3;
    assert_false(gis_viewshed_run(&o, &e));
    print_message("%s\n", e.msg);
    assert_non_null(strstr(e.msg, "outside the DEM"));
    assert_int_equal(access(in_dir("off.tif"), F_OK), -1);
}

/* A geographic DEM of GW × GH texels of 0.01° from (lon0, lat0) at its north-west corner; heights rise to the
 * east, texel (hole_i, 0) nodata (-1: none). */
static void write_geographic(const char *file, int gw, int gh, double lon0, double lat0, int hole_i)
{
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), file, gw, gh, 1, GDT_Float32, NULL);
    double gt[6] = {lon0, 0.01, 0, lat0, 0, -0.01};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH s = srs_of(4326);
    GDALSetSpatialRef(ds, s);
    OSRDestroySpatialReference(s);
    float *v = malloc(sizeof(float) * (size_t)(gw * gh));
    for (int k = 0; k < gw * gh; k++)
        v[k] = k == hole_i ? -9999.0f : (float)(100 + k % gw);
    GDALSetRasterNoDataValue(GDALGetRasterBand(ds, 1), -9999);
    assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, gw, gh, v, gw, gh, GDT_Float32, 0, 0),
                     CE_None);
    free(v);
    GDALClose(ds);
}

/* Issue 58, item 5: valid observers are not refused by round-off: at the highest texel's centre beside a
 * nodata texel, at the corner texels' centres and on the DEM's outer edge, and across the antimeridian on a
 * DEM that spans it (178.5-181.5° E, observer at -179.5°). Off the DEM is still refused. */
static void observers_on_edges_and_across_180(void **st)
{
    (void)st;
    enum { GW = 40, GH = 30 };
    write_geographic(in_dir("edge.tif"), GW, GH, 10, 47, GW - 2); /* the highest is (GW - 1, 0), beside the hole */
    const double at[][2] = {{10 + 0.01 * (GW - 0.5), 47 - 0.005}, {10.005, 47 - 0.01 * (GH - 0.5)},
                            {10.0, 46.9}, {10 + 0.01 * GW, 46.9}};
    err_t e;
    for (size_t k = 0; k < sizeof at / sizeof *at; k++) {
        gis_options o = {.command = GIS_VIEWSHED, .dem = in_dir("edge.tif"), .output = in_dir("edge-vs.tif"),
                         .lon = at[k][0], .lat = at[k][1], .observer_height = 2, .refraction = 0.13};
        if (!gis_viewshed_run(&o, &e))
            fail_msg("observer %zu at %.4f, %.4f: %s", k, at[k][0], at[k][1], e.msg);
    }
    write_geographic(in_dir("dateline.tif"), 300, 20, 178.5, 10, -1);
    gis_options o = {.command = GIS_VIEWSHED, .dem = in_dir("dateline.tif"), .output = in_dir("dl-vs.tif"),
                     .lon = -179.5, .lat = 9.9, .observer_height = 2, .refraction = 0.13};
    if (!gis_viewshed_run(&o, &e))
        fail_msg("observer at -179.5: %s", e.msg);
    double col, row, lon = -179.5, lat = 9.9;
    assert_true(geo_convert(in_dir("dateline.tif"), true, 1, &lon, &lat, &col, &row, &e));
    assert_true(fabs(col - 199.5) < 1e-6 && fabs(row - 9.5) < 1e-6);
    o.lon = 177.0, o.output = in_dir("dl-off.tif");
    assert_false(gis_viewshed_run(&o, &e));
    assert_non_null(strstr(e.msg, "outside the DEM"));
}

/* Issue 58, item 6: --radius crops: only the window that holds the circle is read and written (a 3 km radius
 * on a 20000² DEM read and computed it all), georeferenced where it lies, and each of its texels is the
 * whole DEM's viewshed's; every texel outside it is beyond the radius there. */
static void viewshed_radius_crops(void **st)
{
    (void)st;
    double lon, lat;
    utm_to_lonlat(DEM_GT[0] + 20.5 * 1000, DEM_GT[3] - 30.5 * 1000, &lon, &lat); /* texel (20, 30)'s centre */
    gis_options o = {.command = GIS_VIEWSHED, .dem = in_dir("dem.tif"), .output = in_dir("vs-r.tif"), .lon = lon,
                     .lat = lat, .observer_height = 10, .refraction = 0.13, .radius = 7500};
    err_t e;
    if (!gis_viewshed_run(&o, &e))
        fail_msg("%s", e.msg);
    float hts[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            hts[j * W + i] = (float)hill(i, j);
    unsigned char want[W * H];
    viewshed_desc d = {.heights = hts, .w = W, .h = H, .dx = 1000, .dz = 1000, .col = 20, .row = 30,
                       .observer_height = 10, .refraction = 0.13, .curvature = true, .radius = 7500};
    assert_true(viewshed_compute(&d, want, NULL, &e));
    GDALDatasetH ds = GDALOpen(in_dir("vs-r.tif"), GA_ReadOnly);
    assert_non_null(ds);
    int w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
    double gt[6];
    assert_true(GDALGetGeoTransform(ds, gt) == CE_None);
    int x0 = (int)lround((gt[0] - DEM_GT[0]) / 1000), y0 = (int)lround((DEM_GT[3] - gt[3]) / 1000);
    print_message("radius: 7.5 km around texel (20, 30): a %d x %d window from %d, %d\n", w, h, x0, y0);
    assert_true(w <= 2 * 9 + 1 && h <= 2 * 9 + 1 && w >= 15 && h >= 15 && gt[1] == 1000 && gt[5] == -1000);
    unsigned char *got = malloc((size_t)w * (size_t)h);
    assert_true(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, w, h, got, w, h, GDT_Byte, 0, 0) == CE_None);
    GDALClose(ds);
    int outside = 0, wrong = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            bool in = i >= x0 && i < x0 + w && j >= y0 && j < y0 + h;
            if (in)
                wrong += got[(j - y0) * w + (i - x0)] != want[j * W + i];
            else
                outside += want[j * W + i] != VIEWSHED_NODATA;
        }
    free(got);
    assert_int_equal(wrong, 0);
    assert_int_equal(outside, 0);
}

/* Issue 58, item 8: the viewshed draped keeps its nodata clear (GeoTIFF keeps no alpha in its colour table: the
 * nodata entry expanded to opaque black over the terrain): a 7.5 km radius's window on the DEM, hidden and visible
 * texels opaque in their colours, nodata and the DEM beyond the window clear. */
static void viewshed_drapes_see_through(void **st)
{
    (void)st;
    unsigned char *rgba;
    int w = W, h = H; /* the DEM's own grid: each drape pixel one texel */
    err_t e;
    if (!geo_drape(in_dir("dem.tif"), in_dir("vs-r.tif"), 4096, &rgba, &w, &h, &e))
        fail_msg("%s", e.msg);
    GDALDatasetH ds = GDALOpen(in_dir("vs-r.tif"), GA_ReadOnly);
    int vw = GDALGetRasterXSize(ds), vh = GDALGetRasterYSize(ds);
    double gt[6];
    GDALGetGeoTransform(ds, gt);
    int x0 = (int)lround((gt[0] - DEM_GT[0]) / 1000), y0 = (int)lround((DEM_GT[3] - gt[3]) / 1000);
    unsigned char *v = malloc((size_t)vw * (size_t)vh);
    assert_true(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, vw, vh, v, vw, vh, GDT_Byte, 0, 0) == CE_None);
    GDALClose(ds);
    int counts[3] = {0}, wrong = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            int val = i >= x0 && i < x0 + vw && j >= y0 && j < y0 + vh ? v[(j - y0) * vw + (i - x0)] : VIEWSHED_NODATA;
            const unsigned char *p = rgba + 4 * ((size_t)j * W + (size_t)i);
            int kind = val == VIEWSHED_VISIBLE ? 0 : val == VIEWSHED_HIDDEN ? 1 : 2;
            counts[kind]++;
            wrong += kind == 2 ? p[3] != 0 : p[3] != 255 || p[1] != (kind == 0 ? 210 : 20);
        }
    print_message("viewshed draped: %d visible, %d hidden, %d nodata texels; %d drawn wrong\n", counts[0], counts[1],
                  counts[2], wrong);
    free(v);
    free(rgba);
    assert_true(counts[0] > 10 && counts[1] > 10 && counts[2] > 1000);
    assert_int_equal(wrong, 0);
}

/* Issue 58, item 17: a south-up DEM (positive y pixel size, its first row the southernmost) is the same place as
 * its north-up twin: the viewshed from the same longitude and latitude is the same, written north-up on the
 * same grid (a wrong south-up origin survived the tests). */
static void south_up_dem_is_the_same_place(void **st)
{
    (void)st;
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), in_dir("south.tif"), W, H, 1, GDT_Float32, NULL);
    const double gt[6] = {DEM_GT[0], 1000, 0, DEM_GT[3] - H * 1000, 0, 1000};
    GDALSetGeoTransform(ds, (double *)gt);
    OGRSpatialReferenceH s = srs_of(32633);
    GDALSetSpatialRef(ds, s);
    OSRDestroySpatialReference(s);
    float v[W * H];
    for (int j = 0; j < H; j++) /* file row j is the north-up row H − 1 − j */
        for (int i = 0; i < W; i++)
            v[j * W + i] = (float)hill(i, H - 1 - j);
    assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, W, H, v, W, H, GDT_Float32, 0, 0), CE_None);
    GDALClose(ds);
    double lon, lat;
    utm_to_lonlat(DEM_GT[0] + 20.5 * 1000, DEM_GT[3] - 30.5 * 1000, &lon, &lat);
    err_t e;
    const char *dems[2] = {in_dir("dem.tif"), in_dir("south.tif")}, *outs[2] = {in_dir("vs-n.tif"), in_dir("vs-s.tif")};
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

/* The track's points as OGR reads them: lon, lat, z (or the "ele" field), time (seconds). */
static int ogr_points(const char *file, const char *layer, double (*out)[4], int max)
{
    GDALDatasetH ds = GDALOpenEx(file, GDAL_OF_VECTOR, NULL, NULL, NULL);
    assert_non_null(ds);
    OGRLayerH l = layer ? GDALDatasetGetLayerByName(ds, layer) : GDALDatasetGetLayer(ds, 0);
    assert_non_null(l);
    int n = 0, ele = OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), "ele"),
        tf = OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), "time");
    OGRFeatureH f;
    while ((f = OGR_L_GetNextFeature(l)) != NULL) {
        OGRGeometryH g = OGR_F_GetGeometryRef(f);
        for (int k = 0; k < OGR_G_GetPointCount(g) && n < max; k++, n++) {
            out[n][0] = OGR_G_GetX(g, k), out[n][1] = OGR_G_GetY(g, k);
            out[n][2] = ele >= 0 ? OGR_F_GetFieldAsDouble(f, ele) : OGR_G_GetZ(g, k);
            int y, mo, d, hh, mi, tz;
            float s;
            out[n][3] = tf >= 0 && OGR_F_GetFieldAsDateTimeEx(f, tf, &y, &mo, &d, &hh, &mi, &s, &tz)
                            ? (double)util_days_from_civil(y, mo, d) * 86400 + hh * 3600 + mi * 60 + s
                            : NAN;
        }
        OGR_F_Destroy(f);
    }
    GDALClose(ds);
    return n;
}

static void tracks_round_trip(void **st)
{
    (void)st;
    enum { N = 7 };
    geo_point pts[N];
    double cams[N][3];
    for (int i = 0; i < N; i++) {
        pts[i] = (geo_point){13.8 + 0.01 * i, 47.9 - 0.004 * i, 500 + 10.5 * i, 1780000000.0 + 2 * i};
        cams[i][0] = 30 * i, cams[i][1] = 75, cams[i][2] = 0;
    }
    err_t e;
    const char *name = "walk <b>&amp; \"friends\"";
    assert_true(geo_track_write(in_dir("t.gpx"), name, pts, (const double(*)[3])cams, N, &e));
    assert_true(geo_track_write(in_dir("t.kml"), name, pts, (const double(*)[3])cams, N, &e));
    double got[N + 2][4];
    assert_int_equal(ogr_points(in_dir("t.gpx"), "track_points", got, N + 2), N);
    for (int i = 0; i < N; i++) {
        assert_true(fabs(got[i][0] - pts[i].lon) < 1e-9 && fabs(got[i][1] - pts[i].lat) < 1e-9);
        assert_true(fabs(got[i][2] - pts[i].ele) < 1e-6 && fabs(got[i][3] - pts[i].time) < 1e-3);
    }
    assert_int_equal(ogr_points(in_dir("t.kml"), NULL, got, N + 2), N);
    for (int i = 0; i < N; i++)
        assert_true(fabs(got[i][0] - pts[i].lon) < 1e-8 && fabs(got[i][2] - pts[i].ele) < 1e-3);
    char *text;
    size_t len;
    assert_true(util_read_file(in_dir("t.kml"), &text, &len, &e));
    int flytos = 0;
    for (const char *p = text; (p = strstr(p, "<gx:FlyTo>")) != NULL; p++)
        flytos++;
    assert_int_equal(flytos, N);
    assert_null(strstr(text, "<b>")); /* the name escaped */
    free(text);
    geo_point *back;
    int n;
    assert_true(geo_track_read(in_dir("t.gpx"), &back, &n, &e));
    assert_int_equal(n, N);
    assert_true(fabs(back[3].ele - pts[3].ele) < 1e-6 && fabs(back[3].time - pts[3].time) < 1e-3);
    free(back);
    assert_false(geo_track_write(in_dir("t.txt"), name, pts, NULL, N, &e));
    assert_false(geo_track_read(in_dir("dem.tif"), &back, &n, &e)); /* a raster is no track */
}

/* A flight over the DEM to a GPX track, and the track to a flight 120 m above the ground. */
static void flight_track_flight(void **st)
{
    (void)st;
    /* the world frame: x = (col + ½ − W/2)·1000, z = (row + ½ − H/2)·1000 */
    const char *flight = "{ \"keys\": [\n"
                         " { \"time\": 0, \"position\": [-20000, 2000, -10000], \"yaw\": -60, \"pitch\": -10 },\n"
                         " { \"time\": 40, \"position\": [0, 2200, 0], \"yaw\": -90, \"pitch\": -12 },\n"
                         " { \"time\": 80, \"position\": [15000, 1800, 12000], \"yaw\": -120, \"pitch\": -8 } ] }\n";
    err_t e;
    assert_true(util_write_text_atomic(in_dir("f.json"), flight, "the flight", &e));
    char set[300];
    snprintf(set, sizeof set, "terrain.exaggeration=1");
    gis_options o = {.command = GIS_TRACK, .dem = in_dir("dem.tif"), .path = in_dir("f.json"),
                     .output = in_dir("f.gpx"), .fps = 1, .speed = 30, .height = 120, .sets = {set}, .set_count = 1};
    if (!gis_track_run(&o, &e))
        fail_msg("%s", e.msg);
    o = (gis_options){.command = GIS_TRACK, .dem = in_dir("dem.tif"), .input = in_dir("f.gpx"),
                      .output = in_dir("g.json"), .fps = 1, .speed = 30, .height = 120, .sets = {set}, .set_count = 1};
    if (!gis_track_run(&o, &e))
        fail_msg("%s", e.msg);
    path a, b;
    assert_true(path_load(in_dir("f.json"), &a, &e));
    assert_true(path_load(in_dir("g.json"), &b, &e));
    assert_true(b.count >= 20);
    double worst_xz = 0, worst_y = 0;
    for (int k = 0; k < b.count; k++) {
        path_sample s;
        path_eval(&a, b.keys[k].time, &s); /* the GPX's times are the flight's */
        worst_xz = fmax(worst_xz, hypot(s.position[0] - b.keys[k].position[0], s.position[2] - b.keys[k].position[2]));
        double col = b.keys[k].position[0] / 1000 + W / 2.0 - 0.5, row = b.keys[k].position[2] / 1000 + H / 2.0 - 0.5;
        int i = (int)col, j = (int)row;
        double u = col - i, v = row - j;
        double g = (hill(i, j) * (1 - u) + hill(i + 1, j) * u) * (1 - v) + (hill(i, j + 1) * (1 - u) + hill(i + 1, j + 1) * u) * v;
        worst_y = fmax(worst_y, fabs(b.keys[k].position[1] - (g + 120)));
    }
    print_message("flight -> GPX -> flight: %d keys, worst %.3f m off the first flight's path, %.4f m off 120 m "
                  "above the ground\n", b.count, worst_xz, worst_y);
    assert_true(worst_xz < 1.0); /* a texel is 1000 m: the round trip loses nothing */
    assert_true(worst_y < 0.01);
    path_free(&a);
    path_free(&b);
}

/* Issue 58, item 2: on a polar stereographic DEM (EPSG:3413, the projection fathom recommends near the poles;
 * central meridian 45° W) grid north is the central meridian's: at 0° E true north lies 45° west of it
 * (γ = −(λ − λ0) on the polar stereographic), so the sun's light is turned by −45° on the grid (shadows were
 * 45° off; 25° on the DEM). */
static void sun_on_a_polar_grid(void **st)
{
    (void)st;
    enum { PW = 40, PH = 30 };
    OGRSpatialReferenceH polar = srs_of(3413), g = srs_of(4326);
    OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(g, polar);
    double x = 0, y = 75, z = 0; /* the DEM's centre: 75° N, 0° E */
    assert_true(OCTTransform(t, 1, &x, &y, &z));
    OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(g);
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), in_dir("polar.tif"), PW, PH, 1, GDT_Float32, NULL);
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
             " \"sun\": {\"date\": \"2026-06-21\", \"hour\": 15, \"utc_offset\": 0}}", in_dir("polar.tif"));
    scene s;
    err_t e;
    if (!scene_load_text(text, in_dir("polar.json"), NULL, 0, &s, &e))
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
    assert_false(geo_drape(in_dir("dem.tif"), in_dir("geo.tif"), 4096, &rgba, &w, &h, &e));
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
    assert_int_equal(chdir(dir), 0);
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
    snprintf(want, sizeof want, "%s/ns.geojson", dir);
    assert_string_equal(s.terrain.vectors[0], want);
    assert_string_equal(s.terrain.vectors[1], want);
    snprintf(want, sizeof want, "%s/layers.tif", dir);
    assert_string_equal(s.terrain.imagery[0], want);
    scene_free(&s);
}

/* A GPX text of these parts, written to `name` in the test's folder. */
static const char *write_gpx(const char *name, const char *body)
{
    FILE *f = fopen(in_dir(name), "w");
    fprintf(f, "<?xml version=\"1.0\"?>\n<gpx version=\"1.1\" creator=\"test\" "
               "xmlns=\"http://www.topografix.com/GPX/1/1\">\n%s</gpx>\n", body);
    fclose(f);
    return in_dir(name);
}

/* Issue 58, item 7: tracks read and written as the guide says. A GPX with two tracks gives the first (they
 * were merged); one with waypoints and a route flies the route (it flew the waypoints); a point without
 * <time> takes its time between its neighbours (every time was dropped); a flight written without a sun
 * block starts at the flight's own time base, 1970-01-01T00:00:00Z (it was "now"). */
static void tracks_as_the_guide_says(void **st)
{
    (void)st;
    double lon[4], lat[4];
    for (int i = 0; i < 4; i++) /* east along the DEM's middle row, 6 km apart */
        utm_to_lonlat(DEM_GT[0] + 20000 + 6000 * i, DEM_GT[3] - 24000, &lon[i], &lat[i]);
    char body[4096], pt[4][160];
    static const char *const times[4] = {"2026-05-01T10:00:00Z", "2026-05-01T10:02:00Z", NULL, "2026-05-01T10:06:00Z"};
    for (int i = 0; i < 4; i++)
        snprintf(pt[i], sizeof pt[i], "<trkpt lat=\"%.7f\" lon=\"%.7f\">%s%s%s</trkpt>", lat[i], lon[i],
                 times[i] ? "<time>" : "", times[i] ? times[i] : "", times[i] ? "</time>" : "");
    snprintf(body, sizeof body,
             "<wpt lat=\"%.7f\" lon=\"%.7f\"><name>hut</name></wpt><wpt lat=\"%.7f\" lon=\"%.7f\"/>\n"
             "<trk><trkseg>%s%s%s%s</trkseg></trk>\n<trk><trkseg>%s%s</trkseg></trk>\n",
             lat[3], lon[3], lat[0], lon[0], pt[0], pt[1], pt[2], pt[3], pt[3], pt[0]);
    geo_point *pts;
    int n;
    err_t e;
    if (!geo_track_read(write_gpx("two.gpx", body), &pts, &n, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(n, 4); /* the first track's four points, not the second's two nor the waypoints */
    for (int i = 0; i < 4; i++)
        assert_true(fabs(pts[i].lon - lon[i]) < 1e-6 && (i == 2) == isnan(pts[i].time));
    free(pts);
    snprintf(body, sizeof body,
             "<wpt lat=\"%.7f\" lon=\"%.7f\"/><wpt lat=\"%.7f\" lon=\"%.7f\"/>\n<rte><rtept lat=\"%.7f\" lon=\"%.7f\"/>"
             "<rtept lat=\"%.7f\" lon=\"%.7f\"/><rtept lat=\"%.7f\" lon=\"%.7f\"/></rte>\n",
             lat[3], lon[3], lat[2], lon[2], lat[0], lon[0], lat[1], lon[1], lat[2], lon[2]);
    if (!geo_track_read(write_gpx("route.gpx", body), &pts, &n, &e))
        fail_msg("%s", e.msg);
    assert_true(n == 3 && fabs(pts[0].lon - lon[0]) < 1e-6 && fabs(pts[2].lon - lon[2]) < 1e-6);
    free(pts);
    /* the flight from the first track: its own times, the missing one in between by distance */
    char set[] = "terrain.exaggeration=1";
    gis_options o = {.command = GIS_TRACK, .dem = in_dir("dem.tif"), .input = in_dir("two.gpx"),
                     .output = in_dir("two.json"), .fps = 1, .speed = 30, .height = 120, .sets = {set}, .set_count = 1};
    if (!gis_track_run(&o, &e))
        fail_msg("%s", e.msg);
    path p;
    assert_true(path_load(in_dir("two.json"), &p, &e));
    print_message("tracks: %d keys, at %.1f %.1f ... %.1f s\n", p.count, p.keys[0].time, p.keys[1].time,
                  p.keys[p.count - 1].time);
    assert_int_equal(p.count, 4); /* 6 km apart: each point a key */
    const double want[4] = {0, 120, 240, 360}; /* the untimed third point: between 120 and 360 by distance */
    for (int k = 0; k < 4; k++)
        assert_true(fabs(p.keys[k].time - want[k]) < 0.5);
    path_free(&p);
    /* a flight without a sun block: the GPX's times are the flight's own seconds from the epoch */
    o = (gis_options){.command = GIS_TRACK, .dem = in_dir("dem.tif"), .path = in_dir("two.json"),
                      .output = in_dir("back.gpx"), .fps = 1, .speed = 30, .height = 120, .sets = {set}, .set_count = 1};
    if (!gis_track_run(&o, &e))
        fail_msg("%s", e.msg);
    assert_true(geo_track_read(in_dir("back.gpx"), &pts, &n, &e));
    assert_true(n > 300 && pts[0].time == 0 && fabs(pts[n - 1].time - 360) < 1e-3);
    free(pts);
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
    snprintf(text, sizeof text, fmt, "directional", "direction", in_dir("dem.tif"), "2026-06-21", 9.5);
    scene s;
    err_t e;
    if (!scene_load_text(text, in_dir("sun.json"), NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    double lon, lat, t;
    utm_to_lonlat(DEM_GT[0] + W / 2.0 * 1000, DEM_GT[3] - H / 2.0 * 1000, &lon, &lat); /* the centre */
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
    snprintf(text, sizeof text, fmt, "directional", "direction", in_dir("dem.tif"), "2026-12-21", 1.0);
    assert_true(scene_load_text(text, in_dir("sun.json"), NULL, 0, &s, &e));
    assert_true(s.lights[0].color[0] == 0 && s.sun.elevation < -30); /* a winter's night */
    scene_free(&s);
    snprintf(text, sizeof text, fmt, "point", "position", in_dir("dem.tif"), "2026-06-21", 9.5);
    assert_false(scene_load_text(text, in_dir("sun.json"), NULL, 0, &s, &e));
    assert_non_null(strstr(e.msg, "not a directional light"));
    snprintf(text, sizeof text, fmt, "directional", "direction", in_dir("dem.tif"), "2026-02-30", 9.5);
    assert_false(scene_load_text(text, in_dir("sun.json"), NULL, 0, &s, &e));
    assert_non_null(strstr(e.msg, "sun.date"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(drape_lands_on_the_right_texels), cmocka_unit_test(viewshed_geotiff),
        cmocka_unit_test(tracks_round_trip), cmocka_unit_test(flight_track_flight),
        cmocka_unit_test(sun_block_moves_the_light), cmocka_unit_test(vectors_keep_the_imagery_resolution),
        cmocka_unit_test(vector_widths_in_metres), cmocka_unit_test(observers_on_edges_and_across_180),
        cmocka_unit_test(tracks_as_the_guide_says), cmocka_unit_test(sun_on_a_polar_grid),
        cmocka_unit_test(viewshed_radius_crops), cmocka_unit_test(viewshed_drapes_see_through),
        cmocka_unit_test(set_layers_from_the_users_folder), cmocka_unit_test(imagery_off_the_dem_refused),
        cmocka_unit_test(south_up_dem_is_the_same_place),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
