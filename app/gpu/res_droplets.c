/* res_droplets — a spray's droplets on the GPU: the spheres, their grid (or BVH) and its index as
 * texture buffers (shaders/common/droplets.glsl). Kept while the next scene names the same file and
 * scale (switching presets or effects does not read a million droplets again). */
#include "gpu/res_droplets.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "gpu/texture.h"

static struct {
    droplets drops;
    char file[PATH_MAX_LEN];
    float scale;
    bool bvh;
    GLuint buf[3], tex[3];  /* spheres, cells (or BVH nodes), index: texture buffers */
    double read_s, grid_s;  /* reading the file, building the grid */
} state;

static void release(void)
{
    glDeleteTextures(3, state.tex); /* 0 names are ignored: a half-made upload is freed too */
    glDeleteBuffers(3, state.buf);
    droplets_free(&state.drops);
    memset(&state, 0, sizeof state);
}

static int held(void)
{
    int n = 0;
    for (int i = 0; i < 3; i++)
        n += (state.tex[i] != 0) + (state.buf[i] != 0);
    return n;
}

/* Texels of the second buffer: the grid's cell offsets, or the BVH's nodes (2 texels each). */
static size_t d_cells_or_nodes(const droplets *d)
{
    return d->nodes ? 2 * (size_t)d->node_count : droplets_cell_count(d) + 1;
}

/* The file, its grid (or BVH), three texture buffers (app/data/droplets/droplets.h). */
static bool set(const scene *s, err_t *err)
{
    if (!s->has_droplets || !(s->effects & (1u << EFFECT_DROPLETS))) {
        release();
        return true;
    }
    if (state.tex[0] && !strcmp(state.file, s->droplets.file) && state.scale == s->droplets.scale &&
        state.bvh == s->droplets.bvh)
        return true;
    release();
    double t0 = util_now();
    if (!droplets_read(s->droplets.file, s->droplets.scale, &state.drops, err))
        return false;
    double t1 = util_now();
    if (s->droplets.bvh) {
        droplets_build_bvh(&state.drops);
    } else if (!droplets_build_grid(&state.drops, err)) {
        droplets_free(&state.drops);
        return false;
    }
    state.read_s = t1 - t0;
    state.grid_s = util_now() - t1;
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    size_t cells = d_cells_or_nodes(&state.drops);
    if ((size_t)state.drops.count > (size_t)max_texels || state.drops.refs > (size_t)max_texels || cells > (size_t)max_texels) {
        err_set(err, "droplets file '%s': %d droplets (%zu grid entries) pass this GPU's %d-texel texture buffers; "
                     "thin the data", s->droplets.file, state.drops.count, state.drops.refs, max_texels);
        release();
        return false;
    }
    const droplets *d = &state.drops;
    if (!texture_buffer(GL_RGBA32F, d->spheres, sizeof(float) * 4 * (size_t)d->count, &state.buf[0], &state.tex[0]) ||
        render_resource_fault(res_droplets.name, err) ||
        !(d->nodes ? texture_buffer(GL_RGBA32UI, d->nodes, sizeof(uint32_t) * 4 * cells, &state.buf[1], &state.tex[1])
                   : texture_buffer(GL_R32UI, d->cells, sizeof(uint32_t) * cells, &state.buf[1], &state.tex[1])) ||
        !texture_buffer(GL_R32UI, d->index, sizeof(uint32_t) * (d->refs ? d->refs : 1), &state.buf[2], &state.tex[2])) {
        err_set(err, "droplets file '%s': the GPU has no room for %d droplets (%.0f MB)", s->droplets.file, d->count,
                (double)droplets_bytes(d) / 1e6);
        release();
        return false;
    }
    snprintf(state.file, sizeof state.file, "%s", s->droplets.file);
    state.scale = s->droplets.scale;
    state.bvh = s->droplets.bvh;
    return true;
}

/* The units always (the shaders declare the samplers), the grid when loaded. */
static void uniforms(const scene *s, const uniform_sink *u, int unit)
{
    (void)s;
    uniform_i(u, "uDroplets", unit);
    uniform_i(u, "uDropletCells", unit + 1);
    uniform_i(u, "uDropletIndex", unit + 2);
    uniform_i(u, "uDropletNodes", unit + 3);
    if (!state.tex[0])
        return;
    const droplets *d = &state.drops;
    uniform_fv(u, "uDropletLo", 3, 1, d->lo);
    uniform_fv(u, "uDropletHi", 3, 1, d->hi);
    uniform_fv(u, "uDropletCell", 3, 1, d->cell);
    uniform_iv(u, "uDropletDims", 3, 1, d->dims);
}

static void bind(int unit)
{
    for (int i = 0; i < 3; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)(unit + i));
        glBindTexture(GL_TEXTURE_BUFFER, state.tex[i]);
    }
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 3); /* the BVH's nodes, in the cells' buffer */
    glBindTexture(GL_TEXTURE_BUFFER, state.tex[1]);
}

const render_resource res_droplets = {"droplets", set, 4, uniforms, bind, release, held};

const droplets *res_droplets_loaded(double *read_s, double *grid_s)
{
    if (read_s)
        *read_s = state.read_s;
    if (grid_s)
        *grid_s = state.grid_s;
    return state.tex[0] ? &state.drops : NULL;
}
