/* mesh_sample — the field sampled for the extractor (data/mesh/mesh.h): clipped by the box, a layer at a
 * time, blocks the distance bound proves empty left unevaluated. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "data/mesh/mesh_internal.h"

double mesh_box_distance(const double lo[3], const double hi[3], const float p[3])
{
    double out = 0, in = -1e300;
    for (int k = 0; k < 3; k++) {
        double q = fabs(p[k] - 0.5 * (lo[k] + hi[k])) - 0.5 * (hi[k] - lo[k]);
        out += q > 0 ? q * q : 0;
        in = fmax(in, q);
    }
    return sqrt(out) + fmin(in, 0.0);
}

static double box_distance(const mesh_ctx *c, const float p[3])
{
    return mesh_box_distance(c->g->lo, c->g->hi, p);
}

void mesh_reserve(mesh_ctx *c, size_t n)
{
    if (n <= c->pts_cap)
        return;
    c->pts_cap = n + n / 2;
    c->pts = util_realloc(c->pts, c->pts_cap * 3 * sizeof(float), "mesh probe points");
    c->dst = util_realloc(c->dst, c->pts_cap * sizeof(float), "mesh probe values");
}

bool mesh_eval(mesh_ctx *c, size_t n, bool raw, err_t *err)
{
    for (size_t at = 0; at < n; at += CHUNK) {
        size_t k = n - at < CHUNK ? n - at : CHUNK;
        if (!c->g->field(c->g->user, c->pts + 3 * at, k, c->dst + at, err))
            return false;
    }
    for (size_t i = 0; i < n && !raw; i++) {
        double f = (double)c->dst[i] - c->g->iso, b = box_distance(c, c->pts + 3 * i);
        c->dst[i] = (float)(isnan(f) ? b : fmax(f, b)); /* NaN: outside (a field's guard failed: not a surface) */
    }
    return true;
}

void mesh_sample_pos(const mesh_ctx *c, int i, int j, int k, double p[3])
{
    p[0] = c->o[0] + i * c->h;
    p[1] = c->o[1] + j * c->h;
    p[2] = c->o[2] + k * c->h;
}

/* Which blocks of slab s the surface may cross: the box's distance, then the field's bound, at each
 * block's centre against its half diagonal. */
static bool slab_blocks(mesh_ctx *c, int s, uint8_t *visit, err_t *err)
{
    double r = MESH_BLOCK * c->h * sqrt(3.0) / 2 * 1.001;
    size_t nb = (size_t)c->nb[0] * (size_t)c->nb[1], m = 0;
    mesh_reserve(c, nb);
    int32_t *slot = util_alloc(nb * sizeof *slot, "mesh blocks");
    for (int by = 0; by < c->nb[1]; by++)
        for (int bx = 0; bx < c->nb[0]; bx++) {
            size_t b = (size_t)by * (size_t)c->nb[0] + (size_t)bx;
            int id[3] = {bx, by, s};
            float centre[3];
            for (int k = 0; k < 3; k++) {
                double lo = id[k] * MESH_BLOCK, hi = fmin(lo + MESH_BLOCK, c->n[k]);
                centre[k] = (float)(c->o[k] + 0.5 * (lo + hi) * c->h);
            }
            visit[b] = box_distance(c, centre) <= r;
            slot[b] = -1;
            if (visit[b] && c->g->step > 0) {
                memcpy(c->pts + 3 * m, centre, sizeof centre);
                slot[b] = (int32_t)m++;
            }
        }
    bool ok = mesh_eval(c, m, true, err);
    for (size_t b = 0; ok && b < nb; b++) {
        if (slot[b] >= 0)
            visit[b] = !((c->dst[slot[b]] - c->g->iso) * c->g->step > r);
        c->st->blocks++;
        c->st->skipped += !visit[b];
    }
    free(slot);
    return ok;
}

static bool blocks_of(mesh_ctx *c, int s, const uint8_t **out, err_t *err)
{
    for (int i = 0; i < 2; i++)
        if (c->visit_slab[i] == s) {
            *out = c->visit[i];
            return true;
        }
    int i = c->visit_slab[0] < c->visit_slab[1] ? 0 : 1; /* the older slab's slot */
    c->visit_slab[i] = s;
    *out = c->visit[i];
    return slab_blocks(c, s, c->visit[i], err);
}

/* Sample layer k: every sample of a visited block evaluated, the rest filled. */
bool mesh_sample_layer(mesh_ctx *c, int k, err_t *err)
{
    int nx = c->n[0], ny = c->n[1], W = nx + 1;
    memset(c->mark, 0, c->P);
    for (int s = k / MESH_BLOCK - (k % MESH_BLOCK == 0); s <= k / MESH_BLOCK; s++) {
        if (s < 0 || s >= c->nb[2])
            continue;
        const uint8_t *visit;
        if (!blocks_of(c, s, &visit, err))
            return false;
        for (int by = 0; by < c->nb[1]; by++)
            for (int bx = 0; bx < c->nb[0]; bx++) {
                if (!visit[(size_t)by * (size_t)c->nb[0] + (size_t)bx])
                    continue;
                int x1 = bx * MESH_BLOCK + MESH_BLOCK, y1 = by * MESH_BLOCK + MESH_BLOCK;
                for (int j = by * MESH_BLOCK; j <= (y1 < ny ? y1 : ny); j++)
                    memset(c->mark + (size_t)j * (size_t)W + (size_t)bx * MESH_BLOCK, 1,
                           (size_t)((x1 < nx ? x1 : nx) - bx * MESH_BLOCK + 1));
            }
    }
    size_t m = 0;
    mesh_reserve(c, c->P);
    for (size_t i = 0; i < c->P; i++)
        if (c->mark[i]) {
            float *p = c->pts + 3 * m++;
            p[0] = (float)(c->o[0] + (double)(i % (size_t)W) * c->h);
            p[1] = (float)(c->o[1] + (double)(i / (size_t)W) * c->h);
            p[2] = (float)(c->o[2] + k * c->h);
        }
    if (!mesh_eval(c, m, false, err))
        return false;
    float *v = c->val[k % 3];
    for (size_t i = 0, at = 0; i < c->P; i++)
        v[i] = c->mark[i] ? c->dst[at++] : c->fill;
    c->st->evaluated += (long long)m;
    return true;
}

