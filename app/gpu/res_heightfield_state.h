/* res_heightfield_state — what res_heightfield.c (the resource: its set, in-core load and streamed open) and
 * res_heightfield_stream.c (the streamed terrain's feedback and loads) share. Internal to the two. */
#ifndef FATHOM_RES_HEIGHTFIELD_STATE_H
#define FATHOM_RES_HEIGHTFIELD_STATE_H

#include <epoxy/gl.h>

#include "data/geo/terrain.h"
#include "data/geo/terrain_loader.h"
#include "data/geo/terrain_tiles.h"
#include "gpu/res_heightfield.h"

typedef struct res_heightfield_state {
    GLuint height_tex, max_tex, top_tex, pages_tex, feedback_buf;
    GLuint water_tex; /* terrain.water as lakes or a raster: each texel's water level (data/geo/water.h) */
    terrain_grid grid;
    int slots, tiles, words; /* texture layers; tiles; feedback words a bit set */
    int *slot_tile, *tile_slot;
    unsigned *slot_used; /* the settle pass that last used the slot: the oldest unused one is evicted */
    unsigned pass;
    bool streamed;
    struct dem_stream *stream;
    terrain_loader *loader; /* the window's (res_heightfield_settle_async), started when first asked */
    char path[PATH_MAX_LEN];
    float ex;
    float *tile_buf, *level_buf;
    res_heightfield_stats stats;
    char key[3 * PATH_MAX_LEN + 192]; /* the DEM, its sidecar and a water raster */
    heightfield hf; /* the grid's description; its heights and pyramid live on the GPU */
} res_heightfield_state;

extern res_heightfield_state res_heightfield_now;

/* Tile `tile`'s heights (its window, w × h) and levels into `slot`, and the page table (the tile the slot
 * held, if any, is marked absent). */
void res_heightfield_upload(int tile, const float *heights, const float *levels, int w, int h, int slot);

#endif
