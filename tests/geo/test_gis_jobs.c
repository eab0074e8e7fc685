/* The GIS jobs' files (jobs/gis/gis_job.h), each checked with GDAL and OGR called here directly:
 *  - the viewshed GeoTIFF has the DEM's grid, CRS, nodata and the values computed, and the observer
 *    lands on the texel its longitude and latitude name (on edges and across 180° too; --radius crops);
 *  - GPX and KML written are read back by OGR with the same points, heights and times (a hostile track
 *    name is escaped), and read back by fathom too;
 *  - a flight becomes a track and the track a flight again: its keys lie within a texel of the first
 *    flight's path and `height` above the ground. */
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

static void viewshed_geotiff(void **st)
{
    (void)st;
    double lon, lat;
    fixture_utm_to_lonlat(DEM_GT[0] + 20.5 * 1000, DEM_GT[3] - 30.5 * 1000, &lon, &lat); /* texel (20, 30)'s centre */
    gis_options o = {.command = GIS_VIEWSHED, .dem = fixture_path("dem.tif"), .output = fixture_path("vs.tif"), .lon = lon,
                     .lat = lat, .observer_height = 10, .refraction = 0.13};
    err_t e;
    if (!gis_viewshed_run(&o, &e))
        fail_msg("%s", e.msg);
    double col, row;
    assert_true(geo_convert(fixture_path("dem.tif"), true, 1, &lon, &lat, &col, &row, &e));
    assert_true(fabs(col - 20) < 1e-6 && fabs(row - 30) < 1e-6);
    /* the same computation here, then the file against it */
    float hts[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            hts[j * W + i] = (float)fixture_hill(i, j);
    unsigned char want[W * H], got[W * H];
    viewshed_desc d = {.heights = hts, .w = W, .h = H, .dx = 1000, .dz = 1000, .col = 20, .row = 30,
                       .observer_height = 10, .refraction = 0.13, .curvature = true};
    assert_true(viewshed_compute(&d, want, NULL, &e));
    GDALDatasetH ds = GDALOpen(fixture_path("vs.tif"), GA_ReadOnly);
    assert_non_null(ds);
    double gt[6];
    assert_true(GDALGetGeoTransform(ds, gt) == CE_None);
    for (int k = 0; k < 6; k++)
        assert_true(gt[k] == DEM_GT[k]);
    OGRSpatialReferenceH utm = fixture_srs(32633);
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
    o.output = fixture_path("off.tif");
    o.lon = lon + 3;
    assert_false(gis_viewshed_run(&o, &e));
    print_message("%s\n", e.msg);
    assert_non_null(strstr(e.msg, "outside the DEM"));
    assert_int_equal(access(fixture_path("off.tif"), F_OK), -1);
}

/* A geographic DEM of GW × GH texels of 0.01° from (lon0, lat0) at its north-west corner; heights rise to the
 * east, texel (hole_i, 0) nodata (-1: none). */
static void write_geographic(const char *file, int gw, int gh, double lon0, double lat0, int hole_i)
{
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), file, gw, gh, 1, GDT_Float32, NULL);
    double gt[6] = {lon0, 0.01, 0, lat0, 0, -0.01};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH s = fixture_srs(4326);
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
    write_geographic(fixture_path("edge.tif"), GW, GH, 10, 47, GW - 2); /* the highest is (GW - 1, 0), beside the hole */
    const double at[][2] = {{10 + 0.01 * (GW - 0.5), 47 - 0.005}, {10.005, 47 - 0.01 * (GH - 0.5)},
                            {10.0, 46.9}, {10 + 0.01 * GW, 46.9}};
    err_t e;
    for (size_t k = 0; k < sizeof at / sizeof *at; k++) {
        gis_options o = {.command = GIS_VIEWSHED, .dem = fixture_path("edge.tif"), .output = fixture_path("edge-vs.tif"),
                         .lon = at[k][0], .lat = at[k][1], .observer_height = 2, .refraction = 0.13};
        if (!gis_viewshed_run(&o, &e))
            fail_msg("observer %zu at %.4f, %.4f: %s", k, at[k][0], at[k][1], e.msg);
    }
    write_geographic(fixture_path("dateline.tif"), 300, 20, 178.5, 10, -1);
    gis_options o = {.command = GIS_VIEWSHED, .dem = fixture_path("dateline.tif"), .output = fixture_path("dl-vs.tif"),
                     .lon = -179.5, .lat = 9.9, .observer_height = 2, .refraction = 0.13};
    if (!gis_viewshed_run(&o, &e))
        fail_msg("observer at -179.5: %s", e.msg);
    double col, row, lon = -179.5, lat = 9.9;
    assert_true(geo_convert(fixture_path("dateline.tif"), true, 1, &lon, &lat, &col, &row, &e));
    assert_true(fabs(col - 199.5) < 1e-6 && fabs(row - 9.5) < 1e-6);
    o.lon = 177.0, o.output = fixture_path("dl-off.tif");
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
    fixture_utm_to_lonlat(DEM_GT[0] + 20.5 * 1000, DEM_GT[3] - 30.5 * 1000, &lon, &lat); /* texel (20, 30)'s centre */
    gis_options o = {.command = GIS_VIEWSHED, .dem = fixture_path("dem.tif"), .output = fixture_path("vs-r.tif"), .lon = lon,
                     .lat = lat, .observer_height = 10, .refraction = 0.13, .radius = 7500};
    err_t e;
    if (!gis_viewshed_run(&o, &e))
        fail_msg("%s", e.msg);
    float hts[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            hts[j * W + i] = (float)fixture_hill(i, j);
    unsigned char want[W * H];
    viewshed_desc d = {.heights = hts, .w = W, .h = H, .dx = 1000, .dz = 1000, .col = 20, .row = 30,
                       .observer_height = 10, .refraction = 0.13, .curvature = true, .radius = 7500};
    assert_true(viewshed_compute(&d, want, NULL, &e));
    GDALDatasetH ds = GDALOpen(fixture_path("vs-r.tif"), GA_ReadOnly);
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

/* Issue 58, item 8: the viewshed draped keeps its nodata clear (GeoTIFF keeps no alpha in its colour table: the
 * nodata entry expanded to opaque black over the terrain): a 7.5 km radius's window on the DEM, hidden and visible
 * texels opaque in their colours, nodata and the DEM beyond the window clear. */
static void viewshed_drapes_see_through(void **st)
{
    (void)st;
    unsigned char *rgba;
    int w = W, h = H; /* the DEM's own grid: each drape pixel one texel */
    err_t e;
    if (!geo_drape(fixture_path("dem.tif"), fixture_path("vs-r.tif"), 4096, &rgba, &w, &h, &e))
        fail_msg("%s", e.msg);
    GDALDatasetH ds = GDALOpen(fixture_path("vs-r.tif"), GA_ReadOnly);
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
    assert_true(geo_track_write(fixture_path("t.gpx"), name, pts, (const double(*)[3])cams, N, &e));
    assert_true(geo_track_write(fixture_path("t.kml"), name, pts, (const double(*)[3])cams, N, &e));
    double got[N + 2][4];
    assert_int_equal(ogr_points(fixture_path("t.gpx"), "track_points", got, N + 2), N);
    for (int i = 0; i < N; i++) {
        assert_true(fabs(got[i][0] - pts[i].lon) < 1e-9 && fabs(got[i][1] - pts[i].lat) < 1e-9);
        assert_true(fabs(got[i][2] - pts[i].ele) < 1e-6 && fabs(got[i][3] - pts[i].time) < 1e-3);
    }
    assert_int_equal(ogr_points(fixture_path("t.kml"), NULL, got, N + 2), N);
    for (int i = 0; i < N; i++)
        assert_true(fabs(got[i][0] - pts[i].lon) < 1e-8 && fabs(got[i][2] - pts[i].ele) < 1e-3);
    char *text;
    size_t len;
    assert_true(util_read_file(fixture_path("t.kml"), &text, &len, &e));
    int flytos = 0;
    for (const char *p = text; (p = strstr(p, "<gx:FlyTo>")) != NULL; p++)
        flytos++;
    assert_int_equal(flytos, N);
    assert_null(strstr(text, "<b>")); /* the name escaped */
    free(text);
    geo_point *back;
    int n;
    assert_true(geo_track_read(fixture_path("t.gpx"), &back, &n, &e));
    assert_int_equal(n, N);
    assert_true(fabs(back[3].ele - pts[3].ele) < 1e-6 && fabs(back[3].time - pts[3].time) < 1e-3);
    free(back);
    assert_false(geo_track_write(fixture_path("t.txt"), name, pts, NULL, N, &e));
    assert_false(geo_track_read(fixture_path("dem.tif"), &back, &n, &e)); /* a raster is no track */
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
    assert_true(util_write_text_atomic(fixture_path("f.json"), flight, "the flight", &e));
    char set[300];
    snprintf(set, sizeof set, "terrain.exaggeration=1");
    gis_options o = {.command = GIS_TRACK, .dem = fixture_path("dem.tif"), .path = fixture_path("f.json"),
                     .output = fixture_path("f.gpx"), .fps = 1, .speed = 30, .height = 120, .sets = {set}, .set_count = 1};
    if (!gis_track_run(&o, &e))
        fail_msg("%s", e.msg);
    o = (gis_options){.command = GIS_TRACK, .dem = fixture_path("dem.tif"), .input = fixture_path("f.gpx"),
                      .output = fixture_path("g.json"), .fps = 1, .speed = 30, .height = 120, .sets = {set}, .set_count = 1};
    if (!gis_track_run(&o, &e))
        fail_msg("%s", e.msg);
    path a, b;
    assert_true(path_load(fixture_path("f.json"), &a, &e));
    assert_true(path_load(fixture_path("g.json"), &b, &e));
    assert_true(b.count >= 20);
    double worst_xz = 0, worst_y = 0;
    for (int k = 0; k < b.count; k++) {
        path_sample s;
        path_eval(&a, b.keys[k].time, &s); /* the GPX's times are the flight's */
        worst_xz = fmax(worst_xz, hypot(s.position[0] - b.keys[k].position[0], s.position[2] - b.keys[k].position[2]));
        double col = b.keys[k].position[0] / 1000 + W / 2.0 - 0.5, row = b.keys[k].position[2] / 1000 + H / 2.0 - 0.5;
        int i = (int)col, j = (int)row;
        double u = col - i, v = row - j;
        double g = (fixture_hill(i, j) * (1 - u) + fixture_hill(i + 1, j) * u) * (1 - v) + (fixture_hill(i, j + 1) * (1 - u) + fixture_hill(i + 1, j + 1) * u) * v;
        worst_y = fmax(worst_y, fabs(b.keys[k].position[1] - (g + 120)));
    }
    print_message("flight -> GPX -> flight: %d keys, worst %.3f m off the first flight's path, %.4f m off 120 m "
                  "above the ground\n", b.count, worst_xz, worst_y);
    assert_true(worst_xz < 1.0); /* a texel is 1000 m: the round trip loses nothing */
    assert_true(worst_y < 0.01);
    path_free(&a);
    path_free(&b);
}

/* A GPX text of these parts, written to `name` in the test's folder. */
static const char *write_gpx(const char *name, const char *body)
{
    FILE *f = fopen(fixture_path(name), "w");
    fprintf(f, "<?xml version=\"1.0\"?>\n<gpx version=\"1.1\" creator=\"test\" "
               "xmlns=\"http://www.topografix.com/GPX/1/1\">\n%s</gpx>\n", body);
    fclose(f);
    return fixture_path(name);
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
        fixture_utm_to_lonlat(DEM_GT[0] + 20000 + 6000 * i, DEM_GT[3] - 24000, &lon[i], &lat[i]);
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
    gis_options o = {.command = GIS_TRACK, .dem = fixture_path("dem.tif"), .input = fixture_path("two.gpx"),
                     .output = fixture_path("two.json"), .fps = 1, .speed = 30, .height = 120, .sets = {set}, .set_count = 1};
    if (!gis_track_run(&o, &e))
        fail_msg("%s", e.msg);
    path p;
    assert_true(path_load(fixture_path("two.json"), &p, &e));
    print_message("tracks: %d keys, at %.1f %.1f ... %.1f s\n", p.count, p.keys[0].time, p.keys[1].time,
                  p.keys[p.count - 1].time);
    assert_int_equal(p.count, 4); /* 6 km apart: each point a key */
    const double want[4] = {0, 120, 240, 360}; /* the untimed third point: between 120 and 360 by distance */
    for (int k = 0; k < 4; k++)
        assert_true(fabs(p.keys[k].time - want[k]) < 0.5);
    path_free(&p);
    /* a flight without a sun block: the GPX's times are the flight's own seconds from the epoch */
    o = (gis_options){.command = GIS_TRACK, .dem = fixture_path("dem.tif"), .path = fixture_path("two.json"),
                      .output = fixture_path("back.gpx"), .fps = 1, .speed = 30, .height = 120, .sets = {set}, .set_count = 1};
    if (!gis_track_run(&o, &e))
        fail_msg("%s", e.msg);
    assert_true(geo_track_read(fixture_path("back.gpx"), &pts, &n, &e));
    assert_true(n > 300 && pts[0].time == 0 && fabs(pts[n - 1].time - 360) < 1e-3);
    free(pts);
}

/* fathom water: a DEM of two bowls (one with a notch to the edge, one closed, a nodata texel in a corner) gives
 * the lakes water_fill gives on its heights, depth and surface, on the DEM's grid and CRS; --min-depth leaves the
 * shallower one dry; a DEM without georeferencing is refused with no file. */
static void water_geotiff(void **st)
{
    (void)st;
    enum { WW = 40, WH = 30 };
    static float g[WW * WH];
    for (int j = 0; j < WH; j++)
        for (int i = 0; i < WW; i++) {
            int c = i < 20 ? 10 : 30, r2 = (i - c) * (i - c) + (j - 15) * (j - 15);
            g[j * WW + i] = r2 < 64 ? (float)r2 * (i < 20 ? 1.0f : 0.25f) : 100.0f; /* deep west, shallow east */
        }
    g[15 * WW + 3] = 40; /* the west bowl's notch to the edge: it stands at 40; the east one at its rim, 100 */
    g[15 * WW + 2] = 40;
    g[15 * WW + 1] = 40;
    g[15 * WW + 0] = 40;
    g[0] = NAN;
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), fixture_path("bowls.tif"), WW, WH, 1, GDT_Float32, NULL);
    OGRSpatialReferenceH utm = fixture_srs(32633);
    GDALSetGeoTransform(ds, (double *)DEM_GT);
    GDALSetSpatialRef(ds, utm);
    GDALSetRasterNoDataValue(GDALGetRasterBand(ds, 1), NAN);
    assert_true(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, WW, WH, g, WW, WH, GDT_Float32, 0, 0) == CE_None);
    GDALClose(ds);
    for (int pass = 0; pass < 2; pass++) {
        gis_options o = {.command = GIS_WATER, .dem = fixture_path("bowls.tif"), .output = fixture_path("lakes.tif"),
                         .min_depth = pass ? 50 : 0};
        err_t e;
        if (!gis_water_run(&o, &e))
            fail_msg("%s", e.msg);
        static float want[WW * WH], depth[WW * WH], surface[WW * WH];
        water_fill_desc d = {.ground = g, .w = WW, .h = WH, .dx = 1000, .dz = 1000, .min_depth = o.min_depth};
        water_fill_stats ws;
        assert_true(water_fill(&d, want, &ws, &e));
        assert_int_equal(ws.lakes, pass ? 1 : 2);
        ds = GDALOpen(fixture_path("lakes.tif"), GA_ReadOnly);
        assert_non_null(ds);
        double gt[6];
        assert_true(GDALGetGeoTransform(ds, gt) == CE_None);
        for (int k = 0; k < 6; k++)
            assert_true(gt[k] == DEM_GT[k]);
        assert_true(OSRIsSame(GDALGetSpatialRef(ds), utm));
        assert_int_equal(GDALGetRasterCount(ds), 2);
        assert_true(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, WW, WH, surface, WW, WH, GDT_Float32, 0, 0) == CE_None);
        assert_true(GDALRasterIO(GDALGetRasterBand(ds, 2), GF_Read, 0, 0, WW, WH, depth, WW, WH, GDT_Float32, 0, 0) == CE_None);
        GDALClose(ds);
        size_t wet = 0;
        for (int c = 0; c < WW * WH; c++) {
            assert_true(isnan(want[c]) ? isnan(surface[c]) : surface[c] == want[c]);
            assert_true(isnan(g[c]) ? isnan(depth[c]) : depth[c] == (isnan(want[c]) ? 0.0f : want[c] - g[c]));
            wet += isnan(surface[c]) ? 0u : 1u;
        }
        assert_true(pass ? isnan(surface[15 * WW + 10]) : surface[15 * WW + 10] == 40.0f); /* the west: 40 deep */
        assert_true(surface[15 * WW + 30] == 100.0f && depth[15 * WW + 30] == 100.0f);    /* the east: 100 */
        assert_true(wet > 20);
    }
    /* no georeferencing: refused, nothing written */
    ds = GDALCreate(GDALGetDriverByName("GTiff"), fixture_path("plain.tif"), WW, WH, 1, GDT_Float32, NULL);
    assert_true(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, WW, WH, g, WW, WH, GDT_Float32, 0, 0) == CE_None);
    GDALClose(ds);
    OSRDestroySpatialReference(utm);
    gis_options o = {.command = GIS_WATER, .dem = fixture_path("plain.tif"), .output = fixture_path("plain-lakes.tif")};
    err_t e;
    assert_false(gis_water_run(&o, &e));
    print_message("%s\n", e.msg);
    assert_non_null(strstr(e.msg, "no georeferencing"));
    assert_int_equal(access(fixture_path("plain-lakes.tif"), F_OK), -1);
}

/* Lakes as polygons with a level (terrain.water=FILE.geojson): a texel whose centre a polygon holds takes its level,
 * decided here by OGR's point-in-polygon on each centre in WGS 84 (the polygons' own CRS; GDAL's rasteriser does
 * fathom's in the DEM's UTM); a line is a river in texel coordinates; a point, a polygon without a level: one
 * error each. */
static void water_polygons(void **st)
{
    (void)st;
    double lon[4], lat[4];
    const double corner[4][2] = {{10.2, 12.3}, {30.7, 12.3}, {30.7, 25.6}, {10.2, 25.6}}; /* texels: a quadrilateral */
    for (int k = 0; k < 4; k++)
        fixture_utm_to_lonlat(DEM_GT[0] + (corner[k][0] + 0.5) * 1000 + (k == 2 ? 3000 : 0),
                              DEM_GT[3] - (corner[k][1] + 0.5) * 1000, &lon[k], &lat[k]);
    char file[512]; /* (fixture_path's buffers are reused) */
    snprintf(file, sizeof file, "%s", fixture_path("lakes.geojson"));
    FILE *f = fopen(file, "w");
    fprintf(f, "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Feature\", \"properties\": {\"level\": 120.5}, "
               "\"geometry\": {\"type\": \"Polygon\", \"coordinates\": [[[%.9f, %.9f], [%.9f, %.9f], [%.9f, %.9f], [%.9f, %.9f], "
               "[%.9f, %.9f]]]}}]}\n", lon[0], lat[0], lon[1], lat[1], lon[2], lat[2], lon[3], lat[3], lon[0], lat[0]);
    fclose(f);
    static float lv[W * H];
    err_t e;
    geo_river *rivers;
    int n_rivers;
    if (!geo_water_vectors(fixture_path("dem.tif"), file, W, H, lv, &rivers, &n_rivers, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(n_rivers, 0);
    OGRGeometryH ring = OGR_G_CreateGeometry(wkbLinearRing), poly = OGR_G_CreateGeometry(wkbPolygon);
    for (int k = 0; k <= 4; k++)
        OGR_G_AddPoint_2D(ring, lon[k % 4], lat[k % 4]);
    OGR_G_AddGeometryDirectly(poly, ring);
    int inside = 0, near_edge = 0;
    static double col[W * H], row[W * H], cl[W * H], ct[W * H]; /* every texel centre in WGS 84, in one call */
    for (int k = 0; k < W * H; k++)
        col[k] = k % W, row[k] = k / W;
    assert_true(geo_convert(fixture_path("dem.tif"), false, W * H, col, row, cl, ct, &e));
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            OGRGeometryH pt = OGR_G_CreateGeometry(wkbPoint);
            OGR_G_AddPoint_2D(pt, cl[j * W + i], ct[j * W + i]);
            bool in = OGR_G_Contains(poly, pt);
            OGR_G_DestroyGeometry(pt);
            /* a centre within 1e-6 texels of an edge may fall either way (the reprojection's rounding) */
            if (in != !isnan(lv[j * W + i]) && near_edge++ < 4)
                continue;
            assert_true(in ? lv[j * W + i] == 120.5f : isnan(lv[j * W + i]));
            inside += in;
        }
    OGR_G_DestroyGeometry(poly);
    print_message("water polygons: %d texels inside, %d on an edge\n", inside, near_edge);
    assert_true(inside > 150 && near_edge <= 4);
    /* a line is a river: its course in texel coordinates, its width and depth (3 texels and 1 m unless given) */
    f = fopen(file, "w");
    fprintf(f, "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Feature\", \"properties\": {\"depth\": 3}, "
               "\"geometry\": {\"type\": \"LineString\", \"coordinates\": [[%.9f, %.9f], [%.9f, %.9f]]}}]}\n", lon[0], lat[0],
            lon[2], lat[2]);
    fclose(f);
    if (!geo_water_vectors(fixture_path("dem.tif"), file, W, H, lv, &rivers, &n_rivers, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(n_rivers, 1);
    assert_int_equal(rivers[0].n, 2);
    assert_true(fabs(rivers[0].pt[0][0] - 10.2) < 1e-6 && fabs(rivers[0].pt[0][1] - 12.3) < 1e-6);
    assert_true(fabs(rivers[0].pt[1][0] - 33.7) < 1e-6 && fabs(rivers[0].pt[1][1] - 25.6) < 1e-6);
    assert_true(fabs(rivers[0].width - 3000) < 1e-6 && rivers[0].depth == 3);
    geo_rivers_free(rivers, n_rivers);
    /* a point and a polygon without its level: refused */
    f = fopen(file, "w");
    fprintf(f, "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Feature\", \"properties\": {\"level\": 3}, "
               "\"geometry\": {\"type\": \"Point\", \"coordinates\": [%.9f, %.9f]}}]}\n", lon[0], lat[0]);
    fclose(f);
    assert_false(geo_water_vectors(fixture_path("dem.tif"), file, W, H, lv, &rivers, &n_rivers, &e));
    assert_non_null(strstr(e.msg, "is no polygon or line (Point)"));
    f = fopen(file, "w");
    fprintf(f, "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": \"Feature\", \"properties\": {\"name\": \"x\"}, "
               "\"geometry\": {\"type\": \"Polygon\", \"coordinates\": [[[%.9f, %.9f], [%.9f, %.9f], [%.9f, %.9f], [%.9f, %.9f]]]}}]}\n",
            lon[0], lat[0], lon[1], lat[1], lon[2], lat[2], lon[0], lat[0]);
    fclose(f);
    assert_false(geo_water_vectors(fixture_path("dem.tif"), file, W, H, lv, &rivers, &n_rivers, &e));
    assert_non_null(strstr(e.msg, "has no numeric \"level\" field"));
    unlink(file);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(viewshed_geotiff),
        cmocka_unit_test(tracks_round_trip),
        cmocka_unit_test(flight_track_flight),
        cmocka_unit_test(observers_on_edges_and_across_180),
        cmocka_unit_test(tracks_as_the_guide_says),
        cmocka_unit_test(viewshed_radius_crops),
        cmocka_unit_test(viewshed_drapes_see_through),
        cmocka_unit_test(water_geotiff),
        cmocka_unit_test(water_polygons),
    };
    return cmocka_run_group_tests(tests, fixture_setup, fixture_teardown);
}
