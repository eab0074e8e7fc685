/* check_types — what check-formula finds (check.h says what each check does): shared by check.c,
 * check_probe.c and check_rays.c. */
#ifndef FATHOM_CHECK_TYPES_H
#define FATHOM_CHECK_TYPES_H

#include <stdbool.h>

#define CHECK_TOLERANCE 1.02 /* the crossing is located to within a dense step: a few % of slack */

typedef struct formula_check {
    int points;          /* estimates probed for finiteness */
    int nonfinite;       /* of them NaN or Inf */
    int step_points, step_inside; /* points stepped toward the set by their estimate; of them, landed inside */
    int rays, crossing;  /* rays cast, rays that met the surface */
    int random_rays;     /* of them cast at random (the rest around the worst) */
    int samples;         /* samples compared with their crossing */
    int over;            /* samples whose estimate exceeds the distance (ratio > 1.005: past rounding) */
    double worst, p99;   /* the worst and the 99th-percentile ratio estimate / distance */
    double worst_at[3];  /* where the worst ratio was seen */
    double suggested;    /* the step factor that keeps every sample inside: min(1, 1 / worst) */
    double step;         /* the step factor the formula declares (1 when it declares none), or the scene's */
    bool mode;           /* a Julia set or a hybrid: checked at the scene's step factor */
    bool contained;      /* the set stays inside the bounding sphere */
    bool framing;    /* a fragment: its DE is marched without a bounding sphere, the bound only frames the view */
    double sphere_min;   /* the smallest estimate found on the bounding sphere (the bound lifted) */
    double sphere_at[3]; /* where */
    double reach;        /* the farthest point of the set found beyond the sphere (0: none) */
    bool loops_measured; /* the driver has a loop limiter to measure loops against */
    int loops, loops_declared; /* the most loop iterations an estimate ran; what the formula declares */
    bool ok;
} formula_check;

#endif
