/* dem's functions in the binary: each loads fathom_dem.so (dem.c and GDAL) on first use and calls its
 * own (data/lazy/lazy.h), so a run that opens no DEM never maps GDAL's libraries. */
#include "data/geo/dem.h"

#include "data/lazy/lazy.h"

bool dem_read(const char *path, int max_side, int *w, int *h, float **heights, dem_info *info, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, int, int *, int *, float **, dem_info *, err_t *),
            lazy_symbol(LAZY_DEM, "dem_read", err));
    return f && f(path, max_side, w, h, heights, info, err);
}

bool dem_read_window(const char *path, int x0, int y0, int *w, int *h, int max_side, float **heights, dem_info *info,
                     err_t *err)
{
    LAZY_FN(bool (*f)(const char *, int, int, int *, int *, int, float **, dem_info *, err_t *),
            lazy_symbol(LAZY_DEM, "dem_read_window", err));
    return f && f(path, x0, y0, w, h, max_side, heights, info, err);
}

bool dem_probe(const char *path, int *w, int *h, double range[2], dem_info *info, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, int *, int *, double *, dem_info *, err_t *),
            lazy_symbol(LAZY_DEM, "dem_probe", err));
    return f && f(path, w, h, range, info, err);
}

dem_geo *dem_geo_open(const char *path)
{
    if (dem_is_image(path)) /* a plain image has no georeferencing: no need for GDAL */
        return NULL;
    LAZY_FN(dem_geo * (*f)(const char *), lazy_symbol(LAZY_DEM, "dem_geo_open", NULL));
    return f ? f(path) : NULL;
}

bool dem_geo_lonlat(const dem_geo *g, double col, double row, double *lon, double *lat)
{
    if (!g)
        return false;
    LAZY_FN(bool (*f)(const dem_geo *, double, double, double *, double *),
            lazy_symbol(LAZY_DEM, "dem_geo_lonlat", NULL));
    return f && f(g, col, row, lon, lat);
}

void dem_geo_close(dem_geo *g)
{
    if (!g)
        return;
    LAZY_FN(void (*f)(dem_geo *), lazy_symbol(LAZY_DEM, "dem_geo_close", NULL));
    if (f)
        f(g);
}

bool dem_fill_holes(float *heights, int w, int h, err_t *err)
{
    LAZY_FN(bool (*f)(float *, int, int, err_t *), lazy_symbol(LAZY_DEM, "dem_fill_holes", err));
    return f && f(heights, w, h, err);
}

bool dem_write_hills(const char *path, int n, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, int, err_t *), lazy_symbol(LAZY_DEM, "dem_write_hills", err));
    return f && f(path, n, err);
}

dem_stream *dem_stream_open(const char *path, int *w, int *h, dem_info *info, err_t *err)
{
    LAZY_FN(dem_stream * (*f)(const char *, int *, int *, dem_info *, err_t *),
            lazy_symbol(LAZY_DEM, "dem_stream_open", err));
    return f ? f(path, w, h, info, err) : NULL;
}

bool dem_stream_read(dem_stream *s, int x0, int y0, int w, int h, float *out, err_t *err)
{
    LAZY_FN(bool (*f)(dem_stream *, int, int, int, int, float *, err_t *), lazy_symbol(LAZY_DEM, "dem_stream_read", err));
    return f && f(s, x0, y0, w, h, out, err);
}

unsigned long long dem_stream_bytes(const dem_stream *s)
{
    LAZY_FN(unsigned long long (*f)(const dem_stream *), lazy_symbol(LAZY_DEM, "dem_stream_bytes", NULL));
    return f ? f(s) : 0;
}

void dem_stream_identity(const dem_stream *s, strbuf *key)
{
    LAZY_FN(void (*f)(const dem_stream *, strbuf *), lazy_symbol(LAZY_DEM, "dem_stream_identity", NULL));
    if (f)
        f(s, key);
}

void dem_stream_close(dem_stream *s)
{
    if (!s)
        return;
    LAZY_FN(void (*f)(dem_stream *), lazy_symbol(LAZY_DEM, "dem_stream_close", NULL));
    if (f)
        f(s);
}
