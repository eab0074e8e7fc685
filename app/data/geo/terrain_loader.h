/* terrain_loader — a thread that reads the tiles of a streamed DEM (terrain_stream.h) in the background, so
 * the window keeps drawing while they come: the frame asks for the tiles its pixels wanted, the thread
 * reads each (its own GDAL handle) and builds its pyramid levels, and the frame takes what is ready and
 * uploads it. At most `queue` tiles wait to be read and as many wait to be taken: its memory is bounded
 * (a tile of 512 cells is 1.4 MB). */
#ifndef FATHOM_TERRAIN_LOADER_H
#define FATHOM_TERRAIN_LOADER_H

#include <stdbool.h>

#include "data/geo/terrain_tiles.h"
#include "util.h"

typedef struct terrain_loader terrain_loader;

/* Starts the thread on `path` cut as g says, heights times ex, dx × dz metres a texel. */
terrain_loader *terrain_loader_start(const char *path, const terrain_grid *g, float ex, float dx, float dz, int queue,
                                     err_t *err);
/* Asks for tile `tile` (tiles_x · ty + tx); nothing when it was asked already or the queue is full. */
void terrain_loader_ask(terrain_loader *l, int tile);

typedef struct terrain_loaded {
    int tile, w, h;   /* its window's size */
    float *heights;   /* w × h, as terrain_read_tile gives them */
    float *levels;    /* terrain_tile_build's levels */
    unsigned long long bytes; /* read from the DEM for it */
} terrain_loaded;
/* A tile read and ready (true), to be given back with terrain_loader_done once uploaded; false when none
 * is ready. A read that failed stops the loader (terrain_loader_failed). */
bool terrain_loader_take(terrain_loader *l, terrain_loaded *out);
void terrain_loader_done(terrain_loader *l, terrain_loaded *t);
/* Whether a read failed (*err: why). */
bool terrain_loader_failed(terrain_loader *l, err_t *err);
/* Stops the thread (a read under way finishes first) and frees everything. */
void terrain_loader_stop(terrain_loader *l);

#endif
