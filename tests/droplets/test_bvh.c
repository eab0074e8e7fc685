/* The BVH over boxes: every box in exactly one leaf, every node's box around its contents, depth
 * within the bound, and nearest signed box distances (overlaps: inside several) by traversal equal to brute force — on random boxes,
 * many identical centres, a long thin strip, one box, and 200,000 boxes. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "data/droplets/bvh.h"

static double frand(unsigned *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (*seed >> 8) / 16777216.0;
}

/* Signed: negative inside (shaders/csg/list.glsl prunes with it, so overlaps must work). */
static double box_distance(const float p[3], const float lo[3], const float hi[3])
{
    double s = 0, inside = -INFINITY;
    for (int a = 0; a < 3; a++) {
        double d = fmax((double)lo[a] - p[a], (double)p[a] - hi[a]);
        s += fmax(d, 0.0) * fmax(d, 0.0);
        inside = fmax(inside, d);
    }
    return sqrt(s) + fmin(inside, 0.0);
}

/* The shaders' traversal (shaders/csg/list.glsl) with box distance standing in for the primitives'. */
static double nearest(const bvh_node *nodes, const int *order, float (*lo)[3], float (*hi)[3], const float p[3])
{
    int stack[64], sp = 0;
    double best = INFINITY;
    stack[sp++] = 0;
    while (sp > 0) {
        const bvh_node *n = &nodes[stack[--sp]];
        if (box_distance(p, n->lo, n->hi) >= best)
            continue;
        if (n->count > 0) {
            for (int i = n->first; i < n->first + n->count; i++)
                best = fmin(best, box_distance(p, lo[order[i]], hi[order[i]]));
            continue;
        }
        assert_true(sp + 2 <= 64);
        stack[sp++] = n->first;
        stack[sp++] = n->first + 1;
    }
    return best;
}

static void check(int n, int kind)
{
    unsigned seed = 12345u + (unsigned)n;
    float(*lo)[3] = malloc(sizeof *lo * (size_t)n), (*hi)[3] = malloc(sizeof *hi * (size_t)n);
    for (int i = 0; i < n; i++)
        for (int a = 0; a < 3; a++) {
            double c = kind == 1 ? 0.5 : frand(&seed) * (kind == 2 && a != 0 ? 0.001 : 100.0);
            double h = frand(&seed) * (kind == 1 ? 3.0 : 0.5);
            lo[i][a] = (float)(c - h);
            hi[i][a] = (float)(c + h);
        }
    bvh_node *nodes = malloc(sizeof *nodes * (size_t)bvh_max_nodes(n));
    int *order = malloc(sizeof *order * (size_t)n), *seen = calloc((size_t)n, sizeof *seen);
    int count = bvh_build(n, (const float(*)[3])lo, (const float(*)[3])hi, nodes, order);
    assert_true(count >= 1 && count <= bvh_max_nodes(n));
    for (int k = 0; k < count; k++) {
        const bvh_node *nd = &nodes[k];
        if (nd->count > 0) {
            assert_true(nd->count <= BVH_LEAF_MAX);
            for (int i = nd->first; i < nd->first + nd->count; i++) {
                seen[order[i]]++;
                for (int a = 0; a < 3; a++)
                    assert_true(nd->lo[a] <= lo[order[i]][a] && hi[order[i]][a] <= nd->hi[a]);
            }
        } else {
            assert_true(nd->first > k && nd->first + 1 < count);
            for (int c = 0; c < 2; c++)
                for (int a = 0; a < 3; a++)
                    assert_true(nd->lo[a] <= nodes[nd->first + c].lo[a] && nodes[nd->first + c].hi[a] <= nd->hi[a]);
        }
    }
    for (int i = 0; i < n; i++)
        assert_int_equal(seen[i], 1);
    int depth = bvh_depth(nodes), bound = 2 + (int)ceil(log2(fmax(1.0, n / (double)BVH_LEAF_MAX)));
    assert_true(depth <= bound);
    int queries = n > 20000 ? 200 : 1000;
    for (int q = 0; q < queries; q++) {
        float p[3];
        for (int a = 0; a < 3; a++)
            p[a] = (float)(frand(&seed) * 140.0 - 20.0);
        double brute = INFINITY;
        for (int i = 0; i < n; i++)
            brute = fmin(brute, box_distance(p, lo[i], hi[i]));
        assert_true(nearest(nodes, order, lo, hi, p) == brute);
    }
    fprintf(stderr, "  %6d boxes (%s): %d nodes, depth %d (bound %d)\n", n,
            kind == 0 ? "random" : kind == 1 ? "one centre" : "a strip", count, depth, bound);
    free(lo);
    free(hi);
    free(nodes);
    free(order);
    free(seen);
}

static void bvh_is_sound(void **st)
{
    (void)st;
    check(1, 0);
    check(5, 0);
    check(1000, 0);
    check(1000, 1);
    check(4097, 2);
    check(200000, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(bvh_is_sound)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
