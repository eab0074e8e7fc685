/* check — a formula's distance estimate checked: finite, as a step toward the set (and along rays:
 * check_rays.c; the probes both use: check_probe.c), and its bounding sphere against the set (check.h). */
#include "jobs/check/check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "jobs/check/check_probe.h"
#include "jobs/check/check_rays.h"

enum {
    FINITE_POINTS = 1 << 14, /* random points probed for NaN and Inf */
    SPHERE_POINTS = 8192,    /* the bounding sphere, evenly */
    SPHERE_BEST = 24,        /* then around the points nearest the set ... */
    SPHERE_NEAR = 48,        /* ... this many points each */
    SPHERE_ROUNDS = 4,       /* in rounds of shrinking caps */
    SHELL_POINTS = 1 << 13,  /* random points between the bound and 3 times it */
    STEP_POINTS = 1 << 14,   /* random points in the bound, each stepped toward the set by its estimate */
};

/* Where the first rays aim besides the middle: the random points with the smallest estimates (a set far
 * smaller than its bound, or off its centre, is met all the same). */
static void target_add(check_targets *t, const float *p, double d)
{
    if (!(d >= 0) || (t->n == CHECK_TARGETS && d >= t->d[CHECK_TARGETS - 1]))
        return;
    int i = t->n < CHECK_TARGETS ? t->n++ : CHECK_TARGETS - 1;
    for (; i > 0 && t->d[i - 1] > d; i--) /* kept sorted, nearest first */
        t->d[i] = t->d[i - 1], memcpy(t->at[i], t->at[i - 1], sizeof t->at[i]);
    t->d[i] = d;
    for (int k = 0; k < 3; k++)
        t->at[i][k] = p[k];
}

/* Finiteness over random points in a cube of twice the bound, plus the origin and the axes. */
static bool check_finite(const scene *s, unsigned *seed, formula_check *c, check_targets *near, err_t *err)
{
    double R = s->fractal.bound_radius;
    float *pts = util_alloc(sizeof(float) * 3 * FINITE_POINTS, "check points");
    float *d = util_alloc(sizeof(float) * 2 * FINITE_POINTS, "check estimates");
    for (int i = 0; i < FINITE_POINTS; i++)
        for (int k = 0; k < 3; k++)
            pts[3 * i + k] = (float)check_rnd(seed, -2 * R, 2 * R);
    static const float special[][3] = {{0, 0, 0}, {1e-30f, 0, 0}, {0, 1e-30f, 0}, {0, 0, 1e-30f}, {0, 1, 0},
                                       {0, -1, 0}, {1, 0, 0}, {0, 0, 1}, {1e-3f, 1e-3f, 1e-3f}};
    memcpy(pts, special, sizeof special);
    bool ok = check_probe(s, pts, FINITE_POINTS, d, c, err);
    c->points = FINITE_POINTS;
    for (int i = 0; ok && i < FINITE_POINTS; i++) {
        c->nonfinite += !isfinite(d[2 * i]);
        if (d[2 * i] >= 0 && d[2 * i] < 1e30f)
            target_add(near, pts + 3 * i, d[2 * i]);
    }
    free(pts);
    free(d);
    return ok;
}

/* ---- the estimate as a step toward the set ----------------------------------------------------------- */

/* Each of STEP_POINTS random points in the bound takes the march's step from there: its estimate d
 * times the step factor (over CHECK_TOLERANCE), down the estimate's gradient (central differences),
 * toward where the set is nearest. A step that lands inside the set overshot it: the first point inside
 * along the step, found by bisection at t, makes the ratio at least d / t. This covers the volume around
 * the set evenly (an overshoot confined to a narrow cone, which no ray of a hundred passes, is met by
 * some of these points); the rays below find what this misses, a thin sheet the step jumps over. */
static bool check_steps(const scene *s, unsigned *seed, double step, formula_check *c, err_t *err)
{
    double R = s->fractal.bound_radius, h = 1e-4 * R;
    float inside = (float)(CHECK_INSIDE_REL * R);
    int n = STEP_POINTS, m = 0;
    float *pts = util_alloc(sizeof(float) * 3 * (size_t)n, "check points"), *d = util_alloc(sizeof(float) * 2 * (size_t)n, "check");
    for (int i = 0; i < n; i++) { /* uniform in the ball */
        double u[3], r = R * cbrt(check_rnd(seed, 0, 1));
        check_rnd_dir(seed, u);
        for (int k = 0; k < 3; k++)
            pts[3 * i + k] = (float)(r * u[k]);
    }
    bool ok = check_probe(s, pts, n, d, NULL, err);
    int *keep = util_alloc(sizeof(int) * (size_t)n, "check points");
    for (int i = 0; ok && i < n; i++) /* far enough from the set that a step's landing is told apart from it */
        if (isfinite(d[2 * i]) && d[2 * i] > 200 * inside && d[2 * i] < R)
            keep[m++] = i;
    float *g = util_alloc(sizeof(float) * 3 * 6 * (size_t)n, "check points");
    float *gd = util_alloc(sizeof(float) * 2 * 6 * (size_t)n, "check");
    for (int j = 0; j < m; j++)
        for (int a = 0; a < 6; a++)
            for (int k = 0; k < 3; k++)
                g[3 * (6 * j + a) + k] = pts[3 * keep[j] + k] + (float)(k == a / 2 ? (a % 2 ? -h : h) : 0);
    if (m) /* none kept: nothing to step from (a set that fills the bound, or an estimate out of range) */
        ok = ok && check_probe(s, g, 6 * m, gd, NULL, err);
    /* the step: from p by d · step / tolerance down the gradient; lo, hi bracket "inside" along it */
    double *dir = util_alloc(sizeof(double) * 3 * (size_t)n, "check"), *lo = util_calloc((size_t)n, sizeof(double), "check");
    double *hi = util_alloc(sizeof(double) * (size_t)n, "check");
    for (int j = 0; ok && j < m; j++) {
        double l = 0;
        for (int k = 0; k < 3; k++)
            dir[3 * j + k] = -(gd[2 * (6 * j + 2 * k)] - gd[2 * (6 * j + 2 * k + 1)]), l += dir[3 * j + k] * dir[3 * j + k];
        for (int k = 0; k < 3; k++)
            dir[3 * j + k] = l > 0 && isfinite(l) ? dir[3 * j + k] / sqrt(l) : 0;
        hi[j] = d[2 * keep[j]] * step / CHECK_TOLERANCE;
    }
    float *q = util_alloc(sizeof(float) * 3 * (size_t)n, "check points"), *qd = util_alloc(sizeof(float) * 2 * (size_t)n, "check");
    int *over = util_alloc(sizeof(int) * (size_t)n, "check"), n_over = 0;
    for (int b = 0; ok && m && b <= CHECK_BISECTIONS && (b == 0 || n_over); b++) { /* the step's end, then halvings */
        int count = b == 0 ? m : n_over;
        for (int i = 0; i < count; i++) {
            int j = b == 0 ? i : over[i];
            double t = b == 0 ? hi[j] : 0.5 * (lo[j] + hi[j]);
            for (int k = 0; k < 3; k++)
                q[3 * i + k] = (float)(pts[3 * keep[j] + k] + t * dir[3 * j + k]);
        }
        ok = check_probe(s, q, count, qd, NULL, err);
        for (int i = 0; ok && i < count; i++) {
            int j = b == 0 ? i : over[i];
            bool in = qd[2 * i] < inside;
            if (b == 0 && in && (dir[3 * j] != 0 || dir[3 * j + 1] != 0 || dir[3 * j + 2] != 0))
                over[n_over++] = j;
            else if (b > 0)
                *(in ? &hi[j] : &lo[j]) = 0.5 * (lo[j] + hi[j]);
        }
    }
    c->step_points = m;
    c->step_inside = n_over;
    for (int i = 0; ok && i < n_over; i++)
        check_note_ratio(c, d[2 * keep[over[i]]] / hi[over[i]], pts + 3 * keep[over[i]]);
    free(pts), free(d), free(keep), free(g), free(gd), free(dir), free(lo), free(hi), free(q), free(qd), free(over);
    return ok;
}

/* ---- the bounding sphere holds the set ------------------------------------------------------------- */

/* Points of the sphere of radius r in directions dirs (n of them) probed; the smallest estimate and its
 * point into c when below c->sphere_min. */
static bool sphere_probe(const scene *wide, const double *dirs, int n, double r, float *d, formula_check *c,
                         err_t *err)
{
    float *pts = util_alloc(sizeof(float) * 3 * (size_t)n, "check points");
    for (int i = 0; i < 3 * n; i++)
        pts[i] = (float)(r * dirs[i]);
    bool ok = check_probe(wide, pts, n, d, NULL, err);
    for (int i = 0; ok && i < n; i++)
        if (d[2 * i] < c->sphere_min) {
            c->sphere_min = d[2 * i];
            for (int k = 0; k < 3; k++)
                c->sphere_at[k] = pts[3 * i + k];
        }
    free(pts);
    return ok;
}

static int by_estimate(const void *a, const void *b)
{
    float x = ((const float *)a)[0], y = ((const float *)b)[0];
    return (x > y) - (x < y);
}

/* A set that reaches past its bounding sphere crosses it (or lies apart from the rest, beyond it):
 * the sphere's points are probed with the bound lifted, evenly, then in shrinking caps around the
 * points nearest the set (the smallest estimates), for any point inside; and random points between
 * the bound and 3 times it. */
static bool check_contained(const scene *s, unsigned *seed, formula_check *c, err_t *err)
{
    scene wide = *s; /* the same scene with the bounding sphere out of reach: map() is the estimate */
    double B = s->fractal.bound_radius, r = B * (1 + 1e-3);
    wide.fractal.bound_radius = (float)(8 * B);
    float inside = (float)(CHECK_INSIDE_REL * B);
    c->sphere_min = INFINITY;
    int n = SPHERE_POINTS;
    double *dirs = util_alloc(sizeof(double) * 3 * (size_t)n, "sphere");
    float *d = util_alloc(sizeof(float) * 2 * (size_t)n, "sphere");
    for (int i = 0; i < n; i++) { /* a Fibonacci lattice */
        double z = 1 - (2 * i + 1.0) / n, rho = sqrt(1 - z * z), phi = i * 2.399963229728653;
        dirs[3 * i] = rho * cos(phi), dirs[3 * i + 1] = z, dirs[3 * i + 2] = rho * sin(phi);
    }
    bool ok = sphere_probe(&wide, dirs, n, r, d, c, err);
    double cap = 2 * sqrt(4 * 3.14159265358979 / n); /* radians: twice the lattice's spacing */
    for (int round = 0; ok && round < SPHERE_ROUNDS && c->sphere_min >= inside; round++, cap /= 4) {
        float (*order)[2] = util_alloc(sizeof *order * (size_t)n, "sphere"); /* estimate, index */
        for (int i = 0; i < n; i++)
            order[i][0] = d[2 * i], order[i][1] = (float)i;
        qsort(order, (size_t)n, sizeof *order, by_estimate);
        int m = SPHERE_BEST * SPHERE_NEAR;
        double *next = util_alloc(sizeof(double) * 3 * (size_t)m, "sphere");
        for (int b = 0; b < SPHERE_BEST; b++)
            for (int j = 0; j < SPHERE_NEAR; j++) {
                const double *at = dirs + 3 * (int)order[b][1];
                double u[3], l = 0, *out = next + 3 * (b * SPHERE_NEAR + j), t = check_rnd(seed, 0, cap);
                check_rnd_dir(seed, u);
                for (int k = 0; k < 3; k++)
                    out[k] = at[k] + t * u[k], l += out[k] * out[k];
                for (int k = 0; k < 3; k++)
                    out[k] /= sqrt(l);
            }
        free(order);
        free(dirs);
        free(d);
        dirs = next, n = m;
        d = util_alloc(sizeof(float) * 2 * (size_t)n, "sphere");
        ok = sphere_probe(&wide, dirs, n, r, d, c, err);
    }
    free(dirs);
    free(d);
    /* the shell: denser near the bound */
    float *pts = util_alloc(sizeof(float) * 3 * SHELL_POINTS, "shell"), *e = util_alloc(sizeof(float) * 2 * SHELL_POINTS, "shell");
    for (int i = 0; i < SHELL_POINTS; i++) {
        double u[3], t = check_rnd(seed, 0, 1), rr = r * (1 + 2 * t * t);
        check_rnd_dir(seed, u);
        for (int k = 0; k < 3; k++)
            pts[3 * i + k] = (float)(rr * u[k]);
    }
    ok = ok && check_probe(&wide, pts, SHELL_POINTS, e, NULL, err);
    c->reach = 0;
    for (int i = 0; ok && i < SHELL_POINTS; i++) {
        double rr = sqrt((double)pts[3 * i] * pts[3 * i] + (double)pts[3 * i + 1] * pts[3 * i + 1] +
                         (double)pts[3 * i + 2] * pts[3 * i + 2]);
        if (e[2 * i] < inside && rr > c->reach)
            c->reach = rr;
    }
    free(pts);
    free(e);
    c->framing = s->fractal.formula.fragment; /* FORMULA_EXACT: no sphere clips a fragment */
    c->contained = (c->sphere_min >= inside && c->reach == 0) || c->framing;
    return ok;
}

bool check_formula(const scene *s, unsigned seed, int random_rays, formula_check *out, err_t *err)
{
    /* a Julia set or a hybrid is not the formula its @step was measured for: the scene's own step factor */
    /* a Julia set, a hybrid or a fragment (no @step: its preset's FudgeFactor) steps by the scene's factor */
    bool mode = s->fractal.julia || s->fractal.has_hybrid || s->fractal.formula.fragment;
    *out = (formula_check){.step = mode ? s->quality.step_factor : s->fractal.step > 0 ? s->fractal.step : 1.0,
                           .mode = mode, .random_rays = random_rays > 0 ? random_rays : CHECK_RAYS, .loops_measured = true, .loops_declared = s->fractal.loops};
    if (!program_is_fractal(s->program))
        return err_set(err, "%s: check-formula checks fractal formulas; this scene's program is %s", s->path,
                       program_name(s->program));
    check_targets near = {0};
    if (!render_set_scene(s, NULL, err) || !check_finite(s, &seed, out, &near, err) ||
        !check_steps(s, &seed, out->step, out, err) || !check_rays(s, &seed, out->random_rays, &near, out, err) ||
        !check_contained(s, &seed, out, err))
        return false;
    out->suggested = out->worst > 1 ? 1 / out->worst : 1;
    out->ok = check_passes(out, true);
    return true;
}

bool check_passes(const formula_check *c, bool surface_needed)
{
    return c->nonfinite == 0 && (c->crossing > 0 || !surface_needed) && c->step * c->worst <= CHECK_TOLERANCE &&
           c->contained && (!c->loops_measured || c->loops <= c->loops_declared);
}

void check_describe(const scene *s, const formula_check *c, strbuf *out)
{
    sb_printf(out, "  finite: %d of %d estimates are NaN or Inf\n", c->nonfinite, c->points);
    sb_printf(out, "  steps: from %d random points in the bound, a step of the estimate times the step factor toward "
                   "the set landed inside it from %d\n", c->step_points, c->step_inside);
    sb_printf(out, "  estimate: %d of %d rays met the surface (%d at random, the rest around the worst); over %d "
                   "samples the estimate / distance to the crossing is at worst %.3f (99th percentile %.3f), above 1.005 at %d\n",
              c->crossing, c->rays, c->random_rays, c->samples, c->worst, c->p99, c->over);
    if (c->worst > 1)
        sb_printf(out, "  worst at (%.4g, %.4g, %.4g)\n", c->worst_at[0], c->worst_at[1], c->worst_at[2]);
    sb_printf(out, "  step factor: %s %.3g; every sample stays inside its crossing at %.3g%s\n",
              c->mode ? "the scene's (a Julia set, hybrid or fragment)" : "declared", c->step, c->suggested,
              c->step * c->worst <= CHECK_TOLERANCE ? ""
              : s->fractal.formula.fragment ? ": set quality.step_factor to it or lower (a fragment's preset: FudgeFactor)"
              : c->mode ? ": set quality.step_factor to it or lower"
                        : ": set @step (and quality.step_factor) to it or lower");
    if (c->crossing == 0)
        sb_printf(out, "  no ray met the surface: check @bound and the parameters\n");
    double B = s->fractal.bound_radius;
    if (c->framing)
        sb_printf(out, "  bound: a fragment's DE is marched without a bounding sphere (radius %.4g frames the view)%s\n",
                  B, c->reach > 0 ? "; the set reaches past it" : "");
    else if (c->contained)
        sb_printf(out, "  bound: the set stays inside the bounding sphere (radius %.4g; nearest estimate on it %.3g)\n", B,
                  c->sphere_min);
    else if (c->reach > 0)
        sb_printf(out, "  bound: the set reaches radius %.4g at least, past the bounding sphere's %.4g: it is drawn "
                       "clipped (raise @bound, or fractal.bound_radius)\n", c->reach, B);
    else
        sb_printf(out, "  bound: the set crosses the bounding sphere (radius %.4g) at (%.4g, %.4g, %.4g): it is drawn "
                       "clipped (raise @bound, or fractal.bound_radius)\n", B, c->sphere_at[0], c->sphere_at[1], c->sphere_at[2]);
    if (!c->loops_measured)
        sb_printf(out, "  loops: not measured (this driver has no loop limiter to count them against)\n");
    else
        sb_printf(out, "  loops: an estimate runs at most %d loop iterations; @loops declares %d%s\n", c->loops,
                  c->loops_declared, c->loops <= c->loops_declared ? ""
                  : ": fathom's loop budget would run short and llvmpipe would cut pixels; declare @loops to at "
                    "least that (an expression of the parameters) or bound the loops by FRACTAL_ITERATIONS");
}
