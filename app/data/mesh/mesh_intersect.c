/* mesh_intersect — triangles of one mesh that cross each other (mesh.h): found through a uniform grid of
 * the triangles' bounding boxes, tested by orientation signs in double, and untangled after an
 * extraction by moving the vertices of crossing faces to their patch's mass point.
 *
 * A pair crosses when an edge of one passes through the other's interior (strictly: both ends on
 * either side of its plane, and the edge's line inside its three edges), which is every way two
 * triangles that are not coplanar can cut each other. Faces that share an edge or a vertex are
 * adjacent, not crossing: for those only the far edge counts (a fan folded through its neighbour).
 * Coplanar overlaps and contacts at exactly one point are not counted (a dual contouring mesh has
 * neither away from its pinches, which mesh_split_pinches parts). */
#include "data/mesh/mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void sub(const float *a, const float *b, double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = (double)a[k] - (double)b[k];
}

/* The sign of the volume of (a, b, c, d): positive when d is on the side of abc its normal points to. */
static double orient(const float *a, const float *b, const float *c, const float *d)
{
    double u[3], v[3], w[3];
    sub(b, a, u);
    sub(c, a, v);
    sub(d, a, w);
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

/* Whether segment pq passes through the interior of triangle abc. */
static bool pierces(const float *p, const float *q, const float *a, const float *b, const float *c)
{
    double s1 = orient(a, b, c, p), s2 = orient(a, b, c, q);
    if (!(s1 * s2 < 0))
        return false;
    double e1 = orient(p, q, a, b), e2 = orient(p, q, b, c), e3 = orient(p, q, c, a);
    return (e1 > 0 && e2 > 0 && e3 > 0) || (e1 < 0 && e2 < 0 && e3 < 0);
}

static const float *P(const mesh *m, uint32_t v) { return m->pos + 3 * (size_t)v; }

/* Whether triangles f and g of m cross (see the top of the file). */
static bool crosses(const mesh *m, size_t f, size_t g)
{
    const uint32_t *a = m->tri + 3 * f, *b = m->tri + 3 * g;
    int shared = 0, ia = -1, ib = -1;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (a[i] == b[j])
                shared++, ia = i, ib = j;
    if (shared >= 2)
        return false; /* neighbours across an edge (or a duplicate face: mesh_drop_fins') */
    if (shared == 1) { /* a common corner: the far edge of either through the other */
        const uint32_t *ta = a, *tb = b;
        return pierces(P(m, ta[(ia + 1) % 3]), P(m, ta[(ia + 2) % 3]), P(m, tb[0]), P(m, tb[1]), P(m, tb[2])) ||
               pierces(P(m, tb[(ib + 1) % 3]), P(m, tb[(ib + 2) % 3]), P(m, ta[0]), P(m, ta[1]), P(m, ta[2]));
    }
    for (int i = 0; i < 3; i++)
        if (pierces(P(m, a[i]), P(m, a[(i + 1) % 3]), P(m, b[0]), P(m, b[1]), P(m, b[2])) ||
            pierces(P(m, b[i]), P(m, b[(i + 1) % 3]), P(m, a[0]), P(m, a[1]), P(m, a[2])))
            return true;
    return false;
}

typedef struct grid {
    double lo[3], cell;
    int n[3];
    size_t *start; /* cell c's triangles: item[start[c] .. start[c + 1]) */
    uint32_t *item;
    float (*box)[6]; /* each triangle's bounding box */
} grid;

static void tri_box(const mesh *m, size_t f, float b[6])
{
    for (int k = 0; k < 3; k++) {
        b[k] = b[3 + k] = P(m, m->tri[3 * f])[k];
        for (int i = 1; i < 3; i++) {
            float x = P(m, m->tri[3 * f + (size_t)i])[k];
            b[k] = fminf(b[k], x);
            b[3 + k] = fmaxf(b[3 + k], x);
        }
    }
}

static int cell_at(const grid *G, int k, double x)
{
    int c = (int)floor((x - G->lo[k]) / G->cell);
    return c < 0 ? 0 : c >= G->n[k] ? G->n[k] - 1 : c;
}

/* The grid: cells about twice a triangle's mean box, so most boxes meet one to eight cells, and at most
 * twice as many cells as faces. */
static bool grid_build(const mesh *m, grid *G)
{
    memset(G, 0, sizeof *G);
    G->box = malloc(m->nt * sizeof *G->box);
    if (!G->box)
        return false;
    double hi[3] = {-INFINITY, -INFINITY, -INFINITY}, mean = 0;
    for (int k = 0; k < 3; k++)
        G->lo[k] = INFINITY;
    for (size_t f = 0; f < m->nt; f++) {
        tri_box(m, f, G->box[f]);
        for (int k = 0; k < 3; k++) {
            G->lo[k] = fmin(G->lo[k], G->box[f][k]);
            hi[k] = fmax(hi[k], G->box[f][3 + k]);
            mean += (G->box[f][3 + k] - G->box[f][k]) / (3.0 * (double)m->nt);
        }
    }
    double ext = fmax(hi[0] - G->lo[0], fmax(hi[1] - G->lo[1], hi[2] - G->lo[2]));
    G->cell = fmax(2 * mean, ext / 1024);
    if (!(G->cell > 0))
        G->cell = 1;
    size_t cells;
    do { /* no more cells than twice the faces: the grid's memory follows the mesh's */
        cells = 1;
        for (int k = 0; k < 3; k++) {
            G->n[k] = (int)fmin(1024, floor((hi[k] - G->lo[k]) / G->cell) + 1);
            cells *= (size_t)G->n[k];
        }
        G->cell *= 1.25;
    } while (cells > 2 * m->nt + 8);
    G->cell /= 1.25;
    G->start = calloc(cells + 1, sizeof *G->start);
    if (!G->start)
        return false;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t f = 0; f < m->nt; f++) {
            const float *b = G->box[f];
            int c0[3], c1[3];
            for (int k = 0; k < 3; k++)
                c0[k] = cell_at(G, k, b[k]), c1[k] = cell_at(G, k, b[3 + k]);
            for (int z = c0[2]; z <= c1[2]; z++)
                for (int y = c0[1]; y <= c1[1]; y++)
                    for (int x = c0[0]; x <= c1[0]; x++) {
                        size_t c = ((size_t)z * (size_t)G->n[1] + (size_t)y) * (size_t)G->n[0] + (size_t)x;
                        if (pass == 0)
                            G->start[c + 1]++;
                        else
                            G->item[G->start[c]++] = (uint32_t)f;
                    }
        }
        if (pass == 0) {
            for (size_t c = 0; c < cells; c++)
                G->start[c + 1] += G->start[c];
            G->item = malloc((G->start[cells] + 1) * sizeof *G->item);
            if (!G->item)
                return false;
        } else { /* each start moved to the next cell's: shift back */
            memmove(G->start + 1, G->start, cells * sizeof *G->start);
            G->start[0] = 0;
        }
    }
    return true;
}

static void grid_free(grid *G)
{
    free(G->start);
    free(G->item);
    free(G->box);
}

/* Whether the pair's boxes overlap, with the overlap's low corner in cell (x, y, z): each pair is tested
 * in one cell only. */
static bool pair_here(const grid *G, const float *a, const float *b, int x, int y, int z)
{
    int at[3] = {x, y, z};
    for (int k = 0; k < 3; k++) {
        float lo = fmaxf(a[k], b[k]), hi = fminf(a[3 + k], b[3 + k]);
        if (lo > hi || cell_at(G, k, lo) != at[k])
            return false;
    }
    return true;
}

long long mesh_crossing_faces(const mesh *m, uint8_t *crossed)
{
    if (crossed)
        memset(crossed, 0, m->nt);
    grid G;
    if (m->nt < 2)
        return 0;
    if (!grid_build(m, &G)) {
        grid_free(&G);
        return -1;
    }
    long long pairs = 0;
    for (int z = 0; z < G.n[2]; z++)
        for (int y = 0; y < G.n[1]; y++)
            for (int x = 0; x < G.n[0]; x++) {
                size_t c = ((size_t)z * (size_t)G.n[1] + (size_t)y) * (size_t)G.n[0] + (size_t)x;
                for (size_t i = G.start[c]; i < G.start[c + 1]; i++)
                    for (size_t j = i + 1; j < G.start[c + 1]; j++) {
                        uint32_t f = G.item[i], g = G.item[j];
                        if (!pair_here(&G, G.box[f], G.box[g], x, y, z) || !crosses(m, f, g))
                            continue;
                        pairs++;
                        if (crossed)
                            crossed[f] = crossed[g] = 1;
                    }
            }
    grid_free(&G);
    return pairs;
}

/* Each vertex's neighbours' mean (the corners of its faces, each face's two others), into out. */
static bool ring_means(const mesh *m, float *out)
{
    float *sum = calloc(m->nv * 4 + 1, sizeof *sum);
    if (!sum)
        return false;
    for (size_t f = 0; f < m->nt; f++)
        for (int i = 0; i < 3; i++) {
            uint32_t v = m->tri[3 * f + (size_t)i];
            for (int j = 1; j < 3; j++) {
                const float *q = P(m, m->tri[3 * f + (size_t)((i + j) % 3)]);
                for (int k = 0; k < 3; k++)
                    sum[4 * (size_t)v + (size_t)k] += q[k];
                sum[4 * (size_t)v + 3] += 1;
            }
        }
    for (size_t v = 0; v < m->nv; v++)
        for (int k = 0; k < 3; k++)
            out[3 * v + (size_t)k] = sum[4 * v + 3] > 0 ? sum[4 * v + (size_t)k] / sum[4 * v + 3] : m->pos[3 * v + (size_t)k];
    free(sum);
    return true;
}

long long mesh_untangle(mesh *m, const float *mass, long long *before, long long *left)
{
    uint8_t *crossed = malloc(m->nt ? m->nt : 1), *moved = calloc(m->nv ? m->nv : 1, 1);
    float *ring = malloc((m->nv ? m->nv : 1) * 3 * sizeof(float));
    long long count = 0;
    *before = *left = -1;
    /* rounds: the corners of crossing faces to their mass points (once each, where given), then halfway
     * to their neighbours' mean (a local smoothing: folds open, the surface moves by less than a face) */
    for (int round = 0; crossed && moved && ring && round < 12; round++) {
        *left = mesh_crossing_faces(m, crossed);
        if (round == 0)
            *before = *left;
        if (*left <= 0)
            break;
        bool fresh = false;
        for (size_t f = 0; mass && f < m->nt; f++)
            for (int i = 0; crossed[f] && i < 3; i++) {
                uint32_t v = m->tri[3 * f + (size_t)i];
                if (!moved[v]) {
                    memcpy(m->pos + 3 * (size_t)v, mass + 3 * (size_t)v, 3 * sizeof(float));
                    moved[v] = 1, fresh = true;
                    count++;
                }
            }
        if (fresh || !ring_means(m, ring))
            continue;
        for (size_t f = 0; f < m->nt; f++) /* each corner of a crossing face once this round (bit 1) */
            for (int i = 0; crossed[f] && i < 3; i++) {
                uint32_t v = m->tri[3 * f + (size_t)i];
                if (moved[v] & 2)
                    continue;
                for (int k = 0; k < 3; k++)
                    m->pos[3 * (size_t)v + (size_t)k] = 0.5f * (m->pos[3 * (size_t)v + (size_t)k] + ring[3 * (size_t)v + (size_t)k]);
                count += !moved[v];
                moved[v] |= 3;
            }
        for (size_t v = 0; v < m->nv; v++)
            moved[v] &= 1;
    }
    if (crossed && moved && ring && *left > 0)
        *left = mesh_crossing_faces(m, NULL);
    free(crossed);
    free(moved);
    free(ring);
    return count;
}
