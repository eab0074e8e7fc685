/* res_heightfield — a terrain's heights and max pyramid on the GPU in tiles (app/data/geo/terrain_tiles.h;
 * shaders/terrain/terrain.glsl walks them), through a page table: tile → the texture layer (slot) holding
 * it, or −1.
 *   in core  a DEM whose heights fit the cache (terrain.cache_mb) is read whole and every tile uploaded:
 *            one tile when it fits a texture, else tiles of 4096 cells.
 *   streamed a larger one is never read whole: the tiles' summary (terrain_stream.h) gives the pyramid
 *            above the tiles, and a tile is read from disk when a ray asks for it. The shader marks the
 *            tiles it asked for and did not have, and the resident ones it used, in a bit buffer;
 *            res_heightfield_settle reads it and loads what was asked into free slots or ones this pass
 *            did not use. Until then a missing tile stands as a plateau at its maximum (conservative: no
 *            ray passes through ground the tile holds), so a pass that asked for nothing is exact.
 * Kept while the next scene reads the same unchanged file the same way (a flight's frames, preset and
 * knob switches): a big DEM is read once. */
#include "gpu/res_heightfield.h"

#include "gpu/res_heightfield_state.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/geo/dem.h"
#include "data/geo/terrain_loader.h"
#include "data/geo/terrain_stream.h"
#include "data/geo/water.h"

enum {
    TILE_IN_CORE = 4096,  /* cells a tile when a DEM in core is larger than one texture */
    TILE_STREAMED = 512,  /* cells a tile read from disk: 1.4 MB with its levels */
    TILE_ENV_MAX = 1 << 16,
    AUTO_CACHE_MB = 1536, /* terrain.cache_mb's most when auto: an eighth of the memory, at most this */
};

res_heightfield_state res_heightfield_now;
static res_heightfield_state *const S = &res_heightfield_now;

static void release(void)
{
    terrain_loader_stop(S->loader); /* first: it reads the grid below */
    glDeleteTextures(1, &S->height_tex); /* each on its own: 0 names are ignored */
    glDeleteTextures(1, &S->max_tex);
    glDeleteTextures(1, &S->top_tex);
    glDeleteTextures(1, &S->pages_tex);
    glDeleteTextures(1, &S->water_tex);
    glDeleteBuffers(1, &S->feedback_buf);
    heightfield_free(&S->hf);
    dem_stream_close(S->stream);
    free(S->slot_tile);
    free(S->tile_slot);
    free(S->slot_used);
    free(S->tile_buf);
    free(S->level_buf);
    memset(S, 0, sizeof *S);
}

static int held(void)
{
    return (S->height_tex != 0) + (S->max_tex != 0) + (S->top_tex != 0) + (S->pages_tex != 0) +
           (S->feedback_buf != 0) + (S->water_tex != 0);
}

bool res_heightfield_can_stream(void)
{
    return epoxy_gl_version() >= 43 || epoxy_has_gl_extension("GL_ARB_shader_storage_buffer_object");
}

/* terrain.cache_mb, or auto: an eighth of the machine's memory, at most AUTO_CACHE_MB. */
static double budget_bytes(const scene *s)
{
    if (s->terrain.cache_mb > 0)
        return (double)s->terrain.cache_mb * 1048576.0;
    double auto_mb = util_physical_memory() / 8.0 / 1048576.0;
    return (auto_mb < AUTO_CACHE_MB ? auto_mb : AUTO_CACHE_MB) * 1048576.0;
}

/* Whether s's heightmap streams: a DEM through GDAL whose heights read whole would not fit the cache
 * (DEM_BYTES_PER_TEXEL: their peak while loading). *w, *h: its size. */
static bool streams(const scene *s, int *w, int *h)
{
    static struct { /* the last answer: a flight asks every frame, and a VRT of many files is slow to open */
        char key[PATH_MAX_LEN + 64];
        int w, rows;
        bool streams;
    } memo;
    const char *path = s->terrain.heightmap;
    if (!path[0] || dem_is_image(path))
        return false;
    char key[sizeof memo.key];
    snprintf(key, sizeof key, "%.0f;", budget_bytes(s));
    render_file_key(path, key, sizeof key);
    if (!strcmp(key, memo.key)) {
        *w = memo.w;
        *h = memo.rows;
        return memo.streams;
    }
    dem_info info;
    err_t later; /* a file that cannot be opened: the streamed open reports it (its side limit is the larger) */
    struct dem_stream *d = dem_stream_open(path, w, h, &info, &later);
    if (!d)
        return res_heightfield_can_stream();
    dem_stream_close(d);
    snprintf(memo.key, sizeof memo.key, "%s", key);
    memo.w = *w;
    memo.rows = *h;
    memo.streams = (double)*w * (double)*h * DEM_BYTES_PER_TEXEL > budget_bytes(s) || *w > TERRAIN_MAX_SIDE ||
                   *h > TERRAIN_MAX_SIDE;
    return memo.streams;
}

void res_heightfield_defines(const scene *s, strbuf *out)
{
    int w, h;
    if (s->terrain.heightmap[0] && res_heightfield_can_stream() && streams(s, &w, &h))
        sb_append(out, "#extension GL_ARB_shader_storage_buffer_object : require\n#define TERRAIN_STREAM 1\n");
}

/* FATHOM_TERRAIN_TILE: cells a tile (a power of two), so the tests cross many seams on a small DEM; 0 when unset. */
static bool env_tile(int *tile, err_t *err)
{
    *tile = 0;
    const char *env = getenv("FATHOM_TERRAIN_TILE");
    if (!env)
        return true;
    char *end; /* checked whole: a value past 2^30 once looped forever (1 << 31) */
    long v = strtol(env, &end, 10);
    if (end == env || *end || v < 4 || v > TILE_ENV_MAX)
        return err_set(err, "FATHOM_TERRAIN_TILE='%s': expected a tile side from 4 to %d texels (rounded up to a power "
                            "of two), or unset it", env, TILE_ENV_MAX);
    *tile = 4;
    while (*tile < v)
        *tile *= 2;
    return true;
}

static GLuint array_texture(int w, int h, int layers, int mips)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D_ARRAY, t);
    for (int m = 0; m < mips; m++) {
        int lw = w >> m, lh = h >> m;
        glTexImage3D(GL_TEXTURE_2D_ARRAY, m, GL_R32F, lw > 0 ? lw : 1, lh > 0 ? lh : 1, layers, 0, GL_RED, GL_FLOAT, NULL);
    }
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, mips - 1);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

static GLuint plain_texture(void)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

void res_heightfield_upload(int tile, const float *heights, const float *levels, int w, int h, int slot)
{
    const terrain_grid *g = &S->grid;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D_ARRAY, S->height_tex);
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, slot, w, h, 1, GL_RED, GL_FLOAT, heights);
    glBindTexture(GL_TEXTURE_2D_ARRAY, S->max_tex);
    const float *lv = levels;
    for (int k = 1; k < g->tile_level; k++) {
        int nx, ny;
        terrain_tile_level_size(g, k, &nx, &ny);
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, k - 1, 0, 0, slot, nx, ny, 1, GL_RED, GL_FLOAT, lv);
        lv += (size_t)nx * (size_t)ny;
    }
    int tx = tile % g->tiles_x, ty = tile / g->tiles_x;
    glBindTexture(GL_TEXTURE_2D, S->pages_tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, tx, ty, 1, 1, GL_RED_INTEGER, GL_INT, &slot);
    int old = S->slot_tile[slot];
    if (old >= 0 && old != tile) {
        S->tile_slot[old] = -1;
        int none = -1, ox = old % g->tiles_x, oy = old / g->tiles_x;
        glTexSubImage2D(GL_TEXTURE_2D, 0, ox, oy, 1, 1, GL_RED_INTEGER, GL_INT, &none);
        S->stats.evicted++;
    }
    S->slot_tile[slot] = tile;
    S->tile_slot[tile] = slot;
}

/* The top pyramid from every tile's maximum (tiles_x × tiles_y). */
static void upload_top(const float *tile_max)
{
    const terrain_grid *g = &S->grid;
    float **top = terrain_top_build(g, tile_max);
    S->top_tex = plain_texture();
    int levels = g->levels - g->tile_level, nx, ny;
    for (int m = 0; m < levels; m++) {
        terrain_top_size(g, g->tile_level + m, &nx, &ny);
        glTexImage2D(GL_TEXTURE_2D, m, GL_R32F, nx, ny, 0, GL_RED, GL_FLOAT, top[m]);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
    terrain_top_free(g, top);
}

/* The textures for `slots` tiles and the page table (every tile absent). */
static void allocate(int slots)
{
    const terrain_grid *g = &S->grid;
    S->slots = slots;
    S->tiles = g->tiles_x * g->tiles_y;
    S->height_tex = array_texture(g->slot_w, g->slot_h, slots, 1);
    int nx, ny, mips = g->tile_level > 1 ? g->tile_level - 1 : 1;
    terrain_tile_level_size(g, 1, &nx, &ny);
    S->max_tex = array_texture(nx, ny, slots, mips);
    S->pages_tex = plain_texture();
    int *none = util_alloc(sizeof(int) * (size_t)S->tiles, "the terrain's page table");
    for (int i = 0; i < S->tiles; i++)
        none[i] = -1;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32I, g->tiles_x, g->tiles_y, 0, GL_RED_INTEGER, GL_INT, none);
    free(none);
    S->slot_tile = util_alloc(sizeof(int) * (size_t)slots, "the terrain's slots");
    S->tile_slot = util_alloc(sizeof(int) * (size_t)S->tiles, "the terrain's page table");
    S->slot_used = util_calloc((size_t)slots, sizeof(unsigned), "the terrain's slots");
    for (int i = 0; i < slots; i++)
        S->slot_tile[i] = -1;
    for (int i = 0; i < S->tiles; i++)
        S->tile_slot[i] = -1;
    free(S->level_buf);
    S->level_buf = util_alloc(sizeof(float) * (terrain_tile_level_floats(g) + 1), "a terrain tile's levels");
}

/* Tile t's window of a grid held whole, into S->tile_buf (or the grid itself when it is one tile). */
static const float *window_of(const heightfield *hf, int t, int *w, int *h)
{
    const terrain_grid *g = &S->grid;
    int x0, y0;
    terrain_tile_window(g, t % g->tiles_x, t / g->tiles_x, &x0, &y0, w, h);
    if (g->tiles_x * g->tiles_y == 1)
        return hf->h;
    for (int j = 0; j < *h; j++)
        memcpy(S->tile_buf + (size_t)j * (size_t)*w, hf->h + (size_t)(y0 + j) * (size_t)hf->width + (size_t)x0,
               sizeof(float) * (size_t)*w);
    return S->tile_buf;
}

/* The water of s drawn a texel at a time (lakes, a raster): each texel's level into a texture, and *pyramid the
 * grid the max pyramid is built from, max(ground, water) (conservative for both surfaces); NULL without. */
static bool water_texture(const scene *s, heightfield *hf, float **pyramid, err_t *err)
{
    *pyramid = NULL;
    if (s->terrain.water_mode != WATER_FILL && s->terrain.water_mode != WATER_RASTER)
        return true;
    if (S->grid.tiles_x * S->grid.tiles_y > 1)
        return err_set(err, "terrain.water: lakes and rasters of water are drawn on a DEM that fits one texture (this "
                            "one is %d x %d); give a level instead", hf->width, hf->height);
    size_t n = (size_t)hf->width * (size_t)hf->height;
    float *w = util_alloc(n * sizeof *w, "the terrain's water"), top;
    float ex = s->terrain.exaggeration > 0 ? s->terrain.exaggeration : 1.0f;
    if (!water_grid(hf->h, hf->width, hf->height, hf->dx, hf->dz, s->terrain.heightmap,
                    s->terrain.water_mode == WATER_RASTER ? s->terrain.water_raster : NULL, ex, w, &top, err)) {
        free(w);
        return false;
    }
    hf->hmax = top > hf->hmax ? top : hf->hmax; /* the slab holds the water too */
    S->water_tex = plain_texture();
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, hf->width, hf->height, 0, GL_RED, GL_FLOAT, w);
    for (size_t c = 0; c < n; c++)
        w[c] = w[c] > hf->h[c] ? w[c] : hf->h[c];
    *pyramid = w;
    return true;
}

/* A DEM in core: read whole (heightfield_load) and every tile uploaded. */
static bool load_in_core(const scene *s, const heightfield_desc *d, int tile_cells, err_t *err)
{
    if (!heightfield_load(d, &S->hf, err))
        return false;
    heightfield *hf = &S->hf;
    heightfield_drop_pyramid(hf); /* the tiles build their own levels: the same values */
    GLint max_side = 0, max_layers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    if (!tile_cells && (hf->width > max_side || hf->height > max_side))
        tile_cells = TILE_IN_CORE < max_side ? TILE_IN_CORE : max_side / 2;
    terrain_grid *g = &S->grid;
    terrain_grid_plan(hf->width, hf->height, tile_cells, g);
    int tiles = g->tiles_x * g->tiles_y;
    if (tiles > max_layers)
        return err_set(err, "heightmap '%s' (%dx%d) needs %d tiles; this GPU holds %d: cut the DEM", d->path,
                       hf->width, hf->height, tiles, max_layers);
    float *pyramid;
    if (!water_texture(s, hf, &pyramid, err))
        return false;
    S->tile_buf = tiles > 1 ? util_alloc(sizeof(float) * (size_t)g->slot_w * (size_t)g->slot_h, "a terrain tile") : NULL;
    allocate(tiles);
    float *tile_max = util_alloc(sizeof(float) * (size_t)tiles, "the terrain's tiles");
    for (int t = 0; t < tiles; t++) { /* each tile's levels and upload; its maximum for the top */
        int w, h;
        const float *win = window_of(hf, t, &w, &h);
        terrain_tile_stats st;
        terrain_tile_build(g, t % g->tiles_x, t / g->tiles_x, pyramid ? pyramid : win, hf->dx, hf->dz, S->level_buf, &st);
        res_heightfield_upload(t, win, S->level_buf, w, h, t);
        tile_max[t] = st.max;
    }
    upload_top(tile_max);
    free(tile_max);
    free(pyramid);
    free(hf->h); /* the heights live on the GPU from here: a DEM is not held twice */
    hf->h = NULL;
    free(S->tile_buf);
    S->tile_buf = NULL;
    return true;
}

/* A DEM streamed: its summary (built or from the cache folder), the textures for the slots the cache
 * holds, no tile yet. */
static bool open_streamed(const heightfield_desc *d, int tile_cells, double budget, err_t *err)
{
    heightfield *hf = &S->hf;
    if (!heightfield_open_stream(d, hf, &S->stream, err))
        return false;
    if (!res_heightfield_can_stream())
        return err_set(err, "heightmap '%s' is larger than terrain.cache_mb and streaming it needs OpenGL 4.3 (shader "
                            "storage buffers); this GL has %d.%d: raise terrain.cache_mb or resample the DEM",
                       d->path, epoxy_gl_version() / 10, epoxy_gl_version() % 10);
    terrain_grid *g = &S->grid;
    terrain_grid_plan(hf->width, hf->height, tile_cells ? tile_cells : TILE_STREAMED, g);
    GLint max_layers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    double slot_bytes = 4.0 * ((double)g->slot_w * g->slot_h + (double)terrain_tile_level_floats(g));
    int tiles = g->tiles_x * g->tiles_y;
    double fit = floor(budget / slot_bytes);
    int slots = fit < tiles ? (int)fit : tiles;
    slots = slots < max_layers ? slots : max_layers;
    double one_texture = 1073741823.0 / (4.0 * g->slot_w * g->slot_h); /* llvmpipe's most in one texture: 1 GB */
    slots = slots < one_texture ? slots : (int)one_texture;
    if (slots < 4) /* said before the summary is built: that reads the whole DEM */
        return err_set(err, "heightmap '%s': terrain.cache_mb=%.0f holds %d of its %.1f MB tiles; give it at least %.0f",
                       d->path, budget / 1048576.0, slots, slot_bytes / 1048576.0, ceil(4 * slot_bytes / 1048576.0));
    float ex = d->exaggeration > 0 ? d->exaggeration : 1.0f;
    terrain_summary sum;
    if (!terrain_summary_get(d->path, g, hf->dx, hf->dz, ex, &sum, err))
        return false;
    hf->hmin = sum.hmin, hf->hmax = sum.hmax, hf->lipschitz = sum.lipschitz, hf->holes = sum.holes;
    hf->pw = g->pw, hf->ph = g->ph, hf->levels = g->levels;
    S->stats.summary_s = sum.seconds;
    S->stats.summary_cached = sum.cached;
    S->stats.summary_bytes = sum.bytes;
    if (!heightfield_stream_check(d, hf, err)) {
        terrain_summary_free(&sum);
        return false;
    }
    size_t hole_part = strlen(hf->about);
    if (hf->holes)
        snprintf(hf->about + hole_part, sizeof hf->about - hole_part, ", %zu nodata texels left as holes", hf->holes);
    allocate(slots);
    upload_top(sum.tile_max);
    terrain_summary_free(&sum);
    S->tile_buf = util_alloc(sizeof(float) * (size_t)g->slot_w * (size_t)g->slot_h, "a terrain tile");
    S->words = (tiles + 31) / 32;
    glGenBuffers(1, &S->feedback_buf);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, S->feedback_buf);
    unsigned *zero = util_calloc(2 * (size_t)S->words, sizeof(unsigned), "the terrain's feedback");
    glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(sizeof(unsigned) * 2 * (size_t)S->words), zero, GL_DYNAMIC_READ);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    free(zero);
    S->streamed = true;
    S->ex = ex;
    snprintf(S->path, sizeof S->path, "%s", d->path);
    return true;
}

/* A refused allocation (or the tests' fault) after the uploads: everything given back, one message. */
static bool fault_or_oom(const char *path, err_t *err)
{
    err_t fault;
    if (glGetError() != GL_OUT_OF_MEMORY && !render_resource_fault("heightfield", &fault))
        return true;
    const terrain_grid *g = &S->grid;
    double mb = 4.0 * (double)g->slot_w * g->slot_h * S->slots / 1048576.0;
    int W = g->width, H = g->height;
    release();
    return err_set(err, "heightmap '%s' (%dx%d): the GPU driver refused its %.0f MB of heights (llvmpipe holds at most "
                        "1 GB in one texture); lower terrain.cache_mb, or cut or resample the DEM (gdal_translate "
                        "-outsize)", path, W, H, mb);
}

static bool set(const scene *s, err_t *err)
{
    if (!s->terrain.heightmap[0]) {
        release();
        return true;
    }
    heightfield_desc d = {.path = s->terrain.heightmap, .spacing = {s->terrain.spacing[0], s->terrain.spacing[1]},
                          .height_min = s->terrain.height_min, .height_max = s->terrain.height_max,
                          .exaggeration = s->terrain.exaggeration, .fill_nodata = s->terrain.fill_nodata};
    int tile_cells, w, h;
    if (!env_tile(&tile_cells, err))
        return false;
    double budget = budget_bytes(s);
    bool streamed = streams(s, &w, &h);
    char key[sizeof S->key];
    snprintf(key, sizeof key, "%.9g %.9g|%.9g %.9g|%.9g|%d|%d|%d %.0f|%d;", (double)d.spacing[0], (double)d.spacing[1],
             (double)d.height_min, (double)d.height_max, (double)d.exaggeration, d.fill_nodata, tile_cells, streamed,
             streamed ? budget : 0.0, s->terrain.water_mode);
    render_file_key(d.path, key, sizeof key);
    if (s->terrain.water_mode == WATER_RASTER)
        render_file_key(s->terrain.water_raster, key, sizeof key);
    char side[PATH_MAX_LEN]; /* the sidecar (spacing, height range) counts too */
    terrain_sidecar_path(d.path, side, sizeof side);
    render_file_key(side, key, sizeof key);
    if (S->height_tex && !strcmp(key, S->key))
        return true;
    release();
    while (glGetError() != GL_NO_ERROR)
        ;
    if (streamed && (s->terrain.water_mode == WATER_FILL || s->terrain.water_mode == WATER_RASTER))
        return err_set(err, "terrain.water: lakes and rasters of water are drawn on a DEM read whole, and '%s' streams "
                            "(larger than terrain.cache_mb): raise terrain.cache_mb, or give a level", d.path);
    if (!(streamed ? open_streamed(&d, tile_cells, budget, err) : load_in_core(s, &d, tile_cells, err))) {
        release();
        return false;
    }
    if (!fault_or_oom(d.path, err))
        return false;
    const terrain_grid *g = &S->grid;
    fprintf(stderr, "fathom: %s\n", S->hf.about);
    if (S->streamed)
        fprintf(stderr, "fathom: streamed from disk: %d x %d tiles of %d x %d cells, %d resident at most (%.0f MB; "
                        "terrain.cache_mb), heights %.6g to %.6g m, summary %s in %.2f s\n", g->tiles_x, g->tiles_y,
                1 << g->shift_x, 1 << g->shift_y, S->slots, budget / 1048576.0, (double)S->hf.hmin,
                (double)S->hf.hmax,
                S->stats.summary_cached ? "from the cache folder" : "built", S->stats.summary_s);
    else if (S->tiles > 1)
        fprintf(stderr, "fathom: %d x %d tiles of %d x %d texels\n", g->tiles_x, g->tiles_y, g->slot_w, g->slot_h);
    snprintf(S->key, sizeof S->key, "%s", key);
    return true;
}

/* Its units (always), and the loaded heightfield's grid (shaders/terrain/terrain.glsl) when it holds one. */
static void uniforms(const scene *s, const uniform_sink *u, int unit)
{
    (void)s;
    uniform_i(u, "uHeight", unit);
    uniform_i(u, "uHeightMax", unit + 1);
    uniform_i(u, "uHeightMaxTop", unit + 2); /* the pyramid's upper levels, from whole tiles up */
    uniform_i(u, "uTerrainPages", unit + 3);
    uniform_i(u, "uWaterGrid", unit + 4);
    if (!S->height_tex)
        return;
    const heightfield *hf = &S->hf;
    const terrain_grid *g = &S->grid;
    uniform_iv(u, "uTerrainTiles", 2, 1, (const int[]){g->tiles_x, g->tiles_y});
    uniform_iv(u, "uTerrainTileShift", 2, 1, (const int[]){g->shift_x, g->shift_y});
    uniform_i(u, "uTerrainTileLevel", g->tile_level);
    uniform_i(u, "uTerrainFeedbackWords", S->words);
    uniform_fv(u, "uTerrainOrigin", 2, 1, (const float[]){hf->x0, hf->z0});
    uniform_fv(u, "uTerrainSpacing", 2, 1, (const float[]){hf->dx, hf->dz});
    uniform_f(u, "uTerrainHeightMin", hf->hmin);
    uniform_f(u, "uTerrainHeightMax", hf->hmax);
    uniform_f(u, "uTerrainStepScale", 1.0f / sqrtf(1.0f + hf->lipschitz * hf->lipschitz));
    uniform_i(u, "uTerrainTopLevel", g->levels - 1);
    uniform_iv(u, "uTerrainSize", 2, 1, (const int[]){hf->width, hf->height});
    /* a ray crosses at most pw + ph level-0 cells; each costs an exit and at most a descent, and the
     * walk up and down the pyramid adds a few nodes per level */
    enum { NODES_PER_CELL = 4, NODES_PER_LEVEL = 16 };
    uniform_i(u, "uTerrainMaxNodes", NODES_PER_CELL * (g->pw + g->ph) + NODES_PER_LEVEL * g->levels);
}

static void bind(int unit)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, S->height_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 1);
    glBindTexture(GL_TEXTURE_2D_ARRAY, S->max_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 2);
    glBindTexture(GL_TEXTURE_2D, S->top_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 3);
    glBindTexture(GL_TEXTURE_2D, S->pages_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 4);
    glBindTexture(GL_TEXTURE_2D, S->water_tex);
    if (S->feedback_buf) /* the terrain's block is the only shader storage block: binding 0 */
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, S->feedback_buf);
}

const render_resource res_heightfield = {"heightfield", set, 5, uniforms, bind, release, held};

const heightfield *res_heightfield_loaded(int *tiles_x, int *tiles_y)
{
    if (tiles_x)
        *tiles_x = S->grid.tiles_x;
    if (tiles_y)
        *tiles_y = S->grid.tiles_y;
    return S->height_tex ? &S->hf : NULL;
}

