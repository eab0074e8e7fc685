/* check_probe — the probing check-formula's checks share (check_probe.h): random numbers, probes of the
 * scene's map() that count loops, and where a ratio estimate / distance is noted. */
#include "jobs/check/check_probe.h"

#include <math.h>
#include <stdlib.h>

#include "gpu/render_probe.h"

double check_rnd(unsigned *state, double lo, double hi)
{
    *state = *state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (double)(*state >> 8) / 16777216.0;
}

void check_rnd_dir(unsigned *seed, double v[3])
{
    double l;
    do {
        l = 0;
        for (int k = 0; k < 3; k++)
            v[k] = check_rnd(seed, -1, 1), l += v[k] * v[k];
    } while (l > 1 || l < 1e-4);
    for (int k = 0; k < 3; k++)
        v[k] /= sqrt(l);
}

/* The estimates at n points, and (where the driver has a loop limiter: c->loops_measured) the most loop
 * iterations one of them ran into c->loops (c NULL: not measured): the random points and the first
 * rays' dense samples, near the surface included, where estimates run longest. */
bool check_probe(const scene *s, const float *pts, int n, float *out, formula_check *c, err_t *err)
{
    if (!render_probe(s, NULL, pts, n, out, err))
        return false;
    if (!c || !c->loops_measured)
        return true;
    int *loops = util_alloc(sizeof(int) * (size_t)n, "check loops");
    err_t none;
    c->loops_measured = render_probe_loops(s, pts, n, loops, &none);
    for (int i = 0; c->loops_measured && i < n; i++)
        c->loops = loops[i] > c->loops ? loops[i] : c->loops;
    free(loops);
    return true;
}

/* Above this a ratio counts as over: an exact distance reads up to 1.002 a few steps from its crossing
 * (float positions), which is rounding, not an overshoot. */
static const double OVER_RATIO = 1.005;

void check_note_ratio(formula_check *c, double ratio, const float *p)
{
    c->samples++;
    c->over += ratio > OVER_RATIO;
    if (ratio > c->worst) {
        c->worst = ratio;
        for (int k = 0; k < 3; k++)
            c->worst_at[k] = p[k];
    }
}
