/* check — `fathom check-formula NAME|FILE`: a formula's distance estimate checked before it is trusted,
 * with the shader's own map() probed on the GPU, at its defaults and at each end of each parameter's
 * range (check_corners.c):
 *   - finite: no NaN or Inf over random points in and around its bounding sphere (and on the axes and
 *     at the origin, where guards matter);
 *   - steps (check.c): random points in the bound each take the march's step (estimate × step factor)
 *     down the estimate's gradient; one that lands inside the set overshot it, by at least the
 *     estimate over the distance to the first point inside along the step (bisection). Even over the
 *     volume: an overshoot confined to a narrow cone is met;
 *   - rays (check_rays.c): along random rays through the set, then rounds of rays around the worst, the
 *     estimate at each sample against the distance to the ray's first crossing of the surface (found by
 *     dense stepping, then bisection on "estimate below a tiny threshold"). That distance is at least
 *     the true distance from the sample to the set, so an estimate above it overshoots: sphere tracing
 *     at step factor k tunnels when k · estimate > distance. Finds overshoots at a thin sheet, which a
 *     step jumps over. The report gives the worst ratio, the share above 1, and the step factor that
 *     keeps every sample's step inside (1 / worst ratio);
 *   - the bound: the bounding sphere probed with the bound lifted (evenly, then in shrinking caps around
 *     its points nearest the set) and random points in the shell beyond it: a set that reaches past
 *     its bound is drawn clipped;
 *   - its loops: at the random points and the first rays, the loop iterations one estimate runs,
 *     measured against the driver's loop limiter (llvmpipe's; shaders/common/budget.glsl), against what
 *     it declares (@loops): the loop budget is spent by the declaration, so a formula that loops longer
 *     would be cut by the driver mid-image. Not measurable on a driver without a limiter (a GPU).
 * A formula passes when nothing is non-finite, its @step (1 when absent) times the worst ratio stays
 * within CHECK_TOLERANCE of 1, the set stays inside its bound, no estimate loops more than it declares
 * and (at the defaults) some ray met the surface. */
#ifndef FATHOM_CHECK_H
#define FATHOM_CHECK_H

#include <stdbool.h>

#include "jobs/check/check_types.h"
#include "scene/scene.h"
#include "util.h"

enum { CHECK_RAYS = 192, CHECK_CORNER_RAYS = 64 }; /* random rays at the defaults, at a range's ends */

/* Runs the checks on a fractal scene (its formula and parameters) in the current GL context, after
 * render_init. `seed` fixes the random rays and points; `rays` random rays (0: CHECK_RAYS), then
 * rounds around the worst. */
bool check_formula(const scene *s, unsigned seed, int rays, formula_check *out, err_t *err);

/* Whether a check passes: nothing non-finite, no overshoot past the step factor, the set inside its
 * bound, no loops past @loops, and (surface_needed) some ray met the surface. At a range's end a set
 * may be dust no ray meets: that is what it is, and the rest still holds. */
bool check_passes(const formula_check *c, bool surface_needed);

/* The report as text, one finding a line. */
void check_describe(const scene *s, const formula_check *c, strbuf *out);

/* What `fathom check-formula NAME|FILE [--set ...]` checks: the scene (the fractal one, its formula
 * set by an override) and the overrides. */
typedef struct check_desc {
    const char *scene;
    const char *const *sets;
    int set_count;
    bool defaults_only; /* --quick: not the range ends */
} check_desc;
enum { CHECK_SET_MAX = 160, CHECK_CORNERS_MAX = 64 };

/* The corners of a formula's parameter ranges, as overrides "fractal.KEY=VALUE" into out (at most
 * max; the count): the iterations and each parameter at both ends of its range (and of its gap), a
 * vector's components one at a time, a bool at the value it does not default to; the other
 * parameters stay at their defaults, and a parameter the user's overrides set is not varied. */
int check_corners(const formula *f, const check_desc *d, char (*out)[CHECK_SET_MAX], int max);

/* Opens a headless context, checks the formula at its defaults and at each corner (check_corners),
 * prints the report and the worst parameter set; false (with err) when any fails or the formula
 * cannot be loaded. */
bool check_formula_run(const check_desc *d, err_t *err);

#endif
