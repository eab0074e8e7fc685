/* The probing that check-formula's checks share (check.c, check_rays.c; check_probe.c, below both): random numbers, probes of the
 * scene's map() that count loops, and where a ratio estimate / distance is noted. Private to jobs/check*. */
#ifndef FATHOM_CHECK_PROBE_H
#define FATHOM_CHECK_PROBE_H

#include "jobs/check/check_types.h"
#include "scene/scene.h"
#include "util.h"

enum {
    CHECK_BISECTIONS = 14, /* halvings of a bracket around a crossing */
    CHECK_TARGETS = 32,    /* the random points nearest the set: every other first ray aims at one */
};
#define CHECK_INSIDE_REL 1e-5 /* "on the surface": an estimate below this share of the bound */

/* A uniform random number in [lo, hi) from the state (a linear congruential generator). */
double check_rnd(unsigned *state, double lo, double hi);
/* A random unit vector. */
void check_rnd_dir(unsigned *state, double v[3]);
/* The estimates at n points (2 floats each into out); with c, also the most loop iterations one ran
 * into c->loops where the driver has a loop limiter (c NULL: not measured). */
bool check_probe(const scene *s, const float *pts, int n, float *out, formula_check *c, err_t *err);
/* A ratio estimate / distance of at least `ratio`, seen at p: counted, and the worst kept. */
void check_note_ratio(formula_check *c, double ratio, const float *p);

/* The random points nearest the set, nearest first: where the first rays aim besides the middle. */
typedef struct check_targets {
    int n;
    double at[CHECK_TARGETS][3], d[CHECK_TARGETS];
} check_targets;

#endif
