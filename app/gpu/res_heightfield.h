/* res_heightfield — the terrain's heights and pyramid on the GPU (a render_resource kind): in core, or
 * streamed from disk in tiles when the DEM is larger than terrain.cache_mb (res_heightfield.c). */
#ifndef FATHOM_RES_HEIGHTFIELD_H
#define FATHOM_RES_HEIGHTFIELD_H

#include "data/geo/terrain.h"
#include "gpu/render_resource.h"

/* The loaded grid's description (NULL without one) and its tiles. */
const heightfield *res_heightfield_loaded(int *tiles_x, int *tiles_y);

/* The defines s's program needs: the streamed terrain's feedback (shaders/terrain/terrain.glsl,
 * TERRAIN_STREAM) when s's heightmap will stream; nothing otherwise. */
void res_heightfield_defines(const scene *s, strbuf *out);
/* Whether this GL can stream a terrain (shader storage buffers: GL 4.3). */
bool res_heightfield_can_stream(void);
bool res_heightfield_streamed(void);

/* Streaming: forget what the passes since the last call asked for and used. */
void res_heightfield_watch(void);
typedef enum res_heightfield_settled {
    TERRAIN_SETTLED,     /* the passes since the last watch asked for no tile: what they drew is exact */
    TERRAIN_LOADED,      /* they asked for tiles, now loaded (up to max_loads): draw again */
    TERRAIN_OVER_BUDGET, /* they asked for more than the cache holds beside the tiles they used: draw less */
    TERRAIN_FAILED,      /* a tile could not be read (*err says why) */
    TERRAIN_PENDING,     /* (async) they asked for tiles the loader is still reading: draw again later */
} res_heightfield_settled;
/* Reads what the passes since the last watch asked for and used, loads up to max_loads of the tiles they
 * asked for (into free slots, else ones they did not use), then watches afresh. */
res_heightfield_settled res_heightfield_settle(int max_loads, err_t *err);

/* The window's: the same, but the tiles are read by a loader thread (data/geo/terrain_loader.h); this asks
 * for what the passes wanted and uploads up to max_uploads tiles that are ready, without waiting. */
res_heightfield_settled res_heightfield_settle_async(int max_uploads, err_t *err);

typedef struct res_heightfield_stats {
    int tiles, slots, resident, pending; /* pending: asked for at the last settle and not loaded */
    long loaded, evicted;
    unsigned long long bytes_read;    /* from the DEM for the tiles */
    unsigned long long summary_bytes; /* from the DEM to build the summary (0: it was in the cache folder) */
    double gpu_bytes; /* the slots' textures: heights and their levels */
    double summary_s;
    bool summary_cached;
} res_heightfield_stats;
res_heightfield_stats res_heightfield_get_stats(void);

#endif
