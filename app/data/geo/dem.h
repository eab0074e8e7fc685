/* dem — elevation rasters through GDAL (GeoTIFF, SRTM .hgt, ESRI/AAIGrid ASCII, netCDF, VRT, and
 * every other raster format GDAL reads). Band 1 is taken; its scale and offset are applied, so the
 * heights are the file's own units (metres for every common DEM); nodata texels become NaN.
 *
 * Georeferencing sets the spacing: a projected CRS gives the geotransform's pixel size times the
 * CRS's linear unit; a geographic CRS gives degrees, turned into metres at the DEM's central latitude
 * on a sphere of radius 6,371 km (the IUGG mean Earth radius; the WGS84 ellipsoid differs by < 0.5 %
 * in x and < 1 % in z). Rows that run south to north (a positive y pixel size) are flipped, so row 0
 * is always north. A rotated geotransform is refused: fathom's grid is axis-aligned. */
#ifndef FATHOM_DEM_H
#define FATHOM_DEM_H

#include <stdbool.h>
#include <stddef.h>

#include "util.h"

typedef struct dem_info {
    bool georeferenced;  /* a geotransform and a CRS: spacing holds metres */
    bool geographic;     /* degrees (the spacing is for the central latitude) */
    double spacing[2];   /* metres per texel, x and z (0 without georeferencing) */
    double latitude;     /* geographic: the central latitude the spacing holds at */
    double pixel[2];     /* a geotransform without a CRS: its pixel size, unit unknown (else 0) */
    char crs[96];        /* the CRS's name, e.g. "WGS 84" or "WGS 84 / UTM zone 33N" */
    char type[16];       /* GDAL's name of the band's data type: Int16, Float32, ... */
    bool is_float;       /* Float32/Float64: real values; otherwise integers (still metres) */
    size_t holes;        /* nodata (and NaN) texels */
    double height_unit;  /* metres per unit of the file's heights (the band's unit or the vertical CRS's) */
    char height_unit_name[32]; /* that unit as the file names it ("metre" when it names none) */
} dem_info;

/* Memory a DEM takes per texel while it is read whole (docs/terrain-scale: 9.3 at its peak at 16384²,
 * rounded up): dem_read refuses one that needs more than the machine's memory before reading it (the viewshed
 * and the mesh's DEM solid read so); a terrain larger than its cache streams instead (gpu/res_heightfield.c). */
#define DEM_BYTES_PER_TEXEL 12.0

/* True for a path fathom reads as a plain image (OpenImageIO: PNG, JPEG, EXR, HDR, PFM), whose values
 * are normalised colours; everything else goes to GDAL. */
bool dem_is_image(const char *path);

/* Reads band 1 of `path`: *heights (malloc'd, w × h, row 0 north) in metres, with scale, offset and the
 * band's vertical unit applied (feet converted; an unknown unit refused), nodata and NaN as NaN. Sides above max_side are refused with the size. */
bool dem_read(const char *path, int max_side, int *w, int *h, float **heights, dem_info *info, err_t *err);
/* Only the texels [x0, x0 + *w) × [y0, y0 + *h) (row 0 north, whatever the file's order), read from disk
 * alone: a part of a DEM larger than memory. *w or *h 0: the whole DEM (then they come back its size). */
bool dem_read_window(const char *path, int x0, int y0, int *w, int *h, int max_side, float **heights, dem_info *info,
                     err_t *err);

/* A DEM read a window at a time, whatever its size (a terrain larger than memory: gpu/res_heightfield.c):
 * the file stays open; each read gives what dem_read_window would (metres, NaN holes, row 0 north). Not
 * shared between threads: each opens its own. Sides up to DEM_STREAM_MAX_SIDE. */
#define DEM_STREAM_MAX_SIDE (1 << 22)
typedef struct dem_stream dem_stream;
dem_stream *dem_stream_open(const char *path, int *w, int *h, dem_info *info, err_t *err);
bool dem_stream_read(dem_stream *s, int x0, int y0, int w, int h, float *out, err_t *err);
/* The bytes of the file's values read so far (what the windows asked for, in the band's type). */
unsigned long long dem_stream_bytes(const dem_stream *s);
/* Appends "file|bytes|mtime;" for every file GDAL reads for it (a VRT's sources too): what a cache of
 * facts about the DEM is keyed by. */
void dem_stream_identity(const dem_stream *s, strbuf *key);
void dem_stream_close(dem_stream *s);

/* What framing a camera needs, without reading every texel: size, georeferencing and the height range
 * (GDAL's approximate minimum and maximum, scale and offset applied). */
bool dem_probe(const char *path, int *w, int *h, double range[2], dem_info *info, err_t *err);

/* A DEM's georeferencing, to say where a point of it is on the Earth: fathom's texel coordinates
 * (column, row from the north-west corner, continuous) to longitude and latitude (WGS 84). NULL from
 * dem_geo_open when the file has no geotransform and CRS (or is a plain image). */
typedef struct dem_geo dem_geo;
dem_geo *dem_geo_open(const char *path);
bool dem_geo_lonlat(const dem_geo *g, double col, double row, double *lon, double *lat);
void dem_geo_close(dem_geo *g);

/* Fills NaN texels by GDAL's inverse-distance interpolation from the nearest valid ones
 * (GDALFillNodata); false with a message if it cannot. */
bool dem_fill_holes(float *heights, int w, int h, err_t *err);

/* Writes an n × n Int16 GeoTIFF in metres (SRTM-like: 30 m texels in UTM 33N, rolling hills of
 * wavelengths 60 km down to 3.75 km): bench --terrain-scale's DEMs. */
bool dem_write_hills(const char *path, int n, err_t *err);

#endif
