/* check-formula's rays: the estimate along rays through the set against the distance to each ray's
 * first crossing, found by dense stepping, a fine search and bisection; random rays first, then
 * rounds around the worst (check_probe.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "jobs/check/check_rays.h"

enum {
    SEEDS = 8,       /* the rays with the worst ratios (and thin crossings) ... */
    NEAR_SHARE = 16, /* ... each get one neighbour for every this many first rays */
    ROUNDS = 2,      /* in rounds of shrinking spread */
    STEPS = 1536,    /* dense samples a ray */
    FINE = 64,       /* samples across the two dense steps around a candidate crossing */
    SKIP_STEPS = 4,  /* samples nearer the crossing than this many steps are not compared */
};

/* n rays: origins on the sphere of 1.5 R, unit directions; what each found. */
typedef struct rays {
    int n;
    double *o, *dir;
    double *worst; /* the ray's worst ratio (0: it met no surface) */
    bool *thin;    /* it met a sheet thinner than a dense step */
} rays;

static rays rays_new(int n)
{
    return (rays){.n = n, .o = util_alloc(sizeof(double) * 3 * (size_t)n, "rays"),
                  .dir = util_alloc(sizeof(double) * 3 * (size_t)n, "rays"),
                  .worst = util_calloc((size_t)n, sizeof(double), "rays"), .thin = util_calloc((size_t)n, sizeof(bool), "rays")};
}

static void rays_free(rays *r)
{
    free(r->o), free(r->dir), free(r->worst), free(r->thin);
}

/* Every ratio compared, for the percentile. */
typedef struct ratios {
    double *v;
    size_t n, cap;
} ratios;

static void ratio_add(ratios *r, double x)
{
    if (r->n == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 1 << 16;
        r->v = util_realloc(r->v, sizeof(double) * r->cap, "check ratios");
    }
    r->v[r->n++] = x;
}

/* Bisection of each ray's bracket [lo, hi] on "estimate below the inside threshold". */
static bool bisect(const scene *s, const rays *R, double *lo, double *hi, float inside, err_t *err)
{
    int n = R->n;
    float *pts = util_alloc(sizeof(float) * 3 * (size_t)n, "check points"), *d = util_alloc(sizeof(float) * 2 * (size_t)n, "check");
    bool ok = true;
    for (int b = 0; ok && b < CHECK_BISECTIONS; b++) {
        for (int r = 0; r < n; r++)
            for (int k = 0; k < 3; k++)
                pts[3 * r + k] = (float)(R->o[3 * r + k] + 0.5 * (lo[r] + hi[r]) * R->dir[3 * r + k]);
        ok = check_probe(s, pts, n, d, NULL, err);
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
static bool locate_crossings(const scene *s, const rays *R, double h, float inside, int *first, double *lo,
                             double *hi, err_t *err)
{
    size_t n = (size_t)R->n * FINE;
    float *pts = util_alloc(sizeof(float) * 3 * n, "check points"), *d = util_alloc(sizeof(float) * 2 * n, "check");
    double fine = 2 * h / FINE;
    for (int r = 0; r < R->n; r++)
        for (int j = 0; j < FINE; j++) {
            double t = (first[r] - 1) * h + j * fine;
            for (int k = 0; k < 3; k++)
                pts[3 * ((size_t)r * FINE + (size_t)j) + (size_t)k] = (float)(R->o[3 * r + k] + t * R->dir[3 * r + k]);
        }
    bool ok = check_probe(s, pts, (int)n, d, NULL, err);
    for (int r = 0; ok && r < R->n; r++) {
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

/* Each ray's estimates against the distance to its first crossing, found by dense stepping (the first
 * sample below `inside`; a ray with none but a sample within a quarter step of the surface, a sheet
 * thinner than the step, gets FINE samples across the steps around it), then bisection. */
static bool trace(const scene *s, rays *R, bool loops, formula_check *c, ratios *all, err_t *err)
{
    double B = s->fractal.bound_radius, h = 3 * B / STEPS;
    float inside = (float)(CHECK_INSIDE_REL * B);
    int n = R->n;
    size_t count = (size_t)n * STEPS;
    float *pts = util_alloc(sizeof(float) * 3 * count, "check points"), *d = util_alloc(sizeof(float) * 2 * count, "check");
    for (int r = 0; r < n; r++)
        for (int i = 0; i < STEPS; i++)
            for (int k = 0; k < 3; k++)
                pts[3 * ((size_t)r * STEPS + (size_t)i) + (size_t)k] = (float)(R->o[3 * r + k] + i * h * R->dir[3 * r + k]);
    bool ok = check_probe(s, pts, (int)count, d, loops ? c : NULL, err);
    double *lo = util_calloc((size_t)n, sizeof(double), "rays"), *hi = util_calloc((size_t)n, sizeof(double), "rays");
    int *first = util_alloc(sizeof(int) * (size_t)n, "rays"), *candidate = util_alloc(sizeof(int) * (size_t)n, "rays");
    for (int r = 0; ok && r < n; r++) {
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
    ok = ok && locate_crossings(s, R, h, inside, candidate, lo, hi, err);
    for (int r = 0; ok && r < n; r++)
        if (candidate[r] > 0)
            first[r] = candidate[r], R->thin[r] = true;
    ok = ok && bisect(s, R, lo, hi, inside, err);
    c->rays += n;
    for (int r = 0; ok && r < n; r++) {
        if (first[r] <= 0)
            continue; /* missed the set, or started inside it */
        c->crossing++;
        for (int i = 0; (i + SKIP_STEPS) * h < lo[r]; i++) {
            double est = d[2 * ((size_t)r * STEPS + (size_t)i)], ratio = est / (hi[r] - i * h);
            ratio_add(all, ratio);
            R->worst[r] = fmax(R->worst[r], ratio);
            check_note_ratio(c, ratio, pts + 3 * ((size_t)r * STEPS + (size_t)i));
        }
    }
    free(lo), free(hi), free(first), free(candidate), free(pts), free(d);
    return ok;
}

/* The first rays: from the sphere of 1.5 R toward a random point within R/2 of the centre, every other
 * one toward one of the random points nearest the set (moved by up to 1 % of R). */
static void random_rays(double B, const check_targets *near, unsigned *seed, rays *R)
{
    for (int r = 0; r < R->n; r++) {
        double a[3], t[3], l = 0;
        check_rnd_dir(seed, a);
        for (int k = 0; k < 3; k++) {
            t[k] = r % 2 && near->n ? near->at[(r / 2) % near->n][k] + check_rnd(seed, -0.01 * B, 0.01 * B)
                                    : check_rnd(seed, -0.5 * B, 0.5 * B);
            a[k] *= 1.5 * B, l += (t[k] - a[k]) * (t[k] - a[k]);
        }
        for (int k = 0; k < 3; k++)
            R->o[3 * r + k] = a[k], R->dir[3 * r + k] = (t[k] - a[k]) / sqrt(l);
    }
}

/* The rays to look closer at: the worst ratios first, then thin crossings; their indices into `pick`. */
static int seeds_of(const rays *R, int *pick)
{
    int n = 0;
    bool *taken = util_calloc((size_t)R->n, sizeof(bool), "seeds");
    for (int s = 0; s < SEEDS; s++) {
        int best = -1;
        for (int r = 0; r < R->n; r++) /* a thin crossing counts as bad as a ratio of 1 when no worse is left */
            if (!taken[r] && (R->worst[r] > 0 || R->thin[r]) &&
                (best < 0 || fmax(R->worst[r], R->thin[r]) > fmax(R->worst[best], R->thin[best])))
                best = r;
        if (best < 0)
            break;
        taken[best] = true;
        pick[n++] = best;
    }
    free(taken);
    return n;
}

/* Neighbours of the seed rays: the origin moved along the sphere and the direction turned, by up to
 * `spread` radians. */
static void near_rays(const rays *from, const int *pick, int seeds, int near, double B, double spread, unsigned *seed,
                      rays *R)
{
    for (int s = 0; s < seeds; s++)
        for (int j = 0; j < near; j++) {
            int r = s * near + j, f = pick[s];
            double u[3], v[3], a[3], dl = 0, al = 0;
            check_rnd_dir(seed, u), check_rnd_dir(seed, v);
            double su = check_rnd(seed, 0, spread), sv = check_rnd(seed, 0, spread);
            for (int k = 0; k < 3; k++)
                a[k] = from->o[3 * f + k] + su * 1.5 * B * u[k], al += a[k] * a[k];
            for (int k = 0; k < 3; k++) {
                R->o[3 * r + k] = a[k] * 1.5 * B / sqrt(al);
                R->dir[3 * r + k] = from->dir[3 * f + k] + sv * v[k], dl += R->dir[3 * r + k] * R->dir[3 * r + k];
            }
            for (int k = 0; k < 3; k++)
                R->dir[3 * r + k] /= sqrt(dl);
        }
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Random rays, then rounds of rays around the worst of the last round: an overshoot confined to a
 * narrow cone or a thin fin is found once one ray grazes it. */
bool check_rays(const scene *s, unsigned *seed, int first_rays, const check_targets *near, formula_check *c,
                       err_t *err)
{
    double B = s->fractal.bound_radius;
    ratios all = {0};
    rays last = rays_new(first_rays);
    random_rays(B, near, seed, &last);
    bool ok = trace(s, &last, true, c, &all, err);
    double spread = 0.12; /* radians: about 7 degrees, then a third of it each round */
    for (int round = 0; ok && round < ROUNDS; round++, spread /= 3) {
        int pick[SEEDS], seeds = seeds_of(&last, pick);
        if (seeds == 0)
            break;
        int near_count = first_rays / NEAR_SHARE > 2 ? first_rays / NEAR_SHARE : 2;
        rays next = rays_new(seeds * near_count);
        near_rays(&last, pick, seeds, near_count, B, spread, seed, &next);
        ok = trace(s, &next, false, c, &all, err);
        rays_free(&last);
        last = next;
    }
    rays_free(&last);
    if (ok && all.n) {
        qsort(all.v, all.n, sizeof *all.v, by_value);
        c->p99 = all.v[all.n * 99 / 100];
    }
    free(all.v);
    return ok;
}

