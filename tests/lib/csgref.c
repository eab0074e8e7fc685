#include "csgref.h"

#include <math.h>
#include <string.h>

/* ---- spans ------------------------------------------------------------------------------------- */

static spans none(void) { return (spans){0}; }

static spans one(double t0, double t1)
{
    spans s = {0};
    if (t0 <= t1) {
        s.n = 1;
        s.t0[0] = t0;
        s.t1[0] = t1;
    }
    return s;
}

static void push(spans *s, double t0, double t1)
{
    if (t0 > t1)
        return;
    if (s->n > 0 && t0 <= s->t1[s->n - 1]) { /* touching or overlapping the last: merge */
        s->t1[s->n - 1] = fmax(s->t1[s->n - 1], t1);
        return;
    }
    if (s->n < CSG_MAX_SPANS) {
        s->t0[s->n] = t0;
        s->t1[s->n] = t1;
        s->n++;
    }
}

static spans op_union(spans a, spans b)
{
    spans out = {0};
    int i = 0, j = 0;
    while (i < a.n || j < b.n) {
        bool take_a = j >= b.n || (i < a.n && a.t0[i] <= b.t0[j]);
        if (take_a)
            push(&out, a.t0[i], a.t1[i]), i++;
        else
            push(&out, b.t0[j], b.t1[j]), j++;
    }
    return out;
}

static spans op_intersection(spans a, spans b)
{
    spans out = {0};
    for (int i = 0; i < a.n; i++)
        for (int j = 0; j < b.n; j++)
            push(&out, fmax(a.t0[i], b.t0[j]), fmin(a.t1[i], b.t1[j]));
    return out;
}

static spans complement(spans a)
{
    spans out = {0};
    double from = -INFINITY;
    for (int i = 0; i < a.n; i++) {
        if (a.t0[i] > from)
            push(&out, from, a.t0[i]);
        from = a.t1[i];
    }
    if (from < INFINITY)
        push(&out, from, INFINITY);
    return out;
}

/* A convex solid's span from several convex parts whose union it is: their hull. */
static spans hull(spans a, spans b)
{
    if (!a.n)
        return b;
    if (!b.n)
        return a;
    return one(fmin(a.t0[0], b.t0[0]), fmax(a.t1[a.n - 1], b.t1[b.n - 1]));
}

/* ---- convex primitives, in their own frame (Y axis) -------------------------------------------- */

typedef struct lray {
    double o[3], d[3];
} lray;

/* a t² + b t + c ≤ 0 along the whole line, as spans (the quadric's inside). */
static spans quadric(double a, double b, double c)
{
    const double TINY = 1e-14;
    if (fabs(a) < TINY) {
        if (fabs(b) < TINY)
            return c <= 0 ? one(-INFINITY, INFINITY) : none();
        double t = -c / b;
        return b > 0 ? one(-INFINITY, t) : one(t, INFINITY);
    }
    double disc = b * b - 4 * a * c;
    if (disc < 0)
        return a > 0 ? none() : one(-INFINITY, INFINITY);
    double s = sqrt(disc), q = b > 0 ? -0.5 * (b + s) : -0.5 * (b - s); /* stable roots */
    double r0 = q / a, r1 = q != 0 ? c / q : r0;
    double lo = fmin(r0, r1), hi = fmax(r0, r1);
    if (a > 0)
        return one(lo, hi);
    spans out = {0};
    push(&out, -INFINITY, lo);
    push(&out, hi, INFINITY);
    return out;
}

/* lo ≤ o[axis] + t d[axis] ≤ hi */
static spans slab(const lray *r, int axis, double lo, double hi)
{
    double o = r->o[axis], d = r->d[axis];
    if (d == 0)
        return o >= lo && o <= hi ? one(-INFINITY, INFINITY) : none();
    double ta = (lo - o) / d, tb = (hi - o) / d;
    return one(fmin(ta, tb), fmax(ta, tb));
}

static spans sphere_at(const lray *r, const double c[3], double radius)
{
    double oc[3] = {r->o[0] - c[0], r->o[1] - c[1], r->o[2] - c[2]};
    double a = ref_dot(r->d, r->d), b = 2 * ref_dot(oc, r->d), cc = ref_dot(oc, oc) - radius * radius;
    return quadric(a, b, cc);
}

static spans box_at(const lray *r, const double c[3], const double half[3])
{
    spans s = one(-INFINITY, INFINITY);
    for (int i = 0; i < 3; i++)
        s = op_intersection(s, slab(r, i, c[i] - half[i], c[i] + half[i]));
    return s;
}

/* A finite cylinder whose axis is `axis` through c, of half length h. */
static spans cylinder_at(const lray *r, int axis, const double c[3], double h, double radius)
{
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    double ou = r->o[u] - c[u], ov = r->o[v] - c[v];
    double a = r->d[u] * r->d[u] + r->d[v] * r->d[v], b = 2 * (ou * r->d[u] + ov * r->d[v]);
    double cc = ou * ou + ov * ov - radius * radius;
    return op_intersection(quadric(a, b, cc), slab(r, axis, c[axis] - h, c[axis] + h));
}

static spans round_box(const lray *r, const double half[3], double rr)
{
    /* the Minkowski sum of the inner box (half − rr) and a ball of radius rr: three grown boxes, twelve
     * edge cylinders, eight corner balls; convex, so its span is the hull of theirs */
    static const double ORIGIN[3] = {0, 0, 0};
    double in[3] = {half[0] - rr, half[1] - rr, half[2] - rr};
    spans s = none();
    for (int axis = 0; axis < 3; axis++) {
        double grown[3] = {in[0], in[1], in[2]};
        grown[axis] += rr;
        s = hull(s, box_at(r, ORIGIN, grown));
        int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int su = -1; su <= 1; su += 2)
            for (int sv = -1; sv <= 1; sv += 2) {
                double c[3] = {0, 0, 0};
                c[u] = su * in[u];
                c[v] = sv * in[v];
                s = hull(s, cylinder_at(r, axis, c, in[axis], rr));
            }
    }
    for (int k = 0; k < 8; k++) {
        double c[3] = {(k & 1 ? 1 : -1) * in[0], (k & 2 ? 1 : -1) * in[1], (k & 4 ? 1 : -1) * in[2]};
        s = hull(s, sphere_at(r, c, rr));
    }
    return s;
}

static spans capsule(const lray *r, double h, double radius)
{
    static const double ORIGIN[3] = {0, 0, 0};
    double top[3] = {0, h, 0}, bottom[3] = {0, -h, 0};
    spans s = hull(sphere_at(r, top, radius), sphere_at(r, bottom, radius));
    return h > 0 ? hull(s, cylinder_at(r, 1, ORIGIN, h, radius)) : s;
}

/* Frustum: radius rb at y = −h, rt at y = +h: x² + z² ≤ ρ(y)² with ρ linear, within the slab. */
static spans cone(const lray *r, double h, double rb, double rt)
{
    double k = (rt - rb) / (2 * h), r0 = rb + k * h; /* ρ(y) = r0 + k y */
    double oy = r->o[1], dy = r->d[1];
    double rho0 = r0 + k * oy, rho1 = k * dy; /* ρ along the ray: rho0 + rho1 t */
    double a = r->d[0] * r->d[0] + r->d[2] * r->d[2] - rho1 * rho1;
    double b = 2 * (r->o[0] * r->d[0] + r->o[2] * r->d[2] - rho0 * rho1);
    double c = r->o[0] * r->o[0] + r->o[2] * r->o[2] - rho0 * rho0;
    spans s = op_intersection(quadric(a, b, c), slab(r, 1, -h, h));
    /* only the nappe where ρ ≥ 0: within the slab ρ ≥ 0 always (both radii ≥ 0); keep one span */
    return s.n ? one(s.t0[0], s.t1[s.n - 1]) : s;
}

/* ---- the torus: sphere tracing its exact distance in double -------------------------------------- */

static double sd_torus(const double p[3], double major, double minor)
{
    double q = sqrt(p[0] * p[0] + p[2] * p[2]) - major;
    return sqrt(q * q + p[1] * p[1]) - minor;
}

static spans torus(const lray *r, double major, double minor)
{
    const double TMAX = 1e3, EPS = 1e-12, MIN_STEP = 1e-9;
    enum { MAX_ITER = 200000 };
    spans s = {0};
    double t = 0, p[3];
    for (int k = 0; k < 3; k++)
        p[k] = r->o[k];
    bool inside = sd_torus(p, major, minor) < 0;
    double enter = inside ? -INFINITY : 0;
    for (int it = 0; it < MAX_ITER && t < TMAX; it++) {
        for (int k = 0; k < 3; k++)
            p[k] = r->o[k] + r->d[k] * t;
        double d = sd_torus(p, major, minor);
        if (!inside && d < EPS) { /* reached the surface from outside */
            inside = true;
            enter = t;
            t += MIN_STEP;
        } else if (inside && -d < EPS) { /* reached it from inside */
            inside = false;
            push(&s, enter, t);
            t += MIN_STEP;
        } else {
            t += fabs(d);
        }
    }
    if (inside)
        push(&s, enter, INFINITY);
    return s;
}

/* ---- the tree ------------------------------------------------------------------------------------ */

static lray to_local(const csg_node *n, const dray *r)
{
    double R[3][3];
    ref_rotation(n->rot, R);
    lray l;
    for (int i = 0; i < 3; i++) { /* local = Rᵀ (world − pos) */
        l.o[i] = l.d[i] = 0;
        for (int k = 0; k < 3; k++) {
            l.o[i] += R[k][i] * (r->o[k] - n->pos[k]);
            l.d[i] += R[k][i] * r->d[k];
        }
    }
    return l;
}

spans csgref_spans(const csg_node *n, const dray *r)
{
    static const double ORIGIN[3] = {0, 0, 0};
    lray l = to_local(n, r);
    double half[3] = {0.5 * n->v[0], 0.5 * n->v[1], 0.5 * n->v[2]};
    switch (n->kind) {
    case CSG_SPHERE: return sphere_at(&l, ORIGIN, n->a);
    case CSG_BOX: return box_at(&l, ORIGIN, half);
    case CSG_ROUND_BOX: return round_box(&l, half, n->a);
    case CSG_TORUS: return torus(&l, n->a, n->b);
    case CSG_CYLINDER: return cylinder_at(&l, 1, ORIGIN, 0.5 * n->b, n->a);
    case CSG_CAPSULE: return capsule(&l, 0.5 * n->b, n->a);
    case CSG_CONE: return cone(&l, 0.5 * n->c, n->a, n->b);
    case CSG_PLANE: {
        double len = sqrt(ref_dot(n->v, n->v));
        return quadric(0, ref_dot(l.d, n->v) / len, ref_dot(l.o, n->v) / len);
    }
    default: break;
    }
    dray child = {{l.o[0], l.o[1], l.o[2]}, {l.d[0], l.d[1], l.d[2]}};
    spans acc = csgref_spans(n->children[0], &child);
    for (int i = 1; i < n->nchildren; i++) {
        spans s = csgref_spans(n->children[i], &child);
        acc = n->kind == CSG_UNION          ? op_union(acc, s)
              : n->kind == CSG_INTERSECTION ? op_intersection(acc, s)
                                            : op_intersection(acc, complement(s));
    }
    return acc;
}

double csgref_first_hit(const csg_node *n, const dray *r)
{
    spans s = csgref_spans(n, r);
    for (int i = 0; i < s.n; i++)
        if (s.t1[i] > 0)
            return fmax(s.t0[i], 0);
    return INFINITY;
}

void csgref_json(const csg_node *n, strbuf *out)
{
    static const char *const SHAPE[] = {"sphere", "box", "round_box", "torus", "cylinder", "capsule", "cone", "plane"};
    static const char *const OP[] = {"union", "intersection", "difference"};
    sb_printf(out, "{\"position\": [%.17g, %.17g, %.17g], \"rotation\": [%.17g, %.17g, %.17g], ", n->pos[0],
              n->pos[1], n->pos[2], n->rot[0], n->rot[1], n->rot[2]);
    switch (n->kind) {
    case CSG_SPHERE: sb_printf(out, "\"radius\": %.17g", n->a); break;
    case CSG_BOX: sb_printf(out, "\"size\": [%.17g, %.17g, %.17g]", n->v[0], n->v[1], n->v[2]); break;
    case CSG_ROUND_BOX:
        sb_printf(out, "\"size\": [%.17g, %.17g, %.17g], \"radius\": %.17g", n->v[0], n->v[1], n->v[2], n->a);
        break;
    case CSG_TORUS: sb_printf(out, "\"major\": %.17g, \"minor\": %.17g", n->a, n->b); break;
    case CSG_CYLINDER:
    case CSG_CAPSULE: sb_printf(out, "\"radius\": %.17g, \"height\": %.17g", n->a, n->b); break;
    case CSG_CONE:
        sb_printf(out, "\"radius_bottom\": %.17g, \"radius_top\": %.17g, \"height\": %.17g", n->a, n->b, n->c);
        break;
    case CSG_PLANE: sb_printf(out, "\"normal\": [%.17g, %.17g, %.17g]", n->v[0], n->v[1], n->v[2]); break;
    default: break;
    }
    if (n->kind <= CSG_PLANE) {
        sb_printf(out, ", \"shape\": \"%s\", \"material\": \"m\"}", SHAPE[n->kind]);
        return;
    }
    sb_printf(out, "\"op\": \"%s\", \"children\": [", OP[n->kind - CSG_UNION]);
    for (int i = 0; i < n->nchildren; i++) {
        if (i)
            sb_append(out, ", ");
        csgref_json(n->children[i], out);
    }
    sb_append(out, "]}");
}
