#include "jobs/bench/metrics.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>

#include "view/aov.h"
#include "util.h"

static bool hits(const image_view *v, int x, int y)
{
    return !isinf(v->aov[((size_t)y * (size_t)v->width + (size_t)x) * AOV_FLOATS + AOV_SLOT_DEPTH]);
}

/* How far the edge moved at a flipped pixel: the distance (pixels) to the nearest reference pixel
 * that agrees with the test there (a silhouette grown by one pixel gives 1; capped). */
static double edge_distance(const image_view *ref, int x, int y, bool test_hits)
{
    enum { MAX_SEARCH = 64 };
    double best = MAX_SEARCH;
    for (int r = 1; r < MAX_SEARCH && r < best; r++)
        for (int dy = -r; dy <= r; dy++)
            for (int dx = -r; dx <= r; dx++) {
                if (abs(dx) != r && abs(dy) != r)
                    continue; /* the ring at Chebyshev distance r */
                int xx = x + dx, yy = y + dy;
                if (xx >= 0 && yy >= 0 && xx < ref->width && yy < ref->height && hits(ref, xx, yy) == test_hits)
                    best = fmin(best, sqrt((double)(dx * dx + dy * dy)));
            }
    return best;
}

/* Silhouettes: IoU of the hit masks and the farthest a flipped pixel lies from the reference's edge. */
static void silhouettes(const image_view *test, const image_view *ref, metrics *m)
{
    size_t both = 0, either = 0;
    for (int y = 0; y < ref->height; y++)
        for (int x = 0; x < ref->width; x++) {
            bool a = hits(test, x, y), b = hits(ref, x, y);
            both += a && b;
            either += a || b;
            if (a != b)
                m->edge_max_px = fmax(m->edge_max_px, edge_distance(ref, x, y, a));
        }
    m->iou = either ? (double)both / (double)either : 1.0;
}

/* A pixel of the reference's silhouette: a 4-neighbour misses where it hits (or the reverse), or both
 * hit 5 % apart in depth (one surface before another). */
static bool on_silhouette(const image_view *ref, int x, int y)
{
    const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
    double z = ref->aov[((size_t)y * (size_t)ref->width + (size_t)x) * AOV_FLOATS + AOV_SLOT_DEPTH];
    for (int k = 0; k < 4; k++) {
        int u = x + dx[k], v = y + dy[k];
        if (u < 0 || v < 0 || u >= ref->width || v >= ref->height)
            continue;
        double n = ref->aov[((size_t)v * (size_t)ref->width + (size_t)u) * AOV_FLOATS + AOV_SLOT_DEPTH];
        if (isinf(n) != isinf(z) || (!isinf(z) && fabs(n - z) > 0.05 * fmin(n, z)))
            return true;
    }
    return false;
}

/* The colour's squared error at pixel i, summed over its three channels (display colour, 0..1). */
static double colour_se(const image_view *test, const image_view *ref, size_t i)
{
    double se = 0;
    for (int c = 0; c < 3; c++) {
        double d = ((double)test->srgb[i * 4 + (size_t)c] - (double)ref->srgb[i * 4 + (size_t)c]) / 255.0;
        se += d * d;
    }
    return se;
}

static void edges(const image_view *test, const image_view *ref, metrics *m)
{
    double se = 0;
    for (int y = 0; y < ref->height; y++)
        for (int x = 0; x < ref->width; x++)
            if (on_silhouette(ref, x, y)) {
                se += colour_se(test, ref, (size_t)y * (size_t)ref->width + (size_t)x);
                m->edge_pixels++;
            }
    m->edge_rmse = m->edge_pixels ? sqrt(se / (3.0 * m->edge_pixels)) : 0;
}

metrics metrics_compare(const image_view *test, const image_view *ref, double pixel_angle)
{
    assert(test->width == ref->width && test->height == ref->height);
    size_t n = (size_t)test->width * (size_t)test->height;
    metrics m = {0};
    double se = 0, depth_sum = 0, steps = 0;
    long exhausted = 0;
    size_t flips = 0;
    for (size_t i = 0; i < n; i++) {
        se += colour_se(test, ref, i);
        double ta = test->aov[i * AOV_FLOATS + AOV_SLOT_DEPTH], tr = ref->aov[i * AOV_FLOATS + AOV_SLOT_DEPTH];
        float st = test->aov[i * AOV_FLOATS + AOV_SLOT_STEPS];
        steps += fabsf(st);
        exhausted += st < 0;
        if (isinf(ta) != isinf(tr)) {
            flips++;
        } else if (!isinf(tr)) {
            double foot = (tr + ref->footprint_t0) * pixel_angle; /* 0: a ray that starts on the surface */
            double fp = foot > 0 ? fabs(ta - tr) / foot : ta == tr ? 0.0 : INFINITY;
            depth_sum += fp;
            m.depth_max_fp = fmax(m.depth_max_fp, fp);
            m.depth_pixels++;
        }
    }
    m.rmse = sqrt(se / (3.0 * (double)n));
    m.psnr_db = m.rmse > 0 ? 20.0 * log10(1.0 / m.rmse) : INFINITY;
    m.depth_mean_fp = m.depth_pixels ? depth_sum / m.depth_pixels : 0;
    m.flip_share = (double)flips / (double)n;
    m.mean_steps = steps / (double)n;
    m.exhausted_share = (double)exhausted / (double)n;
    silhouettes(test, ref, &m);
    edges(test, ref, &m);
    return m;
}

void metrics_upscale(const image_view *in, int w, int h, uint8_t **srgb, float **aov)
{
    *srgb = util_alloc((size_t)w * (size_t)h * 4, "an image");
    *aov = util_alloc(sizeof(float) * (size_t)w * (size_t)h * AOV_FLOATS, "an image");
    assert(*srgb && *aov);
    double sx = (double)in->width / w, sy = (double)in->height / h;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            /* sample at the output pixel's centre, in input pixel units */
            double fx = (x + 0.5) * sx - 0.5, fy = (y + 0.5) * sy - 0.5;
            int x0 = (int)floor(fx), y0 = (int)floor(fy);
            double ax = fx - x0, ay = fy - y0;
            int x1 = x0 + 1 < in->width ? x0 + 1 : in->width - 1, y1 = y0 + 1 < in->height ? y0 + 1 : in->height - 1;
            x0 = x0 < 0 ? 0 : x0;
            y0 = y0 < 0 ? 0 : y0;
            size_t o = ((size_t)y * (size_t)w + (size_t)x);
            for (int c = 0; c < 4; c++) {
                double v = (1 - ay) * ((1 - ax) * in->srgb[((size_t)y0 * (size_t)in->width + (size_t)x0) * 4 + (size_t)c] +
                                       ax * in->srgb[((size_t)y0 * (size_t)in->width + (size_t)x1) * 4 + (size_t)c]) +
                           ay * ((1 - ax) * in->srgb[((size_t)y1 * (size_t)in->width + (size_t)x0) * 4 + (size_t)c] +
                                 ax * in->srgb[((size_t)y1 * (size_t)in->width + (size_t)x1) * 4 + (size_t)c]);
                (*srgb)[o * 4 + (size_t)c] = (uint8_t)lround(v);
            }
            int nx = (int)((x + 0.5) * sx), ny = (int)((y + 0.5) * sy);
            nx = nx < in->width ? nx : in->width - 1;
            ny = ny < in->height ? ny : in->height - 1;
            for (int c = 0; c < AOV_FLOATS; c++)
                (*aov)[o * AOV_FLOATS + (size_t)c] = in->aov[((size_t)ny * (size_t)in->width + (size_t)nx) * AOV_FLOATS + (size_t)c];
        }
}

double metrics_median_interval(const double *v, int n, double *lo, double *hi)
{
    assert(n > 0);
    double *c = util_alloc(sizeof *c * (size_t)n, "timings");
    for (int i = 0; i < n; i++)
        c[i] = v[i];
    util_sort(c, n);
    /* P(Bin(n, 1/2) <= j), accumulated term by term: C(n, i) / 2^n */
    int k = 1;
    double term = ldexp(1.0, -n), cdf = term; /* i = 0 */
    for (int j = 1; j < n; j++) {
        if (2 * cdf > 0.05) /* the tail up to j - 1 is too heavy: k = j - 1 at most */
            break;
        k = j;
        term *= (double)(n - j + 1) / j;
        cdf += term;
    }
    *lo = c[k - 1];
    *hi = c[n - k];
    double m = (n % 2) ? c[n / 2] : 0.5 * (c[n / 2 - 1] + c[n / 2]);
    free(c);
    return m;
}

void metrics_pareto(const double *lo, const double *hi, const double *error, int n, bool *front)
{
    for (int i = 0; i < n; i++) {
        front[i] = true;
        for (int j = 0; j < n && front[i]; j++) {
            bool faster = hi[j] < lo[i];      /* measurably */
            bool not_slower = lo[j] <= hi[i]; /* faster, or not measurably slower */
            if (j != i && ((faster && error[j] <= error[i]) || (not_slower && error[j] < error[i])))
                front[i] = false;
        }
    }
}
