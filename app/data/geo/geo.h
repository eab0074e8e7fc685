/* geo — a DEM's place on the Earth, for GIS work: points in and out of its grid, rasters written on its
 * grid (the viewshed), imagery warped onto it (the drape), and GPS tracks read and written. All through
 * GDAL and OGR (in fathom_dem.so with dem.c: data/lazy/lazy.h); files from others are data only: a track's
 * names and times are parsed, never run.
 *
 * Texel coordinates here are fathom's: row 0 is the northern edge, and texel (i, j)'s centre is at
 * (i, j) — whole numbers at texel centres, as viewshed.h and the terrain's cell space count them. */
#ifndef FATHOM_GEO_H
#define FATHOM_GEO_H

#include <stdbool.h>
#include <stddef.h>

#include "util.h"

/* n points' longitudes and latitudes (WGS 84, degrees) to texel coordinates of the DEM at dem_path
 * (to_texel), or texel coordinates to longitudes and latitudes (!to_texel): x and y in, u and v out.
 * Fails with a message for a DEM without georeferencing or a point GDAL cannot transform. */
bool geo_convert(const char *dem_path, bool to_texel, int n, const double *x, const double *y, double *u, double *v,
                 err_t *err);

/* Writes v (w × h bytes, row 0 north: the DEM's own grid, or its window from texel x0, y0) as a GeoTIFF in the
 * DEM's CRS and geotransform (north-up), nodata 255, with a colour table (0 hidden: dark, 1 visible: green, 255
 * transparent) and `description` as its band's description; whole or not at all. */
bool geo_write_mask(const char *dem_path, const char *out_path, int x0, int y0, int w, int h, const unsigned char *v,
                    const char *description, err_t *err);

/* Writes `bands` Float32 rasters (w × h each, row 0 north, the DEM's whole grid) as one GeoTIFF in the DEM's CRS and
 * geotransform, nodata NaN, unit metres, each band described; whole or not at all. */
bool geo_write_floats(const char *dem_path, const char *out_path, int w, int h, int bands, const float *const *v,
                      const char *const *descriptions, err_t *err);

/* True north on the DEM's grid at a place (WGS 84 degrees): *gamma, degrees clockwise from the grid's north (the
 * −Z of a terrain's world) to the meridian's; 0 on a geographic DEM. A true azimuth A is A + *gamma on the grid
 * (on EPSG:3413 at 0° E: −45°; in UTM, −atan(tan(λ − λ0) sin φ)). */
bool geo_true_north(const char *dem_path, double lon, double lat, double *gamma, err_t *err);

/* Warps any raster GDAL reads (an orthophoto, a hillshade, a land-cover map; grey, RGB, RGBA, a
 * palette, 8 or 16 bits or float) onto the DEM's extent in its CRS: *rgba (malloc'd, *w × *h, row 0
 * north, sRGB bytes; alpha 0 where the imagery has no data or does not reach). The resolution is the
 * imagery's own over that extent, the longest side at most max_side (GDAL reads overviews for a
 * smaller one), unless *w and *h come in above 0: then that size. */
bool geo_drape(const char *dem_path, const char *imagery, int max_side, unsigned char **rgba, int *w, int *h,
               err_t *err);

/* Vector data (GPX, KML, GeoJSON, GeoPackage, Shapefile: every layer) drawn onto the DEM's extent at
 * w × h (row 0 north): lines and polygon outlines `width` metres wide (0: a DEM texel), points as discs
 * twice that across, in rgba (0–1; alpha 0 elsewhere), reprojected to the DEM's CRS (a geographic DEM
 * takes the width in degrees of latitude). */
bool geo_vectors(const char *dem_path, const char *vectors, double width, const float rgba[4], int w, int h,
                 unsigned char *out, err_t *err);
/* A river: its course in texel coordinates of the DEM (column, row; texel centres at whole numbers), its width
 * and depth in metres. */
typedef struct geo_river {
    double (*pt)[2];
    int n;
    double width, depth;
} geo_river;
/* Water as vectors (GeoJSON, GeoPackage, Shapefile, KML: every layer), reprojected to the DEM's CRS:
 *  - lakes and reservoirs as polygons, each with its water level in metres in a field named "level": each
 *    texel of the DEM's grid (w × h, row 0 north) whose centre a polygon holds gets its level in out, NaN
 *    elsewhere (the last polygon wins where they overlap);
 *  - rivers as lines, their width and depth in metres in fields "width" and "depth" (or 3 texels and 1 m):
 *    into *rivers (n_rivers; free with geo_rivers_free), for water_rivers to follow the ground.
 * A point, a polygon without a numeric level, or nothing at all: one clear error. */
bool geo_water_vectors(const char *dem_path, const char *vectors, int w, int h, float *out, geo_river **rivers,
                       int *n_rivers, err_t *err);
void geo_rivers_free(geo_river *r, int n);
/* The size every draped layer is composited at: the first imagery's own resolution over the DEM (NULL: none),
 * or finer where a vector layer of one of the widths needs two texels across its lines; the longest side at
 * most max_side. A vector layer never coarsens the imagery under it. */
bool geo_layers_size(const char *dem_path, const char *imagery, const float *widths, int n_widths, int max_side,
                     int *w, int *h, err_t *err);

/* A point of a GPS track: WGS 84 degrees, metres above the ellipsoid's datum (NaN if none), seconds
 * since the Unix epoch (NaN if none). */
typedef struct geo_point {
    double lon, lat, ele, time;
} geo_point;

/* The first track in a vector file GDAL reads (GPX: its track points; KML, GeoJSON, GeoPackage,
 * Shapefile: the first layer's lines, or its points in order), reprojected to WGS 84. At most
 * GEO_TRACK_MAX points. */
#define GEO_TRACK_MAX 1000000
bool geo_track_read(const char *path, geo_point **pts, int *n, err_t *err);

/* Writes a track as GPX (.gpx: one trk with ele and time) or KML (.kml: a LineString placemark,
 * absolute altitudes, and a gx:Tour that flies the camera along it: cameras[i] = heading, tilt and
 * roll in degrees for point i, or NULL for a track only); whole or not at all. */
bool geo_track_write(const char *path, const char *name, const geo_point *pts, const double (*cameras)[3], int n,
                     err_t *err);

/* GDAL's own viewshed (GDALViewshedGenerate, gdal_viewshed's algorithm, edge mode) from texel (col, row)
 * of a north-up DEM, for the bench to compare with the exact one: out as viewshed.h's values;
 * curvature is GDAL's coefficient (1 − k: 0.87 for refraction 0.13; 0 for a flat Earth). */
bool geo_gdal_viewshed(const char *dem_path, int col, int row, double observer_height, double target_height,
                       double curvature, unsigned char *out, err_t *err);

/* The module's writers behind the two above (geo_lazy.c makes them atomic): into `path` as given. */
bool geo_write_mask_file(const char *dem_path, const char *path, int x0, int y0, int w, int h,
                         const unsigned char *v, const char *description, err_t *err);
bool geo_write_floats_file(const char *dem_path, const char *path, int w, int h, int bands, const float *const *v,
                           const char *const *descriptions, err_t *err);
bool geo_track_write_file(const char *path, bool kml, const char *name, const geo_point *pts,
                          const double (*cameras)[3], int n, err_t *err);

#endif
