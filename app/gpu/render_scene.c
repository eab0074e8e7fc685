/* render_scene — the scene on the GPU. render_set_scene() hands over a scene; this file keeps its own
 * copy by value (the caller may free or change its scene at once), loads the textures, cube map and
 * heightfield it names, and uploads every uniform by name (scene_uniforms() says which). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "data/droplets.h"
#include "gpu/render.h"
#include "gpu/render_parts.h"
#include "data/terrain.h"
#include "gpu/texture.h"

static struct {
    scene scene; /* a copy, with map_glsl pointing to our own copy of the caller's */
    char *map_glsl;
    bool have_scene;
    GLuint textures[SCENE_MAX_TEXTURES], envmap;
    /* what each texture and the cube map were read from (path, size, mtime; the heights' flag): the
     * next scene reuses a texture read from the same unchanged file (a flight's every frame, preset
     * and knob switches), and a file changed on disk (R reload) is read again */
    char texture_key[SCENE_MAX_TEXTURES][PATH_MAX_LEN + 64];
    char envmap_key[6 * (PATH_MAX_LEN + 64)];
    int texture_width[SCENE_MAX_TEXTURES]; /* heightmaps: texels across (relief step size) */
    int env_size;
    GLuint height_tex, height_max_tex, height_top_tex; /* terrain: heights, max pyramid (tiles, top) */
    struct terrain_tiles {
        int hx, hy;          /* texels per height tile (the whole grid when it fits one texture) */
        int tiles_x, tiles_y;
        int shift_x, shift_y; /* log2 of cells per pyramid tile */
        int tile_level;      /* the highest pyramid level in the tiles; the ones above are in the top */
    } tiles;
    /* the heightfield is kept while the next scene reads the same file the same way (a flight's
     * frames, preset and knob switches): a big DEM is read once; a changed file is read again */
    char hf_key[PATH_MAX_LEN + 160];
    GLuint csg_list_tex, csg_nodes_tex; /* csg: the primitive list and its BVH */
    heightfield hf;
    /* droplets: kept while the next scene names the same file and scale (switching presets or
     * effects does not read a million droplets again) */
    droplets drops;
    char drops_file[PATH_MAX_LEN];
    float drops_scale;
    bool drops_bvh;
    GLuint drops_buf[3], drops_tex[3]; /* spheres, cells (or BVH nodes), index: texture buffers */
    double drops_read_s, drops_grid_s; /* reading the file, building the grid */
} gpu;

static void free_droplets(void)
{
    if (gpu.drops_tex[0]) {
        glDeleteTextures(3, gpu.drops_tex);
        glDeleteBuffers(3, gpu.drops_buf);
    }
    memset(gpu.drops_tex, 0, sizeof gpu.drops_tex);
    memset(gpu.drops_buf, 0, sizeof gpu.drops_buf);
    droplets_free(&gpu.drops);
    gpu.drops_file[0] = '\0';
}

static void free_heightfield(void)
{
    if (gpu.height_tex) {
        glDeleteTextures(1, &gpu.height_tex);
        glDeleteTextures(1, &gpu.height_max_tex);
        glDeleteTextures(1, &gpu.height_top_tex);
        gpu.height_tex = gpu.height_max_tex = gpu.height_top_tex = 0;
        heightfield_free(&gpu.hf);
    }
    gpu.hf_key[0] = '\0';
}

static void free_csg_list(void)
{
    if (gpu.csg_list_tex) {
        glDeleteTextures(1, &gpu.csg_list_tex);
        glDeleteTextures(1, &gpu.csg_nodes_tex);
        gpu.csg_list_tex = gpu.csg_nodes_tex = 0;
    }
}

static void free_textures(void)
{
    free_csg_list();
    glDeleteTextures(SCENE_MAX_TEXTURES, gpu.textures);
    memset(gpu.textures, 0, sizeof gpu.textures);
    memset(gpu.texture_key, 0, sizeof gpu.texture_key);
    if (gpu.envmap)
        glDeleteTextures(1, &gpu.envmap);
    gpu.envmap = 0;
    gpu.envmap_key[0] = '\0';
}

/* Appends "path|bytes|mtime" of a file to a cache key. */
static void file_key(const char *path, char *key, size_t n)
{
    struct stat st = {0};
    stat(path, &st);
    size_t len = strlen(key);
    snprintf(key + len, n - len, "%s|%lld|%lld.%09ld;", path, (long long)st.st_size, (long long)st.st_mtim.tv_sec,
             st.st_mtim.tv_nsec);
}

/* The scene's textures: each reused from the last scene when read from the same unchanged file, else
 * read; the last scene's others are freed. */
static bool set_textures(const scene *s, err_t *err)
{
    GLuint old[SCENE_MAX_TEXTURES];
    char old_key[SCENE_MAX_TEXTURES][sizeof gpu.texture_key[0]];
    int old_width[SCENE_MAX_TEXTURES];
    memcpy(old, gpu.textures, sizeof old);
    memcpy(old_key, gpu.texture_key, sizeof old_key);
    memcpy(old_width, gpu.texture_width, sizeof old_width);
    memset(gpu.textures, 0, sizeof gpu.textures);
    memset(gpu.texture_key, 0, sizeof gpu.texture_key);
    bool ok = true;
    for (int i = 0; ok && i < s->texture_count; i++) {
        char key[sizeof gpu.texture_key[0]] = "";
        snprintf(key, sizeof key, "%d;", s->texture_linear[i]);
        file_key(s->textures[i], key, sizeof key);
        for (int j = 0; j < SCENE_MAX_TEXTURES && !gpu.textures[i]; j++)
            if (old[j] && !strcmp(old_key[j], key)) {
                gpu.textures[i] = old[j], gpu.texture_width[i] = old_width[j];
                old[j] = 0;
            }
        if (!gpu.textures[i]) {
            int w = 0;
            gpu.textures[i] = s->texture_linear[i] ? texture_load_height(s->textures[i], &w, err)
                                                   : texture_load_2d(s->textures[i], err);
            gpu.texture_width[i] = w;
            ok = gpu.textures[i] != 0;
        }
        if (ok)
            snprintf(gpu.texture_key[i], sizeof gpu.texture_key[i], "%s", key);
    }
    for (int j = 0; j < SCENE_MAX_TEXTURES; j++)
        if (old[j])
            glDeleteTextures(1, &old[j]);
    return ok;
}

/* The cube map: kept when its six files are unchanged, else read. */
static bool set_envmap(const scene *s, err_t *err)
{
    char key[sizeof gpu.envmap_key] = "";
    for (int f = 0; f < 6; f++)
        file_key(s->cubemap[f], key, sizeof key);
    if (gpu.envmap && !strcmp(key, gpu.envmap_key))
        return true;
    if (gpu.envmap)
        glDeleteTextures(1, &gpu.envmap);
    gpu.envmap = texture_load_cube(s->cubemap, &gpu.env_size, err);
    snprintf(gpu.envmap_key, sizeof gpu.envmap_key, "%s", gpu.envmap ? key : "");
    return gpu.envmap != 0;
}

void scene_gpu_shutdown(void)
{
    free_textures();
    free_heightfield();
    free_droplets();
    free(gpu.map_glsl);
    memset(&gpu, 0, sizeof gpu);
}

const scene *scene_gpu_current(void) { return gpu.have_scene ? &gpu.scene : NULL; }

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
    if (env && atoi(env) >= 4)
        tile = 1 << log2i(atoi(env));
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

/* Terrain: heights (exact texelFetch, bilinear done in the shader) and the max pyramid, in tiles. */
static bool upload_heightfield(const scene *s, err_t *err)
{
    heightfield_desc d = {.path = s->terrain.heightmap, .spacing = {s->terrain.spacing[0], s->terrain.spacing[1]},
                          .height_min = s->terrain.height_min, .height_max = s->terrain.height_max,
                          .exaggeration = s->terrain.exaggeration, .fill_nodata = s->terrain.fill_nodata};
    char key[sizeof gpu.hf_key];
    snprintf(key, sizeof key, "%.9g %.9g|%.9g %.9g|%.9g|%d|%s;", (double)d.spacing[0], (double)d.spacing[1],
             (double)d.height_min, (double)d.height_max, (double)d.exaggeration, d.fill_nodata,
             getenv("FATHOM_TERRAIN_TILE") ? getenv("FATHOM_TERRAIN_TILE") : "");
    file_key(d.path, key, sizeof key);
    char side[PATH_MAX_LEN]; /* the sidecar (spacing, height range) counts too */
    terrain_sidecar_path(d.path, side, sizeof side);
    file_key(side, key, sizeof key);
    if (gpu.height_tex && !strcmp(key, gpu.hf_key))
        return true;
    free_heightfield();
    if (!heightfield_load(&d, &gpu.hf, err))
        return false;
    heightfield *hf = &gpu.hf;
    struct terrain_tiles *t = &gpu.tiles;
    if (!plan_tiles(hf, t, err)) {
        heightfield_free(hf);
        return false;
    }
    int layers = t->tiles_x * t->tiles_y;
    int px = 1 << t->shift_x, py = 1 << t->shift_y; /* cells per pyramid tile */
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gpu.height_tex = array_texture(t->hx, t->hy, layers, 1);
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
    gpu.height_max_tex = array_texture(px > 1 ? px / 2 : 1, py > 1 ? py / 2 : 1, layers, mips);
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
    glGenTextures(1, &gpu.height_top_tex);
    glBindTexture(GL_TEXTURE_2D, gpu.height_top_tex);
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
    if (glGetError() == GL_OUT_OF_MEMORY) {
        int W = hf->width, H = hf->height;
        double mb = 4.0 * (double)t->hx * t->hy * layers / 1048576.0;
        free_heightfield();
        return err_set(err, "heightmap '%s' (%dx%d): the GPU driver refused its %.0f MB of heights (llvmpipe holds at "
                            "most 1 GB in one texture: about 16384x16384); cut or resample the DEM (gdal_translate "
                            "-outsize)", d.path, W, H, mb);
    }
    fprintf(stderr, "fathom: %s\n", hf->about);
    if (layers > 1)
        fprintf(stderr, "fathom: %d x %d tiles of %d x %d texels\n", t->tiles_x, t->tiles_y, t->hx, t->hy);
    snprintf(gpu.hf_key, sizeof gpu.hf_key, "%s", key);
    return true;
}

/* texels RGBA texels, row-major in rows CSG_TEXTURE_WIDTH wide (shaders/csg/list.glsl). */
static GLuint texel_texture(const float *data, int texels)
{
    int rows = (texels + CSG_TEXTURE_WIDTH - 1) / CSG_TEXTURE_WIDTH;
    float *padded = calloc((size_t)rows * CSG_TEXTURE_WIDTH * 4, sizeof(float));
    if (!padded)
        return 0;
    memcpy(padded, data, sizeof(float) * 4 * (size_t)texels);
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, CSG_TEXTURE_WIDTH, rows, 0, GL_RGBA, GL_FLOAT, padded);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    free(padded);
    return t;
}

/* A texture buffer over `bytes` of data (shaders read it with texelFetch). */
static bool buffer_texture(GLenum format, const void *data, size_t bytes, GLuint *buf, GLuint *tex)
{
    glGenBuffers(1, buf);
    glBindBuffer(GL_TEXTURE_BUFFER, *buf);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)bytes, data, GL_STATIC_DRAW);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    if (glGetError() == GL_OUT_OF_MEMORY)
        return false;
    glGenTextures(1, tex);
    glBindTexture(GL_TEXTURE_BUFFER, *tex);
    glTexBuffer(GL_TEXTURE_BUFFER, format, *buf);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    return true;
}

/* Texels of the second buffer: the grid's cell offsets, or the BVH's nodes (2 texels each). */
static size_t d_cells_or_nodes(const droplets *d)
{
    return d->nodes ? 2 * (size_t)d->node_count : droplets_cell_count(d) + 1;
}

/* Droplets: the file, its grid (or BVH), three texture buffers (app/data/droplets.h). */
static bool upload_droplets(const scene *s, err_t *err)
{
    if (gpu.drops_tex[0] && !strcmp(gpu.drops_file, s->droplets.file) && gpu.drops_scale == s->droplets.scale &&
        gpu.drops_bvh == s->droplets.bvh)
        return true;
    free_droplets();
    double t0 = util_now();
    if (!droplets_read(s->droplets.file, s->droplets.scale, &gpu.drops, err))
        return false;
    double t1 = util_now();
    if (s->droplets.bvh) {
        droplets_build_bvh(&gpu.drops);
    } else if (!droplets_build_grid(&gpu.drops, err)) {
        droplets_free(&gpu.drops);
        return false;
    }
    gpu.drops_read_s = t1 - t0;
    gpu.drops_grid_s = util_now() - t1;
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    size_t cells = d_cells_or_nodes(&gpu.drops);
    if ((size_t)gpu.drops.count > (size_t)max_texels || gpu.drops.refs > (size_t)max_texels || cells > (size_t)max_texels) {
        err_set(err, "droplets file '%s': %d droplets (%zu grid entries) pass this GPU's %d-texel texture buffers; "
                     "thin the data", s->droplets.file, gpu.drops.count, gpu.drops.refs, max_texels);
        free_droplets();
        return false;
    }
    const droplets *d = &gpu.drops;
    if (!buffer_texture(GL_RGBA32F, d->spheres, sizeof(float) * 4 * (size_t)d->count, &gpu.drops_buf[0], &gpu.drops_tex[0]) ||
        !(d->nodes ? buffer_texture(GL_RGBA32UI, d->nodes, sizeof(uint32_t) * 4 * cells, &gpu.drops_buf[1], &gpu.drops_tex[1])
                   : buffer_texture(GL_R32UI, d->cells, sizeof(uint32_t) * cells, &gpu.drops_buf[1], &gpu.drops_tex[1])) ||
        !buffer_texture(GL_R32UI, d->index, sizeof(uint32_t) * (d->refs ? d->refs : 1), &gpu.drops_buf[2], &gpu.drops_tex[2])) {
        err_set(err, "droplets file '%s': the GPU has no room for %d droplets (%.0f MB)", s->droplets.file, d->count,
                (double)droplets_bytes(d) / 1e6);
        free_droplets();
        return false;
    }
    snprintf(gpu.drops_file, sizeof gpu.drops_file, "%s", s->droplets.file);
    gpu.drops_scale = s->droplets.scale;
    gpu.drops_bvh = s->droplets.bvh;
    return true;
}

const droplets *render_droplets(double *read_s, double *grid_s)
{
    if (read_s)
        *read_s = gpu.drops_read_s;
    if (grid_s)
        *grid_s = gpu.drops_grid_s;
    return gpu.drops_tex[0] ? &gpu.drops : NULL;
}

bool scene_gpu_set(const scene *s, err_t *err)
{
    free_csg_list();
    gpu.have_scene = false;
    if (!set_textures(s, err))
        return false;
    if (!s->terrain.heightmap[0])
        free_heightfield();
    else if (!upload_heightfield(s, err))
        return false;
    if (s->csg_list_count > 0) {
        gpu.csg_list_tex = texel_texture(s->csg_list, s->csg_list_count * CSG_LIST_TEXELS);
        gpu.csg_nodes_tex = texel_texture(s->csg_nodes, s->csg_node_count * CSG_NODE_TEXELS);
        if (!gpu.csg_list_tex || !gpu.csg_nodes_tex)
            return err_set(err, "%s: out of memory for %d primitives", s->path, s->csg_list_count);
    }
    if (s->has_droplets && (s->effects & (1u << EFFECT_DROPLETS))) {
        if (!upload_droplets(s, err))
            return false;
    } else {
        free_droplets();
    }
    if (s->has_cubemap && (s->effects & (1u << EFFECT_ENVMAP))) {
        if (!set_envmap(s, err))
            return false;
    } else if (gpu.envmap) {
        glDeleteTextures(1, &gpu.envmap);
        gpu.envmap = 0;
        gpu.envmap_key[0] = '\0';
        gpu.env_size = 0;
    }
    gpu.scene = *s;
    free(gpu.map_glsl);
    gpu.map_glsl = s->map_glsl ? util_strdup(s->map_glsl) : NULL;
    gpu.scene.map_glsl = gpu.map_glsl; /* its own copy: probes of the current scene compile with it */
    gpu.scene.csg_list = gpu.scene.csg_nodes = NULL;
    gpu.have_scene = true;
    return true;
}

/* A uniform_sink that uploads to one GL program; names the program does not use are skipped. */
static void gl_set(void *user, const char *name, uniform_type type, int comps, int count, const void *data)
{
    GLint loc = glGetUniformLocation(*(const GLuint *)user, name);
    if (loc < 0 || count <= 0)
        return;
    const float *f = data;
    const GLint *i = data;
    switch (comps * 2 + (type == UNIFORM_INT)) {
    case 2: glUniform1fv(loc, count, f); break;
    case 3: glUniform1iv(loc, count, i); break;
    case 4: glUniform2fv(loc, count, f); break;
    case 5: glUniform2iv(loc, count, i); break;
    case 6: glUniform3fv(loc, count, f); break;
    case 7: glUniform3iv(loc, count, i); break;
    case 8: glUniform4fv(loc, count, f); break;
    default: glUniform4iv(loc, count, i); break;
    }
}

/* The loaded heightfield's grid (shaders/terrain/terrain.glsl). */
static void heightfield_uniforms(const heightfield *hf, const uniform_sink *u)
{
    uniform_i(u, "uHeight", UNIT_HEIGHT);
    uniform_i(u, "uHeightMax", UNIT_HEIGHT_MAX);
    uniform_i(u, "uHeightMaxTop", UNIT_HEIGHT_TOP);
    const struct terrain_tiles *t = &gpu.tiles;
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

/* What only the loaded textures know: units, the cube map's mip count, relief heightmap widths. */
static void texture_uniforms(const scene *s, const uniform_sink *u)
{
    static const char *const tex_names[SCENE_MAX_TEXTURES] = {"uTex0", "uTex1", "uTex2", "uTex3"};
    for (int i = 0; i < SCENE_MAX_TEXTURES; i++)
        uniform_i(u, tex_names[i], i);
    uniform_i(u, "uEnvMap", UNIT_ENVMAP);
    uniform_i(u, "uCsgList", UNIT_CSG_LIST);
    uniform_i(u, "uCsgNodes", UNIT_CSG_NODES);
    uniform_i(u, "uDroplets", UNIT_DROPLETS);
    uniform_i(u, "uDropletCells", UNIT_DROPLET_CELLS);
    uniform_i(u, "uDropletIndex", UNIT_DROPLET_INDEX);
    uniform_i(u, "uDropletNodes", UNIT_DROPLET_NODES);
    uniform_f(u, "uEnvMaxLod", gpu.env_size > 0 ? log2f((float)gpu.env_size) : 0.0f);
    float texels[SCENE_MAX_MATERIALS];
    for (int i = 0; i < s->material_count; i++)
        texels[i] = s->materials[i].relief >= 0 ? (float)gpu.texture_width[s->materials[i].relief] : 1.0f;
    uniform_fv(u, "uMatReliefTexels", 1, s->material_count, texels);
}

void scene_gpu_uniforms(GLuint prog, const scene *s)
{
    glUseProgram(prog);
    uniform_sink u = {gl_set, &prog};
    scene_uniforms(s, &u);
    /* the GPU side belongs to the current scene: another scene (a probe's) gets only its own values */
    bool current = gpu.have_scene && !strcmp(gpu.scene.path, s->path) &&
                   !strcmp(gpu.scene.terrain.heightmap, s->terrain.heightmap);
    if (!current)
        return;
    texture_uniforms(s, &u);
    if (gpu.height_tex)
        heightfield_uniforms(&gpu.hf, &u);
    if (gpu.drops_tex[0]) { /* the grid (shaders/common/droplets.glsl) */
        const droplets *d = &gpu.drops;
        uniform_fv(&u, "uDropletLo", 3, 1, d->lo);
        uniform_fv(&u, "uDropletHi", 3, 1, d->hi);
        uniform_fv(&u, "uDropletCell", 3, 1, d->cell);
        uniform_iv(&u, "uDropletDims", 3, 1, d->dims);
    }
}

void scene_gpu_bind_textures(void)
{
    for (int i = 0; i < SCENE_MAX_TEXTURES; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, gpu.textures[i]);
    }
    glActiveTexture(GL_TEXTURE0 + UNIT_ENVMAP);
    glBindTexture(GL_TEXTURE_CUBE_MAP, gpu.envmap);
    glActiveTexture(GL_TEXTURE0 + UNIT_HEIGHT);
    glBindTexture(GL_TEXTURE_2D_ARRAY, gpu.height_tex);
    glActiveTexture(GL_TEXTURE0 + UNIT_HEIGHT_MAX);
    glBindTexture(GL_TEXTURE_2D_ARRAY, gpu.height_max_tex);
    glActiveTexture(GL_TEXTURE0 + UNIT_HEIGHT_TOP);
    glBindTexture(GL_TEXTURE_2D, gpu.height_top_tex);
    glActiveTexture(GL_TEXTURE0 + UNIT_CSG_LIST);
    glBindTexture(GL_TEXTURE_2D, gpu.csg_list_tex);
    glActiveTexture(GL_TEXTURE0 + UNIT_CSG_NODES);
    glBindTexture(GL_TEXTURE_2D, gpu.csg_nodes_tex);
    for (int i = 0; i < 3; i++) {
        glActiveTexture(GL_TEXTURE0 + UNIT_DROPLETS + (GLenum)i);
        glBindTexture(GL_TEXTURE_BUFFER, gpu.drops_tex[i]);
    }
    glActiveTexture(GL_TEXTURE0 + UNIT_DROPLET_NODES); /* the BVH's nodes, in the cells' buffer */
    glBindTexture(GL_TEXTURE_BUFFER, gpu.drops_tex[1]);
    glActiveTexture(GL_TEXTURE0);
}

void render_release_scene(void)
{
    free_textures();
    free_heightfield();
    free_droplets();
    gpu.have_scene = false;
}

bool render_terrain_tiles(int *tiles_x, int *tiles_y)
{
    *tiles_x = gpu.tiles.tiles_x;
    *tiles_y = gpu.tiles.tiles_y;
    return gpu.height_tex != 0;
}

bool render_ground_height(float x, float z, float *height)
{
    if (!gpu.height_tex || !gpu.have_scene)
        return false;
    /* the terrain's map() at height 0 is −h · (its slope bound): probed on the GPU, the heights' home */
    float p[3] = {x, 0.0f, z}, out[2];
    err_t e;
    if (!render_probe(&gpu.scene, NULL, p, 1, out, &e))
        return false;
    float h = -out[0] * sqrtf(1.0f + gpu.hf.lipschitz * gpu.hf.lipschitz);
    if (!isfinite(h) || TERRAIN_IS_HOLE(h)) /* over a nodata hole: no ground */
        return false;
    *height = h;
    return true;
}
