/* terrain_stream — a DEM larger than memory as tiles read from disk (terrain_tiles.h): one tile's heights
 * as the GPU holds them, and the summary of all of them (every tile's maximum for the top pyramid, the
 * height range, the steepest slope, the holes), built once by reading the DEM in parallel and kept in the
 * user's cache folder ($XDG_CACHE_HOME/fathom/terrain, else ~/.cache/fathom/terrain) under the identity
 * of every file GDAL reads for it (a VRT's sources too): a changed source makes a new one. */
#ifndef FATHOM_TERRAIN_STREAM_H
#define FATHOM_TERRAIN_STREAM_H

#include <stdbool.h>
#include <stddef.h>

#include "data/geo/terrain_tiles.h"
#include "util.h"

struct dem_stream;

/* Tile (tx, ty)'s heights as the GPU holds them (terrain_tile_window's w × h): metres × ex, holes
 * TERRAIN_HOLE; the values heightfield_load gives the same texels. */
bool terrain_read_tile(struct dem_stream *s, const terrain_grid *g, int tx, int ty, float ex, float *out, err_t *err);

typedef struct terrain_summary {
    float hmin, hmax, lipschitz;
    size_t holes;
    float *tile_max;          /* tiles_x × tiles_y */
    bool cached;              /* read from the cache folder, not built */
    double seconds;           /* building or reading it */
    unsigned long long bytes; /* read from the DEM to build it */
} terrain_summary;

/* The summary of `path` (a DEM through GDAL) cut as g says, its heights times ex, dx × dz metres a texel:
 * from the cache folder, else built from the DEM with one reader a core and kept there (a cache folder
 * that cannot be written is noted once and skipped). FATHOM_TERRAIN_THREADS limits the readers. */
bool terrain_summary_get(const char *path, const terrain_grid *g, float dx, float dz, float ex, terrain_summary *out,
                         err_t *err);
void terrain_summary_free(terrain_summary *s);

#endif
