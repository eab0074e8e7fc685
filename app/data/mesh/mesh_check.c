/* mesh_check — a mesh's storage, and what it is checked for: closed, manifold, oriented, its
 * components, Euler characteristic, area and volume (data/mesh/mesh.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "data/mesh/mesh.h"
#include "util.h"

uint32_t mesh_add_vertex(mesh *m, const float p[3], const float n[3])
{
    if (m->nv == m->cap_v) {
        m->cap_v = m->cap_v ? 2 * m->cap_v : 1 << 12;
        m->pos = util_realloc(m->pos, m->cap_v * 3 * sizeof(float), "mesh vertices");
        m->nrm = util_realloc(m->nrm, m->cap_v * 3 * sizeof(float), "mesh normals");
    }
    memcpy(m->pos + 3 * m->nv, p, 3 * sizeof(float));
    memcpy(m->nrm + 3 * m->nv, n, 3 * sizeof(float));
    return (uint32_t)m->nv++;
}

void mesh_add_triangle(mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    if (m->nt == m->cap_t) {
        m->cap_t = m->cap_t ? 2 * m->cap_t : 1 << 13;
        m->tri = util_realloc(m->tri, m->cap_t * 3 * sizeof(uint32_t), "mesh triangles");
    }
    uint32_t *t = m->tri + 3 * m->nt++;
    t[0] = a;
    t[1] = b;
    t[2] = c;
}

void mesh_free(mesh *m)
{
    free(m->pos);
    free(m->nrm);
    free(m->col);
    free(m->tri);
    *m = (mesh){0};
}

/* Triangle (a, b, c)'s agreement with its vertices' normals: the sum of the cosines. */
static double agreement(const mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    const float *p0 = m->pos + 3 * (size_t)a, *p1 = m->pos + 3 * (size_t)b, *p2 = m->pos + 3 * (size_t)c;
    double u[3], v[3], n[3], sum = 0;
    for (int k = 0; k < 3; k++) {
        u[k] = p1[k] - p0[k];
        v[k] = p2[k] - p0[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len == 0)
        return -3;
    const uint32_t id[3] = {a, b, c};
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            sum += n[k] / len * m->nrm[3 * (size_t)id[i] + (size_t)k];
    return sum;
}

/* Which diagonal splits quad v: the one whose triangles face as their vertices' normals do (a quad
 * across a sharp edge splits along the edge, not across it). 0: v0–v2, 1: v1–v3. */
int mesh_split_of(const mesh *m, const uint32_t v[4])
{
    double a = agreement(m, v[0], v[1], v[2]) + agreement(m, v[0], v[2], v[3]);
    double b = agreement(m, v[1], v[2], v[3]) + agreement(m, v[1], v[3], v[0]);
    return a >= b ? 0 : 1;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static size_t root(size_t *parent, size_t i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

static void join(size_t *parent, size_t a, size_t b)
{
    a = root(parent, a);
    b = root(parent, b);
    if (a != b)
        parent[a < b ? b : a] = a < b ? a : b;
}

/* Directed edges as (from << 32 | to) << 0 with the triangle in a second array, sorted together. */
typedef struct dedge {
    uint64_t key;
    uint64_t tri;
} dedge;

static int cmp_dedge(const void *a, const void *b)
{
    return cmp_u64(&((const dedge *)a)->key, &((const dedge *)b)->key);
}

static const dedge *find_edge(const dedge *e, size_t n, uint64_t key)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (e[mid].key < key)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < n && e[lo].key == key ? &e[lo] : NULL;
}

/* Fans around each vertex: corner (t, i) joined with the corner at the same vertex in the triangle
 * across its outgoing edge. A vertex whose corners fall in two or more sets is pinched. */
static long long pinched_vertices(const mesh *m, const dedge *e, size_t ne)
{
    size_t nc = 3 * m->nt;
    size_t *parent = util_alloc(nc * sizeof *parent, "mesh check");
    for (size_t i = 0; i < nc; i++)
        parent[i] = i;
    for (size_t t = 0; t < m->nt; t++)
        for (int i = 0; i < 3; i++) {
            uint32_t v = m->tri[3 * t + (size_t)i], next = m->tri[3 * t + (size_t)(i + 1) % 3];
            const dedge *o = find_edge(e, ne, (uint64_t)next << 32 | v);
            if (!o)
                continue;
            for (int j = 0; j < 3; j++)
                if (m->tri[3 * o->tri + (size_t)j] == v)
                    join(parent, 3 * t + (size_t)i, 3 * o->tri + (size_t)j);
        }
    size_t *first = util_alloc(m->nv * sizeof *first, "mesh check");
    for (size_t v = 0; v < m->nv; v++)
        first[v] = SIZE_MAX;
    uint8_t *bad = util_calloc(m->nv, 1, "mesh check");
    long long pinched = 0;
    for (size_t c = 0; c < nc; c++) {
        uint32_t v = m->tri[c];
        size_t r = root(parent, c);
        if (first[v] == SIZE_MAX)
            first[v] = r;
        else if (first[v] != r && !bad[v]) {
            bad[v] = 1;
            pinched++;
        }
    }
    free(bad);
    free(first);
    free(parent);
    return pinched;
}

/* Undirected edges: E, and those not shared by exactly two faces. */
static void count_edges(const mesh *m, mesh_topology *t)
{
    size_t n = 3 * m->nt;
    uint64_t *u = util_alloc((n ? n : 1) * sizeof *u, "mesh check");
    for (size_t i = 0; i < n; i++) {
        uint64_t a = m->tri[i], b = m->tri[i / 3 * 3 + (i + 1) % 3];
        u[i] = a < b ? a << 32 | b : b << 32 | a;
    }
    qsort(u, n, sizeof *u, cmp_u64);
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && u[j] == u[i])
            j++;
        t->edges++;
        t->open_edges += j - i == 1;
        t->nonmanifold_edges += j - i > 2;
        i = j;
    }
    free(u);
}

void mesh_check(const mesh *m, mesh_topology *t)
{
    *t = (mesh_topology){.faces = (long long)m->nt};
    size_t ne = 3 * m->nt;
    dedge *e = util_alloc((ne ? ne : 1) * sizeof *e, "mesh check");
    size_t *parent = util_alloc((m->nv ? m->nv : 1) * sizeof *parent, "mesh check");
    uint8_t *used = util_calloc(m->nv ? m->nv : 1, 1, "mesh check");
    for (size_t v = 0; v < m->nv; v++)
        parent[v] = v;
    for (size_t f = 0; f < m->nt; f++) {
        const uint32_t *v = m->tri + 3 * f;
        const float *a = m->pos + 3 * (size_t)v[0], *b = m->pos + 3 * (size_t)v[1], *c = m->pos + 3 * (size_t)v[2];
        double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double x[3] = {ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0]};
        t->area += 0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        t->volume += (a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) + a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
                      a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0])) / 6;
        t->degenerate += v[0] == v[1] || v[1] == v[2] || v[0] == v[2];
        for (int i = 0; i < 3; i++) {
            e[3 * f + (size_t)i] = (dedge){(uint64_t)v[i] << 32 | v[(i + 1) % 3], f};
            used[v[i]] = 1;
            join(parent, v[i], v[(i + 1) % 3]);
        }
    }
    qsort(e, ne, sizeof *e, cmp_dedge);
    for (size_t i = 0; i + 1 < ne; i++) /* a directed edge twice: faces folded onto each other */
        t->nonmanifold_edges += e[i].key == e[i + 1].key;
    count_edges(m, t);
    for (size_t v = 0; v < m->nv; v++) {
        t->vertices += used[v];
        t->unused_vertices += !used[v];
        t->components += used[v] && root(parent, v) == v;
    }
    t->nonmanifold_vertices = pinched_vertices(m, e, ne);
    t->euler = t->vertices - t->edges + t->faces;
    t->closed_manifold = m->nt > 0 && !t->open_edges && !t->nonmanifold_edges && !t->nonmanifold_vertices && !t->degenerate;
    free(used);
    free(parent);
    free(e);
}

long long mesh_keep_largest(mesh *m)
{
    size_t *parent = util_alloc((m->nv ? m->nv : 1) * sizeof *parent, "mesh shells");
    for (size_t v = 0; v < m->nv; v++)
        parent[v] = v;
    for (size_t f = 0; f < 3 * m->nt; f++)
        join(parent, m->tri[f], m->tri[f / 3 * 3 + (f + 1) % 3]);
    size_t *faces = util_calloc(m->nv ? m->nv : 1, sizeof *faces, "mesh shells");
    size_t best = 0;
    long long shells = 0;
    for (size_t f = 0; f < m->nt; f++) {
        size_t r = root(parent, m->tri[3 * f]);
        shells += faces[r]++ == 0;
        best = faces[r] > faces[best] ? r : best;
    }
    uint32_t *remap = util_alloc((m->nv ? m->nv : 1) * sizeof *remap, "mesh shells");
    size_t nv = 0, nt = 0;
    for (size_t v = 0; v < m->nv; v++) {
        remap[v] = UINT32_MAX;
        if (root(parent, v) == best && faces[best]) {
            memmove(m->pos + 3 * nv, m->pos + 3 * v, 3 * sizeof(float));
            memmove(m->nrm + 3 * nv, m->nrm + 3 * v, 3 * sizeof(float));
            if (m->col)
                memmove(m->col + 3 * nv, m->col + 3 * v, 3 * sizeof(float));
            remap[v] = (uint32_t)nv++;
        }
    }
    for (size_t f = 0; f < m->nt; f++)
        if (remap[m->tri[3 * f]] != UINT32_MAX) {
            for (int i = 0; i < 3; i++)
                m->tri[3 * nt + (size_t)i] = remap[m->tri[3 * f + (size_t)i]];
            nt++;
        }
    m->nv = nv;
    m->nt = nt;
    free(remap);
    free(faces);
    free(parent);
    return shells > 1 ? shells - 1 : 0;
}

static const float *weld_pos;

static int cmp_position(const void *a, const void *b)
{
    const float *p = weld_pos + 3 * (size_t)*(const uint32_t *)a, *q = weld_pos + 3 * (size_t)*(const uint32_t *)b;
    for (int k = 0; k < 3; k++)
        if (p[k] != q[k])
            return p[k] < q[k] ? -1 : 1;
    return 0;
}

/* An attribute (3 floats a vertex, or NULL) kept for the first vertex of each position. */
static float *keep_first(const float *a, const uint32_t *order, const uint32_t *remap, size_t nv, size_t n)
{
    if (!a)
        return NULL;
    float *out = util_alloc((n ? n : 1) * 3 * sizeof(float), "mesh weld");
    for (size_t i = nv; i-- > 0;) /* backwards: the first of each position writes last */
        memcpy(out + 3 * (size_t)remap[order[i]], a + 3 * (size_t)order[i], 3 * sizeof(float));
    return out;
}

long long mesh_weld(mesh *m)
{
    uint32_t *order = util_alloc((m->nv ? m->nv : 1) * sizeof *order, "mesh weld");
    uint32_t *remap = util_alloc((m->nv ? m->nv : 1) * sizeof *remap, "mesh weld");
    for (size_t v = 0; v < m->nv; v++)
        order[v] = (uint32_t)v;
    weld_pos = m->pos;
    qsort(order, m->nv, sizeof *order, cmp_position);
    size_t n = 0;
    for (size_t i = 0; i < m->nv; i++) {
        if (i == 0 || cmp_position(&order[i - 1], &order[i]) != 0)
            n++;
        remap[order[i]] = (uint32_t)(n - 1);
    }
    long long merged = (long long)(m->nv - n);
    if (merged) {
        float *pos = keep_first(m->pos, order, remap, m->nv, n), *nrm = keep_first(m->nrm, order, remap, m->nv, n),
              *col = keep_first(m->col, order, remap, m->nv, n);
        for (size_t i = 0; i < 3 * m->nt; i++)
            m->tri[i] = remap[m->tri[i]];
        free(m->pos), free(m->nrm), free(m->col);
        m->pos = pos, m->nrm = nrm, m->col = col;
        m->nv = m->cap_v = n;
    }
    free(order);
    free(remap);
    return merged;
}

void mesh_compact(mesh *m)
{
    uint32_t *remap = util_alloc((m->nv ? m->nv : 1) * sizeof *remap, "mesh vertices");
    for (size_t v = 0; v < m->nv; v++)
        remap[v] = UINT32_MAX;
    size_t n = 0;
    for (size_t i = 0; i < 3 * m->nt; i++) {
        uint32_t v = m->tri[i];
        if (remap[v] == UINT32_MAX) {
            remap[v] = (uint32_t)n++;
        }
        m->tri[i] = remap[v];
    }
    float *arrays[3] = {m->pos, m->nrm, m->col};
    for (int a = 0; a < 3; a++) {
        if (!arrays[a])
            continue;
        float *out = util_alloc((n ? n : 1) * 3 * sizeof(float), "mesh vertices");
        for (size_t v = 0; v < m->nv; v++)
            if (remap[v] != UINT32_MAX)
                memcpy(out + 3 * (size_t)remap[v], arrays[a] + 3 * v, 3 * sizeof(float));
        free(arrays[a]);
        arrays[a] = out;
    }
    m->pos = arrays[0];
    m->nrm = arrays[1];
    m->col = arrays[2];
    m->nv = m->cap_v = n;
    free(remap);
}

static int cmp_face(const void *a, const void *b)
{
    const uint32_t *x = a, *y = b;
    for (int k = 0; k < 4; k++)
        if (x[k] != y[k])
            return x[k] < y[k] ? -1 : 1;
    return 0;
}

long long mesh_drop_fins(mesh *m)
{
    /* each face as its sorted corners and its index; faces with the same corners come in twos (a fin:
     * the two sides of a collapsed sliver) or more: all of them go */
    uint32_t (*key)[4] = util_alloc((m->nt ? m->nt : 1) * sizeof *key, "mesh fins");
    for (size_t f = 0; f < m->nt; f++) {
        uint32_t a = m->tri[3 * f], b = m->tri[3 * f + 1], c = m->tri[3 * f + 2], t;
        if (a > b) t = a, a = b, b = t;
        if (b > c) t = b, b = c, c = t;
        if (a > b) t = a, a = b, b = t;
        key[f][0] = a, key[f][1] = b, key[f][2] = c, key[f][3] = (uint32_t)f;
    }
    qsort(key, m->nt, sizeof *key, cmp_face);
    uint8_t *drop = util_calloc(m->nt ? m->nt : 1, 1, "mesh fins");
    long long dropped = 0;
    for (size_t i = 0; i < m->nt;) {
        size_t j = i;
        while (j < m->nt && !memcmp(key[j], key[i], 3 * sizeof(uint32_t)))
            j++;
        bool degenerate = key[i][0] == key[i][1] || key[i][1] == key[i][2];
        for (size_t k = i; k < j && (j - i > 1 || degenerate); k++, dropped++)
            drop[key[k][3]] = 1;
        i = j;
    }
    size_t n = 0;
    for (size_t f = 0; f < m->nt; f++)
        if (!drop[f])
            memmove(m->tri + 3 * n++, m->tri + 3 * f, 3 * sizeof(uint32_t));
    m->nt = n;
    free(drop);
    free(key);
    return dropped;
}

/* Whether the directed edge at e[i] is one of a manifold pair: it alone from a to b, and one face from
 * b to a. */
static const dedge *manifold_reverse(const dedge *e, size_t ne, uint64_t key)
{
    const dedge *d = find_edge(e, ne, key);
    if (!d || (d + 1 < e + ne && d[1].key == key))
        return NULL;
    uint64_t rev = (key & 0xffffffffu) << 32 | key >> 32;
    const dedge *r = find_edge(e, ne, rev);
    return r && !(r + 1 < e + ne && r[1].key == rev) ? r : NULL;
}

/* Each copy made at a pinch (vertices old_nv on) moved a thousandth of the way toward the centre of its own fan's
 * faces: at the same place as the original, a reader that merges positions (a slicer, STL) would join the sheets
 * again. */
static void part_copies(mesh *m, size_t old_nv)
{
    size_t n = m->nv - old_nv;
    if (!n)
        return;
    double (*sum)[4] = util_calloc(n, sizeof *sum, "mesh pinches");
    for (size_t f = 0; f < m->nt; f++)
        for (int i = 0; i < 3; i++) {
            uint32_t v = m->tri[3 * f + (size_t)i];
            if (v < old_nv)
                continue;
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++)
                    sum[v - old_nv][k] += m->pos[3 * (size_t)m->tri[3 * f + (size_t)j] + (size_t)k] / 3.0;
            sum[v - old_nv][3] += 1;
        }
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3 && sum[i][3] > 0; k++) {
            float *p = m->pos + 3 * (old_nv + i) + (size_t)k;
            *p += (float)(1e-3 * (sum[i][k] / sum[i][3] - *p));
        }
    free(sum);
}

long long mesh_split_pinches(mesh *m)
{
    size_t ne = 3 * m->nt;
    dedge *e = util_alloc((ne ? ne : 1) * sizeof *e, "mesh pinches");
    for (size_t f = 0; f < m->nt; f++)
        for (int i = 0; i < 3; i++)
            e[3 * f + (size_t)i] = (dedge){(uint64_t)m->tri[3 * f + (size_t)i] << 32 | m->tri[3 * f + (size_t)(i + 1) % 3], f};
    qsort(e, ne, sizeof *e, cmp_dedge);
    size_t *parent = util_alloc((ne ? ne : 1) * sizeof *parent, "mesh pinches");
    for (size_t c = 0; c < ne; c++)
        parent[c] = c;
    for (size_t f = 0; f < m->nt; f++) /* corners at v joined across v's manifold edges only */
        for (int i = 0; i < 3; i++) {
            uint32_t v = m->tri[3 * f + (size_t)i], next = m->tri[3 * f + (size_t)(i + 1) % 3];
            const dedge *o = manifold_reverse(e, ne, (uint64_t)v << 32 | next);
            for (int j = 0; o && j < 3; j++)
                if (m->tri[3 * o->tri + (size_t)j] == v)
                    join(parent, 3 * f + (size_t)i, 3 * o->tri + (size_t)j);
        }
    size_t *first = util_alloc((m->nv ? m->nv : 1) * sizeof *first, "mesh pinches");
    for (size_t v = 0; v < m->nv; v++)
        first[v] = SIZE_MAX;
    uint32_t *copy = util_alloc((ne ? ne : 1) * sizeof *copy, "mesh pinches"); /* a fan's vertex, by its root */
    long long added = 0;
    for (size_t c = 0; c < ne; c++) {
        uint32_t v = m->tri[c];
        size_t r = root(parent, c);
        if (first[v] == SIZE_MAX)
            first[v] = r;
        if (first[v] == r) {
            copy[r] = v;
        } else if (c == r) { /* another fan's first corner (a set's root is its smallest corner) */
            float p[3], n[3];
            memcpy(p, m->pos + 3 * (size_t)v, sizeof p);
            memcpy(n, m->nrm + 3 * (size_t)v, sizeof n);
            copy[r] = mesh_add_vertex(m, p, n);
            added++;
        }
    }
    size_t old_nv = m->nv - (size_t)added;
    for (size_t c = 0; c < ne; c++) /* every corner to its fan's vertex */
        m->tri[c] = copy[root(parent, c)];
    part_copies(m, old_nv);
    free(copy);
    free(first);
    free(parent);
    free(e);
    return added;
}

long long mesh_fill_holes(mesh *m)
{
    size_t ne = 3 * m->nt;
    uint64_t *e = util_alloc((ne ? ne : 1) * sizeof *e, "mesh holes");
    for (size_t i = 0; i < ne; i++)
        e[i] = (uint64_t)m->tri[i] << 32 | m->tri[i / 3 * 3 + (i + 1) % 3];
    qsort(e, ne, sizeof *e, cmp_u64);
    uint64_t *open = util_alloc((ne ? ne : 1) * sizeof *open, "mesh holes"); /* a → b with no b → a, by a */
    size_t no = 0;
    for (size_t i = 0; i < ne; i++) {
        uint64_t rev = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
        if (!bsearch(&rev, e, ne, sizeof *e, cmp_u64))
            open[no++] = e[i];
    }
    uint8_t *used = util_calloc(no ? no : 1, 1, "mesh holes");
    uint32_t *loop = util_alloc((no ? no : 1) * sizeof *loop, "mesh holes");
    long long filled = 0;
    for (size_t s = 0; s < no; s++) {
        size_t n = 0, at = s;
        while (!used[at]) { /* follow the open edges from a to b, then from b on */
            used[at] = 1;
            loop[n++] = (uint32_t)(open[at] >> 32);
            uint64_t from = open[at] & 0xffffffffu, key = from << 32;
            size_t lo = 0, hi = no;
            while (lo < hi) { /* the first open edge leaving b */
                size_t mid = (lo + hi) / 2;
                if (open[mid] < key)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            while (lo < no && open[lo] >> 32 == from && used[lo])
                lo++;
            if (lo == no || open[lo] >> 32 != from)
                break;
            at = lo;
        }
        for (size_t i = 1; n >= 3 && i + 1 < n; i++) /* the hole fanned from its first corner, wound against its rim */
            mesh_add_triangle(m, loop[0], loop[i + 1], loop[i]);
        filled += n >= 3;
    }
    free(loop);
    free(used);
    free(open);
    free(e);
    return filled;
}
