/* geo_internal — what geo.c and geo_vector.c share inside fathom_dem.so: GDAL's set-up, its last
 * message, a DEM's grid and WGS 84. Not for the binary (it holds GDAL types). */
#ifndef FATHOM_GEO_INTERNAL_H
#define FATHOM_GEO_INTERNAL_H

#include <gdal.h>
#include <ogr_srs_api.h>
#include <stdbool.h>

#include "util.h"

/* Registers GDAL's drivers once (the network off), quiets its error printing and resets its error. */
void geo_gdal_init(void);
/* GDAL's last message, or the fallback. */
const char *geo_gdal_msg(const char *fallback);

/* Every GDAL/OGR open of a file the user named, through gdal_trust's policy (data/geo/gdal_trust.h): kind is
 * GDAL_OF_RASTER or GDAL_OF_VECTOR, what is the message's verb and noun ("open the DEM"); NULL with a message. */
GDALDatasetH geo_open(const char *path, unsigned kind, const char *what, err_t *err);

/* A DEM's grid: size, north-up geotransform (pixel corners), CRS (a clone: the caller destroys it). */
typedef struct geo_grid {
    int w, h;
    double gt[6];
    OGRSpatialReferenceH srs;
} geo_grid;

/* The DEM's grid, or false with a message for one without georeferencing. */
bool geo_grid_of(const char *dem_path, geo_grid *g, err_t *err);
/* WGS 84 with x = longitude, y = latitude (the caller destroys it). */
OGRSpatialReferenceH geo_wgs84(void);
/* The drape's size that keeps two texels across a `width`-metre line (geo_vector.c). */
void geo_vector_size(const char *dem_path, double width, int max_side, int *w, int *h);

#endif
