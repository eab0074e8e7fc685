/* DEMs through GDAL: GeoTIFFs written here with GDAL (projected in metres and in US feet, geographic,
 * float, int16 with nodata, scale and offset, south-up) come back with the spacing, heights and holes
 * they were written with; the spacing of a geographic DEM is checked against the haversine distance
 * between neighbouring texel centres. Files GDAL reads but fathom cannot use get one clear error. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmocka.h>
#include <cpl_conv.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include "check.h"
#include "data/geo/dem.h"
#include "scene/scene.h"
#include "data/geo/terrain.h"

static char dir[] = "/tmp/fathom-dem-XXXXXX";

static int setup(void **st)
{
    (void)st;
    GDALAllRegister();
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **st)
{
    (void)st;
    return remove_tree(dir);
}

typedef struct tif {
    const char *name;
    GDALDataType type;
    int w, h;
    const double *gt; /* NULL: no geotransform */
    int epsg;         /* 0: no CRS */
    bool has_nodata;
    double nodata, scale, offset; /* scale 0: none */
} tif;

/* Writes `values` (w × h, row 0 first in the file) as a GeoTIFF; returns its path. */
static const char *write_tif(const tif *t, const double *values)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, t->name);
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path, t->w, t->h, 1, t->type, NULL);
    assert_non_null(ds);
    if (t->gt)
        assert_int_equal(GDALSetGeoTransform(ds, (double *)t->gt), CE_None);
    if (t->epsg) {
        OGRSpatialReferenceH srs = OSRNewSpatialReference(NULL);
        assert_int_equal(OSRImportFromEPSG(srs, t->epsg), OGRERR_NONE);
        assert_int_equal(GDALSetSpatialRef(ds, srs), CE_None);
        OSRDestroySpatialReference(srs);
    }
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    if (t->has_nodata)
        GDALSetRasterNoDataValue(b, t->nodata);
    if (t->scale != 0) {
        GDALSetRasterScale(b, t->scale);
        GDALSetRasterOffset(b, t->offset);
    }
    assert_int_equal(GDALRasterIO(b, GF_Write, 0, 0, t->w, t->h, (void *)values, t->w, t->h, GDT_Float64, 0, 0), CE_None);
    GDALClose(ds);
    return path;
}

static double wave(int i, int j) { return 100 + 37 * sin(0.3 * i) + 21 * cos(0.17 * j) + 0.25 * i; }

/* A w × h Float32 GeoTIFF of the wave in UTM 33N, 30 m texels east and dz north, into v as well. */
static const char *write_wave(const char *name, int w, int h, double dz, double *v)
{
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            v[j * w + i] = (float)wave(i, j);
    const double gt[6] = {500000, 30, 0, 5200000, 0, -dz};
    return write_tif(&(tif){name, GDT_Float32, w, h, gt, 32633, false, 0, 0, 0}, v);
}

/* Projected metres: the geotransform's pixel size is the spacing; Float32 heights come back exactly. */
static void projected_float(void **st)
{
    (void)st;
    enum { W = 40, H = 30 };
    double v[W * H];
    const char *p = write_wave("utm.tif", W, H, 25, v);
    int w, h;
    float *hts;
    dem_info info;
    err_t e;
    assert_true(dem_read(p, 16384, &w, &h, &hts, &info, &e));
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    assert_true(info.georeferenced && !info.geographic && info.is_float);
    assert_string_equal(info.type, "Float32");
    assert_near(info.spacing[0], 30, 1e-9);
    assert_near(info.spacing[1], 25, 1e-9);
    assert_true(strstr(info.crs, "UTM zone 33N") != NULL);
    for (int k = 0; k < W * H; k++)
        assert_near(hts[k], v[k], 0);
    assert_int_equal(info.holes, 0);
    free(hts);
}

/* A CRS in US survey feet: the spacing is in metres (1 ftUS = 1200/3937 m). */
static void projected_feet(void **st)
{
    (void)st;
    double v[4 * 3] = {0};
    const double gt[6] = {6000000, 100, 0, 2000000, 0, -50};
    const char *p = write_tif(&(tif){"feet.tif", GDT_Float32, 4, 3, gt, 2227, false, 0, 0, 0}, v);
    int w, h;
    float *hts;
    dem_info info;
    err_t e;
    assert_true(dem_read(p, 16384, &w, &h, &hts, &info, &e));
    assert_near(info.spacing[0], 100 * 1200.0 / 3937.0, 1e-9);
    assert_near(info.spacing[1], 50 * 1200.0 / 3937.0, 1e-9);
    free(hts);
}

/* Issue 58, item 3: heights in feet become metres (they were drawn 3.28 times too tall, without a word), in
 * what dem_read returns and in dem_probe's range; a unit fathom does not know is refused by name. */
static void vertical_units(void **st)
{
    (void)st;
    static const struct {
        const char *unit;
        double metres;
    } cases[] = {{"ft", 0.3048}, {"US survey foot", 1200.0 / 3937}, {"m", 1}, {"", 1}, {"furlong", 0}};
    double v[3 * 2] = {1000, 2000, 0, 500, 1500, 250};
    const double gt[6] = {500000, 30, 0, 5200000, 0, -30};
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        const char *p = write_tif(&(tif){"unit.tif", GDT_Float32, 3, 2, gt, 32633, false, 0, 0, 0}, v);
        GDALDatasetH ds = GDALOpen(p, GA_Update);
        assert_int_equal(GDALSetRasterUnitType(GDALGetRasterBand(ds, 1), cases[c].unit), CE_None);
        GDALClose(ds);
        int w, h;
        float *hts;
        dem_info info;
        double range[2];
        err_t e;
        bool ok = dem_read(p, 16384, &w, &h, &hts, &info, &e);
        if (cases[c].metres == 0) {
            assert_false(ok);
            assert_non_null(strstr(e.msg, "'furlong'"));
            assert_false(dem_probe(p, &w, &h, range, &info, &e));
            continue;
        }
        assert_true(ok);
        for (int k = 0; k < 6; k++)
            assert_near(hts[k], v[k] * cases[c].metres, 1e-3);
        free(hts);
        assert_true(dem_probe(p, &w, &h, range, &info, &e));
        assert_near(range[1], 2000 * cases[c].metres, 1e-3);
    }
}

/* A window read from disk (dem_read_window, issue 58 item 6) is the whole DEM's texels there, and a window not
 * inside the DEM is refused by name (not left to GDAL's own error). */
static void windows(void **st)
{
    (void)st;
    enum { W = 40, H = 30 };
    double v[W * H];
    const char *p = write_wave("window.tif", W, H, 30, v);
    int w = 7, h = 5;
    float *hts;
    dem_info info;
    err_t e;
    assert_true(dem_read_window(p, 30, 20, &w, &h, 16384, &hts, &info, &e));
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            assert_true(hts[j * w + i] == (float)v[(20 + j) * W + 30 + i]);
    free(hts);
    w = 11, h = 5; /* columns 30-40: one past the edge */
    assert_false(dem_read_window(p, 30, 20, &w, &h, 16384, &hts, &info, &e));
    assert_non_null(strstr(e.msg, "is not inside its 40x30 texels"));
}

/* Great-circle distance on the IUGG mean sphere (haversine): an independent reference for the
 * spacing of a geographic DEM. */
static double haversine(double lat1, double lon1, double lat2, double lon2)
{
    const double R = 6371000, r = M_PI / 180;
    double a = pow(sin(0.5 * (lat2 - lat1) * r), 2) + cos(lat1 * r) * cos(lat2 * r) * pow(sin(0.5 * (lon2 - lon1) * r), 2);
    return 2 * R * asin(sqrt(a));
}

/* Geographic (EPSG:4326), 1 arc second, centred at 46.5° N: metres at the central latitude. Int16
 * with nodata −32768, a scale and an offset: heights are value × scale + offset, nodata are holes. */
static void geographic_int16_nodata(void **st)
{
    (void)st;
    enum { W = 60, H = 40 };
    double v[W * H];
    int holes = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            bool hole = (i - 30) * (i - 30) + (j - 20) * (j - 20) < 49 || i == 0;
            v[j * W + i] = hole ? -32768 : (double)((int)wave(i, j) * 3 - 200);
            holes += hole;
        }
    const double arcsec = 1.0 / 3600, lat_top = 46.5 + 20 * arcsec;
    const double gt[6] = {8.0, arcsec, 0, lat_top, 0, -arcsec};
    const char *p = write_tif(&(tif){"geo.tif", GDT_Int16, W, H, gt, 4326, true, -32768, 0.5, 12.0}, v);
    int w, h;
    float *hts;
    dem_info info;
    err_t e;
    assert_true(dem_read(p, 16384, &w, &h, &hts, &info, &e));
    assert_true(info.georeferenced && info.geographic && !info.is_float);
    assert_string_equal(info.type, "Int16");
    assert_near(info.latitude, 46.5, 1e-9);
    /* neighbouring texel centres on the central parallel and meridian, by haversine */
    double ref_x = haversine(46.5, 8.0, 46.5, 8.0 + arcsec), ref_z = haversine(46.5, 8.0, 46.5 + arcsec, 8.0);
    assert_near(info.spacing[0], ref_x, 1e-6 * ref_x);
    assert_near(info.spacing[1], ref_z, 1e-6 * ref_z);
    assert_int_equal(info.holes, holes);
    for (int k = 0; k < W * H; k++) {
        if (v[k] == -32768)
            assert_true(isnan(hts[k]));
        else
            assert_near(hts[k], v[k] * 0.5 + 12.0, 0);
    }
    free(hts);
}

/* Where a texel is on the Earth (the window's cursor read-out): geographic coordinates come back as
 * the geotransform says; UTM on the central meridian against the footpoint latitude (Snyder 1987,
 * "Map projections: a working manual", eqs. 3-24 to 3-26, 8-18) computed here; a south-up raster's
 * rows count from the north like fathom's; a raster without a CRS has no latitude. */
static void georeference_lonlat(void **st)
{
    (void)st;
    double v[4 * 3] = {0};
    const double arcsec = 1.0 / 3600;
    const double geo[6] = {8.0, arcsec, 0, 46.5, 0, -arcsec};
    dem_geo *g = dem_geo_open(write_tif(&(tif){"ll.tif", GDT_Float32, 4, 3, geo, 4326, false, 0, 0, 0}, v));
    double lon = NAN, lat = NAN; /* clang: assert_true may return, but not to here */
    assert_true(g && dem_geo_lonlat(g, 2.5, 1.0, &lon, &lat));
    assert_near(lon, 8.0 + 2.5 * arcsec, 1e-12);
    assert_near(lat, 46.5 - arcsec, 1e-12);
    dem_geo_close(g);
    const double utm[6] = {500000, 30, 0, 5200000, 0, -25};
    g = dem_geo_open(write_tif(&(tif){"ll-utm.tif", GDT_Float32, 4, 3, utm, 32633, false, 0, 0, 0}, v));
    assert_true(g && dem_geo_lonlat(g, 0, 2, &lon, &lat));
    const double a = 6378137, f = 1 / 298.257223563, e2 = f * (2 - f), k0 = 0.9996, N = 5200000 - 2 * 25;
    double e1 = (1 - sqrt(1 - e2)) / (1 + sqrt(1 - e2));
    double mu = N / k0 / (a * (1 - e2 / 4 - 3 * e2 * e2 / 64 - 5 * e2 * e2 * e2 / 256));
    double phi = mu + (1.5 * e1 - 27 * pow(e1, 3) / 32) * sin(2 * mu) + (21 * e1 * e1 / 16 - 55 * pow(e1, 4) / 32) * sin(4 * mu) +
                 151 * pow(e1, 3) / 96 * sin(6 * mu) + 1097 * pow(e1, 4) / 512 * sin(8 * mu);
    assert_near(lon, 15.0, 1e-9); /* zone 33's central meridian */
    assert_near(lat, phi * 180 / M_PI, 1e-7);
    dem_geo_close(g);
    const double up[6] = {500000, 30, 0, 5200000, 0, 25}; /* south-up: fathom's row 0 is the file's last */
    g = dem_geo_open(write_tif(&(tif){"ll-south.tif", GDT_Float32, 4, 3, up, 32633, false, 0, 0, 0}, v));
    double lat0 = NAN, lat3 = NAN;
    assert_true(dem_geo_lonlat(g, 0, 0, &lon, &lat0) && dem_geo_lonlat(g, 0, 3, &lon, &lat3));
    assert_true(lat0 > lat3); /* north first */
    dem_geo_close(g);
    assert_null(dem_geo_open(write_tif(&(tif){"ll-none.tif", GDT_Float32, 4, 3, NULL, 0, false, 0, 0, 0}, v)));
}

/* A raster stored south to north (positive y pixel size) comes back north row first. */
static void south_up_is_flipped(void **st)
{
    (void)st;
    double v[3 * 4];
    for (int k = 0; k < 12; k++)
        v[k] = k;
    const double gt[6] = {0, 10, 0, 0, 0, 10}; /* row 0 is the southern edge */
    const char *p = write_tif(&(tif){"south.tif", GDT_Float32, 3, 4, gt, 32633, false, 0, 0, 0}, v);
    int w, h;
    float *hts;
    dem_info info;
    err_t e;
    assert_true(dem_read(p, 16384, &w, &h, &hts, &info, &e));
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 3; i++)
            assert_near(hts[j * 3 + i], v[(3 - j) * 3 + i], 0);
    free(hts);
}

/* heightfield_load: the spacing from the georeferencing, holes as TERRAIN_HOLE with their cells −inf
 * in the max pyramid, and terrain.nodata=fill filling them from their surroundings. */
static void holes_and_fill(void **st)
{
    (void)st;
    enum { W = 32, H = 24 };
    double v[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            v[j * W + i] = (i >= 10 && i < 14 && j >= 8 && j < 11) ? -9999 : 50 + i + 2 * j; /* a plane */
    const double gt[6] = {300000, 20, 0, 4000000, 0, -20};
    const char *p = write_tif(&(tif){"holes.tif", GDT_Float32, W, H, gt, 32633, true, -9999, 0, 0}, v);
    heightfield hf;
    err_t e;
    heightfield_desc d = {.path = p, .exaggeration = 1};
    assert_true(heightfield_load(&d, &hf, &e));
    assert_near(hf.dx, 20, 0);
    assert_near(hf.dz, 20, 0);
    assert_int_equal(hf.holes, 12);
    assert_near(hf.hmin, 50, 0);
    assert_near(hf.hmax, 50 + 31 + 46, 0);
    assert_true(TERRAIN_IS_HOLE(hf.h[9 * W + 11]));
    assert_true(isinf(heightfield_cell_max(&hf, 11, 9)) && heightfield_cell_max(&hf, 11, 9) < 0); /* a hole's cell */
    assert_true(isinf(heightfield_cell_max(&hf, 9, 8)));  /* a cell with one hole corner */
    assert_true(!isinf(heightfield_cell_max(&hf, 9, 6))); /* two rows away: a surface */
    /* level 1: the 2x2 cells (10..11, 8..9) are all hole cells; (8..9, 6..7) are not */
    assert_true(isinf(hf.max[1][(size_t)(4 * (hf.pw / 2) + 5)]));
    assert_true(!isinf(hf.max[1][(size_t)(3 * (hf.pw / 2) + 4)]));
    assert_true(strstr(hf.about, "12 nodata texels left as holes") != NULL);
    heightfield_free(&hf);
    d.fill_nodata = true;
    assert_true(heightfield_load(&d, &hf, &e));
    assert_int_equal(hf.holes, 0);
    /* inverse-distance fill of a plane stays within the plane's range around the hole */
    for (int j = 8; j < 11; j++)
        for (int i = 10; i < 14; i++) {
            float x = hf.h[(size_t)(j * W + i)];
            assert_true(x >= 50 + 9 + 2 * 7 - 1e-3 && x <= 50 + 14 + 2 * 11 + 1e-3);
        }
    heightfield_free(&hf);
}

/* What GDAL reads but fathom cannot draw: one error each, naming the file and what to do. */
static void refused(void **st)
{
    (void)st;
    double v[4 * 4] = {0};
    int w, h;
    float *hts;
    dem_info info;
    err_t e;
    const double gt_rot[6] = {0, 10, 2, 0, 1, -10}, gt[6] = {0, 10, 0, 0, 0, -10};
    const char *p = write_tif(&(tif){"rot.tif", GDT_Float32, 4, 4, gt_rot, 32633, false, 0, 0, 0}, v);
    assert_false(dem_read(p, 16384, &w, &h, &hts, &info, &e));
    assert_true(strstr(e.msg, "rotated geotransform") && strstr(e.msg, "gdalwarp"));
    /* a pixel size without a CRS: its unit is unknown, so the scene must give the spacing */
    p = write_tif(&(tif){"nocrs.tif", GDT_Float32, 4, 4, gt, 0, false, 0, 0, 0}, v);
    heightfield hf;
    heightfield_desc d = {.path = p, .exaggeration = 1};
    assert_false(heightfield_load(&d, &hf, &e));
    assert_true(strstr(e.msg, "no CRS") && strstr(e.msg, "terrain.spacing"));
    d.spacing[0] = d.spacing[1] = 5;
    assert_true(heightfield_load(&d, &hf, &e));
    assert_near(hf.dx, 5, 0);
    heightfield_free(&hf);
    /* no georeferencing at all: the same */
    d.path = write_tif(&(tif){"plain.tif", GDT_Float32, 4, 4, NULL, 0, false, 0, 0, 0}, v);
    assert_true(heightfield_load(&d, &hf, &e));
    heightfield_free(&hf);
    d.spacing[0] = d.spacing[1] = 0;
    assert_false(heightfield_load(&d, &hf, &e));
    assert_true(strstr(e.msg, "no spacing") != NULL);
    p = write_tif(&(tif){"big.tif", GDT_Byte, 300, 2, gt, 32633, false, 0, 0, 0}, (double[600]){0});
    assert_false(dem_read(p, 256, &w, &h, &hts, &info, &e));
    assert_true(strstr(e.msg, "300x2") && strstr(e.msg, "256"));
    double all[9];
    for (int k = 0; k < 9; k++)
        all[k] = -1;
    p = write_tif(&(tif){"empty.tif", GDT_Float32, 3, 3, gt, 32633, true, -1, 0, 0}, all);
    d = (heightfield_desc){.path = p, .exaggeration = 1};
    assert_false(heightfield_load(&d, &hf, &e));
    assert_true(strstr(e.msg, "no heights") != NULL);
    d.height_min = 0, d.height_max = 100;
    p = write_tif(&(tif){"range.tif", GDT_Float32, 4, 4, gt, 32633, false, 0, 0, 0}, v);
    d.path = p;
    assert_false(heightfield_load(&d, &hf, &e));
    assert_true(strstr(e.msg, "remove terrain.height_min") != NULL);
    assert_false(dem_read("/nonexistent/dem.tif", 256, &w, &h, &hts, &info, &e));
    assert_true(strstr(e.msg, "cannot read DEM '/nonexistent/dem.tif'") != NULL);
}

/* Hostile numbers in a valid file: a scale or offset that sends heights beyond a float (1e36, 1e39),
 * a pixel size of 1e-30: refused with the reason, by the loader and by the probe that frames the
 * camera (which said "camera ... is at its look-at" before). */
static void hostile_numbers(void **st)
{
    (void)st;
    double v[4 * 4];
    for (int k = 0; k < 16; k++)
        v[k] = 100 + k;
    const double gt[6] = {0, 10, 0, 0, 0, -10}, tiny[6] = {0, 1e-30, 0, 0, 0, -1e-30};
    struct { const char *name; const double *gt; double scale, offset; const char *needle; } cases[] = {
        {"scale.tif", gt, 1e36, 0, "check the band's scale and offset"},
        {"offset.tif", gt, 1, 1e39, "check the band's scale and offset"},
        {"tinyscale.tif", gt, 1e5, 0, "beyond"}, /* 1.15e7 m: finite, but no terrain */
        {"tiny.tif", tiny, 0, 0, "outside 0.001 to"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const char *p = write_tif(&(tif){cases[c].name, GDT_Float32, 4, 4, cases[c].gt, 32633, false, 0,
                                         cases[c].scale, cases[c].offset}, v);
        heightfield hf;
        heightfield_desc d = {.path = p, .exaggeration = 1};
        err_t e = {0};
        double size[2], range[2], spacing[2];
        assert_false(heightfield_load(&d, &hf, &e));
        if (!strstr(e.msg, cases[c].needle))
            fail_msg("%s: load: '%s' lacks '%s'", cases[c].name, e.msg, cases[c].needle);
        assert_false(heightfield_probe(&d, size, range, spacing, &e));
        if (!strstr(e.msg, cases[c].needle))
            fail_msg("%s: probe: '%s' lacks '%s'", cases[c].name, e.msg, cases[c].needle);
    }
    /* an exaggeration that takes sane heights past the bound is refused the same way */
    const char *p = write_tif(&(tif){"sane.tif", GDT_Float32, 4, 4, gt, 32633, false, 0, 0, 0}, v);
    heightfield hf;
    heightfield_desc d = {.path = p, .exaggeration = 1e6f};
    err_t e;
    assert_false(heightfield_load(&d, &hf, &e));
    assert_non_null(strstr(e.msg, "beyond"));
}

/* A VRT whose source is on a web server (here a socket listening on loopback): GDAL is asked for it,
 * but no connection reaches the server (GDAL's network file systems are off), and the error says so
 * or names the failed read. Before, GDAL connected. */
static void no_network(void **st)
{
    (void)st;
    int srv = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
    assert_true(srv >= 0);
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t len = sizeof a;
    assert_int_equal(bind(srv, (struct sockaddr *)&a, sizeof a), 0);
    assert_int_equal(listen(srv, 4), 0);
    assert_int_equal(getsockname(srv, (struct sockaddr *)&a, &len), 0);
    char vrt[256], text[1024];
    snprintf(vrt, sizeof vrt, "%s/net.vrt", dir);
    snprintf(text, sizeof text,
             "<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\"><VRTRasterBand dataType=\"Float32\" band=\"1\">"
             "<SimpleSource><SourceFilename relativeToVRT=\"0\">/vsicurl/http://127.0.0.1:%d/dem.tif</SourceFilename>"
             "<SourceBand>1</SourceBand></SimpleSource></VRTRasterBand></VRTDataset>", ntohs(a.sin_port));
    FILE *f = fopen(vrt, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    CPLSetConfigOption("GDAL_HTTP_TIMEOUT", "2"); /* without the guard, GDAL would wait on our silent server */
    int w, h;
    float *hts = NULL;
    dem_info info;
    err_t e;
    bool read = dem_read(vrt, 256, &w, &h, &hts, &info, &e);
    free(hts);
    snprintf(text, sizeof text, "/vsicurl/http://127.0.0.1:%d/dem.tif", ntohs(a.sin_port));
    assert_false(dem_read(text, 256, &w, &h, &hts, &info, &e));
    int conn = accept(srv, NULL, NULL); /* non-blocking: -1 unless GDAL connected */
    if (conn >= 0)
        close(conn);
    close(srv);
    assert_true(conn < 0);
    assert_false(read);
}

/* An ESRI ASCII grid (text, no CRS) with the scene's spacing: the same heights. */
static void ascii_grid(void **st)
{
    (void)st;
    char path[256];
    snprintf(path, sizeof path, "%s/dem.asc", dir);
    FILE *f = fopen(path, "w");
    fprintf(f, "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -1\n1 2 3\n4 -1 6\n");
    fclose(f);
    int w, h;
    float *hts;
    dem_info info;
    err_t e;
    /* a cell size without a CRS: the unit is unknown, so the scene must say */
    assert_true(dem_read(path, 256, &w, &h, &hts, &info, &e));
    assert_true(!info.georeferenced && info.pixel[0] == 1);
    free(hts);
    heightfield hf;
    heightfield_desc d = {.path = path, .spacing = {2, 3}, .exaggeration = 2};
    assert_true(heightfield_load(&d, &hf, &e));
    assert_near(hf.dz, 3, 0);
    heightfield_free(&hf);
    /* with a .prj beside it, it is georeferenced */
    snprintf(path, sizeof path, "%s/dem.prj", dir);
    f = fopen(path, "w");
    fprintf(f, "PROJCS[\"WGS 84 / UTM zone 33N\",GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],"
               "PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433]],PROJECTION[\"Transverse_Mercator\"],"
               "PARAMETER[\"latitude_of_origin\",0],PARAMETER[\"central_meridian\",15],PARAMETER[\"scale_factor\",0.9996],"
               "PARAMETER[\"false_easting\",500000],PARAMETER[\"false_northing\",0],UNIT[\"metre\",1]]\n");
    fclose(f);
    snprintf(path, sizeof path, "%s/dem.asc", dir);
    d.spacing[0] = d.spacing[1] = 0;
    assert_true(heightfield_load(&d, &hf, &e));
    assert_near(hf.dx, 1, 0);
    assert_int_equal(hf.holes, 1);
    assert_near(hf.h[0], 2, 0); /* × exaggeration */
    assert_near(hf.h[5], 12, 0);
    heightfield_free(&hf);
}

/* The dem scene (fathom --dem FILE): the camera, far distance and haze framed from a DEM it was not
 * written for, wherever it lies; "camera": "auto" anywhere but a terrain is refused. */
static void dem_scene_frames_any_dem(void **st)
{
    (void)st;
    enum { W = 300, H = 120 };
    static double v[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            v[j * W + i] = 1500 + 400 * sin(i * 0.05) * cos(j * 0.07); /* 1100-1900 m */
    const double gt[6] = {700000, 10, 0, 6000000, 0, -10};
    const char *p = write_tif(&(tif){"frame.tif", GDT_Float32, W, H, gt, 32633, false, 0, 0, 0}, v);
    char set[300];
    snprintf(set, sizeof set, "terrain.heightmap=%s", p);
    const char *sets[] = {set};
    scene s;
    err_t e;
    if (!scene_load("dem", sets, 1, &s, &e))
        fail_msg("%s", e.msg);
    double X = W * 10.0, Z = H * 10.0;
    /* above the highest ground, looking down at a point over the footprint below the top */
    assert_true(s.cam_position[1] > 1900);
    assert_true(fabs(s.cam_look_at[0]) < X / 2 && fabs(s.cam_look_at[2]) < Z / 2);
    assert_true(s.cam_look_at[1] >= 1100 && s.cam_look_at[1] < 1900);
    assert_true(s.cam_position[1] > s.cam_look_at[1]);
    assert_true(s.quality.max_dist > hypot(X, Z) && s.quality.max_dist < 20 * hypot(X, Z));
    assert_near(s.terrain.exaggeration, 1, 0); /* relief 800 m over 3 km: shown at true scale */
    assert_true(s.fog_density > 0 && s.fog_density * X < 1);
    scene_free(&s);
    /* a wide flat DEM (a continent at true scale) is exaggerated until its relief shows */
    const double gt2[6] = {700000, 10000, 0, 6000000, 0, -10000};
    p = write_tif(&(tif){"flat.tif", GDT_Float32, W, H, gt2, 32633, false, 0, 0, 0}, v);
    snprintf(set, sizeof set, "terrain.heightmap=%s", p);
    if (!scene_load("dem", sets, 1, &s, &e))
        fail_msg("%s", e.msg);
    assert_near(s.terrain.exaggeration, 20, 1e-4); /* 800 m relief over 3000 km: at the cap */
    assert_true(s.cam_position[1] > 1900 * 20);
    scene_free(&s);
    /* ... unless the scene or the command line sets it: 1 is true scale, not "not set" */
    const char *true_scale[] = {set, "terrain.exaggeration=1"};
    if (!scene_load("dem", true_scale, 2, &s, &e))
        fail_msg("%s", e.msg);
    assert_near(s.terrain.exaggeration, 1, 0);
    assert_true(s.cam_look_at[1] >= 1100 && s.cam_look_at[1] < 5000); /* framed at true heights (x20: > 22,000) */
    scene_free(&s);
    assert_false(scene_load_text("{\"program\": \"csg\", \"camera\": \"auto\", \"objects\": []}", "/tmp/x.json", NULL, 0,
                                 &s, &e));
    assert_true(strstr(e.msg, "camera: expected an object") != NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(projected_float),  cmocka_unit_test(projected_feet), cmocka_unit_test(vertical_units), cmocka_unit_test(windows),   cmocka_unit_test(geographic_int16_nodata),
        cmocka_unit_test(south_up_is_flipped), cmocka_unit_test(holes_and_fill), cmocka_unit_test(refused),
        cmocka_unit_test(ascii_grid),          cmocka_unit_test(dem_scene_frames_any_dem),
        cmocka_unit_test(hostile_numbers),     cmocka_unit_test(no_network),     cmocka_unit_test(georeference_lonlat),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
