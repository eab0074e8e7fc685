/* res_heightfield_stream — a streamed terrain's traffic (res_heightfield.h): the shader's feedback read
 * back, the tiles it asked for loaded at once (offline shots) or by a loader thread while the window goes on
 * (data/geo/terrain_loader.h), the slots evicted oldest first among the ones the last passes did not use. */
#include <stdlib.h>
#include <string.h>

#include "data/geo/dem.h"
#include "data/geo/terrain_loader.h"
#include "data/geo/terrain_stream.h"
#include "gpu/res_heightfield.h"
#include "gpu/res_heightfield_state.h"

enum { LOADER_QUEUE = 16 }; /* tiles the window's loader reads ahead, and holds ready: 22 MB at most */

static res_heightfield_state *const S = &res_heightfield_now;

void res_heightfield_watch(void)
{
    if (!S->feedback_buf)
        return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); /* after the passes before it, before the ones after */
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, S->feedback_buf);
    unsigned *zero = util_calloc(2 * (size_t)S->words, sizeof(unsigned), "the terrain's feedback");
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(sizeof(unsigned) * 2 * (size_t)S->words), zero);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    free(zero);
}

/* The slot for a new tile: a free one, else the one unused longest among those this pass did not use. */
static int free_slot(const unsigned *used)
{
    int best = -1;
    for (int i = 0; i < S->slots; i++) {
        int t = S->slot_tile[i];
        if (t < 0)
            return i;
        if (!(used[t >> 5] >> (t & 31) & 1u) && (best < 0 || S->slot_used[i] < S->slot_used[best]))
            best = i;
    }
    return best;
}

static bool load_tile(int tile, int slot, err_t *err)
{
    const terrain_grid *g = &S->grid;
    int tx = tile % g->tiles_x, ty = tile / g->tiles_x, x0, y0, w, h;
    terrain_tile_window(g, tx, ty, &x0, &y0, &w, &h);
    unsigned long long before = dem_stream_bytes(S->stream);
    if (!terrain_read_tile(S->stream, g, tx, ty, S->ex, S->tile_buf, err))
        return false;
    S->stats.bytes_read += dem_stream_bytes(S->stream) - before;
    terrain_tile_stats st;
    terrain_tile_build(g, tx, ty, S->tile_buf, S->hf.dx, S->hf.dz, S->level_buf, &st);
    res_heightfield_upload(tile, S->tile_buf, S->level_buf, w, h, slot);
    S->stats.loaded++;
    return true;
}

/* The passes' feedback since the last watch (want: words [0, n), used: [n, 2n); malloc'd), then watches
 * afresh; the slots they used are stamped with this pass, *wanted counts the tiles asked for and absent,
 * *in_use the resident ones used. */
static unsigned *read_feedback(int *wanted, int *in_use)
{
    size_t words = (size_t)S->words;
    unsigned *bits = util_alloc(sizeof(unsigned) * 2 * words, "the terrain's feedback");
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); /* the shaders' writes, seen by the read below */
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, S->feedback_buf);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(sizeof(unsigned) * 2 * words), bits);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    const unsigned *want = bits, *used = bits + words;
    S->pass++;
    *wanted = *in_use = 0;
    for (int t = 0; t < S->tiles; t++) {
        bool u = used[t >> 5] >> (t & 31) & 1u;
        if (u && S->tile_slot[t] >= 0)
            S->slot_used[S->tile_slot[t]] = S->pass, ++*in_use;
        if ((want[t >> 5] >> (t & 31) & 1u) && S->tile_slot[t] < 0)
            ++*wanted;
    }
    S->stats.pending = *wanted;
    res_heightfield_watch();
    return bits;
}

static bool asked(const unsigned *want, int t) { return want[t >> 5] >> (t & 31) & 1u; }

res_heightfield_settled res_heightfield_settle(int max_loads, err_t *err)
{
    if (!S->feedback_buf)
        return TERRAIN_SETTLED;
    int wanted, in_use;
    unsigned *bits = read_feedback(&wanted, &in_use);
    const unsigned *want = bits, *used = bits + S->words;
    res_heightfield_settled r = wanted == 0 ? TERRAIN_SETTLED
                                : wanted + in_use > S->slots ? TERRAIN_OVER_BUDGET : TERRAIN_LOADED;
    int loads = 0;
    for (int t = 0; t < S->tiles && r != TERRAIN_SETTLED && loads < max_loads; t++) {
        if (!asked(want, t) || S->tile_slot[t] >= 0)
            continue;
        int slot = free_slot(used);
        if (slot < 0)
            break;
        if (!load_tile(t, slot, err)) {
            r = TERRAIN_FAILED;
            break;
        }
        S->slot_used[slot] = S->pass;
        loads++;
        S->stats.pending--;
    }
    free(bits);
    return r;
}

res_heightfield_settled res_heightfield_settle_async(int max_uploads, err_t *err)
{
    if (!S->feedback_buf)
        return TERRAIN_SETTLED;
    if (!S->loader && !(S->loader = terrain_loader_start(S->path, &S->grid, S->ex, S->hf.dx,
                                                               S->hf.dz, LOADER_QUEUE, err)))
        return TERRAIN_FAILED;
    int wanted, in_use;
    unsigned *bits = read_feedback(&wanted, &in_use);
    const unsigned *want = bits, *used = bits + S->words;
    for (int t = 0; t < S->tiles; t++)
        if (asked(want, t) && S->tile_slot[t] < 0)
            terrain_loader_ask(S->loader, t);
    int uploads = 0;
    terrain_loaded r;
    while (uploads < max_uploads && terrain_loader_take(S->loader, &r)) {
        int slot = S->tile_slot[r.tile] < 0 ? free_slot(used) : -1;
        if (slot >= 0) { /* else resident already, or no slot this frame: asked again if still wanted */
            res_heightfield_upload(r.tile, r.heights, r.levels, r.w, r.h, slot);
            S->slot_used[slot] = S->pass;
            S->stats.loaded++;
            S->stats.bytes_read += r.bytes;
            uploads++;
        }
        terrain_loader_done(S->loader, &r);
    }
    free(bits);
    S->stats.pending = wanted > uploads ? wanted - uploads : 0;
    if (terrain_loader_failed(S->loader, err))
        return TERRAIN_FAILED;
    return uploads ? TERRAIN_LOADED : wanted ? TERRAIN_PENDING : TERRAIN_SETTLED;
}

bool res_heightfield_streamed(void) { return S->streamed; }

res_heightfield_stats res_heightfield_get_stats(void)
{
    res_heightfield_stats st = S->stats;
    st.slots = S->slots;
    st.tiles = S->tiles;
    st.gpu_bytes = S->slots * 4.0 * ((double)S->grid.slot_w * S->grid.slot_h +
                                        (double)terrain_tile_level_floats(&S->grid));
    st.resident = 0;
    for (int i = 0; i < S->slots; i++)
        st.resident += S->slot_tile && S->slot_tile[i] >= 0;
    return st;
}
