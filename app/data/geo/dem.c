#include "data/geo/dem.h"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <cpl_error.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <math.h>
#include <ogr_srs_api.h>
#include <stdio.h>
#include <stdlib.h>
#include <strings.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "data/geo/geo_internal.h"

#define EARTH_RADIUS 6371000.0 /* m: the IUGG mean radius */


/* Spacing in metres from the geotransform and CRS; false (with a message) when it cannot be had. */
static bool georeference(GDALDatasetH ds, const char *path, int h, dem_info *info, err_t *err)
{
    double gt[6];
    if (GDALGetGeoTransform(ds, gt) != CE_None)
        return true; /* no georeferencing: the scene must give the spacing */
    if (gt[2] != 0 || gt[4] != 0)
        return err_set(err, "DEM '%s' has a rotated geotransform (%g, %g): fathom's grid is north-up; warp it first "
                            "(gdalwarp)", path, gt[2], gt[4]);
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
    if (!srs) { /* a pixel size in an unknown unit (degrees? feet?): the scene must give the spacing */
        info->pixel[0] = fabs(gt[1]);
        info->pixel[1] = fabs(gt[5]);
        return true;
    }
    const char *name = OSRGetName(srs);
    snprintf(info->crs, sizeof info->crs, "%s", name ? name : "unnamed CRS");
    if (OSRIsGeographic(srs)) {
        double rad = OSRGetAngularUnits(srs, NULL); /* radians per unit (a degree's for EPSG:4326) */
        double lat = (gt[3] + gt[5] * 0.5 * h) * rad;
        if (!(fabs(lat) < 1.55)) /* 88.8°: the x spacing collapses toward the poles */
            return err_set(err, "DEM '%s' is centred at latitude %.2f°: too near a pole for a flat grid; reproject "
                                "it to a polar CRS (gdalwarp -t_srs EPSG:3413)", path, lat * 180 / M_PI);
        info->geographic = true;
        info->latitude = lat * 180 / M_PI;
        info->spacing[0] = fabs(gt[1]) * rad * EARTH_RADIUS * cos(lat);
        info->spacing[1] = fabs(gt[5]) * rad * EARTH_RADIUS;
    } else {
        double unit = OSRGetLinearUnits(srs, NULL); /* metres per unit */
        info->spacing[0] = fabs(gt[1]) * unit;
        info->spacing[1] = fabs(gt[5]) * unit;
    }
    info->georeferenced = true;
    return true;
}

/* What dem_read refuses before reading: no band, complex values, a side over max_side, more memory
 * than the machine has (app/data/geo/terrain.h: heights on the CPU and the GPU, the pyramid), so that a
 * file is refused up front rather than after minutes of reading. */
static bool check_readable(const char *path, GDALRasterBandH band, int W, int H, int max_side, double bytes_per_texel,
                           err_t *err)
{
    GDALDataType type = band ? GDALGetRasterDataType(band) : GDT_Unknown;
    if (!band)
        return err_set(err, "DEM '%s' has no raster band (a vector file, or a netCDF with several variables: name one "
                            "as NETCDF:\"%s\":VARIABLE)", path, path);
    if (GDALDataTypeIsComplex(type) || type == GDT_Unknown)
        return err_set(err, "DEM '%s' holds %s values: heights must be real numbers", path, GDALGetDataTypeName(type));
    if (W > max_side || H > max_side)
        return err_set(err, "DEM '%s' is %dx%d: the largest side fathom reads is %d texels; cut or resample it "
                            "(gdal_translate -outsize)", path, W, H, max_side);
    double need = (double)W * (double)H * bytes_per_texel;
    double have = util_physical_memory();
    if (bytes_per_texel > 0 && need > have)
        return err_set(err, "DEM '%s' is %dx%d: drawing it takes about %.0f GB and this machine has %.0f GB; cut or "
                            "resample it (gdal_translate -outsize)", path, W, H, need / 1e9, have / 1e9);
    return true;
}

/* Band 1 as floats, in row blocks, with progress on a terminal for big files. */
static bool read_rows(const char *path, GDALRasterBandH band, int x0, int y0, int W, int H, float *v, err_t *err)
{
    bool show = isatty(2) && (size_t)W * (size_t)H > ((size_t)1 << 24);
    const int ROWS = 256;
    for (int y = 0; y < H; y += ROWS) {
        int rows = y + ROWS < H ? ROWS : H - y;
        if (GDALRasterIO(band, GF_Read, x0, y0 + y, W, rows, v + (size_t)y * (size_t)W, W, rows, GDT_Float32, 0, 0) !=
            CE_None)
            return err_set(err, "DEM '%s': reading rows %d-%d failed: %s", path, y0 + y, y0 + y + rows - 1,
                           geo_gdal_msg("I/O error"));
        if (show)
            fprintf(stderr, "\rfathom: reading %s: %3d %%", path, (int)(100.0 * (y + rows) / H));
    }
    if (show)
        fprintf(stderr, "\n");
    return true;
}

/* Metres per unit of the heights: the band's unit (GDALGetRasterUnitType: "m", "ft", "US survey foot"…), else the
 * vertical CRS's of a compound CRS, else metres. A unit fathom does not know is refused with its name, never
 * drawn as metres (feet were drawn 3.28 times too tall). */
static bool vertical_unit(GDALDatasetH ds, GDALRasterBandH band, const char *path, dem_info *info, err_t *err)
{
    static const struct {
        const char *name;
        double metres;
    } UNITS[] = {{"", 1},           {"m", 1},         {"metre", 1},           {"meter", 1},
                 {"metres", 1},     {"meters", 1},    {"ft", 0.3048},         {"foot", 0.3048},
                 {"feet", 0.3048},  {"international foot", 0.3048},           {"us-ft", 1200.0 / 3937},
                 {"ftUS", 1200.0 / 3937}, {"US survey foot", 1200.0 / 3937},  {"foot_us", 1200.0 / 3937},
                 {"US foot", 1200.0 / 3937}, {"km", 1000},    {"dm", 0.1},    {"cm", 0.01},
                 {"mm", 0.001}};
    const char *unit = GDALGetRasterUnitType(band);
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
    info->height_unit = 1;
    if ((!unit || !*unit) && srs && OSRIsCompound(srs)) {
        char *vert = NULL;
        info->height_unit = OSRGetTargetLinearUnits(srs, "VERT_CS", &vert);
        snprintf(info->height_unit_name, sizeof info->height_unit_name, "%s", vert ? vert : "metre");
        return info->height_unit > 0 ||
               err_set(err, "DEM '%s': its vertical CRS has no length unit; give the heights in metres", path);
    }
    for (size_t i = 0; unit && i < sizeof UNITS / sizeof *UNITS; i++)
        if (!strcasecmp(unit, UNITS[i].name)) {
            info->height_unit = UNITS[i].metres;
            snprintf(info->height_unit_name, sizeof info->height_unit_name, "%s", *unit ? unit : "metre");
            return true;
        }
    return err_set(err, "DEM '%s': its heights are in '%.40s', a unit fathom does not know (metres, feet, US survey "
                        "feet, km, cm, mm); convert them to metres (gdal_translate -scale) or set the band's unit",
                   path, unit);
}

/* Raw values to heights in metres: nodata and non-finite values become holes (NaN), the rest take the band's
 * scale and offset, then its unit. */
static void to_heights(GDALRasterBandH band, float *v, size_t n, dem_info *info)
{
    int has_nodata = 0, has_scale = 0, has_offset = 0;
    double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
    double scale = GDALGetRasterScale(band, &has_scale), offset = GDALGetRasterOffset(band, &has_offset);
    if (!has_scale || !isfinite(scale) || scale == 0)
        scale = 1;
    if (!has_offset || !isfinite(offset))
        offset = 0;
    float nd = (float)nodata;
    for (size_t i = 0; i < n; i++) {
        float x = v[i];
        if ((has_nodata && (x == nd || (isnan(nodata) && isnan(x)))) || !isfinite(x)) {
            v[i] = NAN;
            info->holes++;
        } else {
            v[i] = (float)((x * scale + offset) * info->height_unit);
        }
    }
}

/* Row 0 north: a south-up raster (positive y pixel size) is flipped. */
static void flip_south_up(GDALDatasetH ds, float *v, int W, int H)
{
    double gt[6];
    if (GDALGetGeoTransform(ds, gt) == CE_None && gt[5] > 0)
        for (size_t y = 0, rows = (size_t)H, cols = (size_t)W; y < rows / 2; y++)
            for (size_t x = 0; x < cols; x++) {
                float t = v[y * cols + x];
                v[y * cols + x] = v[(rows - 1 - y) * cols + x];
                v[(rows - 1 - y) * cols + x] = t;
            }
}

bool dem_read(const char *path, int max_side, int *w, int *h, float **heights, dem_info *info, err_t *err)
{
    *w = *h = 0;
    return dem_read_window(path, 0, 0, w, h, max_side, heights, info, err);
}

bool dem_read_window(const char *path, int x0, int y0, int *w, int *h, int max_side, float **heights, dem_info *info,
                     err_t *err)
{
    *info = (dem_info){0};
    *heights = NULL;
    geo_gdal_init();
    GDALDatasetH ds = geo_open(path, GDAL_OF_RASTER, "read DEM", err);
    if (!ds)
        return false;
    int W = GDALGetRasterXSize(ds), H = GDALGetRasterYSize(ds);
    if (*w <= 0 || *h <= 0) /* the whole DEM */
        x0 = y0 = 0, *w = W, *h = H;
    GDALRasterBandH band = GDALGetRasterCount(ds) > 0 ? GDALGetRasterBand(ds, 1) : NULL;
    bool ok = x0 >= 0 && y0 >= 0 && x0 + *w <= W && y0 + *h <= H;
    if (!ok)
        err_set(err, "DEM '%s': the window %d,%d + %dx%d is not inside its %dx%d texels", path, x0, y0, *w, *h, W, H);
    ok = ok && check_readable(path, band, *w, *h, max_side, DEM_BYTES_PER_TEXEL, err);
    if (ok) {
        GDALDataType type = GDALGetRasterDataType(band);
        snprintf(info->type, sizeof info->type, "%s", GDALGetDataTypeName(type));
        info->is_float = GDALDataTypeIsFloating(type);
        ok = georeference(ds, path, H, info, err) && vertical_unit(ds, band, path, info, err);
    }
    double gt[6];
    bool south_up = GDALGetGeoTransform(ds, gt) == CE_None && gt[5] > 0; /* its rows counted from the end */
    size_t n = (size_t)*w * (size_t)*h;
    float *v = ok ? malloc(sizeof(float) * n) : NULL;
    if (ok && !v)
        ok = err_set(err, "DEM '%s' (%dx%d): out of memory (%zu MB for the heights)", path, *w, *h, sizeof(float) * n >> 20);
    ok = ok && read_rows(path, band, x0, south_up ? H - y0 - *h : y0, *w, *h, v, err);
    if (ok) {
        to_heights(band, v, n, info);
        flip_south_up(ds, v, *w, *h);
        *heights = v;
    } else {
        free(v);
        *w = *h = 0;
    }
    GDALClose(ds);
    return ok;
}

struct dem_stream {
    GDALDatasetH ds;
    GDALRasterBandH band;
    char path[PATH_MAX_LEN];
    int width, height;
    bool south_up;
    dem_info info;
    unsigned long long bytes; /* read so far: texels asked for times the band's bytes a texel */
};

dem_stream *dem_stream_open(const char *path, int *w, int *h, dem_info *info, err_t *err)
{
    geo_gdal_init();
    GDALDatasetH ds = geo_open(path, GDAL_OF_RASTER, "read DEM", err);
    if (!ds)
        return NULL;
    dem_stream *s = util_calloc(1, sizeof *s, "a DEM reader");
    s->ds = ds;
    snprintf(s->path, sizeof s->path, "%s", path);
    s->width = GDALGetRasterXSize(ds), s->height = GDALGetRasterYSize(ds);
    s->band = GDALGetRasterCount(ds) > 0 ? GDALGetRasterBand(ds, 1) : NULL;
    bool ok = check_readable(path, s->band, s->width, s->height, DEM_STREAM_MAX_SIDE, -1, err);
    if (ok) {
        GDALDataType type = GDALGetRasterDataType(s->band);
        snprintf(s->info.type, sizeof s->info.type, "%s", GDALGetDataTypeName(type));
        s->info.is_float = GDALDataTypeIsFloating(type);
        ok = georeference(ds, path, s->height, &s->info, err) && vertical_unit(ds, s->band, path, &s->info, err);
    }
    double gt[6];
    s->south_up = GDALGetGeoTransform(ds, gt) == CE_None && gt[5] > 0;
    if (!ok) {
        dem_stream_close(s);
        return NULL;
    }
    *w = s->width, *h = s->height;
    *info = s->info;
    return s;
}

bool dem_stream_read(dem_stream *s, int x0, int y0, int w, int h, float *out, err_t *err)
{
    if (x0 < 0 || y0 < 0 || w <= 0 || h <= 0 || x0 + w > s->width || y0 + h > s->height)
        return err_set(err, "DEM '%s': the window %d,%d + %dx%d is not inside its %dx%d texels", s->path, x0, y0, w, h,
                       s->width, s->height);
    if (!read_rows(s->path, s->band, x0, s->south_up ? s->height - y0 - h : y0, w, h, out, err))
        return false;
    s->bytes += (unsigned long long)w * (unsigned long long)h *
                (unsigned long long)GDALGetDataTypeSizeBytes(GDALGetRasterDataType(s->band));
    dem_info info = s->info; /* its holes are the window's */
    to_heights(s->band, out, (size_t)w * (size_t)h, &info);
    flip_south_up(s->ds, out, w, h);
    return true;
}

unsigned long long dem_stream_bytes(const dem_stream *s) { return s->bytes; }

void dem_stream_identity(const dem_stream *s, strbuf *key)
{
    char **files = GDALGetFileList(s->ds);
    for (char **f = files; f && *f; f++) {
        struct stat st;
        if (stat(*f, &st) == 0)
            sb_printf(key, "%s|%lld|%lld.%09ld;", *f, (long long)st.st_size, (long long)st.st_mtim.tv_sec,
                      st.st_mtim.tv_nsec);
        else
            sb_printf(key, "%s;", *f);
    }
    CSLDestroy(files);
    if (!files) /* no files behind it (a /vsimem/ or a driver's own): its path */
        sb_printf(key, "%s;", s->path);
}

void dem_stream_close(dem_stream *s)
{
    if (!s)
        return;
    if (s->ds)
        GDALClose(s->ds);
    free(s);
}

bool dem_probe(const char *path, int *w, int *h, double range[2], dem_info *info, err_t *err)
{
    *info = (dem_info){0};
    geo_gdal_init();
    GDALDatasetH ds = geo_open(path, GDAL_OF_RASTER, "read DEM", err);
    if (!ds)
        return false;
    *w = GDALGetRasterXSize(ds);
    *h = GDALGetRasterYSize(ds);
    GDALRasterBandH band = GDALGetRasterCount(ds) > 0 ? GDALGetRasterBand(ds, 1) : NULL;
    bool ok = band && georeference(ds, path, *h, info, err) && vertical_unit(ds, band, path, info, err);
    if (!band)
        err_set(err, "DEM '%s' has no raster band", path);
    double mm[2] = {0, 0};
    if (ok && GDALComputeRasterMinMax(band, TRUE, mm) != CE_None) /* approximate: overviews or a sample */
        ok = err_set(err, "DEM '%s': no heights to frame (%s)", path, geo_gdal_msg("every texel is nodata"));
    if (ok) {
        int has = 0;
        double scale = GDALGetRasterScale(band, &has), offset = GDALGetRasterOffset(band, NULL);
        if (!has || !isfinite(scale) || scale == 0)
            scale = 1;
        if (!isfinite(offset))
            offset = 0;
        range[0] = (fmin(mm[0] * scale, mm[1] * scale) + offset) * info->height_unit;
        range[1] = (fmax(mm[0] * scale, mm[1] * scale) + offset) * info->height_unit;
    }
    GDALClose(ds);
    return ok;
}

bool dem_fill_holes(float *heights, int w, int h, err_t *err)
{
    geo_gdal_init();
    GDALDriverH mem = GDALGetDriverByName("MEM");
    GDALDatasetH ds = mem ? GDALCreate(mem, "", w, h, 1, GDT_Float32, NULL) : NULL;
    if (!ds)
        return err_set(err, "filling nodata: cannot make a GDAL memory raster: %s", geo_gdal_msg("no MEM driver"));
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    bool ok = GDALRasterIO(band, GF_Write, 0, 0, w, h, heights, w, h, GDT_Float32, 0, 0) == CE_None &&
              GDALSetRasterNoDataValue(band, NAN) == CE_None &&
              /* search as far as the grid reaches: every hole gets a value */
              GDALFillNodata(band, NULL, (double)(w > h ? w : h), 0, 0, NULL, NULL, NULL) == CE_None &&
              GDALRasterIO(band, GF_Read, 0, 0, w, h, heights, w, h, GDT_Float32, 0, 0) == CE_None;
    if (!ok)
        err_set(err, "filling nodata failed: %s", geo_gdal_msg("GDALFillNodata"));
    GDALClose(ds);
    return ok;
}

struct dem_geo {
    double gt[6];
    int height;       /* rows: a south-up raster's rows count from the south */
    OGRCoordinateTransformationH to_wgs84;
};

dem_geo *dem_geo_open(const char *path)
{
    if (dem_is_image(path))
        return NULL;
    geo_gdal_init();
    err_t ignored;
    GDALDatasetH ds = geo_open(path, GDAL_OF_RASTER, "read DEM", &ignored);
    if (!ds)
        return NULL;
    double gt[6];
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
    dem_geo *g = NULL;
    if (srs && GDALGetGeoTransform(ds, gt) == CE_None && gt[2] == 0 && gt[4] == 0) {
        OGRSpatialReferenceH wgs84 = OSRNewSpatialReference(NULL);
        OSRSetWellKnownGeogCS(wgs84, "WGS84");
        OSRSetAxisMappingStrategy(wgs84, OAMS_TRADITIONAL_GIS_ORDER); /* x = longitude, y = latitude */
        OGRSpatialReferenceH from = OSRClone(srs);
        OSRSetAxisMappingStrategy(from, OAMS_TRADITIONAL_GIS_ORDER);
        OGRCoordinateTransformationH t = OCTNewCoordinateTransformation(from, wgs84);
        if (t) {
            g = util_calloc(1, sizeof *g, "a DEM's georeferencing");
            memcpy(g->gt, gt, sizeof gt);
            g->height = GDALGetRasterYSize(ds);
            g->to_wgs84 = t;
        }
        OSRDestroySpatialReference(from);
        OSRDestroySpatialReference(wgs84);
    }
    GDALClose(ds);
    return g;
}

bool dem_geo_lonlat(const dem_geo *g, double col, double row, double *lon, double *lat)
{
    if (!g)
        return false;
    double file_row = g->gt[5] > 0 ? g->height - row : row; /* fathom's row 0 is always north */
    double x = g->gt[0] + col * g->gt[1], y = g->gt[3] + file_row * g->gt[5], z = 0;
    if (!OCTTransform(g->to_wgs84, 1, &x, &y, &z))
        return false;
    *lon = x, *lat = y;
    return true;
}

void dem_geo_close(dem_geo *g)
{
    if (!g)
        return;
    OCTDestroyCoordinateTransformation(g->to_wgs84);
    free(g);
}

bool dem_write_hills(const char *path, int n, err_t *err)
{
    geo_gdal_init();
    char **opts = CSLSetNameValue(NULL, "TILED", "YES");
    opts = CSLSetNameValue(opts, "BIGTIFF", "IF_SAFER");
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path, n, n, 1, GDT_Int16, opts);
    CSLDestroy(opts);
    if (!ds)
        return err_set(err, "cannot write the benchmark DEM '%s': %s", path, CPLGetLastErrorMsg());
    double gt[6] = {500000, 30, 0, 5000000, 0, -30};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(NULL);
    OSRImportFromEPSG(srs, 32633);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
    enum { OCTAVES = 5 };
    int16_t *row = util_alloc(sizeof(int16_t) * (size_t)n, "a DEM row");
    double *col = util_alloc(sizeof(double) * OCTAVES * (size_t)n, "a DEM's columns");
    /* h = Σ a_o sin(f_o x + o) cos(0.8 f_o z − o/2): wavelengths 60 km down to 3.75 km; separable, so
     * the x factors are computed once */
    for (int o = 0; o < OCTAVES; o++)
        for (int i = 0; i < n; i++)
            col[(size_t)o * (size_t)n + (size_t)i] = 900.0 / (1 << o) * sin(2 * M_PI / (60000.0 / (1 << o)) * i * 30.0 + o);
    bool ok = true;
    for (int j = 0; ok && j < n; j++) {
        double zf[OCTAVES];
        for (int o = 0; o < OCTAVES; o++)
            zf[o] = cos(2 * M_PI / (60000.0 / (1 << o)) * 0.8 * j * 30.0 - 0.5 * o);
        for (int i = 0; i < n; i++) {
            double hgt = 1200;
            for (int o = 0; o < OCTAVES; o++)
                hgt += col[(size_t)o * (size_t)n + (size_t)i] * zf[o];
            row[i] = (int16_t)lround(fmax(hgt, 0));
        }
        ok = GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, j, n, 1, row, n, 1, GDT_Int16, 0, 0) == CE_None;
    }
    free(row);
    free(col);
    GDALClose(ds);
    return ok || err_set(err, "writing the benchmark DEM '%s' failed (disk full?)", path);
}
