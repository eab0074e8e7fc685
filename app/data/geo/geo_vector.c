/* geo_vector — OGR's side of geo.h: GPS tracks read and written (GPX through OGR's driver, KML with a
 * gx:Tour by hand) and vector layers burnt onto a DEM's grid. */
#include "data/geo/geo.h"
#include "data/geo/geo_internal.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <math.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- GPS tracks -------------------------------------------------------------------------------- */

/* A feature's "time" field as seconds since the epoch (UTC; a zone the field gives is applied), or NaN. */
static double feature_time(OGRFeatureH f, int field)
{
    int y, mo, d, h, mi, tz;
    float s;
    if (field < 0 || !OGR_F_IsFieldSetAndNotNull(f, field) ||
        !OGR_F_GetFieldAsDateTimeEx(f, field, &y, &mo, &d, &h, &mi, &s, &tz))
        return NAN;
    double t = (double)util_days_from_civil(y, mo, d) * 86400 + h * 3600 + mi * 60 + s;
    return tz > 1 ? t - (tz - 100) * 15 * 60 : t; /* tz: 100 = UTC, each step 15 minutes; 0-1 unknown/local */
}

static bool add_point(geo_point **pts, int *n, int *cap, geo_point p)
{
    if (*n == GEO_TRACK_MAX)
        return false;
    if (*n == *cap) {
        *cap = *cap ? 2 * *cap : 256;
        *pts = util_realloc(*pts, sizeof **pts * (size_t)*cap, "a track's points");
    }
    (*pts)[(*n)++] = p;
    return true;
}

/* The points of one feature: a line's vertices, a point, each part of a multi-geometry in turn. */
static bool feature_points(OGRGeometryH geo, OGRCoordinateTransformationH t, double time, geo_point **pts, int *n,
                           int *cap)
{
    if (!geo)
        return true;
    int parts = OGR_G_GetGeometryCount(geo);
    if (parts > 0) {
        for (int k = 0; k < parts; k++)
            if (!feature_points(OGR_G_GetGeometryRef(geo, k), t, time, pts, n, cap))
                return false;
        return true;
    }
    bool has_z = OGR_G_Is3D(geo);
    for (int k = 0; k < OGR_G_GetPointCount(geo); k++) {
        double x = OGR_G_GetX(geo, k), y = OGR_G_GetY(geo, k), z = OGR_G_GetZ(geo, k);
        if (t && !OCTTransform(t, 1, &x, &y, &z))
            continue;
        if (!add_point(pts, n, cap, (geo_point){x, y, has_z ? z : NAN, time}))
            return false;
    }
    return true;
}

/* The layer a track is read from: GPX's track points (they carry times), else its route points (never its loose
 * waypoints while it has a way), else the first layer with features. */
static OGRLayerH track_layer(GDALDatasetH ds)
{
    static const char *const PREFERRED[] = {"track_points", "route_points"};
    for (size_t k = 0; k < sizeof PREFERRED / sizeof *PREFERRED; k++) {
        OGRLayerH l = GDALDatasetGetLayerByName(ds, PREFERRED[k]);
        if (l && OGR_L_GetFeatureCount(l, 1) > 0)
            return l;
    }
    for (int i = 0; i < GDALDatasetGetLayerCount(ds); i++) {
        OGRLayerH l = GDALDatasetGetLayer(ds, i);
        if (OGR_L_GetFeatureCount(l, 1) > 0)
            return l;
    }
    return NULL;
}

bool geo_track_read(const char *path, geo_point **pts, int *n, err_t *err)
{
    *pts = NULL, *n = 0;
    GDALDatasetH ds = geo_open(path, GDAL_OF_VECTOR, "open the track", err);
    if (!ds)
        return false;
    OGRLayerH l = track_layer(ds);
    OGRSpatialReferenceH from = l ? OGR_L_GetSpatialRef(l) : NULL, w = geo_wgs84();
    OGRSpatialReferenceH src = from ? OSRClone(from) : NULL;
    if (src)
        OSRSetAxisMappingStrategy(src, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH t = src ? OCTNewCoordinateTransformation(src, w) : NULL;
    int cap = 0, field = l ? OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), "time") : -1;
    int ele = l ? OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), "ele") : -1; /* GPX keeps heights in a field */
    /* GPX's points name their track (route): the first one's only, as a GPS tool reads "the track" */
    int owner = l ? OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), "track_fid") : -1;
    if (l && owner < 0)
        owner = OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), "route_fid");
    bool ok = l != NULL, full = false, first_owner = true;
    long long which = 0;
    OGRFeatureH f;
    while (ok && !full && (f = OGR_L_GetNextFeature(l)) != NULL) {
        long long of = owner >= 0 && OGR_F_IsFieldSetAndNotNull(f, owner) ? OGR_F_GetFieldAsInteger64(f, owner) : 0;
        if (first_owner)
            which = of, first_owner = false;
        if (of != which) {
            OGR_F_Destroy(f);
            continue;
        }
        int first = *n;
        full = !feature_points(OGR_F_GetGeometryRef(f), t, feature_time(f, field), pts, n, &cap);
        for (int k = first; ele >= 0 && OGR_F_IsFieldSetAndNotNull(f, ele) && k < *n; k++)
            if (isnan((*pts)[k].ele))
                (*pts)[k].ele = OGR_F_GetFieldAsDouble(f, ele);
        OGR_F_Destroy(f);
    }
    if (t)
        OCTDestroyCoordinateTransformation(t);
    if (src)
        OSRDestroySpatialReference(src);
    OSRDestroySpatialReference(w);
    GDALClose(ds);
    if (ok && !full && *n >= 2)
        return true;
    free(*pts);
    *pts = NULL;
    if (full)
        return err_set(err, "the track '%s' has more than %d points: simplify it first (ogr2ogr -simplify)", path,
                       GEO_TRACK_MAX);
    return err_set(err, "the track '%s' has %s: a track needs a line or at least two points", path,
                   ok ? "fewer than two points" : "no features");
}

/* GPX through OGR's driver: its track_points layer, grouped into one trk by track_fid and
 * track_seg_id, with ele and time. */
static bool write_gpx_to(const char *path, const geo_point *pts, int n, err_t *err)
{
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GPX"), path, 0, 0, 0, GDT_Unknown, NULL);
    if (!ds)
        return err_set(err, "cannot write the GPX '%s': %s", path, geo_gdal_msg("GDAL refused to create it"));
    OGRSpatialReferenceH w = geo_wgs84();
    OGRLayerH l = GDALDatasetCreateLayer(ds, "track_points", w, wkbPoint, NULL);
    OSRDestroySpatialReference(w);
    static const struct { const char *name; OGRFieldType type; } FIELDS[] = {
        {"track_fid", OFTInteger}, {"track_seg_id", OFTInteger}, {"ele", OFTReal}, {"time", OFTDateTime}};
    bool ok = l != NULL;
    int idx[4]; /* the driver's own schema may hold them already: found by name, created if not */
    for (size_t k = 0; ok && k < sizeof FIELDS / sizeof FIELDS[0]; k++) {
        idx[k] = OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), FIELDS[k].name);
        if (idx[k] < 0) {
            OGRFieldDefnH fd = OGR_Fld_Create(FIELDS[k].name, FIELDS[k].type);
            ok = OGR_L_CreateField(l, fd, 1) == OGRERR_NONE;
            OGR_Fld_Destroy(fd);
            idx[k] = OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), FIELDS[k].name);
        }
        ok = ok && idx[k] >= 0;
    }
    for (int i = 0; ok && i < n; i++) {
        OGRFeatureH f = OGR_F_Create(OGR_L_GetLayerDefn(l));
        OGRGeometryH g = OGR_G_CreateGeometry(wkbPoint);
        OGR_G_SetPoint_2D(g, 0, pts[i].lon, pts[i].lat);
        OGR_F_SetGeometryDirectly(f, g);
        OGR_F_SetFieldInteger(f, idx[0], 0);
        OGR_F_SetFieldInteger(f, idx[1], 0);
        if (!isnan(pts[i].ele))
            OGR_F_SetFieldDouble(f, idx[2], pts[i].ele);
        if (!isnan(pts[i].time)) {
            int y, mo, d, h, mi;
            double sec;
            util_civil_from_seconds(pts[i].time, &y, &mo, &d, &h, &mi, &sec);
            OGR_F_SetFieldDateTimeEx(f, idx[3], y, mo, d, h, mi, (float)sec, 100);
        }
        ok = OGR_L_CreateFeature(l, f) == OGRERR_NONE;
        OGR_F_Destroy(f);
    }
    GDALClose(ds);
    return ok || err_set(err, "writing the GPX '%s' failed: %s", path, geo_gdal_msg("is the disk full?"));
}

/* The GPX driver creates its file itself and refuses one that exists (the temporary file the caller
 * made safely): it writes into GDAL's memory file system, and the bytes are copied. */
static bool write_gpx(const char *path, const geo_point *pts, int n, err_t *err)
{
    char mem[64];
    snprintf(mem, sizeof mem, "/vsimem/fathom-track-%p.gpx", (const void *)pts);
    bool ok = write_gpx_to(mem, pts, n, err);
    vsi_l_offset len = 0;
    GByte *bytes = ok ? VSIGetMemFileBuffer(mem, &len, FALSE) : NULL;
    FILE *f = bytes ? fopen(path, "wb") : NULL;
    if (ok && !(f && fwrite(bytes, 1, (size_t)len, f) == (size_t)len))
        ok = err_set(err, "cannot write the GPX '%s' (is the disk full?)", path);
    if (f && fclose(f) != 0 && ok)
        ok = err_set(err, "cannot write the GPX '%s' (is the disk full?)", path);
    VSIUnlink(mem);
    return ok;
}

/* Length of the well-formed UTF-8 sequence at s (RFC 3629: no overlongs, no surrogates, ≤ U+10FFFF), or 0. */
static int utf8_length(const unsigned char *s)
{
    int n = s[0] < 0x80 ? 1 : s[0] >= 0xc2 && s[0] < 0xe0 ? 2 : s[0] >= 0xe0 && s[0] < 0xf0 ? 3
                                                           : s[0] >= 0xf0 && s[0] < 0xf5 ? 4 : 0;
    for (int i = 1; i < n; i++)
        if ((s[i] & 0xc0) != 0x80)
            return 0;
    if ((n == 3 && s[0] == 0xe0 && s[1] < 0xa0) || (n == 3 && s[0] == 0xed && s[1] >= 0xa0) ||
        (n == 4 && s[0] == 0xf0 && s[1] < 0x90) || (n == 4 && s[0] == 0xf4 && s[1] >= 0x90))
        return 0;
    return n;
}

/* Text for XML: the five characters XML reserves as entities, control bytes (C0, DEL, C1) dropped, a
 * byte that is not UTF-8 (a file name in Latin-1) as U+FFFD: the file parses whatever the name. */
static void xml_text(FILE *f, const char *s)
{
    for (const unsigned char *c = (const unsigned char *)s; *c;) {
        int n = utf8_length(c);
        if (n == 0)
            fputs("\xef\xbf\xbd", f), n = 1;
        else if (*c == '<' || *c == '>' || *c == '&' || *c == '"' || *c == '\'')
            fprintf(f, "&#%d;", *c);
        else if ((n == 1 && *c >= 0x20 && *c != 0x7f) || (n == 2 && !(c[0] == 0xc2 && c[1] < 0xa0)) || n > 2)
            fwrite(c, 1, (size_t)n, f);
        c += n;
    }
}

/* KML 2.2 with Google's gx extension: the track as an absolute-altitude LineString, and with cameras a
 * gx:Tour of smooth FlyTos (their durations from the points' times, else one second each). */
static bool write_kml(const char *path, const char *name, const geo_point *pts, const double (*cam)[3], int n,
                      err_t *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return err_set(err, "cannot write the KML '%s'", path);
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\" "
          "xmlns:gx=\"http://www.google.com/kml/ext/2.2\">\n<Document>\n<name>", f);
    xml_text(f, name);
    fputs("</name>\n<Placemark>\n<name>", f);
    xml_text(f, name);
    fputs("</name>\n<LineString>\n<altitudeMode>absolute</altitudeMode>\n<coordinates>\n", f);
    for (int i = 0; i < n; i++)
        fprintf(f, "%.9f,%.9f,%.3f\n", pts[i].lon, pts[i].lat, isnan(pts[i].ele) ? 0 : pts[i].ele);
    fputs("</coordinates>\n</LineString>\n</Placemark>\n", f);
    if (cam) {
        fputs("<gx:Tour>\n<name>", f);
        xml_text(f, name);
        fputs("</name>\n<gx:Playlist>\n", f);
        for (int i = 0; i < n; i++) {
            double dt = i > 0 && !isnan(pts[i].time) && !isnan(pts[i - 1].time) ? pts[i].time - pts[i - 1].time : 1;
            fprintf(f, "<gx:FlyTo><gx:duration>%.3f</gx:duration><gx:flyToMode>smooth</gx:flyToMode><Camera>"
                       "<longitude>%.9f</longitude><latitude>%.9f</latitude><altitude>%.3f</altitude>"
                       "<heading>%.3f</heading><tilt>%.3f</tilt><roll>%.3f</roll>"
                       "<altitudeMode>absolute</altitudeMode></Camera></gx:FlyTo>\n",
                    i == 0 ? 0 : fmax(dt, 0), pts[i].lon, pts[i].lat, isnan(pts[i].ele) ? 0 : pts[i].ele, cam[i][0],
                    cam[i][1], cam[i][2]);
        }
        fputs("</gx:Playlist>\n</gx:Tour>\n", f);
    }
    fputs("</Document>\n</kml>\n", f);
    bool ok = !ferror(f);
    ok = fclose(f) == 0 && ok;
    return ok || err_set(err, "writing the KML '%s' failed (is the disk full?)", path);
}

bool geo_track_write_file(const char *path, bool kml, const char *name, const geo_point *pts,
                          const double (*cameras)[3], int n, err_t *err)
{
    geo_gdal_init();
    return kml ? write_kml(path, name, pts, cameras, n, err) : write_gpx(path, pts, n, err);
}

/* ---- vectors: lines and points burnt onto the DEM's grid ---------------------------------------- */

/* A feature's geometry as an area `width` metres wide, in the DEM's CRS: lines and polygon outlines buffered
 * by half of it, points by all of it (a marker twice the line's width across). The buffer is taken where
 * lengths are metres: `to` carries the feature there (the DEM's CRS if projected, else a transverse Mercator
 * about the DEM's centre) and `back`, if any, from there to the DEM's CRS. NULL if none. */
static OGRGeometryH as_area(OGRGeometryH g, OGRCoordinateTransformationH to, OGRCoordinateTransformationH back,
                            double width)
{
    if (!g)
        return NULL;
    OGRGeometryH c = OGR_G_Clone(g);
    if (to && OGR_G_Transform(c, to) != OGRERR_NONE) {
        OGR_G_DestroyGeometry(c);
        return NULL;
    }
    OGRwkbGeometryType type = wkbFlatten(OGR_G_GetGeometryType(c));
    if (type == wkbPolygon || type == wkbMultiPolygon) { /* outlines: a land-use map's borders */
        OGRGeometryH b = OGR_G_Boundary(c);
        OGR_G_DestroyGeometry(c);
        c = b;
    }
    bool point = type == wkbPoint || type == wkbMultiPoint;
    OGRGeometryH area = c ? OGR_G_Buffer(c, point ? width : width / 2, 8) : NULL;
    if (c)
        OGR_G_DestroyGeometry(c);
    if (area && back && OGR_G_Transform(area, back) != OGRERR_NONE) {
        OGR_G_DestroyGeometry(area);
        return NULL;
    }
    return area;
}

/* The CRS in which a buffer's width is metres: the DEM's own if projected (in its units), else a transverse
 * Mercator about the DEM's centre (scale error under 0.3 % within 500 km of it). */
static OGRSpatialReferenceH metric_crs(const geo_grid *g, double *unit)
{
    OGRSpatialReferenceH m = OSRClone(g->srs);
    *unit = 1;
    if (!OSRIsGeographic(g->srs)) {
        *unit = 1 / OSRGetLinearUnits(g->srs, NULL);
        return m;
    }
    double lon = g->gt[0] + g->w * g->gt[1] / 2, lat = g->gt[3] + g->h * g->gt[5] / 2;
    OSRSetTM(m, lat, lon, 1, 0, 0);
    OSRSetAxisMappingStrategy(m, OAMS_TRADITIONAL_GIS_ORDER);
    return m;
}

/* The shapes burnt at w × h as coverage: each drape texel's alpha is the part of it the shapes cover, counted
 * on an 8 × 8 grid of sub-texels, so a line keeps its width within a sub-texel however it falls (burnt
 * whole texels made a two-texel line one to three texels wide). In strips of at most 16 MB. */
enum { SUB = 8 };
static bool burn_coverage(const geo_grid *g, OGRGeometryH *areas, int n, int w, int h, unsigned char *alpha)
{
    int rows = (int)fmax(1, fmin(h, (double)(1 << 24) / ((double)w * SUB * SUB)));
    double dx = g->w * g->gt[1] / w, dy = g->h * g->gt[5] / h;
    int *bands = (int[]){1};
    double *burn = util_alloc(sizeof(double) * (size_t)(n ? n : 1), "burn values");
    for (int i = 0; i < n; i++)
        burn[i] = 1;
    unsigned char *sub = util_alloc((size_t)w * SUB * (size_t)rows * SUB, "a vector strip");
    bool ok = true;
    for (int r0 = 0; ok && r0 < h; r0 += rows) {
        int sh = (int)fmin(rows, h - r0);
        GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", w * SUB, sh * SUB, 1, GDT_Byte, NULL);
        double gt[6] = {g->gt[0], dx / SUB, 0, g->gt[3] + r0 * dy, 0, dy / SUB};
        ok = mem && GDALSetGeoTransform(mem, gt) == CE_None && GDALSetSpatialRef(mem, g->srs) == CE_None &&
             (n == 0 || GDALRasterizeGeometries(mem, 1, bands, n, areas, NULL, NULL, burn, NULL, NULL, NULL) == CE_None) &&
             GDALRasterIO(GDALGetRasterBand(mem, 1), GF_Read, 0, 0, w * SUB, sh * SUB, sub, w * SUB, sh * SUB, GDT_Byte,
                          0, 0) == CE_None;
        for (int j = 0; ok && j < sh; j++)
            for (int i = 0; i < w; i++) {
                int covered = 0;
                for (int b = 0; b < SUB; b++)
                    for (int a = 0; a < SUB; a++)
                        covered += sub[((size_t)(j * SUB + b) * (size_t)w + (size_t)i) * SUB + (size_t)a] != 0;
                alpha[(size_t)(r0 + j) * (size_t)w + (size_t)i] = (unsigned char)((covered * 255 + SUB * SUB / 2) / (SUB * SUB));
            }
        if (mem)
            GDALClose(mem);
    }
    free(sub);
    free(burn);
    return ok;
}

bool geo_vectors(const char *dem_path, const char *vectors, double width, const float rgba[4], int w, int h,
                 unsigned char *out, err_t *err)
{
    geo_grid g;
    if (!geo_grid_of(dem_path, &g, err))
        return false;
    GDALDatasetH ds = geo_open(vectors, GDAL_OF_VECTOR, "open the vectors", err);
    if (!ds) {
        OSRDestroySpatialReference(g.srs);
        return false;
    }
    double unit, texel_m = OSRIsGeographic(g.srs) ? fabs(g.gt[5]) * 111320.0 : fabs(g.gt[1]) * OSRGetLinearUnits(g.srs, NULL);
    OGRSpatialReferenceH metric = metric_crs(&g, &unit);
    OGRCoordinateTransformationH back = OSRIsGeographic(g.srs) ? OCTNewCoordinateTransformation(metric, g.srs) : NULL;
    double wd = (width > 0 ? width : texel_m) * unit; /* in the metric CRS's units */
    OGRGeometryH *areas = NULL;
    int n = 0, cap = 0;
    for (int l = 0; l < GDALDatasetGetLayerCount(ds); l++) {
        OGRLayerH layer = GDALDatasetGetLayer(ds, l);
        OGRSpatialReferenceH from = OGR_L_GetSpatialRef(layer);
        OGRSpatialReferenceH src = from ? OSRClone(from) : geo_wgs84();
        OSRSetAxisMappingStrategy(src, OAMS_TRADITIONAL_GIS_ORDER);
        OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(src, metric);
        OGRFeatureH f;
        while ((f = OGR_L_GetNextFeature(layer)) != NULL && n < GEO_TRACK_MAX) {
            OGRGeometryH a = as_area(OGR_F_GetGeometryRef(f), t, back, wd);
            if (a) {
                if (n == cap)
                    areas = util_realloc(areas, sizeof *areas * (size_t)(cap = cap ? 2 * cap : 64), "vector shapes");
                areas[n++] = a;
            }
            OGR_F_Destroy(f);
        }
        if (t)
            OCTDestroyCoordinateTransformation(t);
        OSRDestroySpatialReference(src);
    }
    GDALClose(ds);
    if (back)
        OCTDestroyCoordinateTransformation(back);
    OSRDestroySpatialReference(metric);
    unsigned char *alpha = util_alloc((size_t)w * (size_t)h, "a vector layer's coverage");
    bool ok = burn_coverage(&g, areas, n, w, h, alpha);
    for (size_t k = 0; ok && k < (size_t)w * (size_t)h; k++)
        for (int c = 0; c < 4; c++) /* the colour where the shapes reach, its alpha times their coverage */
            out[4 * k + (size_t)c] = alpha[k] ? (unsigned char)fmin(255, fmax(0, rgba[c] * (c < 3 ? 255 : alpha[k])) + 0.5) : 0;
    free(alpha);
    for (int i = 0; i < n; i++)
        OGR_G_DestroyGeometry(areas[i]);
    free(areas);
    OSRDestroySpatialReference(g.srs);
    if (ok && n == 0)
        return err_set(err, "the vectors '%s' hold no lines, points or polygons GDAL could place on the DEM", vectors);
    return ok || err_set(err, "cannot draw the vectors '%s' on the DEM: %s", vectors, geo_gdal_msg("rasterising failed"));
}

/* ---- water: polygons with a level burnt onto the DEM's grid, rivers as lines -------------------- */

/* Feature f's level (its "level" field) into *level; false with err naming the feature. */
static bool feature_level(OGRFeatureH f, const char *vectors, long index, double *level, err_t *err)
{
    int field = OGR_F_GetFieldIndex(f, "level");
    OGRFieldType type = field >= 0 ? OGR_Fld_GetType(OGR_F_GetFieldDefnRef(f, field)) : OFTString;
    if (field < 0 || !OGR_F_IsFieldSetAndNotNull(f, field) || (type != OFTReal && type != OFTInteger && type != OFTInteger64))
        return err_set(err, "terrain.water: polygon %ld of '%s' has no numeric \"level\" field: each lake or reservoir "
                            "needs its water level in metres there", index, vectors);
    *level = OGR_F_GetFieldAsDouble(f, field);
    return (isfinite(*level) && fabs(*level) <= 1e5) ||
           err_set(err, "terrain.water: polygon %ld of '%s' has level %g: expected metres from -100000 to 100000", index,
                   vectors, *level);
}

/* Field `name` of f as a number in (0, 1e5], or def when it has none. */
static double feature_number(OGRFeatureH f, const char *name, double def)
{
    int field = OGR_F_GetFieldIndex(f, name);
    double v = field >= 0 && OGR_F_IsFieldSetAndNotNull(f, field) ? OGR_F_GetFieldAsDouble(f, field) : def;
    return isfinite(v) && v > 0 && v <= 1e5 ? v : def;
}

/* A line (or each line of a multi-line) in the DEM's CRS as a river in texel coordinates, appended to *r. */
static void add_river(const geo_grid *g, OGRGeometryH line, double width, double depth, geo_river **r, int *n)
{
    if (wkbFlatten(OGR_G_GetGeometryType(line)) == wkbMultiLineString) {
        for (int k = 0; k < OGR_G_GetGeometryCount(line); k++)
            add_river(g, OGR_G_GetGeometryRef(line, k), width, depth, r, n);
        return;
    }
    int np = OGR_G_GetPointCount(line);
    if (np < 2 || *n >= GEO_TRACK_MAX)
        return;
    *r = util_realloc(*r, sizeof **r * (size_t)(*n + 1), "the rivers");
    geo_river *v = &(*r)[(*n)++];
    *v = (geo_river){.pt = util_alloc(sizeof *v->pt * (size_t)np, "a river"), .n = np, .width = width, .depth = depth};
    for (int k = 0; k < np; k++) { /* texel centres at whole numbers (geo_convert's convention) */
        v->pt[k][0] = (OGR_G_GetX(line, k) - g->gt[0]) / g->gt[1] - 0.5;
        v->pt[k][1] = (OGR_G_GetY(line, k) - g->gt[3]) / g->gt[5] - 0.5;
    }
}

/* What geo_water_vectors gathers: the polygons (in the DEM's CRS) with their levels, and the rivers. */
typedef struct water_shapes {
    OGRGeometryH *shapes;
    double *levels;
    long n, cap;
    geo_river *rivers;
    int n_rivers;
} water_shapes;

/* Feature f (the index-th), its geometry carried to the DEM's CRS by t: a polygon with its level, or a river;
 * false with err for anything else. */
static bool water_feature(const geo_grid *g, OGRFeatureH f, OGRCoordinateTransformationH t, const char *vectors,
                          long index, water_shapes *ws, err_t *err)
{
    OGRGeometryH geo = OGR_F_GetGeometryRef(f);
    OGRwkbGeometryType type = geo ? wkbFlatten(OGR_G_GetGeometryType(geo)) : wkbUnknown;
    double level = 0;
    if (type == wkbLineString || type == wkbMultiLineString) { /* a river: 3 texels wide, 1 m deep, unless given */
        OGRGeometryH c = OGR_G_Clone(geo);
        double texel_m = OSRIsGeographic(g->srs) ? fabs(g->gt[5]) * 111320.0 : fabs(g->gt[1]) * OSRGetLinearUnits(g->srs, NULL);
        if (!t || OGR_G_Transform(c, t) == OGRERR_NONE)
            add_river(g, c, feature_number(f, "width", 3 * texel_m), feature_number(f, "depth", 1), &ws->rivers,
                      &ws->n_rivers);
        OGR_G_DestroyGeometry(c);
        return true;
    }
    if (type != wkbPolygon && type != wkbMultiPolygon)
        return err_set(err, "terrain.water: feature %ld of '%s' is no polygon or line (%s): lakes are polygons with a "
                            "level, rivers lines", index, vectors, geo ? OGRGeometryTypeToName(type) : "no geometry");
    if (!feature_level(f, vectors, index, &level, err))
        return false;
    OGRGeometryH c = OGR_G_Clone(geo);
    if (t && OGR_G_Transform(c, t) != OGRERR_NONE) {
        OGR_G_DestroyGeometry(c);
        return true;
    }
    if (ws->n == ws->cap) {
        ws->cap = ws->cap ? 2 * ws->cap : 64;
        ws->shapes = util_realloc(ws->shapes, sizeof *ws->shapes * (size_t)ws->cap, "the water's polygons");
        ws->levels = util_realloc(ws->levels, sizeof *ws->levels * (size_t)ws->cap, "the water's polygons");
    }
    ws->shapes[ws->n] = c;
    ws->levels[ws->n++] = level;
    return true;
}

/* The polygons' levels at the texel centres they hold (GDAL's rasteriser), NaN elsewhere, into out. */
static bool burn_levels(const geo_grid *g, const water_shapes *ws, int w, int h, float *out)
{
    GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", w, h, 1, GDT_Float32, NULL);
    GDALRasterBandH b = mem ? GDALGetRasterBand(mem, 1) : NULL;
    bool ok = mem && GDALSetGeoTransform(mem, (double *)g->gt) == CE_None && GDALSetSpatialRef(mem, g->srs) == CE_None &&
              GDALFillRaster(b, NAN, 0) == CE_None &&
              (ws->n == 0 || GDALRasterizeGeometries(mem, 1, (int[]){1}, (int)ws->n, ws->shapes, NULL, NULL, ws->levels,
                                                     NULL, NULL, NULL) == CE_None) &&
              GDALRasterIO(b, GF_Read, 0, 0, w, h, out, w, h, GDT_Float32, 0, 0) == CE_None;
    if (mem)
        GDALClose(mem);
    return ok;
}

bool geo_water_vectors(const char *dem_path, const char *vectors, int w, int h, float *out, geo_river **rivers,
                       int *n_rivers, err_t *err)
{
    *rivers = NULL, *n_rivers = 0;
    geo_grid g;
    if (!geo_grid_of(dem_path, &g, err))
        return false;
    GDALDatasetH ds = geo_open(vectors, GDAL_OF_VECTOR, "open the water's polygons", err);
    if (!ds) {
        OSRDestroySpatialReference(g.srs);
        return false;
    }
    water_shapes ws = {0};
    long index = 0;
    bool ok = (g.w == w && g.h == h) ||
              err_set(err, "terrain.water: the DEM '%s' is %d x %d and its heights %d x %d", dem_path, g.w, g.h, w, h);
    for (int l = 0; ok && l < GDALDatasetGetLayerCount(ds); l++) {
        OGRLayerH layer = GDALDatasetGetLayer(ds, l);
        OGRSpatialReferenceH from = OGR_L_GetSpatialRef(layer);
        OGRSpatialReferenceH src = from ? OSRClone(from) : geo_wgs84();
        OSRSetAxisMappingStrategy(src, OAMS_TRADITIONAL_GIS_ORDER);
        OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(src, g.srs);
        OGRFeatureH f;
        while (ok && (f = OGR_L_GetNextFeature(layer)) != NULL && ws.n < GEO_TRACK_MAX) {
            ok = water_feature(&g, f, t, vectors, index++, &ws, err);
            OGR_F_Destroy(f);
        }
        if (t)
            OCTDestroyCoordinateTransformation(t);
        OSRDestroySpatialReference(src);
    }
    GDALClose(ds);
    if (ok && ws.n == 0 && ws.n_rivers == 0)
        ok = err_set(err, "terrain.water: '%s' holds no polygon or line GDAL could place on the DEM", vectors);
    if (ok && !burn_levels(&g, &ws, w, h, out))
        ok = err_set(err, "terrain.water: cannot place '%s' on the DEM: %s", vectors, geo_gdal_msg("rasterising failed"));
    for (long i = 0; i < ws.n; i++)
        OGR_G_DestroyGeometry(ws.shapes[i]);
    free(ws.shapes);
    free(ws.levels);
    OSRDestroySpatialReference(g.srs);
    if (ok) {
        *rivers = ws.rivers, *n_rivers = ws.n_rivers;
    } else {
        for (int i = 0; i < ws.n_rivers; i++)
            free(ws.rivers[i].pt);
        free(ws.rivers);
    }
    return ok;
}

/* The drape's size for `width`-wide lines: two texels across a line, at least the DEM's own texels,
 * the longest side at most max_side. */
void geo_vector_size(const char *dem_path, double width, int max_side, int *w, int *h)
{
    geo_grid g;
    err_t ignore;
    *w = *h = 0;
    if (!geo_grid_of(dem_path, &g, &ignore))
        return;
    double unit = OSRIsGeographic(g.srs) ? 1 / 111320.0 : 1 / OSRGetLinearUnits(g.srs, NULL);
    OSRDestroySpatialReference(g.srs);
    double px = fmin(width > 0 ? width * unit / 2 : fabs(g.gt[1]), fabs(g.gt[1]));
    double ew = g.w * fabs(g.gt[1]), eh = g.h * fabs(g.gt[5]), scale = fmin(1.0, max_side / fmax(ew / px, eh / px));
    *w = (int)fmax(2, round(ew / px * scale));
    *h = (int)fmax(2, round(eh / px * scale));
}

