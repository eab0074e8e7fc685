/* An analytic CSG ray tracer in double precision, independent of the shaders: exact ray–primitive
 * intervals for every csg primitive (closed forms; the torus by sphere tracing its exact distance in
 * double to 1e-12), combined by interval arithmetic for union, intersection and difference, under
 * rotations and translations. The same tree also prints itself as a scene file's "objects", so the
 * renderer and the reference draw one scene. */
#ifndef FATHOM_TEST_CSGREF_H
#define FATHOM_TEST_CSGREF_H

#include <stdbool.h>

#include "reference.h"
#include "util.h"

typedef enum csg_kind {
    CSG_SPHERE, CSG_BOX, CSG_ROUND_BOX, CSG_TORUS, CSG_CYLINDER, CSG_CAPSULE, CSG_CONE, CSG_PLANE,
    CSG_UNION, CSG_INTERSECTION, CSG_DIFFERENCE
} csg_kind;

enum { CSG_MAX_CHILDREN = 4, CSG_MAX_SPANS = 16 };

/* Sizes as in the scene file: sphere a = radius; box/round_box v = size (full), a = radius; torus
 * a = major, b = minor; cylinder/capsule a = radius, b = height (full); cone a = radius_bottom,
 * b = radius_top, c = height; plane v = normal. */
typedef struct csg_node {
    csg_kind kind;
    double pos[3], rot[3]; /* degrees, X then Y then Z, object to world */
    double a, b, c, v[3];
    int nchildren;
    const struct csg_node *children[CSG_MAX_CHILDREN];
} csg_node;

/* Sorted, disjoint [t0, t1] spans where the ray is inside the solid (t may be ±inf). */
typedef struct spans {
    int n;
    double t0[CSG_MAX_SPANS], t1[CSG_MAX_SPANS];
} spans;

spans csgref_spans(const csg_node *n, const dray *r);
/* The first surface at t > 0 along r: +inf when none. (A camera inside a solid: 0.) */
double csgref_first_hit(const csg_node *n, const dray *r);
/* Appends the node as a scene-file JSON node (material "m"). */
void csgref_json(const csg_node *n, strbuf *out);

#endif
