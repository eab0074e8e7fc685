/* terrain_tiles — a heightfield cut into tiles that can live apart: each tile holds its cells' heights
 * and its own levels of the max pyramid (app/data/geo/terrain.h), and one small pyramid over the tiles'
 * maxima holds the levels above. The GPU keeps any subset of the tiles (gpu/res_heightfield.c: all of a
 * DEM that fits its cache, else the ones the view asked for); the pyramid's values are the same as the
 * whole grid's (heightfield_load's), so a ray walks the same nodes whichever tiles are resident.
 *
 * A tile covers 2^shift_x × 2^shift_y cells and holds their corners: (cells + 1) texels a side, so it
 * shares its last column and row with its neighbours (a cell never needs a second tile), clipped to the
 * grid. Tile (tx, ty) starts at texel (tx << shift_x, ty << shift_y). Pure C. */
#ifndef FATHOM_TERRAIN_TILES_H
#define FATHOM_TERRAIN_TILES_H

#include <stdbool.h>
#include <stddef.h>

typedef struct terrain_grid {
    int width, height;     /* texels */
    int pw, ph, levels;    /* the whole pyramid: padded cells (powers of two) and its levels (terrain.h) */
    int shift_x, shift_y;  /* log2 of a tile's cells */
    int tiles_x, tiles_y;
    int tile_level;        /* the level whose nodes are whole tiles: levels 1 … tile_level − 1 live in the tiles,
                              tile_level … levels − 1 in the top pyramid */
    int slot_w, slot_h;    /* texels a tile holds at most */
} terrain_grid;

/* Tiles of tile_cells cells a side (a power of two, at least 4); 0: one tile for the whole grid. */
void terrain_grid_plan(int width, int height, int tile_cells, terrain_grid *g);

/* The texels tile (tx, ty) holds: [x0, x0 + w) × [y0, y0 + h). */
void terrain_tile_window(const terrain_grid *g, int tx, int ty, int *x0, int *y0, int *w, int *h);

/* Nodes of level k (1 … tile_level − 1) in one tile, each side at least 1; and the floats all of a
 * tile's levels take (terrain_tile_levels' output). */
void terrain_tile_level_size(const terrain_grid *g, int k, int *nx, int *ny);
size_t terrain_tile_level_floats(const terrain_grid *g);

/* What a tile's heights say about the whole (every texel counted in one tile only). */
typedef struct terrain_tile_stats {
    float max;       /* its highest cell (the top pyramid's node at tile_level); −inf without a surface */
    float hmin, hmax; /* its real heights (+inf, −inf with none) */
    float lipschitz; /* its steepest cell's gradient bound (terrain.h) */
    size_t holes;    /* its nodata texels */
} terrain_tile_stats;

/* From tile (tx, ty)'s heights (its window, row-major; holes TERRAIN_HOLE): its levels 1 … tile_level − 1
 * packed one after another into `levels` (NULL: not wanted), and its stats (dx, dz: metres per texel). */
void terrain_tile_build(const terrain_grid *g, int tx, int ty, const float *heights, float dx, float dz, float *levels,
                        terrain_tile_stats *stats);

/* The top pyramid from every tile's maximum (tiles_x × tiles_y): levels tile_level … levels − 1, each
 * (pw >> k) × (ph >> k) at least 1, nodes beyond the tiles −inf. top[k − tile_level], malloc'd. */
float **terrain_top_build(const terrain_grid *g, const float *tile_max);
void terrain_top_size(const terrain_grid *g, int k, int *nx, int *ny);
void terrain_top_free(const terrain_grid *g, float **top);

#endif
