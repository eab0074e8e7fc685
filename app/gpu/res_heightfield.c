/* res_heightfield — a terrain's heights and max pyramid on the GPU, in texture-array tiles when the
 * grid is larger than one texture (app/data/geo/terrain.h has the pyramid; shaders/terrain/terrain.glsl
 * walks it). Kept while the next scene reads the same unchanged file the same way (a flight's frames,
 * preset and knob switches): a big DEM is read once. */
#include "gpu/res_heightfield.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/geo/dem.h"

static struct {
    GLuint height_tex, height_max_tex, height_top_tex; /* heights, max pyramid (tiles, top) */
    struct terrain_tiles {
        int hx, hy;          /* texels per height tile (the whole grid when it fits one texture) */
        int tiles_x, tiles_y;
        int shift_x, shift_y; /* log2 of cells per pyramid tile */
        int tile_level;      /* the highest pyramid level in the tiles; the ones above are in the top */
    } tiles;
    char key[PATH_MAX_LEN + 160];
    heightfield hf; /* the grid's description; its heights and pyramid live on the GPU */
} state;

static void release(void)
{
    glDeleteTextures(1, &state.height_tex); /* each on its own: 0 names are ignored */
    glDeleteTextures(1, &state.height_max_tex);
    glDeleteTextures(1, &state.height_top_tex);
    heightfield_free(&state.hf);
    memset(&state, 0, sizeof state);
}

static int held(void) { return (state.height_tex != 0) + (state.height_max_tex != 0) + (state.height_top_tex != 0); }

enum { TILE_ENV_MAX = 1 << 16 };

static int log2i(int v)
{
    int k = 0;
    while ((1 << k) < v)
        k++;
    return k;
}

/* Terrain tiles: one when the grid fits a texture; else square tiles of `tile` texels (a power of
 * two; FATHOM_TERRAIN_TILE overrides it, so the tests cross many seams on a small DEM). */
static bool plan_tiles(const heightfield *hf, struct terrain_tiles *t, err_t *err)
{
    GLint max_side = 0, max_layers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    int tile = 4096;
    const char *env = getenv("FATHOM_TERRAIN_TILE");
    if (env) { /* checked whole: a value past 2^30 once looped forever (1 << 31) */
        char *end;
        long v = strtol(env, &end, 10);
        if (end == env || *end || v < 4 || v > TILE_ENV_MAX)
            return err_set(err, "FATHOM_TERRAIN_TILE='%s': expected a tile side from 4 to %d texels (rounded up to "
                                "a power of two), or unset it", env, TILE_ENV_MAX);
        tile = 1 << log2i((int)v);
    }
    while (tile > max_side)
        tile /= 2;
    bool one = hf->width <= tile && hf->height <= tile;
    if (!env && hf->width <= max_side && hf->height <= max_side)
        one = true; /* the whole grid in one texture: no seams */
    *t = (struct terrain_tiles){0};
    if (one) {
        t->hx = hf->width, t->hy = hf->height;
        t->shift_x = log2i(hf->pw), t->shift_y = log2i(hf->ph);
    } else {
        t->hx = hf->width < tile ? hf->width : tile;
        t->hy = hf->height < tile ? hf->height : tile;
        t->shift_x = log2i(hf->pw < tile ? hf->pw : tile);
        t->shift_y = log2i(hf->ph < tile ? hf->ph : tile);
    }
    t->tiles_x = (hf->width + t->hx - 1) / t->hx;
    t->tiles_y = (hf->height + t->hy - 1) / t->hy;
    int shift = t->shift_x > t->shift_y ? t->shift_x : t->shift_y;
    t->tile_level = shift < hf->levels - 1 ? shift : hf->levels - 1;
    if (t->tiles_x * t->tiles_y > max_layers)
        return err_set(err, "heightmap '%s' (%dx%d) needs %d tiles of %d texels; this GPU holds %d: cut the DEM",
                       hf->about, hf->width, hf->height, t->tiles_x * t->tiles_y, tile, max_layers);
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

/* Uploads the block at (x0, y0) of a src_w × src_h grid, at most tw × th and clipped to the grid, as
 * `layer` of mip `mip`, straight from the grid (no copy: GL reads the rows in place). Texels of an edge
 * tile beyond the grid stay undefined: the shader clamps to the grid and the pyramid's padding
 * nodes above them are −inf, so none is ever read. */
static void upload_block(const float *src, int src_w, int src_h, int x0, int y0, int tw, int th, int mip, int layer)
{
    int w = src_w - x0 < tw ? src_w - x0 : tw, h = src_h - y0 < th ? src_h - y0 : th;
    if (w <= 0 || h <= 0)
        return;
    glPixelStorei(GL_UNPACK_ROW_LENGTH, src_w);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, x0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, y0);
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, mip, 0, 0, layer, w, h, 1, GL_RED, GL_FLOAT, src);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
}

/* A DEM whose heights the driver cannot hold is refused before it is read (llvmpipe holds 1 GB in one texture: a
 * 20000² DEM was refused after 88 s and 3.1 GB of reading): the heights' texture, planned from the file's size,
 * is allocated first and given back. */
static bool heights_fit(const char *path, err_t *err)
{
    int w, h;
    double range[2];
    dem_info info;
    err_t later; /* a file that cannot be probed is heightfield_load's to report */
    if (dem_is_image(path) || !dem_probe(path, &w, &h, range, &info, &later) ||
        (double)w * (double)h * DEM_BYTES_PER_TEXEL > util_physical_memory()) /* the load says so, at once */
        return true;
    heightfield stub = {.width = w, .height = h, .pw = 1 << log2i(w - 1), .ph = 1 << log2i(h - 1)};
    stub.levels = log2i(stub.pw > stub.ph ? stub.pw : stub.ph) + 1;
    snprintf(stub.about, sizeof stub.about, "%s", path);
    struct terrain_tiles t;
    if (!plan_tiles(&stub, &t, err))
        return false;
    while (glGetError() != GL_NO_ERROR)
        ;
    GLuint tex = array_texture(t.hx, t.hy, t.tiles_x * t.tiles_y, 1);
    bool ok = glGetError() != GL_OUT_OF_MEMORY;
    glDeleteTextures(1, &tex);
    return ok || err_set(err, "heightmap '%s' (%dx%d): the GPU driver cannot hold its %.0f MB of heights (llvmpipe "
                              "holds at most 1 GB in one texture: about 16384x16384); cut or resample the DEM "
                              "(gdal_translate -outsize)", path, w, h, 4.0 * t.hx * t.hy * t.tiles_x * t.tiles_y / 1048576.0);
}

/* Terrain: heights (exact texelFetch, bilinear done in the shader) and the max pyramid, in tiles. */
static bool set(const scene *s, err_t *err)
{
    if (!s->terrain.heightmap[0]) {
        release();
        return true;
    }
    heightfield_desc d = {.path = s->terrain.heightmap, .spacing = {s->terrain.spacing[0], s->terrain.spacing[1]},
                          .height_min = s->terrain.height_min, .height_max = s->terrain.height_max,
                          .exaggeration = s->terrain.exaggeration, .fill_nodata = s->terrain.fill_nodata};
    char key[sizeof state.key];
    snprintf(key, sizeof key, "%.9g %.9g|%.9g %.9g|%.9g|%d|%s;", (double)d.spacing[0], (double)d.spacing[1],
             (double)d.height_min, (double)d.height_max, (double)d.exaggeration, d.fill_nodata,
             getenv("FATHOM_TERRAIN_TILE") ? getenv("FATHOM_TERRAIN_TILE") : "");
    render_file_key(d.path, key, sizeof key);
    char side[PATH_MAX_LEN]; /* the sidecar (spacing, height range) counts too */
    terrain_sidecar_path(d.path, side, sizeof side);
    render_file_key(side, key, sizeof key);
    if (state.height_tex && !strcmp(key, state.key))
        return true;
    release();
    if (!heights_fit(d.path, err) || !heightfield_load(&d, &state.hf, err))
        return false;
    heightfield *hf = &state.hf;
    struct terrain_tiles *t = &state.tiles;
    if (!plan_tiles(hf, t, err)) {
        heightfield_free(hf);
        return false;
    }
    int layers = t->tiles_x * t->tiles_y;
    int px = 1 << t->shift_x, py = 1 << t->shift_y; /* cells per pyramid tile */
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    state.height_tex = array_texture(t->hx, t->hy, layers, 1);
    for (int ty = 0; ty < t->tiles_y; ty++)
        for (int tx = 0; tx < t->tiles_x; tx++)
            upload_block(hf->h, hf->width, hf->height, tx * t->hx, ty * t->hy, t->hx, t->hy, 0, ty * t->tiles_x + tx);
    /* the heights live on the GPU from here (the pyramid was built from them; the ground under the
     * walking camera is a probe of the shader's own surface): a DEM is not held twice */
    free(hf->h);
    hf->h = NULL;
    /* pyramid levels 1…tile_level in the tiles (mip k−1 = level k), each tile's share of the level; a
     * tile's nodes beyond the level's padded size do not exist (their parents are −inf) */
    int mips = t->tile_level > 0 ? t->tile_level : 1;
    state.height_max_tex = array_texture(px > 1 ? px / 2 : 1, py > 1 ? py / 2 : 1, layers, mips);
    for (int k = 1; k <= t->tile_level; k++) {
        int lw = hf->pw >> k, lh = hf->ph >> k; /* the level's size, at least 1 */
        lw = lw > 0 ? lw : 1, lh = lh > 0 ? lh : 1;
        int nx = px >> k, ny = py >> k; /* nodes per tile */
        nx = nx > 0 ? nx : 1, ny = ny > 0 ? ny : 1;
        for (int ty = 0; ty < t->tiles_y; ty++)
            for (int tx = 0; tx < t->tiles_x; tx++)
                upload_block(hf->max[k], lw, lh, tx * nx, ty * ny, nx, ny, k - 1, ty * t->tiles_x + tx);
    }
    /* the levels above, whole */
    int top = hf->levels - 1 - t->tile_level;
    glGenTextures(1, &state.height_top_tex);
    glBindTexture(GL_TEXTURE_2D, state.height_top_tex);
    float none = -INFINITY;
    for (int m = 0; m < (top > 0 ? top : 1); m++) {
        int k = t->tile_level + 1 + m, lw = hf->pw >> k, lh = hf->ph >> k;
        glTexImage2D(GL_TEXTURE_2D, m, GL_R32F, lw > 0 ? lw : 1, lh > 0 ? lh : 1, 0, GL_RED, GL_FLOAT,
                     top > 0 ? hf->max[k] : &none);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, top > 0 ? top - 1 : 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    heightfield_drop_pyramid(hf); /* on the GPU now */
    err_t fault;
    if (glGetError() == GL_OUT_OF_MEMORY || render_resource_fault(res_heightfield.name, &fault)) {
        int W = hf->width, H = hf->height;
        double mb = 4.0 * (double)t->hx * t->hy * layers / 1048576.0;
        release();
        return err_set(err, "heightmap '%s' (%dx%d): the GPU driver refused its %.0f MB of heights (llvmpipe holds at "
                            "most 1 GB in one texture: about 16384x16384); cut or resample the DEM (gdal_translate "
                            "-outsize)", d.path, W, H, mb);
    }
    fprintf(stderr, "fathom: %s\n", hf->about);
    if (layers > 1)
        fprintf(stderr, "fathom: %d x %d tiles of %d x %d texels\n", t->tiles_x, t->tiles_y, t->hx, t->hy);
    snprintf(state.key, sizeof state.key, "%s", key);
    return true;
}

/* Its units (always), and the loaded heightfield's grid (shaders/terrain/terrain.glsl) when it holds one. */
static void uniforms(const scene *s, const uniform_sink *u, int unit)
{
    (void)s;
    uniform_i(u, "uHeight", unit);
    uniform_i(u, "uHeightMax", unit + 1);
    uniform_i(u, "uHeightMaxTop", unit + 2); /* the pyramid's upper levels, above its tiles */
    if (!state.height_tex)
        return;
    const heightfield *hf = &state.hf;
    const struct terrain_tiles *t = &state.tiles;
    uniform_iv(u, "uTerrainTile", 2, 1, (const int[]){t->hx, t->hy});
    uniform_i(u, "uTerrainTilesX", t->tiles_x);
    uniform_iv(u, "uTerrainTileShift", 2, 1, (const int[]){t->shift_x, t->shift_y});
    uniform_i(u, "uTerrainTileLevel", t->tile_level);
    uniform_fv(u, "uTerrainOrigin", 2, 1, (const float[]){hf->x0, hf->z0});
    uniform_fv(u, "uTerrainSpacing", 2, 1, (const float[]){hf->dx, hf->dz});
    uniform_f(u, "uTerrainHeightMin", hf->hmin);
    uniform_f(u, "uTerrainHeightMax", hf->hmax);
    uniform_f(u, "uTerrainStepScale", 1.0f / sqrtf(1.0f + hf->lipschitz * hf->lipschitz));
    uniform_i(u, "uTerrainTopLevel", hf->levels - 1);
    uniform_iv(u, "uTerrainSize", 2, 1, (const int[]){hf->width, hf->height});
    /* a ray crosses at most pw + ph level-0 cells; each costs an exit and at most a descent, and the
     * walk up and down the pyramid adds a few nodes per level */
    enum { NODES_PER_CELL = 4, NODES_PER_LEVEL = 16 };
    uniform_i(u, "uTerrainMaxNodes", NODES_PER_CELL * (hf->pw + hf->ph) + NODES_PER_LEVEL * hf->levels);
}


static void bind(int unit)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, state.height_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 1);
    glBindTexture(GL_TEXTURE_2D_ARRAY, state.height_max_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 2);
    glBindTexture(GL_TEXTURE_2D, state.height_top_tex);
}

const render_resource res_heightfield = {"heightfield", set, 3, uniforms, bind, release, held};

const heightfield *res_heightfield_loaded(int *tiles_x, int *tiles_y)
{
    if (tiles_x)
        *tiles_x = state.tiles.tiles_x;
    if (tiles_y)
        *tiles_y = state.tiles.tiles_y;
    return state.height_tex ? &state.hf : NULL;
}
