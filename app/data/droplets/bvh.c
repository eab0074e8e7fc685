#include "data/droplets/bvh.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>

typedef struct builder {
    const float (*lo)[3], (*hi)[3];
    bvh_node *nodes;
    int *order;
    int count;
} builder;

int bvh_max_nodes(int n) { return n < 1 ? 1 : 2 * n - 1; }

static float centre(const builder *b, int i, int axis) { return b->lo[i][axis] + b->hi[i][axis]; }

/* Quickselect: order[lo..hi) partitioned so that the k-th smallest centre along axis sits at k. */
static void select_kth(const builder *b, int *order, int lo, int hi, int k, int axis)
{
    while (hi - lo > 1) {
        float pivot = centre(b, order[lo + (hi - lo) / 2], axis);
        int i = lo, j = hi - 1;
        while (i <= j) {
            while (centre(b, order[i], axis) < pivot)
                i++;
            while (centre(b, order[j], axis) > pivot)
                j--;
            if (i <= j) {
                int t = order[i];
                order[i++] = order[j];
                order[j--] = t;
            }
        }
        if (k <= j)
            hi = j + 1;
        else if (k >= i)
            lo = i;
        else
            return;
    }
}

static void build(builder *b, int node, int first, int count)
{
    bvh_node *n = &b->nodes[node];
    float clo[3] = {INFINITY, INFINITY, INFINITY}, chi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int a = 0; a < 3; a++) {
        n->lo[a] = INFINITY;
        n->hi[a] = -INFINITY;
    }
    for (int k = first; k < first + count; k++) {
        int i = b->order[k];
        for (int a = 0; a < 3; a++) {
            n->lo[a] = fminf(n->lo[a], b->lo[i][a]);
            n->hi[a] = fmaxf(n->hi[a], b->hi[i][a]);
            clo[a] = fminf(clo[a], centre(b, i, a));
            chi[a] = fmaxf(chi[a], centre(b, i, a));
        }
    }
    if (count <= BVH_LEAF_MAX) {
        n->first = first;
        n->count = count;
        return;
    }
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (chi[a] - clo[a] > chi[axis] - clo[axis])
            axis = a;
    int half = count / 2;
    select_kth(b, b->order, first, first + count, first + half, axis);
    int left = b->count;
    b->count += 2;
    n->first = left;
    n->count = 0;
    build(b, left, first, half);
    build(b, left + 1, first + half, count - half);
}

int bvh_build(int n, const float (*lo)[3], const float (*hi)[3], bvh_node *nodes, int *order)
{
    assert(n >= 1);
    builder b = {lo, hi, nodes, order, 1};
    for (int i = 0; i < n; i++)
        order[i] = i;
    build(&b, 0, 0, n);
    assert(b.count <= bvh_max_nodes(n));
    return b.count;
}

static int depth_of(const bvh_node *nodes, int i)
{
    if (nodes[i].count > 0)
        return 1;
    int a = depth_of(nodes, nodes[i].first), c = depth_of(nodes, nodes[i].first + 1);
    return 1 + (a > c ? a : c);
}

int bvh_depth(const bvh_node *nodes) { return depth_of(nodes, 0); }
