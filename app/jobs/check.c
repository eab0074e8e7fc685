/* check — a formula's distance estimate against the distance to the surface along rays (check.h). */
#include "jobs/check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/gpu.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"

enum {
    FINITE_POINTS = 1 << 14, /* random points probed for NaN and Inf */
    RAYS = 96,               /* rays through the set */
    STEPS = 2048,            /* dense samples a ray */
    FINE = 64,               /* samples across the two dense steps around a candidate crossing */
    BISECTIONS = 14,         /* halvings of the fine step that bracket the crossing */
    SKIP_STEPS = 4,          /* samples nearer the crossing than this many steps are not compared */
};
static const double INSIDE_REL = 1e-5; /* "on the surface": an estimate below this share of the bound */

static double rnd(unsigned *state, double lo, double hi)
{
    *state = *state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (double)(*state >> 8) / 16777216.0;
}

/* The estimates at n points, and (where the driver has a loop limiter: c->loops_measured) the most loop
 * iterations one of them ran into c->loops (c NULL: not measured): the random points and the dense
 * samples along the rays, near the surface included, where estimates run longest. */
static bool probe(const scene *s, const float *pts, int n, float *out, formula_check *c, err_t *err)
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

/* Finiteness over random points in a cube of twice the bound, plus the origin and the axes. */
static bool check_finite(const scene *s, unsigned *seed, formula_check *c, err_t *err)
{
    double R = s->fractal.bound_radius;
    float *pts = util_alloc(sizeof(float) * 3 * FINITE_POINTS, "check points");
    float *d = util_alloc(sizeof(float) * 2 * FINITE_POINTS, "check estimates");
    for (int i = 0; i < FINITE_POINTS; i++)
        for (int k = 0; k < 3; k++)
            pts[3 * i + k] = (float)rnd(seed, -2 * R, 2 * R);
    static const float special[][3] = {{0, 0, 0}, {1e-30f, 0, 0}, {0, 1e-30f, 0}, {0, 0, 1e-30f}, {0, 1, 0},
                                       {0, -1, 0}, {1, 0, 0}, {0, 0, 1}, {1e-3f, 1e-3f, 1e-3f}};
    memcpy(pts, special, sizeof special);
    bool ok = probe(s, pts, FINITE_POINTS, d, c, err);
    c->points = FINITE_POINTS;
    for (int i = 0; ok && i < FINITE_POINTS; i++)
        c->nonfinite += !isfinite(d[2 * i]);
    free(pts);
    free(d);
    return ok;
}

/* Bisection of each ray's bracket [lo, hi] on "estimate below the inside threshold". */
static bool bisect(const scene *s, const float *o, const float *dir, double *lo, double *hi, int n, float inside,
                   err_t *err)
{
    float *pts = util_alloc(sizeof(float) * 3 * (size_t)n, "check points"), *d = util_alloc(sizeof(float) * 2 * (size_t)n, "check");
    bool ok = true;
    for (int b = 0; ok && b < BISECTIONS; b++) {
        for (int r = 0; r < n; r++)
            for (int k = 0; k < 3; k++)
                pts[3 * r + k] = (float)(o[3 * r + k] + 0.5 * (lo[r] + hi[r]) * dir[3 * r + k]);
        ok = probe(s, pts, n, d, NULL, err);
        for (int r = 0; ok && r < n; r++)
            *(d[2 * r] < inside ? &hi[r] : &lo[r]) = 0.5 * (lo[r] + hi[r]);
    }
    free(pts);
    free(d);
    return ok;
}

/* For each ray with a candidate sample first[r] (-1: none, left as it is), the first of FINE samples
 * over [t - h, t + h] whose estimate is below `inside` brackets the crossing in [lo, hi]; a ray with
 * none passed by (first -1). */
static bool locate_crossings(const scene *s, const float *o, const float *dir, double h, float inside, int *first,
                             double *lo, double *hi, err_t *err)
{
    size_t n = (size_t)RAYS * FINE;
    float *pts = util_alloc(sizeof(float) * 3 * n, "check points"), *d = util_alloc(sizeof(float) * 2 * n, "check");
    double fine = 2 * h / FINE;
    for (int r = 0; r < RAYS; r++)
        for (int j = 0; j < FINE; j++) {
            double t = (first[r] - 1) * h + j * fine;
            for (int k = 0; k < 3; k++)
                pts[3 * ((size_t)r * FINE + (size_t)j) + (size_t)k] = (float)(o[3 * r + k] + t * dir[3 * r + k]);
        }
    bool ok = probe(s, pts, (int)n, d, NULL, err);
    for (int r = 0; ok && r < RAYS; r++) {
        if (first[r] <= 0)
            continue;
        int hit = -1;
        for (int j = 0; j < FINE && hit < 0; j++)
            if (d[2 * ((size_t)r * FINE + (size_t)j)] < inside)
                hit = j;
        if (hit <= 0) { /* passed within a step of the set without meeting it */
            first[r] = -1;
            continue;
        }
        hi[r] = (first[r] - 1) * h + hit * fine;
        lo[r] = hi[r] - fine;
    }
    free(pts);
    free(d);
    return ok;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The estimate along each ray against the distance to its first crossing. */
static bool check_rays(const scene *s, unsigned *seed, formula_check *c, err_t *err)
{
    double R = s->fractal.bound_radius, len = 3 * R, h = len / STEPS;
    float inside = (float)(INSIDE_REL * R);
    size_t n = (size_t)RAYS * STEPS;
    float *o = util_alloc(sizeof(float) * 3 * RAYS, "rays"), *dir = util_alloc(sizeof(float) * 3 * RAYS, "rays");
    float *pts = util_alloc(sizeof(float) * 3 * n, "check points"), *d = util_alloc(sizeof(float) * 2 * n, "check");
    for (int r = 0; r < RAYS; r++) { /* from the sphere of 1.5 R toward a point within R/2 of the centre */
        double a[3], t[3], l = 0;
        do {
            l = 0;
            for (int k = 0; k < 3; k++)
                a[k] = rnd(seed, -1, 1), l += a[k] * a[k];
        } while (l > 1 || l < 1e-4);
        for (int k = 0; k < 3; k++)
            a[k] *= 1.5 * R / sqrt(l), t[k] = rnd(seed, -0.5 * R, 0.5 * R);
        double dl = sqrt((t[0] - a[0]) * (t[0] - a[0]) + (t[1] - a[1]) * (t[1] - a[1]) + (t[2] - a[2]) * (t[2] - a[2]));
        for (int k = 0; k < 3; k++) {
            o[3 * r + k] = (float)a[k], dir[3 * r + k] = (float)((t[k] - a[k]) / dl);
            for (int i = 0; i < STEPS; i++)
                pts[3 * ((size_t)r * STEPS + (size_t)i) + (size_t)k] = (float)(a[k] + i * h * dir[3 * r + k]);
        }
    }
    bool ok = probe(s, pts, (int)n, d, c, err);
    double lo[RAYS], hi[RAYS];
    int first[RAYS];
    /* the first sample below `inside` brackets the crossing with the one before it; a ray with none
     * but a sample within a quarter step of the surface (a sheet thinner than the step) gets FINE
     * samples across the steps around that one */
    int candidate[RAYS];
    for (int r = 0; ok && r < RAYS; r++) {
        first[r] = candidate[r] = -1;
        for (int i = 0; i < STEPS && first[r] < 0; i++) {
            float e = d[2 * ((size_t)r * STEPS + (size_t)i)];
            if (e < inside)
                first[r] = i;
            else if (e < 0.25 * h && candidate[r] < 0)
                candidate[r] = i;
        }
        lo[r] = first[r] > 0 ? (first[r] - 1) * h : 0, hi[r] = first[r] > 0 ? first[r] * h : 0;
        if (first[r] >= 0)
            candidate[r] = -1;
    }
    ok = ok && locate_crossings(s, o, dir, h, inside, candidate, lo, hi, err);
    for (int r = 0; ok && r < RAYS; r++)
        if (candidate[r] > 0)
            first[r] = candidate[r];
    ok = ok && bisect(s, o, dir, lo, hi, RAYS, inside, err);
    double *ratios = util_alloc(sizeof(double) * n, "ratios");
    c->rays = RAYS;
    for (int r = 0; ok && r < RAYS; r++) {
        if (first[r] <= 0)
            continue; /* missed the set, or started inside it */
        c->crossing++;
        for (int i = 0; (i + SKIP_STEPS) * h < lo[r]; i++) {
            double est = d[2 * ((size_t)r * STEPS + (size_t)i)], dist = hi[r] - i * h, ratio = est / dist;
            ratios[c->samples++] = ratio;
            c->over += ratio > 1;
            if (ratio > c->worst) {
                c->worst = ratio;
                for (int k = 0; k < 3; k++)
                    c->worst_at[k] = o[3 * r + k] + i * h * dir[3 * r + k];
            }
        }
    }
    if (c->samples) {
        qsort(ratios, (size_t)c->samples, sizeof *ratios, by_value);
        c->p99 = ratios[(size_t)c->samples * 99 / 100];
    }
    free(ratios);
    free(o);
    free(dir);
    free(pts);
    free(d);
    return ok;
}

bool check_formula(const scene *s, unsigned seed, formula_check *out, err_t *err)
{
    /* a Julia set or a hybrid is not the formula its @step was measured for: the scene's own step factor */
    bool mode = s->fractal.julia || s->fractal.has_hybrid;
    *out = (formula_check){.step = mode ? s->quality.step_factor : s->fractal.formula.step > 0 ? s->fractal.formula.step : 1.0,
                           .mode = mode, .loops_measured = true, .loops_declared = s->fractal.loops};
    if (!program_is_fractal(s->program))
        return err_set(err, "%s: check-formula checks fractal formulas; this scene's program is %s", s->path,
                       program_name(s->program));
    if (!render_set_scene(s, NULL, err) || !check_finite(s, &seed, out, err) || !check_rays(s, &seed, out, err))
        return false;
    out->suggested = out->worst > 1 ? 1 / out->worst : 1;
    out->ok = out->nonfinite == 0 && out->crossing > 0 && out->step * out->worst <= CHECK_TOLERANCE &&
              (!out->loops_measured || out->loops <= out->loops_declared);
    return true;
}

void check_describe(const scene *s, const formula_check *c, strbuf *out)
{
    const formula *f = &s->fractal.formula;
    sb_printf(out, "formula %s (%s)%s%s%s: %s\n", f->name, f->file, s->fractal.julia ? ", Julia set" : "",
              s->fractal.has_hybrid ? ", hybrid with " : "", s->fractal.has_hybrid ? s->fractal.hybrid.name : "",
              c->ok ? "passes" : "FAILS");
    sb_printf(out, "  finite: %d of %d estimates are NaN or Inf\n", c->nonfinite, c->points);
    sb_printf(out, "  bound: %d of %d rays met the surface; over %d samples the estimate / distance to the "
                   "crossing is at worst %.3f (99th percentile %.3f), above 1 at %d\n",
              c->crossing, c->rays, c->samples, c->worst, c->p99, c->over);
    if (c->worst > 1)
        sb_printf(out, "  worst at (%.4g, %.4g, %.4g)\n", c->worst_at[0], c->worst_at[1], c->worst_at[2]);
    sb_printf(out, "  step factor: %s %.3g; every sample stays inside its crossing at %.3g%s\n",
              c->mode ? "the scene's (a Julia set or hybrid)" : "declared", c->step, c->suggested,
              c->step * c->worst <= CHECK_TOLERANCE ? ""
              : c->mode ? ": set quality.step_factor to it or lower"
                        : ": set @step (and quality.step_factor) to it or lower");
    if (c->crossing == 0)
        sb_printf(out, "  no ray met the surface: check @bound and the parameters\n");
    if (!c->loops_measured)
        sb_printf(out, "  loops: not measured (this driver has no loop limiter to count them against)\n");
    else
        sb_printf(out, "  loops: an estimate runs at most %d loop iterations; @loops declares %d%s\n", c->loops,
                  c->loops_declared, c->loops <= c->loops_declared ? ""
                  : ": fathom's loop budget would run short and llvmpipe would cut pixels; declare @loops to at "
                    "least that (an expression of the parameters) or bound the loops by FRACTAL_ITERATIONS");
}

bool check_formula_run(const check_desc *d, err_t *err)
{
    scene s;
    if (!scene_load(d->scene, d->sets, d->set_count, &s, err))
        return false;
    if (!gpu_open(&(gpu_desc){.headless = true}, err)) {
        scene_free(&s);
        return false;
    }
    formula_check c;
    bool ok = render_init(err) && check_formula(&s, 1u, &c, err);
    if (ok) {
        strbuf text = {0};
        check_describe(&s, &c, &text);
        fputs(text.data, stdout);
        sb_free(&text);
        if (!c.ok)
            ok = err_set(err, "formula %s fails its check (above)", s.fractal.formula.name);
    }
    render_shutdown();
    gpu_close();
    scene_free(&s);
    return ok;
}
