/* viewshed — exact visibility over a bilinear heightfield with Earth curvature (viewshed.h). */
#include "data/geo/viewshed.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Index of (i, j) in a row-major grid w wide. */
static size_t at(int w, int i, int j) { return (size_t)j * (size_t)w + (size_t)i; }

typedef struct pyramid {
    int levels;
    int nx[32], nz[32]; /* nodes a side at each level (level 0: the cells) */
    double *max[32];    /* each node's highest corner height; −inf where it has no surface */
} pyramid;

/* Level 0: each cell's highest corner (−inf for a cell with a nodata corner: no surface); level L:
 * the maximum of 2×2 nodes of level L − 1. */
static void pyramid_build(const viewshed_desc *d, pyramid *p)
{
    memset(p, 0, sizeof *p);
    int cx = d->w - 1, cz = d->h - 1;
    p->nx[0] = cx, p->nz[0] = cz;
    p->max[0] = util_alloc(sizeof(double) * (size_t)cx * (size_t)cz, "the viewshed's cell maxima");
    for (int j = 0; j < cz; j++)
        for (int i = 0; i < cx; i++) {
            const float *r0 = d->heights + at(d->w, i, j), *r1 = r0 + d->w;
            double m = fmax(fmax(r0[0], r0[1]), fmax(r1[0], r1[1]));
            bool hole = isnan(r0[0]) || isnan(r0[1]) || isnan(r1[0]) || isnan(r1[1]);
            p->max[0][at(cx, i, j)] = hole ? -INFINITY : m;
        }
    int L = 0;
    while (p->nx[L] > 1 || p->nz[L] > 1) {
        int nx = (p->nx[L] + 1) / 2, nz = (p->nz[L] + 1) / 2;
        double *m = util_alloc(sizeof(double) * (size_t)nx * (size_t)nz, "the viewshed's pyramid");
        for (int j = 0; j < nz; j++)
            for (int i = 0; i < nx; i++) {
                double v = -INFINITY;
                for (int q = 0; q < 4; q++) {
                    int a = 2 * i + (q & 1), b = 2 * j + (q >> 1);
                    if (a < p->nx[L] && b < p->nz[L])
                        v = fmax(v, p->max[L][at(p->nx[L], a, b)]);
                }
                m[at(nx, i, j)] = v;
            }
        L++;
        p->nx[L] = nx, p->nz[L] = nz, p->max[L] = m;
    }
    p->levels = L + 1;
}

static void pyramid_free(pyramid *p)
{
    for (int L = 0; L < p->levels; L++)
        free(p->max[L]);
}

static double texel(const viewshed_desc *d, int i, int j) { return d->heights[at(d->w, i, j)]; }

/* The ground under a continuous texel position (bilinear); NaN over a hole. */
static double ground(const viewshed_desc *d, double c, double r)
{
    int i = (int)fmin(floor(c), d->w - 2), j = (int)fmin(floor(r), d->h - 2);
    double u = c - i, v = r - j, wt[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v}, sum = 0;
    for (int k = 0; k < 4; k++) /* a corner of no weight adds nothing, a nodata one either (NaN × 0 is NaN) */
        sum += wt[k] > 0 ? wt[k] * texel(d, i + (k & 1), j + (k >> 1)) : 0;
    return sum;
}

/* One line of sight: from the observer (cell coordinates o, eye height yo) to a target e away in cell
 * coordinates, its point at sight height yt (already dropped by the curvature) and the drop factor
 * cD2 = c·D² (the drop at parameter s is cD2·s²). */
typedef struct sight {
    double oc, or_, ec, er, yo, yt, cD2;
} sight;

/* The line's parameter interval inside [x0, x1] × [z0, z1] (cell coordinates); false if it misses. */
static bool clip(const sight *l, double x0, double x1, double z0, double z1, double *sa, double *sb)
{
    double a = 0, b = 1;
    const double o[2] = {l->oc, l->or_}, e[2] = {l->ec, l->er}, lo[2] = {x0, z0}, hi[2] = {x1, z1};
    for (int k = 0; k < 2; k++) {
        if (e[k] == 0) {
            if (o[k] < lo[k] || o[k] > hi[k])
                return false;
            continue;
        }
        double t0 = (lo[k] - o[k]) / e[k], t1 = (hi[k] - o[k]) / e[k];
        if (t0 > t1) {
            double t = t0;
            t0 = t1, t1 = t;
        }
        a = fmax(a, t0), b = fmin(b, t1);
    }
    *sa = a, *sb = b;
    return a <= b;
}

/* Whether cell (i, j)'s patch rises above the sight line on [sa, sb]: the clearance
 * f(s) = yo + s (yt − yo) + cD2 s² − h(s) is A s² + B s + C there (h bilinear along a line). */
static bool cell_blocks(const viewshed_desc *d, const sight *l, int i, int j, double sa, double sb)
{
    double h00 = texel(d, i, j), h10 = texel(d, i + 1, j), h01 = texel(d, i, j + 1), h11 = texel(d, i + 1, j + 1);
    double a = h10 - h00, b = h01 - h00, c = h00 - h10 - h01 + h11;
    double u0 = l->oc - i, v0 = l->or_ - j;
    double A = l->cD2 - c * l->ec * l->er;
    double B = (l->yt - l->yo) - (a * l->ec + b * l->er + c * (u0 * l->er + v0 * l->ec));
    double C = l->yo - (h00 + a * u0 + b * v0 + c * u0 * v0);
    double m = fmin((A * sa + B) * sa + C, (A * sb + B) * sb + C);
    if (A > 0) {
        double s = -B / (2 * A);
        if (s > sa && s < sb)
            m = fmin(m, (A * s + B) * s + C);
    }
    return m < -VIEWSHED_TIE;
}

/* Whether the sight line stays clear: the pyramid descended from its top, nodes the line passes above
 * skipped. Counts the nodes visited. */
static bool sight_clear(const viewshed_desc *d, const pyramid *p, const sight *l, size_t *visits)
{
    typedef struct { int L, i, j; } node;
    node stack[32 * 4 + 8];
    int n = 0, top = p->levels - 1;
    for (int j = 0; j < p->nz[top]; j++)
        for (int i = 0; i < p->nx[top]; i++)
            stack[n++] = (node){top, i, j};
    double rise = l->yt - l->yo;
    while (n > 0) {
        node q = stack[--n];
        (*visits)++;
        double m = p->max[q.L][at(p->nx[q.L], q.i, q.j)];
        if (m == -INFINITY)
            continue;
        double side = (double)(1 << q.L), sa, sb;
        double x0 = q.i * side, z0 = q.j * side;
        double x1 = fmin(x0 + side, p->nx[0]), z1 = fmin(z0 + side, p->nz[0]);
        if (!clip(l, x0, x1, z0, z1, &sa, &sb))
            continue;
        /* the clearance's lowest bound over the node: the line's lower end plus the smallest drop (s ≥ sa) */
        double floor_line = l->yo + fmin(sa * rise, sb * rise) + l->cD2 * sa * sa;
        if (m <= floor_line + VIEWSHED_TIE)
            continue;
        if (q.L == 0) {
            if (cell_blocks(d, l, q.i, q.j, sa, sb))
                return false;
            continue;
        }
        /* the child nearest the target is popped first: a hidden texel is most often hidden by the ground
         * just before it (its own back slope), so its blocker is found sooner (512²: 75 nodes a texel, 114
         * in the fixed order, 126 nearest the observer first) */
        int flip = 3 ^ ((l->ec < 0) | (l->er < 0) << 1);
        for (int k = 3; k >= 0; k--) {
            int c = k ^ flip, ci = 2 * q.i + (c & 1), cj = 2 * q.j + (c >> 1);
            if (ci < p->nx[q.L - 1] && cj < p->nz[q.L - 1])
                stack[n++] = (node){q.L - 1, ci, cj};
        }
    }
    return true;
}

typedef struct job {
    const viewshed_desc *d;
    const pyramid *p;
    unsigned char *out;
    double yo, c; /* eye height; the drop's factor (1 − k) / 2R (0: flat) */
    int first, step; /* rows first, first + step, ... */
    size_t visits;
} job;

static void *run_rows(void *arg)
{
    job *jb = arg;
    const viewshed_desc *d = jb->d;
    double r2 = d->radius > 0 ? d->radius * d->radius : INFINITY;
    for (int j = jb->first; j < d->h; j += jb->step)
        for (int i = 0; i < d->w; i++) {
            unsigned char *o = jb->out + at(d->w, i, j);
            double ht = texel(d, i, j);
            double mx = (i - d->col) * d->dx, mz = (j - d->row) * d->dz, D2 = mx * mx + mz * mz;
            if (isnan(ht) || D2 > r2) {
                *o = VIEWSHED_NODATA;
                continue;
            }
            sight l = {d->col, d->row, i - d->col, j - d->row, jb->yo, ht + d->target_height - jb->c * D2, jb->c * D2};
            *o = sight_clear(d, jb->p, &l, &jb->visits) ? VIEWSHED_VISIBLE : VIEWSHED_HIDDEN;
        }
    return NULL;
}

bool viewshed_compute(const viewshed_desc *d, unsigned char *out, viewshed_stats *stats, err_t *err)
{
    if (d->w < 2 || d->h < 2)
        return err_set(err, "the viewshed needs a DEM of at least 2 × 2 texels (this one is %d × %d)", d->w, d->h);
    /* on the DEM: within its extent, half a texel past the edge texels' centres (there, the edge's ground) */
    const double e = 1e-6; /* a point given in degrees comes back a hair off where it was meant */
    if (!(d->col >= -0.5 - e && d->col <= d->w - 0.5 + e && d->row >= -0.5 - e && d->row <= d->h - 0.5 + e))
        return err_set(err, "the observer (texel %.1f, %.1f) is outside the DEM (-0.5 to %g, -0.5 to %g): give a point "
                            "on it", d->col, d->row, d->w - 0.5, d->h - 0.5);
    viewshed_desc on = *d; /* a texel centre snapped to it; past the edge texels' centres, the edge's */
    on.col = fmin(fmax(fabs(d->col - round(d->col)) < e ? round(d->col) : d->col, 0), d->w - 1);
    on.row = fmin(fmax(fabs(d->row - round(d->row)) < e ? round(d->row) : d->row, 0), d->h - 1);
    d = &on;
    double g = ground(d, d->col, d->row);
    if (isnan(g))
        return err_set(err, "the observer (texel %.1f, %.1f) stands over a nodata hole of the DEM: move it onto ground",
                       d->col, d->row);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    pyramid p;
    pyramid_build(d, &p);
    int threads = d->threads > 0 ? d->threads : (int)sysconf(_SC_NPROCESSORS_ONLN);
    threads = threads < 1 ? 1 : threads > 64 ? 64 : threads;
    job jobs[64];
    pthread_t tid[64];
    bool started[64] = {false};
    double c = d->curvature ? (1 - d->refraction) / (2 * VIEWSHED_EARTH_RADIUS) : 0;
    for (int t = 0; t < threads; t++) {
        jobs[t] = (job){d, &p, out, g + d->observer_height, c, t, threads, 0};
        started[t] = t > 0 && pthread_create(&tid[t], NULL, run_rows, &jobs[t]) == 0;
    }
    size_t visits = 0;
    for (int t = 0; t < threads; t++) { /* a thread that could not start has its rows run here */
        if (started[t])
            pthread_join(tid[t], NULL);
        else
            run_rows(&jobs[t]);
        visits += jobs[t].visits;
    }
    pyramid_free(&p);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    viewshed_stats st = {0};
    for (size_t k = 0; k < (size_t)d->w * (size_t)d->h; k++)
        st.visible += out[k] == VIEWSHED_VISIBLE, st.hidden += out[k] == VIEWSHED_HIDDEN, st.nodata += out[k] == VIEWSHED_NODATA;
    st.nodes_per_texel = (double)visits / ((double)d->w * d->h);
    st.threads = threads;
    st.seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    if (stats)
        *stats = st;
    return true;
}
