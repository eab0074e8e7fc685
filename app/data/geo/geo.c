/* geo — GIS input and output on a DEM's grid through GDAL (geo.h): places, the viewshed GeoTIFF, the drape, GDAL's
 * own viewshed; tracks and vectors are geo_vector.c's. */
#include "data/geo/geo.h"
#include "data/geo/geo_internal.h"

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

#include "data/geo/gdal_trust.h"

void geo_gdal_init(void)
{
    static bool done;
    if (!done) {
        GDALAllRegister();
        gdal_trust_init();
        GDALSetCacheMax64((GIntBig)64 << 20); /* rows are read once: a small block cache, not 5 % of RAM */
        done = true;
    }
    CPLSetErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
}

const char *geo_gdal_msg(const char *fallback)
{
    const char *m = CPLGetLastErrorMsg();
    return m && *m ? m : fallback;
}

GDALDatasetH geo_open(const char *path, unsigned kind, const char *what, err_t *err)
{
    geo_gdal_init();
    char why[256];
    if (!gdal_trust_path(path, why, sizeof why)) {
        err_set(err, "cannot %s '%s': %s", what, path, why);
        return NULL;
    }
    GDALDatasetH ds = GDALOpenEx(path, kind | GDAL_OF_READONLY, gdal_trust_drivers(), NULL, NULL);
    if (!ds)
        err_set(err, "cannot %s '%s': %s", what, path,
                geo_gdal_msg(kind & GDAL_OF_VECTOR ? "not a vector file GDAL reads (GPX, KML, GeoJSON, GeoPackage, "
                                                     "Shapefile)"
                                                   : "not a raster GDAL reads"));
    return ds;
}


bool geo_grid_of(const char *dem_path, geo_grid *g, err_t *err)
{
    GDALDatasetH ds = geo_open(dem_path, GDAL_OF_RASTER, "open the DEM", err);
    if (!ds)
        return false;
    *g = (geo_grid){GDALGetRasterXSize(ds), GDALGetRasterYSize(ds), {0}, NULL};
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
    bool ok = srs && GDALGetGeoTransform(ds, g->gt) == CE_None && g->gt[2] == 0 && g->gt[4] == 0;
    if (ok) {
        g->srs = OSRClone(srs);
        OSRSetAxisMappingStrategy(g->srs, OAMS_TRADITIONAL_GIS_ORDER);
        if (g->gt[5] > 0) { /* south-up: fathom's row 0 is north (data/geo/dem.h) */
            g->gt[3] += g->gt[5] * g->h;
            g->gt[5] = -g->gt[5];
        }
    }
    GDALClose(ds);
    return ok || err_set(err, "the DEM '%s' has no georeferencing (a north-up geotransform and a CRS): fathom cannot "
                              "place it on the Earth; give a GeoTIFF, .hgt or other georeferenced DEM", dem_path);
}

OGRSpatialReferenceH geo_wgs84(void)
{
    OGRSpatialReferenceH s = OSRNewSpatialReference(NULL);
    OSRSetWellKnownGeogCS(s, "WGS84");
    OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER); /* x = longitude, y = latitude */
    return s;
}

bool geo_convert(const char *dem_path, bool to_texel, int n, const double *x, const double *y, double *u, double *v,
                 err_t *err)
{
    geo_grid g;
    if (!geo_grid_of(dem_path, &g, err))
        return false;
    OGRSpatialReferenceH w = geo_wgs84();
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
        if (ok && to_texel && OSRIsGeographic(g.srs)) { /* the turn nearest the DEM: -179.5° on one past 180° */
            double turn = 360 / (OSRGetAngularUnits(g.srs, NULL) * 180 / M_PI), mid = g.gt[0] + g.gt[1] * g.w / 2;
            px += turn * round((mid - px) / turn);
        }
        if (ok && to_texel) {
            px = (px - g.gt[0]) / g.gt[1] - 0.5;
            py = (py - g.gt[3]) / g.gt[5] - 0.5;
        }
        u[i] = px, v[i] = py;
        if (!ok)
            err_set(err, "cannot transform the point %g, %g %s: %s", x[i], y[i],
                    to_texel ? "(longitude, latitude) into the DEM's CRS" : "(texel) into longitude and latitude",
                    geo_gdal_msg("outside the CRS's domain"));
    }
    if (!t)
        err_set(err, "cannot transform between WGS 84 and the CRS of '%s': %s", dem_path, geo_gdal_msg("PROJ refused"));
    else
        OCTDestroyCoordinateTransformation(t);
    OSRDestroySpatialReference(w);
    OSRDestroySpatialReference(g.srs);
    return ok;
}

bool geo_true_north(const char *dem_path, double lon, double lat, double *gamma, err_t *err)
{
    *gamma = 0;
    geo_grid g;
    if (!geo_grid_of(dem_path, &g, err))
        return false;
    bool projected = !OSRIsGeographic(g.srs);
    OSRDestroySpatialReference(g.srs);
    if (!projected) /* a geographic grid's north is the meridian's */
        return true;
    /* the meridian through the place, 10 m north of it on the sphere, in the DEM's CRS */
    double x[2] = {lon, lon}, y[2] = {lat, lat + 10 / 111195.0}, col[2], row[2];
    if (!geo_convert(dem_path, true, 2, x, y, col, row, err))
        return false;
    double east = (col[1] - col[0]) * g.gt[1], north = (row[1] - row[0]) * g.gt[5]; /* CRS units, y north */
    *gamma = atan2(east, north) * 180 / M_PI;
    return true;
}

/* GDAL writes a GeoTIFF's tiles as it closes it and cannot say when the disk refused one: the file
 * read back, every byte against what was meant. */
static bool read_back_equal(const char *path, int w, int h, const unsigned char *v)
{
    err_t ignored;
    GDALDatasetH ds = geo_open(path, GDAL_OF_RASTER, "read back", &ignored);
    unsigned char *got = ds ? malloc((size_t)w * (size_t)h) : NULL;
    bool ok = got && GDALGetRasterXSize(ds) == w && GDALGetRasterYSize(ds) == h &&
              GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, w, h, got, w, h, GDT_Byte, 0, 0) == CE_None &&
              memcmp(got, v, (size_t)w * (size_t)h) == 0;
    free(got);
    if (ds)
        GDALClose(ds);
    return ok;
}

/* A tiled, deflated GeoTIFF at path on grid g (its CRS taken: g->srs is freed), errors reset; NULL with a
 * message when GDAL refuses. */
static GDALDatasetH create_on_grid(geo_grid *g, const char *path, int w, int h, int bands, GDALDataType type, err_t *err)
{
    CPLErrorReset();
    char **opts = CSLSetNameValue(NULL, "COMPRESS", "DEFLATE");
    opts = CSLSetNameValue(opts, "TILED", "YES");
    if (type == GDT_Float32)
        opts = CSLSetNameValue(opts, "PREDICTOR", "3"); /* floating point: smaller */
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path, w, h, bands, type, opts);
    CSLDestroy(opts);
    if (ds) {
        GDALSetGeoTransform(ds, g->gt);
        GDALSetSpatialRef(ds, g->srs);
    }
    OSRDestroySpatialReference(g->srs);
    if (!ds)
        err_set(err, "cannot write '%s': %s", path, geo_gdal_msg("GDAL refused to create it"));
    return ds;
}

bool geo_write_mask_file(const char *dem_path, const char *out_path, int x0, int y0, int w, int h,
                         const unsigned char *v, const char *description, err_t *err)
{
    geo_grid g;
    if (!geo_grid_of(dem_path, &g, err))
        return false;
    if (x0 < 0 || y0 < 0 || x0 + w > g.w || y0 + h > g.h) {
        OSRDestroySpatialReference(g.srs);
        return err_set(err, "a %d × %d raster at %d, %d does not fit the DEM's %d × %d grid", w, h, x0, y0, g.w, g.h);
    }
    g.gt[0] += x0 * g.gt[1]; /* the window's corner (north-up: geo_grid_of) */
    g.gt[3] += y0 * g.gt[5];
    GDALDatasetH ds = create_on_grid(&g, out_path, w, h, 1, GDT_Byte, err);
    if (!ds)
        return false;
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    GDALSetRasterNoDataValue(b, 255);
    GDALSetDescription(b, description);
    GDALColorTableH ct = GDALCreateColorTable(GPI_RGB);
    /* GeoTIFF keeps no alpha in a colour table: opaque colours, nodata clear by its value (geo_drape) */
    const GDALColorEntry hidden = {30, 20, 60, 255}, visible = {60, 210, 90, 255}, none = {0, 0, 0, 0};
    GDALSetColorEntry(ct, 0, &hidden);
    GDALSetColorEntry(ct, 1, &visible);
    for (int i = 2; i < 256; i++)
        GDALSetColorEntry(ct, i, &none);
    GDALSetRasterColorTable(b, ct);
    GDALDestroyColorTable(ct);
    bool ok = GDALRasterIO(b, GF_Write, 0, 0, w, h, (void *)v, w, h, GDT_Byte, 0, 0) == CE_None;
    GDALClose(ds); /* GDAL 3.6's close returns nothing: its errors are the last error, the read-back the rest */
    ok = ok && CPLGetLastErrorType() < CE_Failure && read_back_equal(out_path, w, h, v);
    return ok || err_set(err, "cannot write '%s': %s", out_path, geo_gdal_msg("it does not read back whole (is the "
                                                                              "disk full?)"));
}

/* Band b of a Float32 file equals v (NaN where v is NaN). */
static bool read_back_floats(GDALDatasetH ds, int b, int w, int h, const float *v)
{
    float *got = malloc((size_t)w * (size_t)h * sizeof *got);
    bool ok = got && GDALRasterIO(GDALGetRasterBand(ds, b), GF_Read, 0, 0, w, h, got, w, h, GDT_Float32, 0, 0) == CE_None;
    for (size_t i = 0; ok && i < (size_t)w * (size_t)h; i++)
        ok = isnan(v[i]) ? isnan(got[i]) : got[i] == v[i];
    free(got);
    return ok;
}

bool geo_write_floats_file(const char *dem_path, const char *out_path, int w, int h, int bands, const float *const *v,
                           const char *const *descriptions, err_t *err)
{
    geo_grid g;
    if (!geo_grid_of(dem_path, &g, err))
        return false;
    if (w != g.w || h != g.h) {
        OSRDestroySpatialReference(g.srs);
        return err_set(err, "a %d × %d raster does not fit the DEM's %d × %d grid", w, h, g.w, g.h);
    }
    GDALDatasetH ds = create_on_grid(&g, out_path, w, h, bands, GDT_Float32, err);
    if (!ds)
        return false;
    bool ok = true;
    for (int b = 0; ok && b < bands; b++) {
        GDALRasterBandH band = GDALGetRasterBand(ds, b + 1);
        GDALSetRasterNoDataValue(band, NAN);
        GDALSetDescription(band, descriptions[b]);
        GDALSetRasterUnitType(band, "m");
        ok = GDALRasterIO(band, GF_Write, 0, 0, w, h, (void *)v[b], w, h, GDT_Float32, 0, 0) == CE_None;
    }
    GDALClose(ds);
    ok = ok && CPLGetLastErrorType() < CE_Failure;
    err_t ignored;
    GDALDatasetH back = ok ? geo_open(out_path, GDAL_OF_RASTER, "read back", &ignored) : NULL;
    ok = back && GDALGetRasterXSize(back) == w && GDALGetRasterYSize(back) == h && GDALGetRasterCount(back) == bands;
    for (int b = 0; ok && b < bands; b++)
        ok = read_back_floats(back, b + 1, w, h, v[b]);
    if (back)
        GDALClose(back);
    return ok || err_set(err, "cannot write '%s': %s", out_path, geo_gdal_msg("it does not read back whole (is the "
                                                                              "disk full?)"));
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
        err_set(err, "cannot read the imagery '%s' as colours: %s", path, geo_gdal_msg("unsupported bands"));
    else if (palette) /* the palette's fourth component, its alpha */
        GDALSetRasterColorInterpretation(GDALGetRasterBand(v, 4), GCI_AlphaBand);
    return v;
}

/* The imagery's own resolution over the DEM's extent (its pixel size once in the DEM's CRS), the
 * longest side at most max_side; at least 2 × 2. */
static void drape_size(GDALDatasetH src, const geo_grid *g, int max_side, int *w, int *h)
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

bool geo_layers_size(const char *dem_path, const char *imagery, const float *widths, int n_widths, int max_side,
                     int *w, int *h, err_t *err)
{
    *w = *h = 0;
    if (imagery) {
        geo_grid g;
        if (!geo_grid_of(dem_path, &g, err))
            return false;
        GDALDatasetH src = geo_open(imagery, GDAL_OF_RASTER, "open the imagery", err);
        if (src) {
            drape_size(src, &g, max_side, w, h);
            GDALClose(src);
        }
        OSRDestroySpatialReference(g.srs);
        if (!src)
            return false;
    }
    for (int i = 0; i < n_widths; i++) { /* a finer size where a line needs two texels across */
        int vw, vh;
        geo_vector_size(dem_path, widths[i], max_side, &vw, &vh);
        if ((long)vw * vh > (long)*w * *h)
            *w = vw, *h = vh;
    }
    return *w > 0 && *h > 0 ? true : err_set(err, "cannot size the drape on the DEM '%s'", dem_path);
}

static bool warp_into(GDALDatasetH view, GDALDatasetH dst, const char *path, err_t *err)
{
    int bands = GDALGetRasterCount(view);
    bool src_alpha = GDALGetRasterColorInterpretation(GDALGetRasterBand(view, bands)) == GCI_AlphaBand;
    char **argv = NULL;
    argv = CSLAddString(argv, "-r");
    argv = CSLAddString(argv, "bilinear");
    argv = CSLAddString(argv, "-dstalpha");
    if (src_alpha) /* warped as a band of values, its own (a palette's 120 stays 120): GDAL's source alpha is a
                    * mask that makes every pixel it lets through opaque */
        argv = CSLAddString(argv, "-nosrcalpha");
    GDALWarpAppOptions *o = GDALWarpAppOptionsNew(argv, NULL);
    CSLDestroy(argv);
    int usage = 0;
    GDALDatasetH r = o ? GDALWarp(NULL, dst, 1, &view, o, &usage) : NULL;
    GDALWarpAppOptionsFree(o);
    return r || err_set(err, "cannot warp the imagery '%s' onto the DEM: %s", path, geo_gdal_msg("GDALWarp failed"));
}

/* The warped bands (grey, RGB, each with alpha last) as RGBA bytes. */
/* The warped bands as RGBA: the colours, and as alpha the coverage (the last band) times the imagery's own alpha
 * if it has one (the band before). */
static bool read_rgba(GDALDatasetH dst, int colours, bool own_alpha, int w, int h, unsigned char *rgba)
{
    size_t n = (size_t)w * (size_t)h;
    unsigned char *band = util_alloc(n, "a band of the imagery");
    bool ok = true;
    for (int c = 0; ok && c < 4; c++) {
        int src = c == 3 ? GDALGetRasterCount(dst) : (colours == 1 ? 1 : c + 1);
        ok = GDALRasterIO(GDALGetRasterBand(dst, src), GF_Read, 0, 0, w, h, band, w, h, GDT_Byte, 0, 0) == CE_None;
        for (size_t k = 0; ok && k < n; k++)
            rgba[4 * k + (size_t)c] = band[k];
    }
    ok = ok && (!own_alpha || GDALRasterIO(GDALGetRasterBand(dst, colours + 1), GF_Read, 0, 0, w, h, band, w, h,
                                           GDT_Byte, 0, 0) == CE_None);
    for (size_t k = 0; ok && own_alpha && k < n; k++)
        rgba[4 * k + 3] = (unsigned char)((rgba[4 * k + 3] * band[k] + 127) / 255);
    free(band);
    return ok;
}

bool geo_drape(const char *dem_path, const char *imagery, int max_side, unsigned char **rgba, int *w, int *h,
               err_t *err)
{
    geo_grid g;
    if (!geo_grid_of(dem_path, &g, err))
        return false;
    GDALDatasetH src = geo_open(imagery, GDAL_OF_RASTER, "open the imagery", err);
    bool ok = src != NULL;
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
        int out = colours + alpha + 1; /* the colours, the imagery's alpha if any, the warp's coverage */
        dst = GDALCreate(GDALGetDriverByName("MEM"), "", *w, *h, out, GDT_Byte, NULL);
        double gt[6] = {g.gt[0], g.w * g.gt[1] / *w, 0, g.gt[3], 0, g.h * g.gt[5] / *h};
        ok = dst && GDALSetGeoTransform(dst, gt) == CE_None && GDALSetSpatialRef(dst, g.srs) == CE_None;
        if (ok)
            GDALSetRasterColorInterpretation(GDALGetRasterBand(dst, out), GCI_AlphaBand);
        ok = ok && warp_into(view, dst, imagery, err);
    }
    if (ok) {
        *rgba = util_alloc(4 * (size_t)*w * (size_t)*h, "the draped imagery");
        ok = read_rgba(dst, colours, alpha, *w, *h, *rgba) || err_set(err, "reading the warped imagery failed");
        size_t k = 0, n = (size_t)*w * (size_t)*h;
        while (ok && k < n && (*rgba)[4 * k + 3] == 0)
            k++;
        if (ok && k == n) /* nothing of it on the DEM: a wrong file or CRS, not a layer to draw as nothing */
            ok = err_set(err, "the imagery '%s' lies wholly off the DEM '%s' (or is all nodata): check that it covers "
                              "the DEM's area and that its CRS is right (gdalinfo)", imagery, dem_path);
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

/* ---- GDAL's own viewshed, for the bench's comparison -------------------------------------------- */

bool geo_gdal_viewshed(const char *dem_path, int col, int row, double observer_height, double target_height,
                       double curvature, unsigned char *out, err_t *err)
{
    geo_grid g;
    if (!geo_grid_of(dem_path, &g, err))
        return false;
    OSRDestroySpatialReference(g.srs);
    GDALDatasetH ds = geo_open(dem_path, GDAL_OF_RASTER, "open the DEM", err);
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
    return ok || err_set(err, "GDAL's viewshed failed on '%s': %s", dem_path, geo_gdal_msg("no message"));
}

