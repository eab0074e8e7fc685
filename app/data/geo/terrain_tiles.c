#include "data/geo/terrain_tiles.h"

#include <math.h>
#include <stdlib.h>

#include "data/geo/terrain.h"
#include "util.h"

static int log2_ceil(int v)
{
    int k = 0;
    while ((1 << k) < v)
        k++;
    return k;
}

static int at_least_1(int v) { return v > 0 ? v : 1; }

/* min and max of heights that are never NaN (holes are TERRAIN_HOLE): inlined, where fminf and fmaxf are
 * library calls that took 22 % of a summary's time */
static inline float lo2(float a, float b) { return a < b ? a : b; }
static inline float hi2(float a, float b) { return a > b ? a : b; }

void terrain_grid_plan(int width, int height, int tile_cells, terrain_grid *g)
{
    *g = (terrain_grid){.width = width, .height = height};
    int cw = width > 1 ? width - 1 : 1, ch = height > 1 ? height - 1 : 1;
    int sx = log2_ceil(cw), sy = log2_ceil(ch); /* as terrain.c's build(): padded cells, levels */
    g->pw = 1 << sx, g->ph = 1 << sy;
    g->levels = (sx > sy ? sx : sy) + 1;
    int t = tile_cells > 0 ? log2_ceil(tile_cells) : 30;
    g->shift_x = sx < t ? sx : t;
    g->shift_y = sy < t ? sy : t;
    g->tiles_x = (cw + (1 << g->shift_x) - 1) >> g->shift_x;
    g->tiles_y = (ch + (1 << g->shift_y) - 1) >> g->shift_y;
    int shift = g->shift_x > g->shift_y ? g->shift_x : g->shift_y;
    g->tile_level = shift < g->levels - 1 ? shift : g->levels - 1;
    g->slot_w = (1 << g->shift_x) + 1 < width ? (1 << g->shift_x) + 1 : width;
    g->slot_h = (1 << g->shift_y) + 1 < height ? (1 << g->shift_y) + 1 : height;
}

void terrain_tile_window(const terrain_grid *g, int tx, int ty, int *x0, int *y0, int *w, int *h)
{
    *x0 = tx << g->shift_x, *y0 = ty << g->shift_y;
    *w = g->width - *x0 < g->slot_w ? g->width - *x0 : g->slot_w;
    *h = g->height - *y0 < g->slot_h ? g->height - *y0 : g->slot_h;
}

void terrain_tile_level_size(const terrain_grid *g, int k, int *nx, int *ny)
{
    *nx = at_least_1((1 << g->shift_x) >> k);
    *ny = at_least_1((1 << g->shift_y) >> k);
}

size_t terrain_tile_level_floats(const terrain_grid *g)
{
    size_t n = 0;
    for (int k = 1; k < g->tile_level; k++) {
        int nx, ny;
        terrain_tile_level_size(g, k, &nx, &ny);
        n += (size_t)nx * (size_t)ny;
    }
    return n;
}

/* The highest corner of the tile's cell (i, j) (local), −inf beyond the grid or touching a hole: as
 * heightfield_cell_max. */
static float cell_max(const float *hgt, int w, int h, int i, int j)
{
    if (i >= w - 1 || j >= h - 1)
        return -INFINITY;
    const float *r0 = hgt + (size_t)j * (size_t)w + (size_t)i, *r1 = r0 + w;
    float lo = lo2(lo2(r0[0], r0[1]), lo2(r1[0], r1[1]));
    return TERRAIN_IS_HOLE(lo) ? -INFINITY : hi2(hi2(r0[0], r0[1]), hi2(r1[0], r1[1]));
}

/* A level-k node's value from level k − 1's (n_x × n_y, or the cells when k == 1): the 2×2 below it that
 * exist, as build() takes them. */
static float node(const float *below, int bx, int by, const float *hgt, int w, int h, int k, int i, int j)
{
    float m = -INFINITY;
    for (int b = 0; b < 2; b++)
        for (int a = 0; a < 2; a++) {
            int x = 2 * i + a, y = 2 * j + b;
            if (x < bx && y < by)
                m = hi2(m, k == 1 ? cell_max(hgt, w, h, x, y) : below[(size_t)y * (size_t)bx + (size_t)x]);
        }
    return m;
}

void terrain_tile_build(const terrain_grid *g, int tx, int ty, const float *hgt, float dx, float dz, float *levels,
                        terrain_tile_stats *st)
{
    int x0, y0, w, h;
    terrain_tile_window(g, tx, ty, &x0, &y0, &w, &h);
    int cx = 1 << g->shift_x, cy = 1 << g->shift_y;
    *st = (terrain_tile_stats){.max = -INFINITY, .hmin = INFINITY, .hmax = -INFINITY};
    /* texels this tile owns: its shared last column and row belong to the next tile, except at the grid's edge */
    int ow = tx == g->tiles_x - 1 ? w : cx, oh = ty == g->tiles_y - 1 ? h : cy;
    for (int j = 0; j < oh; j++) {
        const float *r = hgt + (size_t)j * (size_t)w;
        for (int i = 0; i < ow; i++) {
            if (TERRAIN_IS_HOLE(r[i])) {
                st->holes++;
                continue;
            }
            st->hmin = lo2(st->hmin, r[i]);
            st->hmax = hi2(st->hmax, r[i]);
        }
    }
    float g2 = 0, top = -INFINITY;
    for (int j = 0; j + 1 < h; j++) { /* its cells: the steepest (terrain.c's build()) and the highest */
        const float *r0 = hgt + (size_t)j * (size_t)w, *r1 = r0 + w;
        for (int i = 0; i + 1 < w; i++) {
            float a = r0[i], b = r0[i + 1], c = r1[i], d = r1[i + 1];
            if (TERRAIN_IS_HOLE(lo2(lo2(a, b), lo2(c, d))))
                continue;
            float gx = hi2(fabsf(b - a), fabsf(d - c)) / dx, gz = hi2(fabsf(c - a), fabsf(d - b)) / dz;
            g2 = hi2(g2, gx * gx + gz * gz); /* squared here, its root once below */
            top = hi2(top, hi2(hi2(a, b), hi2(c, d)));
        }
    }
    st->lipschitz = g2, st->max = top;
    st->lipschitz = sqrtf(st->lipschitz);
    if (!levels)
        return;
    const float *below = NULL;
    int bx = cx, by = cy; /* level 0: the cells */
    for (int k = 1; k < g->tile_level; k++) {
        int nx, ny;
        terrain_tile_level_size(g, k, &nx, &ny);
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++)
                levels[(size_t)j * (size_t)nx + (size_t)i] = node(below, bx, by, hgt, w, h, k, i, j);
        below = levels;
        levels += (size_t)nx * (size_t)ny;
        bx = nx, by = ny;
    }
}

void terrain_top_size(const terrain_grid *g, int k, int *nx, int *ny)
{
    *nx = at_least_1(g->pw >> k);
    *ny = at_least_1(g->ph >> k);
}

float **terrain_top_build(const terrain_grid *g, const float *tile_max)
{
    int n = g->levels - g->tile_level;
    float **top = util_calloc((size_t)n, sizeof *top, "the terrain's top pyramid");
    for (int k = g->tile_level; k < g->levels; k++) {
        int nx, ny;
        terrain_top_size(g, k, &nx, &ny);
        float *lv = top[k - g->tile_level] = util_alloc(sizeof(float) * (size_t)nx * (size_t)ny, "the terrain's top pyramid");
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++) {
                float m = -INFINITY;
                if (k == g->tile_level) {
                    if (i < g->tiles_x && j < g->tiles_y)
                        m = tile_max[(size_t)j * (size_t)g->tiles_x + (size_t)i];
                } else {
                    int bx, by;
                    terrain_top_size(g, k - 1, &bx, &by);
                    m = node(top[k - 1 - g->tile_level], bx, by, NULL, 0, 0, k, i, j);
                }
                lv[(size_t)j * (size_t)nx + (size_t)i] = m;
            }
    }
    return top;
}

void terrain_top_free(const terrain_grid *g, float **top)
{
    if (!top)
        return;
    for (int k = 0; k < g->levels - g->tile_level; k++)
        free(top[k]);
    free(top);
}
