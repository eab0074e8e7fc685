/* geo's functions in the binary: each loads fathom_dem.so (geo.c and GDAL) on first use (data/lazy/lazy.h);
 * the writers write into a temporary file beside the output and rename it over (util_atomic), so
 * an output is whole or absent. */
#include "data/geo/geo.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "data/lazy/lazy.h"

bool geo_convert(const char *dem_path, bool to_texel, int n, const double *x, const double *y, double *u, double *v,
                 err_t *err)
{
    LAZY_FN(bool (*f)(const char *, bool, int, const double *, const double *, double *, double *, err_t *),
            lazy_symbol(LAZY_DEM, "geo_convert", err));
    return f && f(dem_path, to_texel, n, x, y, u, v, err);
}

bool geo_drape(const char *dem_path, const char *imagery, int max_side, unsigned char **rgba, int *w, int *h,
               err_t *err)
{
    LAZY_FN(bool (*f)(const char *, const char *, int, unsigned char **, int *, int *, err_t *),
            lazy_symbol(LAZY_DEM, "geo_drape", err));
    return f && f(dem_path, imagery, max_side, rgba, w, h, err);
}

bool geo_vectors(const char *dem_path, const char *vectors, double width, const float rgba[4], int w, int h,
                 unsigned char *out, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, const char *, double, const float *, int, int, unsigned char *, err_t *),
            lazy_symbol(LAZY_DEM, "geo_vectors", err));
    return f && f(dem_path, vectors, width, rgba, w, h, out, err);
}

bool geo_water_vectors(const char *dem_path, const char *vectors, int w, int h, float *out, geo_river **rivers,
                       int *n_rivers, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, const char *, int, int, float *, geo_river **, int *, err_t *),
            lazy_symbol(LAZY_DEM, "geo_water_vectors", err));
    *rivers = NULL, *n_rivers = 0;
    return f && f(dem_path, vectors, w, h, out, rivers, n_rivers, err);
}

void geo_rivers_free(geo_river *r, int n)
{
    for (int i = 0; i < n; i++)
        free(r[i].pt);
    free(r);
}

bool geo_layers_size(const char *dem_path, const char *imagery, const float *widths, int n_widths, int max_side,
                     int *w, int *h, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, const char *, const float *, int, int, int *, int *, err_t *),
            lazy_symbol(LAZY_DEM, "geo_layers_size", err));
    return f && f(dem_path, imagery, widths, n_widths, max_side, w, h, err);
}

bool geo_true_north(const char *dem_path, double lon, double lat, double *gamma, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, double, double, double *, err_t *), lazy_symbol(LAZY_DEM, "geo_true_north", err));
    *gamma = 0;
    return f && f(dem_path, lon, lat, gamma, err);
}

bool geo_track_read(const char *path, geo_point **pts, int *n, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, geo_point **, int *, err_t *), lazy_symbol(LAZY_DEM, "geo_track_read", err));
    return f && f(path, pts, n, err);
}

bool geo_gdal_viewshed(const char *dem_path, int col, int row, double observer_height, double target_height,
                       double curvature, unsigned char *out, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, int, int, double, double, double, unsigned char *, err_t *),
            lazy_symbol(LAZY_DEM, "geo_gdal_viewshed", err));
    return f && f(dem_path, col, row, observer_height, target_height, curvature, out, err);
}

bool geo_write_mask(const char *dem_path, const char *out_path, int x0, int y0, int w, int h, const unsigned char *v,
                    const char *description, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, const char *, int, int, int, int, const unsigned char *, const char *, err_t *),
            lazy_symbol(LAZY_DEM, "geo_write_mask_file", err));
    util_atomic a;
    if (!f || !util_atomic_open(&a, out_path, err))
        return false;
    if (!f(dem_path, a.tmp, x0, y0, w, h, v, description, err)) {
        util_atomic_abort(&a);
        return false;
    }
    return util_atomic_commit(&a, err);
}

bool geo_write_floats(const char *dem_path, const char *out_path, int w, int h, int bands, const float *const *v,
                      const char *const *descriptions, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, const char *, int, int, int, const float *const *, const char *const *, err_t *),
            lazy_symbol(LAZY_DEM, "geo_write_floats_file", err));
    util_atomic a;
    if (!f || !util_atomic_open(&a, out_path, err))
        return false;
    if (!f(dem_path, a.tmp, w, h, bands, v, descriptions, err)) {
        util_atomic_abort(&a);
        return false;
    }
    return util_atomic_commit(&a, err);
}

bool geo_track_write(const char *path, const char *name, const geo_point *pts, const double (*cameras)[3], int n,
                     err_t *err)
{
    LAZY_FN(bool (*f)(const char *, bool, const char *, const geo_point *, const double (*)[3], int, err_t *),
            lazy_symbol(LAZY_DEM, "geo_track_write_file", err));
    const char *dot = strrchr(path, '.');
    bool kml = dot && !strcasecmp(dot, ".kml"), gpx = dot && !strcasecmp(dot, ".gpx");
    if (!kml && !gpx)
        return err_set(err, "bad track file '%s': the name must end in .gpx or .kml", path);
    util_atomic a;
    if (!f || !util_atomic_open(&a, path, err))
        return false;
    if (!f(a.tmp, kml, name, pts, cameras, n, err)) {
        util_atomic_abort(&a);
        return false;
    }
    return util_atomic_commit(&a, err);
}
