/* bvh — a bounding volume hierarchy over axis-aligned boxes, for distance queries on the GPU (the csg
 * program's primitive list; the droplets can share it). Pure C.
 *
 * Layout, as the shaders read it: nodes[0] is the root. An inner node (count 0) has its two children
 * at nodes[first] and nodes[first + 1]; a leaf holds order[first … first + count − 1], indices into
 * the caller's boxes. Every node's box contains its children's (or its boxes') boxes, so the distance
 * from a point to a node's box is a lower bound on its distance to anything inside.
 * Built by median split of the box centres along the widest axis: depth ≤ ⌈log2(n / leaf_max)⌉ + 1.
 */
#ifndef FATHOM_BVH_H
#define FATHOM_BVH_H

enum { BVH_LEAF_MAX = 4, BVH_MAX_DEPTH = 48 };

typedef struct bvh_node {
    float lo[3], hi[3];
    int first, count; /* count 0: inner node, children at first and first + 1 */
} bvh_node;

/* Nodes needed for n boxes at most (allocate this many). */
int bvh_max_nodes(int n);

/* Builds over n ≥ 1 boxes; fills nodes and order (n entries). Returns the node count. */
int bvh_build(int n, const float (*lo)[3], const float (*hi)[3], bvh_node *nodes, int *order);

/* Depth of the tree (1: the root is a leaf). */
int bvh_depth(const bvh_node *nodes);

#endif
