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

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/geo/dem.h"
#include "data/geo/terrain_stream.h"

enum {
    TILE_IN_CORE = 4096,  /* cells a tile when a DEM in core is larger than one texture */
    TILE_STREAMED = 512,  /* cells a tile read from disk: 1.4 MB with its levels */
    TILE_ENV_MAX = 1 << 16,
    AUTO_CACHE_MB = 1536, /* terrain.cache_mb's most when auto: an eighth of the memory, at most this */
};

static struct {
    GLuint height_tex, max_tex, top_tex, pages_tex, feedback_buf;
    terrain_grid grid;
    int slots, tiles, words; /* texture layers; tiles; feedback words a bit set */
    int *slot_tile, *tile_slot;
    unsigned *slot_used; /* the settle pass that last used the slot: the oldest unused one is evicted */
    unsigned pass;
    bool streamed;
    struct dem_stream *stream;
    float ex;
    float *tile_buf, *level_buf;
    res_heightfield_stats stats;
    char key[PATH_MAX_LEN + 192];
    heightfield hf; /* the grid's description; its heights and pyramid live on the GPU */
} state;

static void release(void)
{
    glDeleteTextures(1, &state.height_tex); /* each on its own: 0 names are ignored */
    glDeleteTextures(1, &state.max_tex);
    glDeleteTextures(1, &state.top_tex);
    glDeleteTextures(1, &state.pages_tex);
    glDeleteBuffers(1, &state.feedback_buf);
    heightfield_free(&state.hf);
    dem_stream_close(state.stream);
    free(state.slot_tile);
    free(state.tile_slot);
    free(state.slot_used);
    free(state.tile_buf);
    free(state.level_buf);
    memset(&state, 0, sizeof state);
}

static int held(void)
{
    return (state.height_tex != 0) + (state.max_tex != 0) + (state.top_tex != 0) + (state.pages_tex != 0) +
           (state.feedback_buf != 0);
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
    err_t later; /* a file that cannot be opened is the load's to report */
    struct dem_stream *d = dem_stream_open(path, w, h, &info, &later);
    if (!d)
        return false;
    dem_stream_close(d);
    snprintf(memo.key, sizeof memo.key, "%s", key);
    memo.w = *w;
    memo.rows = *h;
    memo.streams = (double)*w * (double)*h * DEM_BYTES_PER_TEXEL > budget_bytes(s);
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

/* Tile `tile`'s heights (its window, w × h) and levels (state.level_buf) into `slot`, and the page table. */
static void upload_tile(int tile, const float *heights, int w, int h, int slot)
{
    const terrain_grid *g = &state.grid;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindTexture(GL_TEXTURE_2D_ARRAY, state.height_tex);
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, slot, w, h, 1, GL_RED, GL_FLOAT, heights);
    glBindTexture(GL_TEXTURE_2D_ARRAY, state.max_tex);
    const float *lv = state.level_buf;
    for (int k = 1; k < g->tile_level; k++) {
        int nx, ny;
        terrain_tile_level_size(g, k, &nx, &ny);
        glTexSubImage3D(GL_TEXTURE_2D_ARRAY, k - 1, 0, 0, slot, nx, ny, 1, GL_RED, GL_FLOAT, lv);
        lv += (size_t)nx * (size_t)ny;
    }
    int tx = tile % g->tiles_x, ty = tile / g->tiles_x;
    glBindTexture(GL_TEXTURE_2D, state.pages_tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, tx, ty, 1, 1, GL_RED_INTEGER, GL_INT, &slot);
    int old = state.slot_tile[slot];
    if (old >= 0 && old != tile) {
        state.tile_slot[old] = -1;
        int none = -1, ox = old % g->tiles_x, oy = old / g->tiles_x;
        glTexSubImage2D(GL_TEXTURE_2D, 0, ox, oy, 1, 1, GL_RED_INTEGER, GL_INT, &none);
        state.stats.evicted++;
    }
    state.slot_tile[slot] = tile;
    state.tile_slot[tile] = slot;
}

/* The textures for `slots` tiles, the page table (every tile absent) and the top pyramid. */
static void allocate(int slots, float **top)
{
    const terrain_grid *g = &state.grid;
    state.slots = slots;
    state.tiles = g->tiles_x * g->tiles_y;
    state.height_tex = array_texture(g->slot_w, g->slot_h, slots, 1);
    int nx, ny, mips = g->tile_level > 1 ? g->tile_level - 1 : 1;
    terrain_tile_level_size(g, 1, &nx, &ny);
    state.max_tex = array_texture(nx, ny, slots, mips);
    state.pages_tex = plain_texture();
    int *none = util_alloc(sizeof(int) * (size_t)state.tiles, "the terrain's page table");
    for (int i = 0; i < state.tiles; i++)
        none[i] = -1;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32I, g->tiles_x, g->tiles_y, 0, GL_RED_INTEGER, GL_INT, none);
    free(none);
    state.top_tex = plain_texture();
    int levels = g->levels - g->tile_level;
    for (int m = 0; m < levels; m++) {
        terrain_top_size(g, g->tile_level + m, &nx, &ny);
        glTexImage2D(GL_TEXTURE_2D, m, GL_R32F, nx, ny, 0, GL_RED, GL_FLOAT, top[m]);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
    state.slot_tile = util_alloc(sizeof(int) * (size_t)slots, "the terrain's slots");
    state.tile_slot = util_alloc(sizeof(int) * (size_t)state.tiles, "the terrain's page table");
    state.slot_used = util_calloc((size_t)slots, sizeof(unsigned), "the terrain's slots");
    for (int i = 0; i < slots; i++)
        state.slot_tile[i] = -1;
    for (int i = 0; i < state.tiles; i++)
        state.tile_slot[i] = -1;
    free(state.level_buf);
    state.level_buf = util_alloc(sizeof(float) * (terrain_tile_level_floats(g) + 1), "a terrain tile's levels");
}

/* Tile t's window of a grid held whole, into state.tile_buf (or the grid itself when it is one tile). */
static const float *window_of(const heightfield *hf, int t, int *w, int *h)
{
    const terrain_grid *g = &state.grid;
    int x0, y0;
    terrain_tile_window(g, t % g->tiles_x, t / g->tiles_x, &x0, &y0, w, h);
    if (g->tiles_x * g->tiles_y == 1)
        return hf->h;
    for (int j = 0; j < *h; j++)
        memcpy(state.tile_buf + (size_t)j * (size_t)*w, hf->h + (size_t)(y0 + j) * (size_t)hf->width + (size_t)x0,
               sizeof(float) * (size_t)*w);
    return state.tile_buf;
}

/* A DEM in core: read whole (heightfield_load) and every tile uploaded. */
static bool load_in_core(const heightfield_desc *d, int tile_cells, err_t *err)
{
    if (!heightfield_load(d, &state.hf, err))
        return false;
    heightfield *hf = &state.hf;
    heightfield_drop_pyramid(hf); /* the tiles build their own levels: the same values */
    GLint max_side = 0, max_layers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    if (!tile_cells && (hf->width > max_side || hf->height > max_side))
        tile_cells = TILE_IN_CORE < max_side ? TILE_IN_CORE : max_side / 2;
    terrain_grid *g = &state.grid;
    terrain_grid_plan(hf->width, hf->height, tile_cells, g);
    int tiles = g->tiles_x * g->tiles_y;
    if (tiles > max_layers)
        return err_set(err, "heightmap '%s' (%dx%d) needs %d tiles; this GPU holds %d: cut the DEM", d->path,
                       hf->width, hf->height, tiles, max_layers);
    state.tile_buf = tiles > 1 ? util_alloc(sizeof(float) * (size_t)g->slot_w * (size_t)g->slot_h, "a terrain tile") : NULL;
    float *tile_max = util_alloc(sizeof(float) * (size_t)tiles, "the terrain's tiles");
    for (int t = 0; t < tiles; t++) { /* the maxima first: the top pyramid is allocated with the textures */
        int w, h;
        const float *win = window_of(hf, t, &w, &h);
        terrain_tile_stats st;
        terrain_tile_build(g, t % g->tiles_x, t / g->tiles_x, win, hf->dx, hf->dz, NULL, &st);
        tile_max[t] = st.max;
    }
    float **top = terrain_top_build(g, tile_max);
    free(tile_max);
    allocate(tiles, top);
    terrain_top_free(g, top);
    for (int t = 0; t < tiles; t++) {
        int w, h;
        const float *win = window_of(hf, t, &w, &h);
        terrain_tile_stats st;
        terrain_tile_build(g, t % g->tiles_x, t / g->tiles_x, win, hf->dx, hf->dz, state.level_buf, &st);
        upload_tile(t, win, w, h, t);
    }
    free(hf->h); /* the heights live on the GPU from here: a DEM is not held twice */
    hf->h = NULL;
    free(state.tile_buf);
    state.tile_buf = NULL;
    return true;
}

/* A DEM streamed: its summary (built or from the cache folder), the textures for the slots the cache
 * holds, no tile yet. */
static bool open_streamed(const heightfield_desc *d, int tile_cells, double budget, err_t *err)
{
    if (!res_heightfield_can_stream())
        return err_set(err, "heightmap '%s' is larger than terrain.cache_mb and streaming it needs OpenGL 4.3 (shader "
                            "storage buffers); this GL has %d.%d: raise terrain.cache_mb or resample the DEM",
                       d->path, epoxy_gl_version() / 10, epoxy_gl_version() % 10);
    heightfield *hf = &state.hf;
    if (!heightfield_open_stream(d, hf, &state.stream, err))
        return false;
    terrain_grid *g = &state.grid;
    terrain_grid_plan(hf->width, hf->height, tile_cells ? tile_cells : TILE_STREAMED, g);
    float ex = d->exaggeration > 0 ? d->exaggeration : 1.0f;
    terrain_summary sum;
    if (!terrain_summary_get(d->path, g, hf->dx, hf->dz, ex, &sum, err))
        return false;
    hf->hmin = sum.hmin, hf->hmax = sum.hmax, hf->lipschitz = sum.lipschitz, hf->holes = sum.holes;
    hf->pw = g->pw, hf->ph = g->ph, hf->levels = g->levels;
    state.stats.summary_s = sum.seconds;
    state.stats.summary_cached = sum.cached;
    state.stats.summary_bytes = sum.bytes;
    if (!heightfield_stream_check(d, hf, err)) {
        terrain_summary_free(&sum);
        return false;
    }
    size_t hole_part = strlen(hf->about);
    if (hf->holes)
        snprintf(hf->about + hole_part, sizeof hf->about - hole_part, ", %zu nodata texels left as holes", hf->holes);
    GLint max_layers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    double slot_bytes = 4.0 * ((double)g->slot_w * g->slot_h + (double)terrain_tile_level_floats(g));
    int tiles = g->tiles_x * g->tiles_y;
    double fit = floor(budget / slot_bytes);
    int slots = fit < tiles ? (int)fit : tiles;
    slots = slots < max_layers ? slots : max_layers;
    double one_texture = 1073741823.0 / (4.0 * g->slot_w * g->slot_h); /* llvmpipe's most in one texture: 1 GB */
    slots = slots < one_texture ? slots : (int)one_texture;
    if (slots < 4) {
        terrain_summary_free(&sum);
        return err_set(err, "heightmap '%s': terrain.cache_mb=%.0f holds %d of its %.1f MB tiles; give it at least %.0f",
                       d->path, budget / 1048576.0, slots, slot_bytes / 1048576.0, ceil(4 * slot_bytes / 1048576.0));
    }
    float **top = terrain_top_build(g, sum.tile_max);
    terrain_summary_free(&sum);
    allocate(slots, top);
    terrain_top_free(g, top);
    state.tile_buf = util_alloc(sizeof(float) * (size_t)g->slot_w * (size_t)g->slot_h, "a terrain tile");
    state.words = (tiles + 31) / 32;
    glGenBuffers(1, &state.feedback_buf);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, state.feedback_buf);
    glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(sizeof(unsigned) * 2 * (size_t)state.words), NULL, GL_DYNAMIC_READ);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    state.streamed = true;
    state.ex = ex;
    res_heightfield_watch();
    return true;
}

/* A refused allocation (or the tests' fault) after the uploads: everything given back, one message. */
static bool fault_or_oom(const char *path, err_t *err)
{
    err_t fault;
    if (glGetError() != GL_OUT_OF_MEMORY && !render_resource_fault("heightfield", &fault))
        return true;
    const terrain_grid *g = &state.grid;
    double mb = 4.0 * (double)g->slot_w * g->slot_h * state.slots / 1048576.0;
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
    char key[sizeof state.key];
    snprintf(key, sizeof key, "%.9g %.9g|%.9g %.9g|%.9g|%d|%d|%d %.0f;", (double)d.spacing[0], (double)d.spacing[1],
             (double)d.height_min, (double)d.height_max, (double)d.exaggeration, d.fill_nodata, tile_cells, streamed,
             streamed ? budget : 0.0);
    render_file_key(d.path, key, sizeof key);
    char side[PATH_MAX_LEN]; /* the sidecar (spacing, height range) counts too */
    terrain_sidecar_path(d.path, side, sizeof side);
    render_file_key(side, key, sizeof key);
    if (state.height_tex && !strcmp(key, state.key))
        return true;
    release();
    while (glGetError() != GL_NO_ERROR)
        ;
    if (!(streamed ? open_streamed(&d, tile_cells, budget, err) : load_in_core(&d, tile_cells, err))) {
        release();
        return false;
    }
    if (!fault_or_oom(d.path, err))
        return false;
    const terrain_grid *g = &state.grid;
    fprintf(stderr, "fathom: %s\n", state.hf.about);
    if (state.streamed)
        fprintf(stderr, "fathom: streamed from disk: %d x %d tiles of %d x %d cells, %d resident at most (%.0f MB; "
                        "terrain.cache_mb), heights %.6g to %.6g m, summary %s in %.2f s\n", g->tiles_x, g->tiles_y,
                1 << g->shift_x, 1 << g->shift_y, state.slots, budget / 1048576.0, (double)state.hf.hmin,
                (double)state.hf.hmax,
                state.stats.summary_cached ? "from the cache folder" : "built", state.stats.summary_s);
    else if (state.tiles > 1)
        fprintf(stderr, "fathom: %d x %d tiles of %d x %d texels\n", g->tiles_x, g->tiles_y, g->slot_w, g->slot_h);
    snprintf(state.key, sizeof state.key, "%s", key);
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
    if (!state.height_tex)
        return;
    const heightfield *hf = &state.hf;
    const terrain_grid *g = &state.grid;
    uniform_iv(u, "uTerrainTiles", 2, 1, (const int[]){g->tiles_x, g->tiles_y});
    uniform_iv(u, "uTerrainTileShift", 2, 1, (const int[]){g->shift_x, g->shift_y});
    uniform_i(u, "uTerrainTileLevel", g->tile_level);
    uniform_i(u, "uTerrainFeedbackWords", state.words);
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
    glBindTexture(GL_TEXTURE_2D_ARRAY, state.height_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 1);
    glBindTexture(GL_TEXTURE_2D_ARRAY, state.max_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 2);
    glBindTexture(GL_TEXTURE_2D, state.top_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 3);
    glBindTexture(GL_TEXTURE_2D, state.pages_tex);
    if (state.feedback_buf) /* the terrain's block is the only shader storage block: binding 0 */
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, state.feedback_buf);
}

const render_resource res_heightfield = {"heightfield", set, 4, uniforms, bind, release, held};

const heightfield *res_heightfield_loaded(int *tiles_x, int *tiles_y)
{
    if (tiles_x)
        *tiles_x = state.grid.tiles_x;
    if (tiles_y)
        *tiles_y = state.grid.tiles_y;
    return state.height_tex ? &state.hf : NULL;
}

void res_heightfield_watch(void)
{
    if (!state.feedback_buf)
        return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); /* after the passes before it, before the ones after */
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, state.feedback_buf);
    unsigned *zero = util_calloc(2 * (size_t)state.words, sizeof(unsigned), "the terrain's feedback");
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(sizeof(unsigned) * 2 * (size_t)state.words), zero);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    free(zero);
}

/* The slot for a new tile: a free one, else the one unused longest among those this pass did not use. */
static int free_slot(const unsigned *used)
{
    int best = -1;
    for (int i = 0; i < state.slots; i++) {
        int t = state.slot_tile[i];
        if (t < 0)
            return i;
        if (!(used[t >> 5] >> (t & 31) & 1u) && (best < 0 || state.slot_used[i] < state.slot_used[best]))
            best = i;
    }
    return best;
}

static bool load_tile(int tile, int slot, err_t *err)
{
    const terrain_grid *g = &state.grid;
    int tx = tile % g->tiles_x, ty = tile / g->tiles_x, x0, y0, w, h;
    terrain_tile_window(g, tx, ty, &x0, &y0, &w, &h);
    unsigned long long before = dem_stream_bytes(state.stream);
    if (!terrain_read_tile(state.stream, g, tx, ty, state.ex, state.tile_buf, err))
        return false;
    state.stats.bytes_read += dem_stream_bytes(state.stream) - before;
    terrain_tile_stats st;
    terrain_tile_build(g, tx, ty, state.tile_buf, state.hf.dx, state.hf.dz, state.level_buf, &st);
    upload_tile(tile, state.tile_buf, w, h, slot);
    state.stats.loaded++;
    return true;
}

res_heightfield_settled res_heightfield_settle(int max_loads, err_t *err)
{
    if (!state.feedback_buf)
        return TERRAIN_SETTLED;
    size_t words = (size_t)state.words;
    unsigned *bits = util_alloc(sizeof(unsigned) * 2 * words, "the terrain's feedback");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); /* the shaders' writes, seen by the read below */
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, state.feedback_buf);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(sizeof(unsigned) * 2 * words), bits);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    const unsigned *want = bits, *used = bits + words;
    state.pass++;
    int wanted = 0, in_use = 0;
    for (int t = 0; t < state.tiles; t++) {
        bool u = used[t >> 5] >> (t & 31) & 1u;
        if (u && state.tile_slot[t] >= 0)
            state.slot_used[state.tile_slot[t]] = state.pass, in_use++;
        if ((want[t >> 5] >> (t & 31) & 1u) && state.tile_slot[t] < 0)
            wanted++;
    }
    state.stats.pending = wanted;
    res_heightfield_settled r = wanted == 0 ? TERRAIN_SETTLED
                                : wanted + in_use > state.slots ? TERRAIN_OVER_BUDGET : TERRAIN_LOADED;
    int loads = 0;
    for (int t = 0; t < state.tiles && r != TERRAIN_SETTLED && loads < max_loads; t++) {
        if (!(want[t >> 5] >> (t & 31) & 1u) || state.tile_slot[t] >= 0)
            continue;
        int slot = free_slot(used);
        if (slot < 0)
            break;
        if (!load_tile(t, slot, err)) {
            r = TERRAIN_FAILED;
            break;
        }
        state.slot_used[slot] = state.pass;
        loads++;
        state.stats.pending--;
    }
    free(bits);
    res_heightfield_watch();
    return r;
}

bool res_heightfield_streamed(void) { return state.streamed; }

res_heightfield_stats res_heightfield_get_stats(void)
{
    res_heightfield_stats st = state.stats;
    st.slots = state.slots;
    st.tiles = state.tiles;
    st.gpu_bytes = state.slots * 4.0 * ((double)state.grid.slot_w * state.grid.slot_h +
                                        (double)terrain_tile_level_floats(&state.grid));
    st.resident = 0;
    for (int i = 0; i < state.slots; i++)
        st.resident += state.slot_tile && state.slot_tile[i] >= 0;
    return st;
}
