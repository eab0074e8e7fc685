/* mesh — dual contouring of a distance field in layers, sparse by blocks (data/mesh/mesh.h). */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "data/mesh/mesh_internal.h"

/* A crossing on the edge from a to b (values fa, fb of opposite signs), by linear interpolation. */
static int32_t add_crossing(mesh_ctx *c, xbuf *x, const double a[3], float fa, const double b[3], float fb)
{
    if (x->n == x->cap) {
        x->cap = x->cap ? 2 * x->cap : 4096;
        x->c = util_realloc(x->c, x->cap * sizeof *x->c, "mesh crossings");
        x->bracket = util_realloc(x->bracket, x->cap * sizeof *x->bracket, "mesh crossings");
    }
    float *br = x->bracket[x->n];
    double t = fa / ((double)fa - fb);
    for (int k = 0; k < 3; k++) {
        br[k] = (float)a[k];
        br[4 + k] = (float)b[k];
        x->c[x->n].p[k] = (float)(a[k] + t * (b[k] - a[k]));
    }
    br[3] = fa;
    br[7] = fb;
    br[8] = 0;
    c->st->crossings++;
    c->st->unbounded += fa == c->fill || fb == c->fill;
    return (int32_t)x->n++;
}

/* Each crossing located by the Illinois variant of regula falsi (Dowell & Jarratt 1971: the end kept
 * twice in a row has its value halved, so a curved field converges too), then its normal by central
 * differences. */
static bool resolve(mesh_ctx *c, xbuf *x, err_t *err)
{
    size_t n = x->n;
    mesh_reserve(c, 6 * n);
    for (int round = 0; round < MESH_ROUNDS; round++) {
        for (size_t i = 0; i < n; i++)
            memcpy(c->pts + 3 * i, x->c[i].p, sizeof x->c[i].p);
        if (!mesh_eval(c, n, false, err))
            return false;
        for (size_t i = 0; i < n; i++) {
            float *br = x->bracket[i], fq = c->dst[i];
            int side = (fq < 0) == (br[3] < 0) ? 0 : 4; /* the end with fq's sign moves to the point */
            memcpy(br + side, x->c[i].p, sizeof(float) * 3);
            br[side + 3] = fq;
            if (br[8] == (float)(side + 1)) /* the other end kept twice: halve its value */
                br[7 - side] *= 0.5f;
            br[8] = (float)(side + 1);
            double t = br[3] / ((double)br[3] - br[7]);
            for (int k = 0; k < 3; k++)
                x->c[i].p[k] = (float)(br[k] + t * (br[4 + k] - br[k]));
        }
    }
    float e = (float)(0.05 * c->h);
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 6; d++) {
            float *p = c->pts + 3 * (6 * i + (size_t)d);
            memcpy(p, x->c[i].p, sizeof(float) * 3);
            p[d / 2] += d & 1 ? -e : e;
        }
    if (!mesh_eval(c, 6 * n, false, err))
        return false;
    for (size_t i = 0; i < n; i++) {
        const float *f = c->dst + 6 * i;
        float g[3] = {f[0] - f[1], f[2] - f[3], f[4] - f[5]};
        float len = sqrtf(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        for (int k = 0; k < 3; k++) /* no gradient (a flat field): the edge's own direction */
            x->c[i].n[k] = len > 0 && isfinite(len) ? g[k] / len : (float)(x->bracket[i][4 + k] != x->bracket[i][k]);
    }
    return true;
}

/* An edge whose ends have one sign and values summing below a voxel over the step factor may hold a
 * feature thinner than a voxel (its ends both within a voxel of a surface): its midpoint is checked. */
static void thin_candidate(mesh_ctx *c, const double a[3], float fa, const double b[3], float fb)
{
    if (!(fabsf(fa) + fabsf(fb) < c->h / (c->g->step > 0 ? c->g->step : 1)) || fa == c->fill || fb == c->fill)
        return;
    if (c->mid_n == c->mid_cap) {
        c->mid_cap = c->mid_cap ? 2 * c->mid_cap : 4096;
        c->mid = util_realloc(c->mid, c->mid_cap * sizeof *c->mid, "mesh thin features");
    }
    float *m = c->mid[c->mid_n++];
    for (int k = 0; k < 3; k++)
        m[k] = (float)(0.5 * (a[k] + b[k]));
    m[3] = fa < 0 ? -1.0f : 1.0f;
}

/* The candidates' midpoints evaluated: those of the other sign are features the grid misses. */
static bool thin_check(mesh_ctx *c, err_t *err)
{
    mesh_reserve(c, c->mid_n);
    for (size_t i = 0; i < c->mid_n; i++)
        memcpy(c->pts + 3 * i, c->mid[i], 3 * sizeof(float));
    if (!mesh_eval(c, c->mid_n, false, err))
        return false;
    for (size_t i = 0; i < c->mid_n; i++)
        c->st->thin += (c->dst[i] < 0) != (c->mid[i][3] < 0);
    c->mid_n = 0;
    return true;
}

/* The crossings of plane k's x and y edges. */
static bool plane_crossings(mesh_ctx *c, int k, err_t *err)
{
    int W = c->n[0] + 1;
    xbuf *x = &c->plane[k % 3];
    x->n = 0;
    const float *v = c->val[k % 3];
    int32_t *xe = c->xe[k % 3], *ye = c->ye[k % 3];
    for (int j = 0; j <= c->n[1]; j++)
        for (int i = 0; i <= c->n[0]; i++) {
            size_t s = (size_t)j * (size_t)W + (size_t)i;
            double a[3], b[3];
            mesh_sample_pos(c, i, j, k, a);
            xe[s] = ye[s] = -1;
            if (i < c->n[0]) {
                mesh_sample_pos(c, i + 1, j, k, b);
                if ((v[s] < 0) != (v[s + 1] < 0))
                    xe[s] = add_crossing(c, x, a, v[s], b, v[s + 1]);
                else
                    thin_candidate(c, a, v[s], b, v[s + 1]);
            }
            if (j < c->n[1]) {
                mesh_sample_pos(c, i, j + 1, k, b);
                if ((v[s] < 0) != (v[s + (size_t)W] < 0))
                    ye[s] = add_crossing(c, x, a, v[s], b, v[s + (size_t)W]);
                else
                    thin_candidate(c, a, v[s], b, v[s + (size_t)W]);
            }
        }
    return resolve(c, x, err) && thin_check(c, err);
}

/* The crossings of the z edges between planes k and k + 1. */
static bool slab_crossings(mesh_ctx *c, int k, err_t *err)
{
    int W = c->n[0] + 1;
    xbuf *x = &c->slab[k % 2];
    x->n = 0;
    const float *v0 = c->val[k % 3], *v1 = c->val[(k + 1) % 3];
    int32_t *ze = c->ze[k % 2];
    for (int j = 0; j <= c->n[1]; j++)
        for (int i = 0; i <= c->n[0]; i++) {
            size_t s = (size_t)j * (size_t)W + (size_t)i;
            ze[s] = -1;
            double a[3], b[3];
            mesh_sample_pos(c, i, j, k, a);
            mesh_sample_pos(c, i, j, k + 1, b);
            if ((v0[s] < 0) != (v1[s] < 0))
                ze[s] = add_crossing(c, x, a, v0[s], b, v1[s]);
            else
                thin_candidate(c, a, v0[s], b, v1[s]);
        }
    return resolve(c, x, err) && thin_check(c, err);
}

/* Cell (i, j, k)'s edge e: its crossing. */
static const crossing *edge_crossing(const mesh_ctx *c, int i, int j, int k, int e)
{
    int a = e / 4, u = e & 1, v = e >> 1 & 1, W = c->n[0] + 1;
    int32_t id;
    if (a == 0)
        id = c->xe[(k + v) % 3][(size_t)(j + u) * (size_t)W + (size_t)i];
    else if (a == 1)
        id = c->ye[(k + v) % 3][(size_t)j * (size_t)W + (size_t)(i + u)];
    else
        id = c->ze[k % 2][(size_t)(j + v) * (size_t)W + (size_t)(i + u)];
    const xbuf *x = a == 2 ? &c->slab[k % 2] : &c->plane[(k + v) % 3];
    return id >= 0 ? &x->c[id] : NULL;
}

/* Patch p of cell (i, j, k) (corner lo): its vertex by the quadric of its crossings, its normal their mean. */
static void patch_vertex(mesh_ctx *c, const mesh_cell_case *kc, int p, int i, int j, int k, const double lo[3])
{
    float pt[12][3], nm[12][3], sum[3] = {0, 0, 0}, out[3];
    int n = 0;
    for (int e = 0; e < 12; e++)
        if (kc->patch_of[e] == p) {
            const crossing *x = edge_crossing(c, i, j, k, e);
            if (!x) /* (a patch's edge always crosses: no crossing would be a table's bug) */
                continue;
            memcpy(pt[n], x->p, sizeof pt[n]);
            memcpy(nm[n], x->n, sizeof nm[n]);
            for (int d = 0; d < 3; d++)
                sum[d] += x->n[d];
            n++;
        }
    if (c->m->nv == c->mass_cap) {
        c->mass_cap = c->mass_cap ? 2 * c->mass_cap : 4096;
        c->mass = util_realloc(c->mass, c->mass_cap * 3 * sizeof(float), "mesh mass points");
    }
    for (int d = 0; d < 3; d++) {
        double m = 0;
        for (int q = 0; q < n; q++)
            m += (double)pt[q][d] / n;
        c->mass[3 * c->m->nv + (size_t)d] = (float)m;
    }
    bool clamped;
    mesh_qef_solve((const float(*)[3])pt, (const float(*)[3])nm, n, lo, c->h, out, &clamped);
    c->st->clamped += clamped;
    float len = sqrtf(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    for (int d = 0; d < 3; d++)
        sum[d] = len > 0 ? sum[d] / len : 0;
    mesh_add_vertex(c->m, out, sum);
}

/* Cell layer k's corner signs (between sample layers k and k + 1). */
static void cell_configs(mesh_ctx *c, int k)
{
    int W = c->n[0] + 1;
    for (int j = 0; j < c->n[1]; j++)
        for (int i = 0; i < c->n[0]; i++) {
            int cfg = 0;
            for (int q = 0; q < 8; q++) {
                size_t s = (size_t)(j + (q >> 1 & 1)) * (size_t)W + (size_t)(i + (q & 1));
                cfg |= (c->val[(k + (q >> 2)) % 3][s] < 0) << q;
            }
            c->cfg[k % 3][(size_t)j * (size_t)c->n[0] + (size_t)i] = (uint8_t)cfg;
        }
}

/* Cell (i, j, k)'s faces to flip: those whose two segments one patch holds on both sides (mesh_case).
 * Needs cell layers k − 1 and k + 1's corner signs. */
static int flips_of(const mesh_ctx *c, int i, int j, int k)
{
    const uint8_t *here = c->cfg[k % 3];
    size_t nx = (size_t)c->n[0], cell = (size_t)j * nx + (size_t)i;
    int twice = mesh_case(here[cell], 0)->twice, flips = 0;
    for (int f = 0; f < 6 && twice; f++) {
        if (!(twice >> f & 1))
            continue;
        int a = f / 2, d = f & 1 ? 1 : -1, ni = i + (a == 0) * d, nj = j + (a == 1) * d, nk = k + (a == 2) * d;
        if (ni < 0 || nj < 0 || nk < 0 || ni >= c->n[0] || nj >= c->n[1] || nk >= c->n[2])
            continue;
        int other = c->cfg[nk % 3][(size_t)nj * nx + (size_t)ni];
        flips |= (mesh_case(other, 0)->twice >> (f ^ 1) & 1) << f;
    }
    return flips;
}

/* The vertices of cell layer k (from first on) moved onto the level along their normals, MESH_PROJECT
 * steps of the field's value, each kept in its cell: where the quadric's point is off a curved or
 * rough level (a fractal's), the vertex lands on it; where it is on it (a sharp edge), nothing moves. */
static bool project(mesh_ctx *c, int k, size_t first, err_t *err)
{
    size_t n = c->m->nv - first;
    mesh_reserve(c, n);
    for (int round = 0; round < MESH_PROJECT && n; round++) {
        memcpy(c->pts, c->m->pos + 3 * first, n * 3 * sizeof(float));
        if (!mesh_eval(c, n, false, err))
            return false;
        for (size_t v = 0; v < n; v++) {
            float *p = c->m->pos + 3 * (first + v);
            const float *nm = c->m->nrm + 3 * (first + v);
            double lo[3];
            mesh_sample_pos(c, c->cell_of[v][0], c->cell_of[v][1], k, lo);
            for (int d = 0; d < 3; d++)
                p[d] = (float)fmin(fmax(p[d] - c->dst[v] * nm[d], lo[d]), lo[d] + c->h);
        }
    }
    return true;
}

/* Cell layer k (between planes k and k + 1): a vertex for each patch of each cell. */
static bool cell_layer(mesh_ctx *c, int k, err_t *err)
{
    size_t first = c->m->nv;
    for (int j = 0; j < c->n[1]; j++)
        for (int i = 0; i < c->n[0]; i++) {
            size_t cell = (size_t)j * (size_t)c->n[0] + (size_t)i;
            int cfg = c->cfg[k % 3][cell], flips = cfg && cfg != 255 ? flips_of(c, i, j, k) : 0;
            c->flips[k & 1][cell] = (uint8_t)flips;
            c->first[k & 1][cell] = -1;
            const mesh_cell_case *kc = mesh_case(cfg, flips);
            if (!kc->patches)
                continue;
            c->first[k & 1][cell] = (int32_t)c->m->nv;
            double lo[3];
            mesh_sample_pos(c, i, j, k, lo);
            for (int p = 0; p < kc->patches; p++) {
                size_t v = c->m->nv - first;
                if (v == c->cell_cap) {
                    c->cell_cap = c->cell_cap ? 2 * c->cell_cap : 4096;
                    c->cell_of = util_realloc(c->cell_of, c->cell_cap * sizeof *c->cell_of, "mesh cells");
                }
                c->cell_of[v][0] = i;
                c->cell_of[v][1] = j;
                patch_vertex(c, kc, p, i, j, k, lo);
            }
        }
    return project(c, k, first, err);
}

/* The quad of the edge along axis a at sample (i, j) of plane or slab k: the four cells around it,
 * counter-clockwise seen from +a, reversed when the edge runs from outside to inside. */
static void quad(mesh_ctx *c, int a, int i, int j, int k, bool inside_first)
{
    static const int ring[4][2] = {{-1, -1}, {0, -1}, {0, 0}, {-1, 0}};
    uint32_t v[4];
    for (int r = 0; r < 4; r++) {
        int ob = ring[r][0], oc = ring[r][1], ci = i, cj = j, ck = k, e;
        if (a == 0) { /* b = y, c = z */
            cj += ob, ck += oc, e = -ob + 2 * -oc;
        } else if (a == 1) { /* b = z, c = x */
            ck += ob, ci += oc, e = 4 + -oc + 2 * -ob;
        } else { /* b = x, c = y */
            ci += ob, cj += oc, e = 8 + -ob + 2 * -oc;
        }
        size_t cell = (size_t)cj * (size_t)c->n[0] + (size_t)ci;
        const mesh_cell_case *kc = mesh_case(c->cfg[ck % 3][cell], c->flips[ck & 1][cell]);
        v[r] = (uint32_t)(c->first[ck & 1][cell] + kc->patch_of[e]);
    }
    if (!inside_first) {
        uint32_t t = v[1];
        v[1] = v[3];
        v[3] = t;
    }
    int s = mesh_split_of(c->m, v);
    mesh_add_triangle(c->m, v[s], v[s + 1], v[(s + 2) % 4]);
    mesh_add_triangle(c->m, v[s], v[(s + 2) % 4], v[(s + 3) % 4]);
}

/* The quads of slab k's z edges and, k > 0, of plane k's x and y edges. */
static void quads(mesh_ctx *c, int k)
{
    int W = c->n[0] + 1;
    for (int j = 0; j <= c->n[1]; j++) /* (the outermost samples lie outside the box: no crossing has a side */
        for (int i = 0; i <= c->n[0]; i++) { /* without cells) */
            size_t s = (size_t)j * (size_t)W + (size_t)i;
            bool inside = c->val[k % 3][s] < 0, mid_i = i > 0 && i < c->n[0], mid_j = j > 0 && j < c->n[1];
            if (c->ze[k % 2][s] >= 0 && mid_i && mid_j)
                quad(c, 2, i, j, k, inside);
            if (k == 0)
                continue;
            if (c->xe[k % 3][s] >= 0 && mid_j)
                quad(c, 0, i, j, k, inside);
            if (c->ye[k % 3][s] >= 0 && mid_i)
                quad(c, 1, i, j, k, inside);
        }
}

static void ctx_free(mesh_ctx *c)
{
    free(c->mass);
    for (int i = 0; i < 3; i++) {
        free(c->val[i]);
        free(c->xe[i]);
        free(c->ye[i]);
        free(c->cfg[i]);
        free(c->plane[i].c);
        free(c->plane[i].bracket);
    }
    for (int i = 0; i < 2; i++) {
        free(c->first[i]);
        free(c->flips[i]);
        free(c->visit[i]);
        free(c->ze[i]);
        free(c->slab[i].c);
        free(c->slab[i].bracket);
    }
    free(c->mark);
    free(c->cell_of);
    free(c->mid);
    free(c->pts);
    free(c->dst);
}

static bool ctx_init(mesh_ctx *c, const mesh_grid *g, mesh *out, mesh_stats *st, err_t *err)
{
    double ext = 0;
    for (int k = 0; k < 3; k++) {
        if (!(g->hi[k] > g->lo[k]) || !isfinite(g->hi[k] - g->lo[k]))
            return err_set(err, "mesh: the box's side %d is empty (%g to %g)", k, g->lo[k], g->hi[k]);
        ext = fmax(ext, g->hi[k] - g->lo[k]);
    }
    if (g->res < 2 || g->res > MESH_MAX_RES)
        return err_set(err, "mesh: resolution %d is out of range: 2 to %d cells along the longest side", g->res,
                       MESH_MAX_RES);
    *c = (mesh_ctx){.g = g, .h = ext / g->res, .m = out, .st = st, .visit_slab = {-1, -1}};
    for (int k = 0; k < 3; k++) { /* a cell of margin on each side: the outermost samples lie outside the box */
        c->n[k] = (int)ceil((g->hi[k] - g->lo[k]) / c->h - 1e-9) + 2;
        c->o[k] = g->lo[k] - c->h;
        c->nb[k] = (c->n[k] + MESH_BLOCK - 1) / MESH_BLOCK;
        st->cells[k] = c->n[k];
    }
    c->fill = (float)(MESH_BLOCK * c->h);
    c->P = (size_t)(c->n[0] + 1) * (size_t)(c->n[1] + 1);
    size_t cells = (size_t)c->n[0] * (size_t)c->n[1], blocks = (size_t)c->nb[0] * (size_t)c->nb[1];
    for (int i = 0; i < 3; i++) {
        c->val[i] = util_alloc(c->P * sizeof(float), "mesh samples");
        c->xe[i] = util_alloc(c->P * sizeof(int32_t), "mesh crossings");
        c->ye[i] = util_alloc(c->P * sizeof(int32_t), "mesh crossings");
        c->cfg[i] = util_calloc(cells, 1, "mesh cells");
    }
    for (int i = 0; i < 2; i++) {
        c->first[i] = util_alloc(cells * sizeof(int32_t), "mesh cells");
        c->flips[i] = util_alloc(cells, "mesh cells");
        c->visit[i] = util_alloc(blocks, "mesh blocks");
        c->ze[i] = util_alloc(c->P * sizeof(int32_t), "mesh crossings");
    }
    c->mark = util_alloc(c->P, "mesh samples");
    st->voxel = c->h;
    st->samples = (long long)c->P * (c->n[2] + 1);
    return true;
}

/* The layers' own arrays (ctx_init's): samples, crossings, cell configurations, block visits. */
static size_t layer_bytes(const int n[3], const int nb[3])
{
    size_t P = (size_t)(n[0] + 1) * (size_t)(n[1] + 1), cells = (size_t)n[0] * (size_t)n[1];
    return 3 * (P * 12 + cells) + 2 * (P * 4 + cells * 5 + (size_t)nb[0] * (size_t)nb[1]) + P;
}

bool mesh_extract_size(const mesh_grid *g, double *samples, double *bytes)
{
    double ext = 0;
    for (int k = 0; k < 3; k++)
        ext = fmax(ext, g->hi[k] - g->lo[k]);
    if (!(ext > 0) || g->res < 2 || g->res > MESH_MAX_RES)
        return false;
    int n[3], nb[3];
    *samples = 1;
    for (int k = 0; k < 3; k++) { /* as ctx_init counts them */
        n[k] = (int)ceil((g->hi[k] - g->lo[k]) / (ext / g->res) - 1e-9) + 2;
        nb[k] = (n[k] + MESH_BLOCK - 1) / MESH_BLOCK;
        *samples *= n[k] + 1;
    }
    *bytes = (double)layer_bytes(n, nb);
    return true;
}

static size_t ctx_bytes(const mesh_ctx *c)
{
    size_t fixed = layer_bytes(c->n, c->nb);
    size_t xb = (c->plane[0].cap + c->plane[1].cap + c->plane[2].cap + c->slab[0].cap + c->slab[1].cap) *
                (sizeof(crossing) + sizeof(float[9]));
    return fixed + xb + c->pts_cap * 16 + c->mid_cap * sizeof(float[4]) + c->cell_cap * sizeof(int32_t[2]) +
           c->mass_cap * sizeof(float[3]);
}

bool mesh_extract(const mesh_grid *g, mesh *out, mesh_stats *st, err_t *err)
{
    mesh_free(out);
    *st = (mesh_stats){0};
    mesh_ctx c;
    if (!ctx_init(&c, g, out, st, err))
        return false;
    bool ok = true;
    for (int k = 0; ok && k <= c.n[2]; k++) { /* sample layer k; cell layer k − 1's corners; cell layer k − 2 meshed */
        ok = mesh_sample_layer(&c, k, err) && plane_crossings(&c, k, err) && (k == 0 || slab_crossings(&c, k - 1, err));
        if (ok && k >= 1)
            cell_configs(&c, k - 1);
        if (ok && k >= 2) {
            ok = cell_layer(&c, k - 2, err);
            if (ok)
                quads(&c, k - 2);
        }
        if (ok && k == c.n[2]) { /* the last cell layer: nothing above it */
            memset(c.cfg[k % 3], 0, (size_t)c.n[0] * (size_t)c.n[1]);
            ok = cell_layer(&c, k - 1, err);
            if (ok)
                quads(&c, k - 1);
        }
        size_t bytes = ctx_bytes(&c);
        st->peak_bytes = bytes > st->peak_bytes ? bytes : st->peak_bytes;
        if (ok && g->progress)
            g->progress(g->user, (double)(k + 1) / (c.n[2] + 1));
    }
    if (ok) /* faces the quadric's points made cross: back to their patches' mass points */
        st->untangled = mesh_untangle(out, c.mass, &st->crossing, &st->crossing_left);
    ctx_free(&c);
    if (!ok)
        mesh_free(out);
    return ok;
}
