/* Independent double-precision references for the GL probes: closed-form ray–sphere and ray–box
 * (slab) intersections, CSG by ray intervals, the torus by root bracketing of its quartic implicit
 * function, and Snell refraction. None of this shares code with the shaders. */
#ifndef FATHOM_TEST_REFERENCE_H
#define FATHOM_TEST_REFERENCE_H

#include <stdbool.h>

typedef struct dray {
    double o[3], d[3]; /* d unit */
} dray;

typedef struct dhit {
    bool hit;
    double t;
    double n[3];   /* outward unit normal of the solid at the hit */
    double crease; /* distance from the hit point to the nearest edge or CSG seam (normals are undefined there) */
} dhit;

/* The inside of a convex solid along a ray: [t0, t1] with the normals there. */
typedef struct dinterval {
    bool hit;
    double t0, t1;
    double n0[3], n1[3];
} dinterval;

/* Object-to-world rotation from Euler degrees (X, then Y, then Z), row-major. */
void ref_rotation(const double deg[3], double R[3][3]);

dinterval ref_sphere(const dray *r, const double c[3], double radius);
dinterval ref_box(const dray *r, const double c[3], double R[3][3], const double half[3]);
/* Distance from a point on the box's surface (at ray parameter t) to the box's nearest edge. */
double ref_box_crease(const dray *r, double t, const double c[3], double R[3][3], const double half[3]);

dhit ref_first(dinterval a);                 /* the first entry at t >= 0 */
dhit ref_difference(dinterval a, dinterval b); /* a minus b */
dhit ref_intersection(dinterval a, dinterval b);
dhit ref_torus(const dray *r, const double c[3], double R[3][3], double major, double minor, double tmax);

/* Exact signed distances of the primitives (negative inside), for "is this point on the surface?". */
double ref_sd_sphere(const double p[3], const double c[3], double radius);
double ref_sd_box(const double p[3], const double c[3], double R[3][3], const double half[3]);
double ref_sd_torus(const double p[3], const double c[3], double R[3][3], double major, double minor);

/* Snell: refracts unit d at unit normal n (facing against d), eta = n_from / n_to; false on TIR. */
bool ref_refract(const double d[3], const double n[3], double eta, double out[3]);

double ref_dot(const double a[3], const double b[3]);

#endif
