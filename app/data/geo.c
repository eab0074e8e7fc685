/* geo — GIS input and output on a DEM's grid through GDAL and OGR (geo.h). */
#include "data/geo.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <gdal_utils.h>
#include <math.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/gdal_net.h"

static void geo_init(void)
{
    static bool done;
    if (!done) {
        GDALAllRegister();
        gdal_network_off();
        done = true;
    }
    CPLSetErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
}

static const char *gdal_msg(const char *fallback)
{
    const char *m = CPLGetLastErrorMsg();
    return m && *m ? m : fallback;
}

/* A DEM's grid: size, north-up geotransform (pixel corners), CRS (a clone: the caller destroys it). */
typedef struct grid {
    int w, h;
    double gt[6];
    OGRSpatialReferenceH srs;
} grid;

static bool grid_of(const char *dem_path, grid *g, err_t *err)
{
    geo_init();
    GDALDatasetH ds = GDALOpenEx(dem_path, GDAL_OF_RASTER | GDAL_OF_READONLY, NULL, NULL, NULL);
    if (!ds)
        return err_set(err, "cannot open the DEM '%s': %s", dem_path, gdal_msg("not a raster GDAL reads"));
    *g = (grid){GDALGetRasterXSize(ds), GDALGetRasterYSize(ds), {0}, NULL};
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
    bool ok = srs && GDALGetGeoTransform(ds, g->gt) == CE_None && g->gt[2] == 0 && g->gt[4] == 0;
    if (ok) {
        g->srs = OSRClone(srs);
        OSRSetAxisMappingStrategy(g->srs, OAMS_TRADITIONAL_GIS_ORDER);
        if (g->gt[5] > 0) { /* south-up: fathom's row 0 is north (data/dem.h) */
            g->gt[3] += g->gt[5] * g->h;
            g->gt[5] = -g->gt[5];
        }
    }
    GDALClose(ds);
    return ok || err_set(err, "the DEM '%s' has no georeferencing (a north-up geotransform and a CRS): fathom cannot "
                              "place it on the Earth; give a GeoTIFF, .hgt or other georeferenced DEM", dem_path);
}

static OGRSpatialReferenceH wgs84(void)
{
    OGRSpatialReferenceH s = OSRNewSpatialReference(NULL);
    OSRSetWellKnownGeogCS(s, "WGS84");
    OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER); /* x = longitude, y = latitude */
    return s;
}

bool geo_convert(const char *dem_path, bool to_texel, int n, const double *x, const double *y, double *u, double *v,
                 err_t *err)
{
    grid g;
    if (!grid_of(dem_path, &g, err))
        return false;
    OGRSpatialReferenceH w = wgs84();
    OGRCoordinateTransformationH t = to_texel ? OCTNewCoordinateTransformation(w, g.srs)
                                              : OCTNewCoordinateTransformation(g.srs, w);
    bool ok = t != NULL;
    for (int i = 0; ok && i < n; i++) {
        double px = x[i], py = y[i], pz = 0;
        if (!to_texel) { /* texel centres at whole numbers: the pixel's centre is at +0.5 */
            px = g.gt[0] + (x[i] + 0.5) * g.gt[1];
            py = g.gt[3] + (y[i] + 0.5) * g.gt[5];
        }
        ok = OCTTransform(t, 1, &px, &py, &pz) && isfinite(px) && isfinite(py);
        if (ok && to_texel) {
            px = (px - g.gt[0]) / g.gt[1] - 0.5;
            py = (py - g.gt[3]) / g.gt[5] - 0.5;
        }
        u[i] = px, v[i] = py;
        if (!ok)
            err_set(err, "cannot transform the point %g, %g %s: %s", x[i], y[i],
                    to_texel ? "(longitude, latitude) into the DEM's CRS" : "(texel) into longitude and latitude",
                    gdal_msg("outside the CRS's domain"));
    }
    if (!t)
        err_set(err, "cannot transform between WGS 84 and the CRS of '%s': %s", dem_path, gdal_msg("PROJ refused"));
    else
        OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(w);
    OSRDestroySpatialReference(g.srs);
    return ok;
}

bool geo_write_mask_file(const char *dem_path, const char *out_path, int w, int h, const unsigned char *v,
                         const char *description, err_t *err)
{
    grid g;
    if (!grid_of(dem_path, &g, err))
        return false;
    if (g.w != w || g.h != h) {
        OSRDestroySpatialReference(g.srs);
        return err_set(err, "a %d × %d raster does not fit the DEM's %d × %d grid", w, h, g.w, g.h);
    }
    char **opts = CSLSetNameValue(NULL, "COMPRESS", "DEFLATE");
    opts = CSLSetNameValue(opts, "TILED", "YES");
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), out_path, w, h, 1, GDT_Byte, opts);
    CSLDestroy(opts);
    if (!ds) {
        OSRDestroySpatialReference(g.srs);
        return err_set(err, "cannot write '%s': %s", out_path, gdal_msg("GDAL refused to create it"));
    }
    GDALSetGeoTransform(ds, g.gt);
    GDALSetSpatialRef(ds, g.srs);
    OSRDestroySpatialReference(g.srs);
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    GDALSetRasterNoDataValue(b, 255);
    GDALSetDescription(b, description);
    GDALColorTableH ct = GDALCreateColorTable(GPI_RGB);
    const GDALColorEntry hidden = {30, 20, 60, 120}, visible = {60, 210, 90, 170}, none = {0, 0, 0, 0};
    GDALSetColorEntry(ct, 0, &hidden);
    GDALSetColorEntry(ct, 1, &visible);
    for (int i = 2; i < 256; i++)
        GDALSetColorEntry(ct, i, &none);
    GDALSetRasterColorTable(b, ct);
    GDALDestroyColorTable(ct);
    bool ok = GDALRasterIO(b, GF_Write, 0, 0, w, h, (void *)v, w, h, GDT_Byte, 0, 0) == CE_None;
    GDALClose(ds);
    return ok || err_set(err, "writing '%s' failed: %s", out_path, gdal_msg("is the disk full?"));
}

/* ---- imagery: any raster warped onto the DEM's extent ------------------------------------------ */

/* A Byte RGB(A) or grey view of src (a VRT in memory): a palette expanded to RGBA, other types scaled
 * from their own range to 0–255. NULL with a message when GDAL cannot. */
static GDALDatasetH byte_view(GDALDatasetH src, const char *path, err_t *err)
{
    GDALRasterBandH b1 = GDALGetRasterBand(src, 1);
    bool palette = GDALGetRasterColorTable(b1) != NULL, bytes = GDALGetRasterDataType(b1) == GDT_Byte;
    int n = GDALGetRasterCount(src);
    bool alpha = n > 1 && GDALGetRasterColorInterpretation(GDALGetRasterBand(src, n)) == GCI_AlphaBand;
    char **argv = CSLAddString(NULL, "-of");
    argv = CSLAddString(argv, "VRT");
    /* grey, grey + alpha, RGB or RGBA: a multispectral file's first three bands as its colours */
    for (int b = 1; !palette && b <= (n - alpha >= 3 ? 3 : 1); b++)
        argv = CSLAddString(CSLAddString(argv, "-b"), CPLSPrintf("%d", b));
    if (alpha && !palette)
        argv = CSLAddString(CSLAddString(argv, "-b"), CPLSPrintf("%d", n));
    if (palette) {
        argv = CSLAddString(argv, "-expand");
        argv = CSLAddString(argv, "rgba");
    } else if (!bytes) {
        argv = CSLAddString(argv, "-ot");
        argv = CSLAddString(argv, "Byte");
        argv = CSLAddString(argv, "-scale"); /* each band's own minimum and maximum to 0 and 255 */
    }
    GDALTranslateOptions *o = GDALTranslateOptionsNew(argv, NULL);
    CSLDestroy(argv);
    GDALDatasetH v = o ? GDALTranslate("", src, o, NULL) : NULL;
    GDALTranslateOptionsFree(o);
    if (!v)
        err_set(err, "cannot read the imagery '%s' as colours: %s", path, gdal_msg("unsupported bands"));
    return v;
}

/* The imagery's own resolution over the DEM's extent (its pixel size once in the DEM's CRS), the
 * longest side at most max_side; at least 2 × 2. */
static void drape_size(GDALDatasetH src, const grid *g, int max_side, int *w, int *h)
{
    char *wkt = NULL;
    OSRExportToWkt(g->srs, &wkt);
    char **to = CSLSetNameValue(NULL, "DST_SRS", wkt);
    CPLFree(wkt);
    void *t = GDALCreateGenImgProjTransformer2(src, NULL, to);
    CSLDestroy(to);
    double gt[6], ext[4];
    int pw = 0, ph = 0;
    double px = fabs(g->gt[1]); /* no estimate: the DEM's own texels */
    if (t && GDALSuggestedWarpOutput2(src, GDALGenImgProjTransform, t, gt, &pw, &ph, ext, 0) == CE_None && gt[1] > 0)
        px = gt[1];
    if (t)
        GDALDestroyGenImgProjTransformer(t);
    double ew = g->w * fabs(g->gt[1]), eh = g->h * fabs(g->gt[5]);
    double scale = fmin(1.0, max_side / fmax(ew / px, eh / px));
    *w = (int)fmax(2, round(ew / px * scale));
    *h = (int)fmax(2, round(eh / px * scale));
}

static bool warp_into(GDALDatasetH view, GDALDatasetH dst, const char *path, err_t *err)
{
    int bands = GDALGetRasterCount(view);
    bool src_alpha = GDALGetRasterColorInterpretation(GDALGetRasterBand(view, bands)) == GCI_AlphaBand;
    char **argv = NULL;
    argv = CSLAddString(argv, "-r");
    argv = CSLAddString(argv, "bilinear");
    argv = CSLAddString(argv, "-dstalpha");
    if (src_alpha)
        argv = CSLAddString(argv, "-srcalpha");
    GDALWarpAppOptions *o = GDALWarpAppOptionsNew(argv, NULL);
    CSLDestroy(argv);
    int usage = 0;
    GDALDatasetH r = o ? GDALWarp(NULL, dst, 1, &view, o, &usage) : NULL;
    GDALWarpAppOptionsFree(o);
    return r || err_set(err, "cannot warp the imagery '%s' onto the DEM: %s", path, gdal_msg("GDALWarp failed"));
}

/* The warped bands (grey, RGB, each with alpha last) as RGBA bytes. */
static bool read_rgba(GDALDatasetH dst, int colours, int w, int h, unsigned char *rgba)
{
    unsigned char *band = util_alloc((size_t)w * (size_t)h, "a row of the imagery");
    bool ok = true;
    for (int c = 0; ok && c < 4; c++) {
        int src = c == 3 ? colours + 1 : (colours == 1 ? 1 : c + 1);
        ok = GDALRasterIO(GDALGetRasterBand(dst, src), GF_Read, 0, 0, w, h, band, w, h, GDT_Byte, 0, 0) == CE_None;
        for (size_t k = 0; ok && k < (size_t)w * (size_t)h; k++)
            rgba[4 * k + (size_t)c] = band[k];
    }
    free(band);
    return ok;
}

bool geo_drape(const char *dem_path, const char *imagery, int max_side, unsigned char **rgba, int *w, int *h,
               err_t *err)
{
    grid g;
    if (!grid_of(dem_path, &g, err))
        return false;
    GDALDatasetH src = GDALOpenEx(imagery, GDAL_OF_RASTER | GDAL_OF_READONLY, NULL, NULL, NULL);
    bool ok = src != NULL;
    if (!ok)
        err_set(err, "cannot open the imagery '%s': %s", imagery, gdal_msg("not a raster GDAL reads"));
    if (ok && (!GDALGetSpatialRef(src) && !GDALGetGCPCount(src)))
        ok = err_set(err, "the imagery '%s' has no georeferencing: fathom cannot tell where it lies on the DEM "
                          "(give it a CRS and geotransform, e.g. gdal_translate -a_srs -a_ullr)", imagery);
    GDALDatasetH view = ok ? byte_view(src, imagery, err) : NULL;
    ok = view != NULL;
    int bands = ok ? GDALGetRasterCount(view) : 0;
    bool alpha = ok && GDALGetRasterColorInterpretation(GDALGetRasterBand(view, bands)) == GCI_AlphaBand;
    int colours = bands - alpha >= 3 ? 3 : 1;
    GDALDatasetH dst = NULL;
    if (ok) {
        if (*w <= 0 || *h <= 0) /* else the size asked (a second layer matching the first) */
            drape_size(src, &g, max_side, w, h);
        dst = GDALCreate(GDALGetDriverByName("MEM"), "", *w, *h, colours + 1, GDT_Byte, NULL);
        double gt[6] = {g.gt[0], g.w * g.gt[1] / *w, 0, g.gt[3], 0, g.h * g.gt[5] / *h};
        ok = dst && GDALSetGeoTransform(dst, gt) == CE_None && GDALSetSpatialRef(dst, g.srs) == CE_None;
        if (ok)
            GDALSetRasterColorInterpretation(GDALGetRasterBand(dst, colours + 1), GCI_AlphaBand);
        ok = ok && warp_into(view, dst, imagery, err);
    }
    if (ok) {
        *rgba = util_alloc(4 * (size_t)*w * (size_t)*h, "the draped imagery");
        ok = read_rgba(dst, colours, *w, *h, *rgba) || err_set(err, "reading the warped imagery failed");
        if (!ok)
            free(*rgba);
    }
    if (dst)
        GDALClose(dst);
    if (view)
        GDALClose(view);
    if (src)
        GDALClose(src);
    OSRDestroySpatialReference(g.srs);
    return ok;
}

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

/* The layer a track is read from: GPX's track points (they carry times), else the first with features. */
static OGRLayerH track_layer(GDALDatasetH ds)
{
    OGRLayerH l = GDALDatasetGetLayerByName(ds, "track_points");
    if (l && OGR_L_GetFeatureCount(l, 1) > 0)
        return l;
    for (int i = 0; i < GDALDatasetGetLayerCount(ds); i++) {
        l = GDALDatasetGetLayer(ds, i);
        if (OGR_L_GetFeatureCount(l, 1) > 0)
            return l;
    }
    return NULL;
}

bool geo_track_read(const char *path, geo_point **pts, int *n, err_t *err)
{
    geo_init();
    *pts = NULL, *n = 0;
    GDALDatasetH ds = GDALOpenEx(path, GDAL_OF_VECTOR | GDAL_OF_READONLY, NULL, NULL, NULL);
    if (!ds)
        return err_set(err, "cannot open the track '%s': %s", path,
                       gdal_msg("not a vector file GDAL reads (GPX, KML, GeoJSON, GeoPackage, Shapefile)"));
    OGRLayerH l = track_layer(ds);
    OGRSpatialReferenceH from = l ? OGR_L_GetSpatialRef(l) : NULL, w = wgs84();
    OGRSpatialReferenceH src = from ? OSRClone(from) : NULL;
    if (src)
        OSRSetAxisMappingStrategy(src, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH t = src ? OCTNewCoordinateTransformation(src, w) : NULL;
    int cap = 0, field = l ? OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), "time") : -1;
    int ele = l ? OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(l), "ele") : -1; /* GPX keeps heights in a field */
    bool ok = l != NULL, full = false;
    OGRFeatureH f;
    while (ok && !full && (f = OGR_L_GetNextFeature(l)) != NULL) {
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
        return err_set(err, "cannot write the GPX '%s': %s", path, gdal_msg("GDAL refused to create it"));
    OGRSpatialReferenceH w = wgs84();
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
    return ok || err_set(err, "writing the GPX '%s' failed: %s", path, gdal_msg("is the disk full?"));
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

/* Text for XML: the five characters XML reserves as entities, control bytes dropped. */
static void xml_text(FILE *f, const char *s)
{
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '<' || c == '>' || c == '&' || c == '"' || c == '\'')
            fprintf(f, "&#%d;", c);
        else if (c >= 0x20 && c != 0x7f)
            fputc(c, f);
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
    geo_init();
    return kml ? write_kml(path, name, pts, cameras, n, err) : write_gpx(path, pts, n, err);
}

/* ---- GDAL's own viewshed, for the bench's comparison -------------------------------------------- */

bool geo_gdal_viewshed(const char *dem_path, int col, int row, double observer_height, double target_height,
                       double curvature, unsigned char *out, err_t *err)
{
    grid g;
    if (!grid_of(dem_path, &g, err))
        return false;
    OSRDestroySpatialReference(g.srs);
    GDALDatasetH ds = GDALOpenEx(dem_path, GDAL_OF_RASTER | GDAL_OF_READONLY, NULL, NULL, NULL);
    double gt[6];
    if (!ds || GDALGetGeoTransform(ds, gt) != CE_None || gt[5] > 0) {
        if (ds)
            GDALClose(ds);
        return err_set(err, "GDAL's viewshed: '%s' is not a north-up georeferenced raster", dem_path);
    }
    double x = gt[0] + (col + 0.5) * gt[1], y = gt[3] + (row + 0.5) * gt[5];
    /* 1 visible, 0 hidden, 255 nodata; GVM_Edge: GDAL's default (gdal_viewshed -om NORMAL) */
    GDALDatasetH v = GDALViewshedGenerate(GDALGetRasterBand(ds, 1), "MEM", "", NULL, x, y, observer_height,
                                          target_height, 1, 0, 255, 255, curvature, GVM_Edge, 0, NULL, NULL,
                                          GVOT_NORMAL, NULL);
    bool ok = v && GDALRasterIO(GDALGetRasterBand(v, 1), GF_Read, 0, 0, g.w, g.h, out, g.w, g.h, GDT_Byte, 0, 0) ==
                       CE_None;
    if (v)
        GDALClose(v);
    GDALClose(ds);
    return ok || err_set(err, "GDAL's viewshed failed on '%s': %s", dem_path, gdal_msg("no message"));
}

/* ---- vectors: lines and points burnt onto the DEM's grid ---------------------------------------- */

/* A feature's geometry in the DEM's CRS as an area `width` wide: lines and polygon outlines buffered
 * by half of it, points by all of it (a marker twice the line's width across). NULL if none. */
static OGRGeometryH as_area(OGRGeometryH g, OGRCoordinateTransformationH t, double width)
{
    if (!g)
        return NULL;
    OGRGeometryH c = OGR_G_Clone(g);
    if (t && OGR_G_Transform(c, t) != OGRERR_NONE) {
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
    return area;
}

bool geo_vectors(const char *dem_path, const char *vectors, double width, const float rgba[4], int w, int h,
                 unsigned char *out, err_t *err)
{
    grid g;
    if (!grid_of(dem_path, &g, err))
        return false;
    GDALDatasetH ds = GDALOpenEx(vectors, GDAL_OF_VECTOR | GDAL_OF_READONLY, NULL, NULL, NULL);
    if (!ds) {
        OSRDestroySpatialReference(g.srs);
        return err_set(err, "cannot open the vectors '%s': %s", vectors,
                       gdal_msg("not a vector file GDAL reads (GPX, KML, GeoJSON, GeoPackage, Shapefile)"));
    }
    /* width in the CRS's units: metres, or degrees of latitude for a geographic DEM */
    double unit = OSRIsGeographic(g.srs) ? 1 / 111320.0 : 1 / OSRGetLinearUnits(g.srs, NULL);
    double wd = (width > 0 ? width : fabs(g.gt[1]) / unit) * unit;
    OGRGeometryH *areas = NULL;
    int n = 0, cap = 0;
    for (int l = 0; l < GDALDatasetGetLayerCount(ds); l++) {
        OGRLayerH layer = GDALDatasetGetLayer(ds, l);
        OGRSpatialReferenceH from = OGR_L_GetSpatialRef(layer);
        OGRSpatialReferenceH src = from ? OSRClone(from) : wgs84();
        OSRSetAxisMappingStrategy(src, OAMS_TRADITIONAL_GIS_ORDER);
        OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(src, g.srs);
        OGRFeatureH f;
        while ((f = OGR_L_GetNextFeature(layer)) != NULL && n < GEO_TRACK_MAX) {
            OGRGeometryH a = as_area(OGR_F_GetGeometryRef(f), t, wd);
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
    GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", w, h, 4, GDT_Byte, NULL);
    double gt[6] = {g.gt[0], g.w * g.gt[1] / w, 0, g.gt[3], 0, g.h * g.gt[5] / h};
    bool ok = mem && GDALSetGeoTransform(mem, gt) == CE_None && GDALSetSpatialRef(mem, g.srs) == CE_None;
    int bands[4] = {1, 2, 3, 4};
    double *burn = util_alloc(sizeof(double) * 4 * (size_t)(n ? n : 1), "burn values");
    for (int i = 0; i < 4 * n; i++)
        burn[i] = fmin(255, fmax(0, rgba[i % 4] * 255)); /* each shape burns the colour into the four bands */
    ok = ok && (n == 0 || GDALRasterizeGeometries(mem, 4, bands, n, areas, NULL, NULL, burn, NULL, NULL, NULL) == CE_None);
    for (int c = 0; ok && c < 4; c++) {
        unsigned char *band = util_alloc((size_t)w * (size_t)h, "a vector band");
        ok = GDALRasterIO(GDALGetRasterBand(mem, c + 1), GF_Read, 0, 0, w, h, band, w, h, GDT_Byte, 0, 0) == CE_None;
        for (size_t k = 0; ok && k < (size_t)w * (size_t)h; k++)
            out[4 * k + (size_t)c] = band[k];
        free(band);
    }
    for (int i = 0; i < n; i++)
        OGR_G_DestroyGeometry(areas[i]);
    free(areas);
    free(burn);
    if (mem)
        GDALClose(mem);
    OSRDestroySpatialReference(g.srs);
    if (ok && n == 0)
        return err_set(err, "the vectors '%s' hold no lines, points or polygons GDAL could place on the DEM", vectors);
    return ok || err_set(err, "cannot draw the vectors '%s' on the DEM: %s", vectors, gdal_msg("rasterising failed"));
}

/* The drape's size for `width`-wide lines: two texels across a line, at least the DEM's own texels,
 * the longest side at most max_side. */
void geo_vector_size(const char *dem_path, double width, int max_side, int *w, int *h)
{
    grid g;
    err_t ignore;
    *w = *h = 0;
    if (!grid_of(dem_path, &g, &ignore))
        return;
    double unit = OSRIsGeographic(g.srs) ? 1 / 111320.0 : 1 / OSRGetLinearUnits(g.srs, NULL);
    OSRDestroySpatialReference(g.srs);
    double px = fmin(width > 0 ? width * unit / 2 : fabs(g.gt[1]), fabs(g.gt[1]));
    double ew = g.w * fabs(g.gt[1]), eh = g.h * fabs(g.gt[5]), scale = fmin(1.0, max_side / fmax(ew / px, eh / px));
    *w = (int)fmax(2, round(ew / px * scale));
    *h = (int)fmax(2, round(eh / px * scale));
}
