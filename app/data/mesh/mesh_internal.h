/* mesh_internal — the extractor's state, shared by its rooms: mesh.c (crossings, cells, faces) and
 * mesh_sample.c (the field sampled in layers, sparse by blocks). Not for other modules. */
#ifndef FATHOM_MESH_INTERNAL_H
#define FATHOM_MESH_INTERNAL_H

#include "data/mesh/mesh.h"

enum { CHUNK = 1 << 20, /* points a field call takes at most */
       MESH_ROUNDS = 6, /* Illinois steps a crossing takes */
       MESH_PROJECT = 2 /* steps a vertex takes onto the level along its normal */ };

typedef struct crossing {
    float p[3], n[3];
} crossing;

typedef struct xbuf { /* the crossings of one plane's x and y edges, or of one slab's z edges */
    crossing *c;
    float (*bracket)[9]; /* while resolving: a, fa, b, fb along the edge (a and b as xyz, f after), the side moved last */
    size_t n, cap;
} xbuf;

typedef struct mesh_ctx {
    const mesh_grid *g;
    int n[3];        /* cells along x, y, z */
    double o[3], h;  /* sample (0, 0, 0) and the cell side */
    size_t P;        /* samples a layer */
    float fill;      /* the value of a sample no visited block holds */
    float *val[3];   /* three sample layers (a cell layer's faces are decided with the next one's cells) */
    int32_t *xe[3], *ye[3], *ze[2]; /* crossing ids at each sample: its x and y edges in a plane, its z edge in a slab */
    xbuf plane[3], slab[2];
    int32_t *first[2]; /* each cell's first vertex (−1: none), two cell layers */
    uint8_t *cfg[3];   /* each cell's corner signs, three cell layers */
    uint8_t *flips[2]; /* each cell's faces resolved the other way (mesh_case) */
    uint8_t *visit[2]; /* blocks visited, two slabs */
    int visit_slab[2], nb[3];
    uint8_t *mark;     /* samples of the layer to evaluate */
    int32_t (*cell_of)[2]; /* the cell (i, j) of each vertex of the cell layer being made */
    size_t cell_cap;
    float (*mid)[4];   /* thin-feature candidates: an edge's midpoint and its ends' sign */
    size_t mid_n, mid_cap;
    float *pts, *dst;  /* field call buffers */
    size_t pts_cap;
    float *mass;       /* each vertex's patch mass point (mesh_untangle's fallback) */
    size_t mass_cap;
    mesh *m;
    mesh_stats *st;
} mesh_ctx;

/* Room for n points in c->pts and n values in c->dst. */
void mesh_reserve(mesh_ctx *c, size_t n);
/* The clipped field (max(field − iso, box)) at the n points in c->pts, into c->dst; raw: the field alone. */
bool mesh_eval(mesh_ctx *c, size_t n, bool raw, err_t *err);
/* Sample (i, j, k)'s position. */
void mesh_sample_pos(const mesh_ctx *c, int i, int j, int k, double p[3]);
/* Sample layer k into c->val[k % 3]: every sample of a visited block evaluated, the rest filled. */
bool mesh_sample_layer(mesh_ctx *c, int k, err_t *err);

#endif
