/* terrain — a heightfield under fathom's geometry contract. Pure C (image reading through image_io).
 *
 * Contract: samples sit at texel centres of a regular grid, `spacing` metres apart in x and z, centred
 * on the world origin; row 0 is the northern edge (−Z), column 0 the western (−X). Texel (i, j) is at
 * x = x0 + (i + ½)·dx, z = z0 + (j + ½)·dz with x0 = −W·dx/2, z0 = −H·dz/2. Between the four nearest
 * centres the surface is bilinear; it exists only between the outermost centres. The terrain is the
 * solid column under that surface: a ray that reaches the footprint's side below the surface hits
 * the side (a ray starting inside hits at once); rays that leave the footprint above it miss.
 * Heights are metres × exaggeration, Y up. An 8/16-bit image maps 0…max to height_min…height_max;
 * a float image holds metres.
 *
 * The max pyramid (Tevs, Ihrke, Seidel 2008, "Maximum Mipmaps for Fast, Accurate, and Scalable Dynamic
 * Height Field Rendering"): level 0 holds, per cell between four centres, the highest of its corners
 * (a bilinear patch never rises above them); level k the maximum of 2×2 nodes of level k−1. Sizes are
 * padded to powers of two (padding = −inf, never hit) so GL's mip sizes line up with the nodes.
 * Cells with a nodata corner have no surface (−inf). On the GPU (render_scene.c) a DEM larger than
 * one texture is cut into tiles: heights and pyramid levels 1…log2(tile) in texture arrays, one layer
 * per tile, and the levels above in one small texture.
 */
#ifndef FATHOM_TERRAIN_H
#define FATHOM_TERRAIN_H

#include <stdbool.h>

#include "util.h"

typedef struct heightfield {
    int width, height; /* texels */
    float *h;          /* metres, row-major, row 0 north */
    float dx, dz;      /* metres per texel */
    float x0, z0;      /* world x, z of the grid's corner (the north-west edge of texel 0) */
    float hmin, hmax;
    float lipschitz; /* max |∇h| of the bilinear surface: (y − h) / sqrt(1 + L²) bounds the distance */
    int levels, pw, ph; /* pyramid: levels, padded level-0 size (cells) */
    float **max;        /* max[k]: (pw >> k) × (ph >> k), each side at least 1; max[0] is NULL (level 0
                           is heightfield_cell_max, never stored), all NULL after heightfield_drop_pyramid */
    size_t holes;       /* nodata texels (TERRAIN_HOLE in h) */
    char about[320];    /* what was read: size, type, CRS, spacing, holes (the log line) */
} heightfield;

/* A nodata texel's height: the four cells around it have no surface (rays pass through the hole),
 * and the clearance above it is huge. Below any real height and far from float's limits. */
#define TERRAIN_HOLE (-1e30f)
#define TERRAIN_IS_HOLE(h) ((h) < -1e20f) /* also a height interpolated with any weight on a hole */

typedef struct heightfield_desc {
    const char *path;
    float spacing[2]; /* dx, dz; 0: from the sidecar NAME.json */
    float height_min, height_max; /* integer images; both 0: from the sidecar */
    float exaggeration;
    bool fill_nodata; /* fill holes from their surroundings (GDALFillNodata) instead of leaving them */
} heightfield_desc;

/* The longest side of a heightmap: beyond one GL texture (render_scene.c tiles it), bounded so a
 * typo in a header cannot ask for terabytes. */
#define TERRAIN_MAX_SIDE 65536

/* Spacing in metres per texel: above 0, finite, at most this (a light year of texels is a typo). */
#define TERRAIN_SPACING_MAX 1e6
#define TERRAIN_SPACING_MIN 1e-3 /* a millimetre: below it a DEM's georeferencing is wrong */
#define TERRAIN_HEIGHT_MAX 1e7   /* metres either way; beyond, a band's scale or offset is wrong (and floats overflow) */
bool terrain_spacing_ok(double metres);

/* Plain images (PNG, JPEG: 0…max → height_min…height_max; EXR, HDR, PFM: metres) through image_io;
 * every other raster (GeoTIFF, .hgt, ASCII grid, netCDF, VRT, ...) through GDAL (app/data/geo/dem.h), which
 * gives metres and, when the file is georeferenced, the spacing. Nodata and NaN texels become holes.
 * Refuses what cannot be drawn: a missing or non-finite spacing or height range, a reversed range, a
 * height range on a GDAL DEM (its values are metres already), a DEM without one real height. */
bool heightfield_load(const heightfield_desc *d, heightfield *hf, err_t *err);
/* A GDAL DEM for reading in windows (gpu/res_heightfield.c streams one larger than its cache): *hf gets the
 * grid, spacing, origin and the about line heightfield_load would give, without one height read (hmin,
 * hmax, lipschitz and holes are the caller's, from the tiles: then heightfield_stream_check). */
struct dem_stream;
bool heightfield_open_stream(const heightfield_desc *d, heightfield *hf, struct dem_stream **stream, err_t *err);
/* heightfield_load's refusals of what the heights hold (no real height; heights beyond the limit). */
bool heightfield_stream_check(const heightfield_desc *d, const heightfield *hf, err_t *err);
/* From heights already in memory (tests): w × h metres, row 0 north; NaN marks a hole. */
void heightfield_from(const float *heights, int w, int h, float dx, float dz, heightfield *hf);
void heightfield_free(heightfield *hf);
/* The highest corner of cell (i, j) (the pyramid's level 0); −inf for padding and cells touching a hole. */
float heightfield_cell_max(const heightfield *hf, int i, int j);
/* Frames a camera without loading the heights: the footprint in metres (x, z), the height range after
 * exaggeration (GDAL's approximate one for DEMs) and the spacing. */
bool heightfield_probe(const heightfield_desc *d, double size[2], double range[2], double spacing[2], err_t *err);
/* Frees the max pyramid once it is on the GPU. */
void heightfield_drop_pyramid(heightfield *hf);

/* The sidecar of a heightmap: NAME.json beside NAME.EXT (spacing and height range of an image). */
void terrain_sidecar_path(const char *path, char *out, size_t n);

#endif
