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
    float **max;        /* max[k]: (pw >> k) × (ph >> k) */
} heightfield;

typedef struct heightfield_desc {
    const char *path;
    float spacing[2]; /* dx, dz; 0: from the sidecar NAME.json */
    float height_min, height_max; /* integer images; both 0: from the sidecar */
    float exaggeration;
} heightfield_desc;

/* Spacing in metres per texel: above 0, finite, at most this (a light year of texels is a typo). */
#define TERRAIN_SPACING_MAX 1e6
bool terrain_spacing_ok(double metres);

/* Refuses what cannot be drawn: a missing or non-finite spacing or height range, a reversed range, and
 * heights that are NaN or infinite (the error counts them and names the first texel). */
bool heightfield_load(const heightfield_desc *d, heightfield *hf, err_t *err);
/* From heights already in memory (tests): w × h metres, row 0 north. */
void heightfield_from(const float *heights, int w, int h, float dx, float dz, heightfield *hf);
void heightfield_free(heightfield *hf);

/* Bilinear height at world (x, z), clamped to the footprint. */
float heightfield_at(const heightfield *hf, float x, float z);

#endif
