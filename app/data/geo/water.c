/* water — depressions filled by priority-flood (data/geo/water.h). */
#include "data/geo/water.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "data/geo/dem.h"
#include "data/geo/geo.h"

typedef struct cell {
    float z;
    uint32_t i;
} cell;

typedef struct heap { /* a binary min-heap of cells by height */
    cell *a;
    size_t n, cap;
} heap;

static void heap_push(heap *q, float z, uint32_t i)
{
    if (q->n == q->cap) {
        q->cap = q->cap ? 2 * q->cap : 4096;
        q->a = util_realloc(q->a, q->cap * sizeof *q->a, "water's queue");
    }
    size_t k = q->n++;
    while (k > 0 && q->a[(k - 1) / 2].z > z) {
        q->a[k] = q->a[(k - 1) / 2];
        k = (k - 1) / 2;
    }
    q->a[k] = (cell){z, i};
}

static cell heap_pop(heap *q)
{
    cell top = q->a[0], last = q->a[--q->n];
    size_t k = 0;
    for (;;) {
        size_t c = 2 * k + 1;
        if (c >= q->n)
            break;
        if (c + 1 < q->n && q->a[c + 1].z < q->a[c].z)
            c++;
        if (!(q->a[c].z < last.z))
            break;
        q->a[k] = q->a[c];
        k = c;
    }
    if (q->n)
        q->a[k] = last;
    return top;
}

static const int DI[8] = {-1, 0, 1, -1, 1, -1, 0, 1}, DJ[8] = {-1, -1, -1, 0, 0, 1, 1, 1};

/* A cell on the grid's edge or next to nodata: water leaves the grid through it. */
static bool drains(const float *g, int w, int h, int i, int j)
{
    if (i == 0 || j == 0 || i == w - 1 || j == h - 1)
        return true;
    for (int k = 0; k < 8; k++)
        if (isnan(g[(size_t)(j + DJ[k]) * (size_t)w + (size_t)(i + DI[k])]))
            return true;
    return false;
}

/* Lakes (8-connected raised cells, one level each) shallower or smaller than asked left dry. */
static void keep_lakes(const water_fill_desc *d, float *s, water_fill_stats *st)
{
    size_t n = (size_t)d->w * (size_t)d->h;
    uint32_t *stack = util_alloc(n * sizeof *stack, "water's lakes");
    uint8_t *seen = util_calloc(n, 1, "water's lakes");
    for (size_t c0 = 0; c0 < n; c0++) {
        if (isnan(s[c0]) || seen[c0])
            continue;
        size_t top = 0, first = 0, cells = 0;
        double deepest = 0, volume = 0;
        stack[top++] = (uint32_t)c0;
        seen[c0] = 1;
        while (first < top) { /* breadth first: the stack holds the whole lake afterwards */
            uint32_t c = stack[first++];
            int i = (int)(c % (uint32_t)d->w), j = (int)(c / (uint32_t)d->w);
            double depth = (double)s[c] - d->ground[c];
            deepest = fmax(deepest, depth);
            volume += depth * d->dx * d->dz;
            cells++;
            for (int k = 0; k < 8; k++) {
                int a = i + DI[k], b = j + DJ[k];
                size_t q = (size_t)b * (size_t)d->w + (size_t)a;
                if (a >= 0 && b >= 0 && a < d->w && b < d->h && !seen[q] && !isnan(s[q])) {
                    seen[q] = 1;
                    stack[top++] = (uint32_t)q;
                }
            }
        }
        if (deepest < d->min_depth || (double)cells * d->dx * d->dz < d->min_area) {
            for (size_t k = 0; k < top; k++)
                s[stack[k]] = NAN;
            st->dropped++;
            continue;
        }
        st->lakes++;
        st->wet += cells;
        st->volume += volume;
        st->deepest = fmax(st->deepest, deepest);
    }
    free(stack);
    free(seen);
}

/* The ground at texel coordinates (x, y), bilinear; NaN off the grid or over a hole. */
static double ground_at(const float *g, int w, int h, double x, double y)
{
    if (!(x >= 0 && y >= 0 && x <= w - 1 && y <= h - 1))
        return NAN;
    int i = (int)fmin(floor(x), w > 1 ? w - 2 : 0), j = (int)fmin(floor(y), h > 1 ? h - 2 : 0);
    int i1 = i + (w > 1), j1 = j + (h > 1);
    double a = x - i, b = y - j;
    double v = (1 - b) * ((1 - a) * g[(size_t)j * (size_t)w + (size_t)i] + a * g[(size_t)j * (size_t)w + (size_t)i1]) +
               b * ((1 - a) * g[(size_t)j1 * (size_t)w + (size_t)i] + a * g[(size_t)j1 * (size_t)w + (size_t)i1]);
    return v < -1e20 ? NAN : v;
}

void water_rivers(const float *ground, int w, int h, double dx, double dz, float ex, const geo_river *r, int n,
                  float *out)
{
    float *best = util_alloc((size_t)w * (size_t)h * sizeof *best, "the rivers"); /* each texel's nearest step */
    float *river = util_alloc((size_t)w * (size_t)h * sizeof *river, "the rivers");
    for (int k = 0; k < n; k++) {
        const geo_river *v = &r[k];
        for (size_t c = 0; c < (size_t)w * (size_t)h; c++)
            river[c] = WATER_DRY, best[c] = INFINITY;
        bool down = !(ground_at(ground, w, h, v->pt[0][0], v->pt[0][1]) <
                      ground_at(ground, w, h, v->pt[v->n - 1][0], v->pt[v->n - 1][1])); /* from the higher end */
        double level = INFINITY, rx = 0.5 * v->width / dx, rz = 0.5 * v->width / dz;
        for (int s = 0; s + 1 < v->n; s++) {
            const double *a = v->pt[down ? s : v->n - 1 - s], *b = v->pt[down ? s + 1 : v->n - 2 - s];
            int steps = (int)fmax(1, ceil(2 * fmax(fabs(b[0] - a[0]), fabs(b[1] - a[1]))));
            for (int q = s == 0 ? 0 : 1; q <= steps; q++) {
                double x = a[0] + (b[0] - a[0]) * q / steps, y = a[1] + (b[1] - a[1]) * q / steps;
                double g = ground_at(ground, w, h, x, y);
                if (isnan(g))
                    continue;
                level = fmin(level, g + v->depth * ex);
                for (int j = (int)ceil(y - rz); j <= (int)floor(y + rz); j++)
                    for (int i = (int)ceil(x - rx); i <= (int)floor(x + rx); i++) {
                        if (i < 0 || j < 0 || i >= w || j >= h)
                            continue;
                        double ex2 = ((i - x) * dx) * ((i - x) * dx) + ((j - y) * dz) * ((j - y) * dz);
                        size_t c = (size_t)j * (size_t)w + (size_t)i;
                        if (ex2 <= 0.25 * v->width * v->width && ex2 < best[c] && ground[c] > -1e20f) {
                            best[c] = (float)ex2;
                            river[c] = (float)level;
                        }
                    }
            }
        }
        for (size_t c = 0; c < (size_t)w * (size_t)h; c++)
            out[c] = river[c] > out[c] ? river[c] : out[c];
    }
    free(river);
    free(best);
}

bool water_is_vector(const char *file)
{
    static const char *const EXT[] = {".geojson", ".json", ".gpkg", ".shp", ".kml", ".gml", ".fgb"};
    const char *dot = strrchr(file, '.');
    for (size_t i = 0; dot && i < sizeof EXT / sizeof EXT[0]; i++)
        if (!strcasecmp(dot, EXT[i]))
            return true;
    return false;
}

bool water_grid(const float *ground, int w, int h, double dx, double dz, const char *dem, const char *raster, float ex,
                float *out, float *top, err_t *err)
{
    size_t n = (size_t)w * (size_t)h;
    *top = WATER_DRY;
    if (raster && water_is_vector(raster)) {
        geo_river *rivers;
        int n_rivers;
        if (!geo_water_vectors(dem, raster, w, h, out, &rivers, &n_rivers, err))
            return false;
        for (size_t c = 0; c < n; c++)
            out[c] = isnan(out[c]) || ground[c] < -1e20f ? WATER_DRY : out[c] * ex;
        water_rivers(ground, w, h, dx, dz, ex, rivers, n_rivers, out);
        geo_rivers_free(rivers, n_rivers);
    } else if (raster) {
        int rw, rh;
        float *v = NULL;
        dem_info info;
        if (!dem_read(raster, 1 << 16, &rw, &rh, &v, &info, err))
            return false;
        if (rw != w || rh != h) {
            free(v);
            return err_set(err, "terrain.water: the raster '%s' is %d x %d texels and the DEM %d x %d: water is read on the "
                                "DEM's own grid (gdalwarp -ts %d %d -te with the DEM's extent puts it there)",
                           raster, rw, rh, w, h, w, h);
        }
        for (size_t c = 0; c < n; c++) /* over nodata ground (a hole) no water either */
            out[c] = isnan(v[c]) || ground[c] < -1e20f ? WATER_DRY : v[c] * ex;
        free(v);
    } else {
        float *g = util_alloc(n * sizeof *g, "the lakes' ground");
        for (size_t c = 0; c < n; c++)
            g[c] = ground[c] < -1e20f ? NAN : ground[c];
        water_fill_desc d = {.ground = g, .w = w, .h = h, .dx = 1, .dz = 1};
        water_fill_stats st;
        bool ok = water_fill(&d, out, &st, err);
        free(g);
        if (!ok)
            return false;
        for (size_t c = 0; c < n; c++)
            out[c] = isnan(out[c]) ? WATER_DRY : out[c];
    }
    for (size_t c = 0; c < n; c++)
        *top = out[c] > *top ? out[c] : *top;
    return true;
}

bool water_fill(const water_fill_desc *d, float *surface, water_fill_stats *st, err_t *err)
{
    (void)err;
    *st = (water_fill_stats){0};
    int w = d->w, h = d->h;
    size_t n = (size_t)w * (size_t)h;
    const float *g = d->ground;
    uint8_t *closed = util_calloc(n, 1, "water's cells");
    float *f = surface; /* the filled heights first, then the water's level where raised */
    heap open = {0};
    uint32_t *pit = util_alloc(n * sizeof *pit, "water's pit"); /* each cell enters it at most once */
    size_t pit_head = 0, pit_tail = 0;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            size_t c = (size_t)j * (size_t)w + (size_t)i;
            f[c] = g[c];
            if (isnan(g[c]))
                closed[c] = 1;
            else if (drains(g, w, h, i, j)) {
                closed[c] = 1;
                heap_push(&open, g[c], (uint32_t)c);
            }
        }
    while (open.n || pit_head < pit_tail) {
        uint32_t c = pit_head < pit_tail ? pit[pit_head++] : heap_pop(&open).i;
        int i = (int)(c % (uint32_t)w), j = (int)(c / (uint32_t)w);
        for (int k = 0; k < 8; k++) {
            int a = i + DI[k], b = j + DJ[k];
            if (a < 0 || b < 0 || a >= w || b >= h)
                continue;
            size_t q = (size_t)b * (size_t)w + (size_t)a;
            if (closed[q])
                continue;
            closed[q] = 1;
            if (f[q] <= f[c]) { /* lower (or level): flooded to c's height, and on from there at once */
                f[q] = f[c];
                pit[pit_tail++] = (uint32_t)q;
            } else {
                heap_push(&open, f[q], (uint32_t)q);
            }
        }
    }
    free(open.a);
    free(pit);
    free(closed);
    for (size_t c = 0; c < n; c++) /* raised cells are water; the rest (and nodata) dry */
        if (!(f[c] > g[c]))
            f[c] = NAN;
    keep_lakes(d, f, st);
    return true;
}
