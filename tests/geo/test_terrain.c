/* Terrain: first hits on a real DEM, and on a 4096² DEM and a long strip generated here, against an
 * exact ray–bilinear-heightfield intersection in double,
 * a thin ridge that only the exact method never tunnels through, and the height fog against
 * numerical quadrature in double. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <epoxy/gl.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include "check.h"
#include "gltest.h"
#include "data/media/image_io.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "data/geo/terrain.h"

/* ---- the reference: a ray against the solid column under a bilinear heightfield, in double ------- */

static double texel(const heightfield *hf, int i, int j) { return hf->h[j * hf->width + i]; }

static double height_cell(const heightfield *hf, double cx, double cz)
{
    cx = fmin(fmax(cx, 0), hf->width - 1);
    cz = fmin(fmax(cz, 0), hf->height - 1);
    int i = (int)fmin(floor(cx), hf->width - 2), j = (int)fmin(floor(cz), hf->height - 2);
    double a = cx - i, b = cz - j;
    return (1 - b) * ((1 - a) * texel(hf, i, j) + a * texel(hf, i + 1, j)) +
           b * ((1 - a) * texel(hf, i, j + 1) + a * texel(hf, i + 1, j + 1));
}

/* Smallest s in [0, s_end] with y(s) = h(s) on cell (i, j), or −1. */
static double cell_root(const heightfield *hf, int i, int j, double cx, double cz, double ux, double uz, double y,
                        double dy, double s_end)
{
    double h00 = texel(hf, i, j), h10 = texel(hf, i + 1, j), h01 = texel(hf, i, j + 1), h11 = texel(hf, i + 1, j + 1);
    if (TERRAIN_IS_HOLE(fmin(fmin(h00, h10), fmin(h01, h11))))
        return -1; /* nodata: no surface in this cell */
    double a = h10 - h00, b = h01 - h00, c = h00 - h10 - h01 + h11, u = cx - i, v = cz - j;
    double A = -c * ux * uz, B = dy - (a * ux + b * uz + c * (u * uz + v * ux)), C = y - (h00 + a * u + b * v + c * u * v);
    if (C <= 0)
        return 0;
    double roots[2];
    int n = 0;
    if (fabs(A) < 1e-300) {
        if (B != 0)
            roots[n++] = -C / B;
    } else {
        double disc = B * B - 4 * A * C;
        if (disc >= 0) {
            double q = -0.5 * (B + copysign(sqrt(disc), B));
            roots[n++] = q / A;
            if (q != 0)
                roots[n++] = C / q;
        }
    }
    double best = -1;
    for (int k = 0; k < n; k++)
        if (roots[k] >= 0 && roots[k] <= s_end * (1 + 1e-12) + 1e-9 && (best < 0 || roots[k] < best)) /* flat at the slab's floor */
            best = roots[k];
    return best;
}

static bool ref_terrain(const heightfield *hf, const dray *r, double *t_hit)
{
    double lo[3] = {hf->x0 + 0.5 * hf->dx, hf->hmin, hf->z0 + 0.5 * hf->dz};
    double hi[3] = {hf->x0 + (hf->width - 0.5) * hf->dx, hf->hmax, hf->z0 + (hf->height - 0.5) * hf->dz};
    double t0 = 0, t1 = INFINITY;
    for (int k = 0; k < 3; k++) {
        if (r->d[k] == 0) {
            if (r->o[k] < lo[k] || r->o[k] > hi[k])
                return false;
            continue;
        }
        double a = (lo[k] - r->o[k]) / r->d[k], b = (hi[k] - r->o[k]) / r->d[k];
        t0 = fmax(t0, fmin(a, b));
        t1 = fmin(t1, fmax(a, b));
    }
    if (t0 > t1)
        return false;
    double ux = r->d[0] / hf->dx, uz = r->d[2] / hf->dz; /* cell-space velocity */
    double t = t0;
    for (int guard = 0; guard < 4 * (hf->width + hf->height) && t <= t1; guard++) {
        double cx = (r->o[0] + r->d[0] * t - hf->x0) / hf->dx - 0.5, cz = (r->o[2] + r->d[2] * t - hf->z0) / hf->dz - 0.5;
        double y = r->o[1] + r->d[1] * t;
        /* the cell the ray is in, or about to enter */
        int i = (int)floor(cx + (ux > 0 ? 1e-9 : ux < 0 ? -1e-9 : 0)), j = (int)floor(cz + (uz > 0 ? 1e-9 : uz < 0 ? -1e-9 : 0));
        i = i < 0 ? 0 : i > hf->width - 2 ? hf->width - 2 : i;
        j = j < 0 ? 0 : j > hf->height - 2 ? hf->height - 2 : j;
        /* enters below the surface: the column's side (a cell with a nodata corner has no column) */
        bool solid = !TERRAIN_IS_HOLE(fmin(fmin(texel(hf, i, j), texel(hf, i + 1, j)), fmin(texel(hf, i, j + 1), texel(hf, i + 1, j + 1))));
        if (guard == 0 && solid && y <= height_cell(hf, cx, cz)) {
            *t_hit = t;
            return true;
        }
        double tx = ux > 0 ? (i + 1 - cx) / ux : ux < 0 ? (i - cx) / ux : INFINITY;
        double tz = uz > 0 ? (j + 1 - cz) / uz : uz < 0 ? (j - cz) / uz : INFINITY;
        double s_end = fmin(fmin(tx, tz), t1 - t);
        double s = cell_root(hf, i, j, cx, cz, ux, uz, y, r->d[1], s_end);
        if (s >= 0) {
            *t_hit = t + s;
            return true;
        }
        t += fmax(s_end, 1e-9);
    }
    return false;
}

/* How long the ray stays under the surface after entering it at t (fine steps in double). */
static double dip_length(const heightfield *hf, const dray *r, double t)
{
    double step = 0.01 * fmin(hf->dx, hf->dz), s = 0;
    for (; s < 1e6; s += step) {
        double x = r->o[0] + r->d[0] * (t + s + step), z = r->o[2] + r->d[2] * (t + s + step);
        double y = r->o[1] + r->d[1] * (t + s + step);
        if (y > height_cell(hf, (x - hf->x0) / hf->dx - 0.5, (z - hf->z0) / hf->dz - 0.5))
            break;
    }
    return s + step;
}

/* ---- first hits on the Jacksboro DEM -------------------------------------------------------------- */

typedef struct view {
    const char *what;
    double eye[3], at[3], fov;
} view;

static void check_views_in(const char *scene_name, const char *method, const char *const *sets, int nsets, bool exact,
                           const view *views, int nv)
{
    scene s;
    err_t e;
    if (!scene_load(scene_name, sets, nsets, &s, &e))
        fail_msg("%s", e.msg);
    heightfield hf;
    heightfield_desc d = {.path = s.terrain.heightmap, .spacing = {s.terrain.spacing[0], s.terrain.spacing[1]},
                          .height_min = s.terrain.height_min, .height_max = s.terrain.height_max,
                          .exaggeration = s.terrain.exaggeration};
    if (!heightfield_load(&d, &hf, &e))
        fail_msg("%s", e.msg);
    static float aov[W * H * AOV];
    for (int v = 0; v < nv; v++) {
        camera cam = cam_at(views[v].eye[0], views[v].eye[1], views[v].eye[2], views[v].at[0], views[v].at[1],
                            views[v].at[2], views[v].fov);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int hits = 0, misses = 0, grazing = 0, disagree = 0, tunnelled = 0;
        double worst = 0, samples = 0;
        for (int row = 0; row < H; row++)
            for (int x = 0; x < W; x++) {
                dray r = pixel_ray(&cam, x, row, W, H);
                double t_ref = INFINITY;
                bool hit = ref_terrain(&hf, &r, &t_ref);
                float t = aov[(row * W + x) * AOV + 3];
                samples += aov[(row * W + x) * AOV + 4];
                grazing += fabs(r.d[1]) < 1e-3;
                if (!hit && isinf(t)) {
                    misses++;
                    continue;
                }
                /* float resolution of a height, spread along the ray by how steeply it meets the surface */
                double tol, step_here = 0;
                if (exact) {
                    tol = 2e-5 * (fabs(t_ref) + hf.hmax) + 0.02 * fmin(hf.dx, hf.dz);
                } else { /* the bracket left after the binary search */
                    double dt = s.quality.linear_step * fmin(hf.dx, hf.dz) / fmax(hypot(r.d[0], r.d[2]), 1e-3);
                    double t_walk = 0, grown = dt;
                    while (t_walk < (hit ? t_ref : 0) && grown < 1e12)
                        t_walk += grown, grown *= s.quality.step_growth;
                    tol = grown / ldexp(1.0, s.quality.binary_steps) + 2e-5 * (fabs(t_ref) + hf.hmax);
                    step_here = grown;
                }
                if (hit != !isinf(t) || (hit && fabs(t - t_ref) > tol)) {
                    /* the lab's method may step over a sliver of surface thinner than its step: allowed */
                    if (!exact && hit && (isinf(t) || t > t_ref) && dip_length(&hf, &r, t_ref) < step_here) {
                        tunnelled++;
                        continue;
                    }
                    disagree++;
                    if (disagree <= 3)
                        fprintf(stderr, "  %s %s pixel (%d,%d): depth %.4f, exact %s%.4f (tol %.3g)\n", method,
                                views[v].what, x, row, (double)t, hit ? "" : "miss ", hit ? t_ref : 0.0, tol);
                    continue;
                }
                worst = fmax(worst, fabs(t - t_ref) / tol);
                hits++;
            }
        fprintf(stderr, "%-7s %-28s %4d hits (worst %.2f of tolerance), %4d misses, %4d grazing rays, "
                "%.1f height samples/px, %d stepped over a sliver thinner than a step, %d disagree\n", method,
                views[v].what, hits, worst, misses, grazing, samples / (W * H), tunnelled, disagree);
        if (disagree)
            fail_msg("%s: %d pixels disagree with the exact intersection", views[v].what, disagree);
    }
    heightfield_free(&hf);
    scene_free(&s);
}

static void check_views(const char *method, const char *const *sets, int nsets, bool exact, const view *views, int nv)
{
    check_views_in("jacksboro", method, sets, nsets, exact, views, nv);
}

static const view VIEWS[] = {
    {"grazing (|dir.y| < 1e-3)", {-3000, 860, 9000}, {9000, 860, -9000}, 0.1},
    {"inside the slab", {3000, 1250, 6000}, {-2000, 500, -3000}, 60},
    {"below the surface", {0, 100, 0}, {3000, 300, 1000}, 60},
    {"footprint edge, from outside", {1000, 900, 20000}, {0, 600, 0}, 35},
    {"leaving the footprint", {-14000, 2600, 2000}, {9000, 1400, -1000}, 50},
};

static void maxmip_first_hits(void **st)
{
    (void)st;
    const char *sets[] = {"terrain.method=maxmip", "quality.spp=1", "quality.max_steps=4096"};
    check_views("maxmip", sets, 3, true, VIEWS, 5);
}

static void linear_first_hits(void **st)
{
    (void)st;
    /* the lab's method at the reference preset: steps of a quarter texel, no growth, 12 bisections */
    const char *sets[] = {"terrain.method=linear", "quality.preset=reference", "quality.spp=1", "quality.max_steps=4096"};
    check_views("linear", sets, 4, false, VIEWS + 1, 4); /* grazing rays: see the ridge test */
}

/* An n × n float DEM in a new directory made from dir (a mkdtemp template) as NAME.exr (path[128]), and a
 * terrain scene on it with 1 m texels in json[1024]; more: more of the quality block (", \"k\": v"). */
static void square_dem(char *dir, const char *name, const float *heights, int n, const char *more, char *path,
                       char *json)
{
    assert_non_null(mkdtemp(dir));
    snprintf(path, 128, "%s/%s.exr", dir, name);
    err_t e;
    assert_true(image_write_f32(path, n, n, 1, (const char *const[]){"Y"}, heights, &e));
    snprintf(json, 1024,
             "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"quality\": {\"spp\": 1%s},"
             " \"terrain\": {\"heightmap\": \"%s\", \"spacing\": [1, 1]}}", more, path);
}

/* ---- a thin ridge and grazing rays ------------------------------------------------------------------ */

static void thin_ridge(void **st)
{
    (void)st;
    enum { N = 64 };
    static float heights[N * N];
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++)
            heights[j * N + i] = i == N / 2 ? 10.0f : 0.0f; /* one texel column: a 2-texel-wide tent, 10 m high */
    char dir[] = "/tmp/fathom-ridge-XXXXXX", path[128], json[1024];
    square_dem(dir, "ridge", heights, N, ", \"max_steps\": 1024", path, json);
    /* level rays at 7 m cross the ridge where it is 0.6 texel wide */
    camera cam = cam_at(-30, 7, 0.3, 30, 7, -0.2, 1.0);
    static float aov[W * H * AOV];
    const char *methods[][3] = {{"terrain.method=maxmip", "quality.preset=draft", "maxmip, draft"},
                                {"terrain.method=linear", "quality.preset=reference", "linear, reference"},
                                {"terrain.method=linear", "quality.preset=draft", "linear, draft"}};
    int hit_share[3];
    for (int m = 0; m < 3; m++) {
        scene s;
        const char *sets[] = {methods[m][0], methods[m][1], "quality.spp=1"};
        load_text(json, sets, 3, &s);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int hits = 0;
        for (int i = 0; i < W * H; i++)
            hits += !isinf(aov[i * AOV + 3]) && fabs(aov[i * AOV + 3] - 29.7) < 1.0; /* at the ridge */
        hit_share[m] = 100 * hits / (W * H);
        fprintf(stderr, "ridge, %-18s: %3d %% of level rays stop at the ridge\n", methods[m][2], hit_share[m]);
        scene_free(&s);
    }
    unlink(path);
    rmdir(dir);
    assert_int_equal(hit_share[0], 100); /* exact: never tunnels, at any preset */
    assert_int_equal(hit_share[1], 100); /* quarter-texel steps catch a 0.6-texel ridge */
    assert_true(hit_share[2] < 50);      /* 2-texel steps jump it: the test can fail */
}

/* The terrain is a solid from its lowest height up to the ground. Rays going down reach a little below
 * the lowest height (so ground lying exactly there, a sea clamped flat, is met inside the slab, not
 * decided by rounding at its exit); a ray that enters a side wall in that sliver is under the floor
 * and must miss. Before, it hit the wall 1–2 mm below the floor (a strip along the bottom edge). */
static void no_wall_below_the_floor(void **st)
{
    (void)st;
    enum { N = 64 };
    static float heights[N * N];
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) /* flat at 0 (the minimum) with a 10 m hill in the middle */
            heights[j * N + i] = (float)fmax(0, 10 - 0.5 * hypot(i - N / 2, j - N / 2));
    char dir[] = "/tmp/fathom-floor-XXXXXX", path[128], json[1024];
    square_dem(dir, "floor", heights, N, "", path, json);
    static float aov[W * H * AOV];
    const char *methods[] = {"terrain.method=maxmip", "terrain.method=linear"};
    for (int m = 0; m < 2; m++) {
        scene s;
        const char *sets[] = {methods[m], "quality.spp=1"};
        load_text(json, sets, 2, &s);
        /* from outside the footprint, level with the floor, looking a hair down at the side wall */
        camera cam = cam_at(-20, 0.0005, 31.7, 40, -0.004, 32.2, 20);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int below = 0, hits = 0;
        double lowest = INFINITY;
        for (int row = 0; row < H; row++)
            for (int x = 0; x < W; x++) {
                float t = aov[(row * W + x) * AOV + AOV_SLOT_DEPTH];
                if (isinf(t))
                    continue;
                dray r = pixel_ray(&cam, x, row, W, H);
                double y = r.o[1] + r.d[1] * t;
                hits++;
                lowest = fmin(lowest, y);
                below += y < -1e-5;
            }
        fprintf(stderr, "  %s: %d hits, %d below the floor (lowest at %.3g m)\n", methods[m], hits, below, lowest);
        assert_true(hits > 20); /* the hill and the floor beyond the wall; before the fix 4 more below */
        assert_int_equal(below, 0);
        scene_free(&s);
    }
    unlink(path);
    rmdir(dir);
}

/* ---- DEMs the tests were not written on: big, long and thin, flat at the bottom ---------------------- */

/* A w × h float DEM of rolling hills (sum of sines, 0–300 m) with a sea clamped flat at 0, 30 m
 * texels, written as EXR with its scene file; returns the scene's path. */
static void synthetic_dem(const char *dir, const char *name, int w, int h, bool holes, char *scene_path, size_t n)
{
    float *heights = malloc(sizeof(float) * (size_t)w * (size_t)h);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double x = i * 0.013, z = j * 0.017;
            double v = 120 + 90 * sin(x) * cos(z * 0.7) + 60 * sin(0.37 * x + 1.3 * z) + 25 * cos(2.9 * x - 2.3 * z);
            /* nodata (NaN): a round hole, a one-texel line and scattered single texels */
            int di = i - w / 2, dj = j - h / 2;
            bool hole = holes && (di * di + dj * dj < (w / 8) * (w / 8) || i == w / 4 || (i * 7 + j * 13) % 97 == 0);
            heights[(size_t)j * (size_t)w + (size_t)i] = hole ? NAN : (float)fmax(v, 0.0); /* sea: exactly the minimum */
        }
    char exr[256];
    snprintf(exr, sizeof exr, "%s/%s.exr", dir, name);
    err_t e;
    if (!image_write_f32(exr, w, h, 1, (const char *const[]){"Y"}, heights, &e))
        fail_msg("%s", e.msg);
    free(heights);
    snprintf(scene_path, n, "%s/%s.json", dir, name);
    FILE *f = fopen(scene_path, "w");
    fprintf(f, "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"quality\": {\"max_dist\": 1e6}, \"terrain\": {\"heightmap\": \"%s.exr\", "
               "\"spacing\": [30, 30]}}", name);
    fclose(f);
}

/* Removes NAME.exr and NAME.json for each name, then the folder. */
static void remove_dems(const char *dir, const char *const *names)
{
    char file[320];
    for (int k = 0; names[k]; k++) {
        snprintf(file, sizeof file, "%s/%s.exr", dir, names[k]);
        unlink(file);
        snprintf(file, sizeof file, "%s/%s.json", dir, names[k]);
        unlink(file);
    }
    rmdir(dir);
}

/* The exact traversal on DEMs it was not written on. Each fails without one fix:
 *  - 4096², far rays: the nudge past a node's face must exceed the rounding of a position recomputed
 *    from an origin thousands of cells away, or the walk stalls and reports a miss (9 pixels);
 *  - a 1000 × 150 strip: the max pyramid's upper levels need a side of at least 1 on the short axis,
 *    or they are all −inf and nothing is drawn (every pixel);
 *  - the sea exactly at the minimum height: the slab of a descending ray reaches a little below hmin,
 *    or float rounding at the slab's exit decides hit or miss (16 pixels). */
static void big_and_odd_grids(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-dems-XXXXXX", big[300], strip[300];
    assert_non_null(mkdtemp(dir));
    synthetic_dem(dir, "big", 4096, 4096, false, big, sizeof big);     /* 123 km square */
    synthetic_dem(dir, "strip", 1000, 150, false, strip, sizeof strip); /* 30 × 4.5 km: 6.7:1 */
    const char *sets[] = {"terrain.method=maxmip", "quality.spp=1", "quality.preset=final"};
    /* over the big DEM: oblique from a corner across thousands of cells, grazing, and straight down on
     * the flat sea (heights exactly the minimum) */
    const view big_views[] = {
        {"4096²: oblique, far", {-55000, 2500, -55000}, {20000, 0, 15000}, 50},
        {"4096²: grazing", {-30000, 310, 40000}, {30000, 250, -40000}, 20},
        {"4096²: down on the sea", {10000, 3000, 10000}, {10100, 0, 10050}, 60},
    };
    const view strip_views[] = {
        {"1000×150: along the strip", {-16000, 900, 0}, {10000, 100, 0}, 40},
        {"1000×150: across it", {0, 1500, 9000}, {0, 100, 0}, 60},
    };
    check_views_in(strip, "maxmip", sets, 3, true, strip_views, 2);
    check_views_in(big, "maxmip", sets, 3, true, big_views, 3);
    remove_dems(dir, (const char *const[]){"strip", "big", NULL});
}

/* Nodata holes (NaN in the file): rays pass through a hole's cells and meet its walls where the
 * column goes on, against the same reference with no surface in cells that touch a hole. Both
 * methods: maxmip exactly, the linear search within its step (its walls are found by bisection). */
static void nodata_holes(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-holes-XXXXXX", scene_path[300];
    assert_non_null(mkdtemp(dir));
    synthetic_dem(dir, "holes", 256, 192, true, scene_path, sizeof scene_path);
    const view views[] = {
        {"holes: oblique", {-5000, 1500, -4000}, {0, 50, 0}, 50},
        {"holes: down into the round hole", {300, 2500, 200}, {0, 0, 0}, 40},
        {"holes: grazing the line", {-2000, 200, -3500}, {-2000, 150, 3000}, 30},
    };
    const char *maxmip[] = {"terrain.method=maxmip", "quality.spp=1", "quality.preset=final"};
    check_views_in(scene_path, "maxmip", maxmip, 3, true, views, 3);
    const char *linear[] = {"terrain.method=linear", "quality.preset=reference", "quality.spp=1", "quality.max_steps=4096"};
    check_views_in(scene_path, "linear", linear, 4, false, views, 2);
    remove_dems(dir, (const char *const[]){"holes", NULL});
}

/* DEMs in tiles: with tiles of 64 texels (FATHOM_TERRAIN_TILE) the long strip and the holes DEM cross
 * dozens of tile seams, in the heights and in every pyramid level; every pixel still agrees with the
 * reference. Then a 16-bit GeoTIFF wider than the GL texture limit (16384 on llvmpipe), tiled by
 * default: before tiling it could not be drawn at all. */
static void tiled_grids(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-tiles-XXXXXX", strip[300], holes[300], wide[300], file[320];
    assert_non_null(mkdtemp(dir));
    synthetic_dem(dir, "strip", 1000, 150, false, strip, sizeof strip);
    synthetic_dem(dir, "holes", 256, 192, true, holes, sizeof holes);
    setenv("FATHOM_TERRAIN_TILE", "64", 1);
    const char *maxmip[] = {"terrain.method=maxmip", "quality.spp=1", "quality.preset=final"};
    const view strip_views[] = {
        {"tiles of 64: along the strip", {-16000, 900, 0}, {10000, 100, 0}, 40},
        {"tiles of 64: across it", {0, 1500, 9000}, {0, 100, 0}, 60},
    };
    const view hole_views[] = {
        {"tiles of 64: holes, oblique", {-5000, 1500, -4000}, {0, 50, 0}, 50},
        {"tiles of 64: holes, grazing", {-2000, 200, -3500}, {-2000, 150, 3000}, 30},
    };
    check_views_in(strip, "maxmip", maxmip, 3, true, strip_views, 2);
    int tx = 0, ty = 0;
    assert_true(render_terrain_tiles(&tx, &ty));
    assert_int_equal(tx, 16); /* 1000 / 64 */
    assert_int_equal(ty, 3);
    check_views_in(holes, "maxmip", maxmip, 3, true, hole_views, 2);
    const char *linear[] = {"terrain.method=linear", "quality.preset=reference", "quality.spp=1", "quality.max_steps=4096"};
    check_views_in(holes, "linear", linear, 4, false, hole_views, 1);
    unsetenv("FATHOM_TERRAIN_TILE");

    /* 16,500 x 48 Int16 metres, UTM 30 m: wider than one texture */
    enum { WW = 16500, WH = 48 };
    int16_t *v = malloc(sizeof(int16_t) * WW * WH);
    for (int j = 0; j < WH; j++)
        for (int i = 0; i < WW; i++)
            v[j * WW + i] = (int16_t)(200 + 150 * sin(i * 0.021) * cos(j * 0.3) + 80 * sin(i * 0.0037));
    snprintf(file, sizeof file, "%s/wide.tif", dir);
    GDALAllRegister();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), file, WW, WH, 1, GDT_Int16, NULL);
    double gt[6] = {400000, 30, 0, 5000000, 0, -30};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(NULL);
    OSRImportFromEPSG(srs, 32632);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
    assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, WW, WH, v, WW, WH, GDT_Int16, 0, 0), CE_None);
    GDALClose(ds);
    free(v);
    snprintf(wide, sizeof wide, "%s/wide.json", dir);
    FILE *f = fopen(wide, "w");
    fprintf(f, "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"quality\": {\"max_dist\": 1e6}, "
               "\"terrain\": {\"heightmap\": \"wide.tif\"}}");
    fclose(f);
    const view wide_views[] = {
        {"16500x48: along, across 4 seams", {-250000, 3000, 0}, {100000, 0, 0}, 30},
        {"16500x48: over a seam", {-122000 + 30 * 4096 - 247500, 2500, -900}, {30 * 4096 - 247500, 200, 0}, 50},
    };
    check_views_in(wide, "maxmip", maxmip, 3, true, wide_views, 2);
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    assert_true(render_terrain_tiles(&tx, &ty));
    fprintf(stderr, "16500x48 on a GPU whose textures reach %d: %d x %d tiles\n", max_side, tx, ty);
    if (max_side < WW)
        assert_true(tx > 1);
    unlink(file);
    remove_dems(dir, (const char *const[]){"strip", "holes", "wide", NULL});
}

/* The heightfield stays on the GPU while scenes read the same file (a flight's frames), and a file
 * rewritten on disk (R reload) is read again: the key holds its size and modification time. */
static void changed_file_is_read_again(void **st)
{
    (void)st;
    enum { N = 16 };
    float heights[N * N];
    char dir[] = "/tmp/fathom-reread-XXXXXX", path[128], json[512];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/dem.exr", dir);
    snprintf(json, sizeof json, "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"quality\": {\"spp\": 1}, "
             "\"terrain\": {\"heightmap\": \"%s\", \"spacing\": [1, 1]}}", path);
    camera cam = cam_at(0, 50, 0.01, 0, 0, 0, 30); /* straight down on the middle */
    static float aov[W * H * AOV];
    double depth[3];
    err_t e;
    for (int k = 0; k < 3; k++) {
        if (k != 1) { /* k = 1 draws again without touching the file */
            for (int i = 0; i < N * N; i++)
                heights[i] = k ? 20.0f : 5.0f;
            assert_true(image_write_f32(path, N, N, 1, (const char *const[]){"Y"}, heights, &e));
        }
        scene s;
        load_text(json, NULL, 0, &s);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        depth[k] = aov[(H / 2 * W + W / 2) * AOV + AOV_SLOT_DEPTH];
        scene_free(&s);
    }
    fprintf(stderr, "depth to the middle: %.3f, again %.3f, after the file changed %.3f\n", depth[0], depth[1], depth[2]);
    assert_near(depth[0], 45, 0.05);
    assert_near(depth[1], 45, 0.05);
    assert_near(depth[2], 30, 0.05);
    unlink(path);
    rmdir(dir);
}

/* The heights live only on the GPU once uploaded; the walking camera's ground is a probe of the
 * shader's surface. It must equal the bilinear surface in double (the CPU reference) everywhere on the
 * footprint, and report no ground over a nodata hole. */
static void ground_height_probe(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-ground-XXXXXX", scene_path[300];
    assert_non_null(mkdtemp(dir));
    synthetic_dem(dir, "holes", 256, 192, true, scene_path, sizeof scene_path);
    scene s;
    err_t e;
    if (!scene_load(scene_path, NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    heightfield hf;
    heightfield_desc d = {.path = s.terrain.heightmap, .spacing = {s.terrain.spacing[0], s.terrain.spacing[1]},
                          .exaggeration = 1};
    if (!heightfield_load(&d, &hf, &e))
        fail_msg("%s", e.msg);
    camera cam = cam_at(0, 3000, 1, 0, 0, 0, 40);
    draw(&s, &cam, 8, 8, 1, NULL, NULL, NULL); /* puts the scene on the GPU */
    int checked = 0, holes = 0;
    double worst = 0;
    for (int k = 0; k < 400; k++) {
        double x = hf.x0 + hf.dx * (0.5 + (hf.width - 1) * ((k * 0.6180339887) - floor(k * 0.6180339887)));
        double z = hf.z0 + hf.dz * (0.5 + (hf.height - 1) * ((k * 0.7548776662) - floor(k * 0.7548776662)));
        double cx = (x - hf.x0) / hf.dx - 0.5, cz = (z - hf.z0) / hf.dz - 0.5;
        int i = (int)fmin(floor(cx), hf.width - 2), j = (int)fmin(floor(cz), hf.height - 2);
        bool hole = TERRAIN_IS_HOLE(fmin(fmin(texel(&hf, i, j), texel(&hf, i + 1, j)),
                                         fmin(texel(&hf, i, j + 1), texel(&hf, i + 1, j + 1))));
        float g;
        bool got = render_ground_height((float)x, (float)z, &g);
        if (hole) {
            assert_false(got);
            holes++;
            continue;
        }
        assert_true(got);
        worst = fmax(worst, fabs(g - height_cell(&hf, cx, cz)));
        checked++;
    }
    fprintf(stderr, "ground probe: %d points within %.2g m of the bilinear surface in double, %d over holes\n", checked,
            worst, holes);
    assert_true(worst < 1e-3 * (hf.hmax - hf.hmin) && holes > 0 && checked > 300);
    heightfield_free(&hf);
    scene_free(&s);
    remove_dems(dir, (const char *const[]){"holes", NULL});
}

/* terrain.normals=patch: the normal at each hit is the hit bilinear patch's own, against its gradient
 * in double at the reference's hit point (pixels whose hit lies within 0.01 cell of a cell edge are
 * left out: the surface has a crease there). The smooth default differs: the test can fail. */
static void patch_normals_are_exact(void **st)
{
    (void)st;
    static float aov[W * H * AOV];
    double worst[2] = {0, 0};
    for (int mode = 0; mode < 2; mode++) {
        scene s;
        err_t e;
        const char *sets[] = {"quality.spp=1", mode ? "terrain.normals=smooth" : "terrain.normals=patch"};
        if (!scene_load("jacksboro", sets, 2, &s, &e))
            fail_msg("%s", e.msg);
        heightfield hf;
        heightfield_desc d = {.path = s.terrain.heightmap, .height_min = s.terrain.height_min,
                              .height_max = s.terrain.height_max, .exaggeration = s.terrain.exaggeration};
        if (!heightfield_load(&d, &hf, &e))
            fail_msg("%s", e.msg);
        int checked = 0;
        for (int v = 0; v < 2; v++) {
            const view *vw = &VIEWS[v + 1]; /* inside the slab; below the surface (looking up at it) */
            camera cam = cam_at(vw->eye[0], vw->eye[1], vw->eye[2], vw->at[0], vw->at[1], vw->at[2], vw->fov);
            draw(&s, &cam, W, H, 1, NULL, aov, NULL);
            for (int row = 0; row < H; row++)
                for (int x = 0; x < W; x++) {
                    dray r = pixel_ray(&cam, x, row, W, H);
                    double t;
                    if (!ref_terrain(&hf, &r, &t) || t == 0)
                        continue;
                    double cx = (r.o[0] + r.d[0] * t - hf.x0) / hf.dx - 0.5, cz = (r.o[2] + r.d[2] * t - hf.z0) / hf.dz - 0.5;
                    int i = (int)floor(cx), j = (int)floor(cz);
                    double u = cx - i, w = cz - j;
                    if (fmin(fmin(u, 1 - u), fmin(w, 1 - w)) < 0.01 || i < 0 || j < 0 || i > hf.width - 2 || j > hf.height - 2)
                        continue;
                    if (r.o[1] + r.d[1] * t < height_cell(&hf, cx, cz) - 0.01) /* the column's floor or side */
                        continue;
                    double h00 = texel(&hf, i, j), h10 = texel(&hf, i + 1, j), h01 = texel(&hf, i, j + 1),
                           h11 = texel(&hf, i + 1, j + 1), k = h00 - h10 - h01 + h11;
                    double gx = (h10 - h00 + k * w) / hf.dx, gz = (h01 - h00 + k * u) / hf.dz;
                    double n[3] = {-gx, 1, -gz}, len = sqrt(gx * gx + 1 + gz * gz);
                    const float *a = &aov[(row * W + x) * AOV + AOV_SLOT_NORMAL];
                    double c = (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / len;
                    worst[mode] = fmax(worst[mode], acos(fmin(c, 1.0)) * 57.29577951308232);
                    checked++;
                }
        }
        fprintf(stderr, "%s normals: %d hits checked, worst angle to the patch's normal %.4f°\n", mode ? "smooth" : "patch",
                checked, worst[mode]);
        assert_true(checked > W * H / 4);
        heightfield_free(&hf);
        scene_free(&s);
    }
    assert_true(worst[0] < 0.05); /* float rounding of the hit point and the normal */
    assert_true(worst[1] > 1.0);  /* the smooth normal is not the patch's */
}

/* ---- height fog against quadrature in double -------------------------------------------------------- */

static double tau_quadrature(double sigma0, double b, double y0, double oy, double dy, double s)
{
    enum { N = 200000 }; /* composite Simpson; the integrand is smooth */
    double h = s / N, sum = 0;
    for (int i = 0; i <= N; i++) {
        double w = (i == 0 || i == N) ? 1 : (i % 2 ? 4 : 2);
        sum += w * sigma0 * exp(-b * (oy + dy * i * h - y0));
    }
    return sum * h / 3;
}

static void fog_against_quadrature(void **st)
{
    (void)st;
    const double sigma0 = 2e-4, y0 = 400;
    const double falloffs[] = {0.0015, 0.05}; /* gentle, and very steep */
    const double oys[] = {0, 400, 3000};
    const double dys[] = {0, 1e-7, -1e-7, 1e-3, -1e-3, 0.3, -0.3, 1, -1};
    const double lengths[] = {10, 1e4, 1e6};
    enum { MAXN = 256 };
    static float pts[MAXN * 3], out[MAXN * 2], naive[MAXN * 2];
    double want[MAXN];
    for (size_t f = 0; f < 2; f++) {
        char json[512];
        snprintf(json, sizeof json,
                 "{\"program\": \"csg\", \"fog\": {\"density\": %g, \"falloff\": %g, \"height\": %g},"
                 " \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": \"sphere\", \"material\": \"m\"}]}",
                 sigma0, falloffs[f], y0);
        scene s;
        load_text(json, NULL, 0, &s);
        int n = 0;
        for (size_t a = 0; a < 3; a++)
            for (size_t b = 0; b < sizeof dys / sizeof dys[0]; b++)
                for (size_t c = 0; c < 3; c++) {
                    pts[n * 3] = (float)oys[a], pts[n * 3 + 1] = (float)dys[b], pts[n * 3 + 2] = (float)lengths[c];
                    want[n++] = tau_quadrature(sigma0, falloffs[f], y0, oys[a], (float)dys[b], lengths[c]);
                }
        err_t e;
        assert_true(render_probe_with(&s, "fogprobe.frag", NULL, pts, n, out, &e));
        assert_true(render_probe_with(&s, "fogprobe.frag", "#define FOG_NAIVE 1\n", pts, n, naive, &e));
        int naive_wrong = 0;
        double worst = 0;
        for (int i = 0; i < n; i++) {
            double T = exp(-(double)out[2 * i]), Tref = exp(-want[i]);
            /* transmittance and in-scatter (1 − T) both within float precision */
            if (!isfinite(out[2 * i]) || fabs(T - Tref) > 2e-5 + 1e-4 * Tref)
                fail_msg("fog b=%g, y=%g, dir.y=%g, s=%g: tau %g, quadrature %g", falloffs[f], (double)pts[i * 3],
                         (double)pts[i * 3 + 1], (double)pts[i * 3 + 2], (double)out[2 * i], want[i]);
            if (want[i] < 30 && fabs(out[2 * i] - want[i]) > 1e-4 * want[i] + 1e-7)
                fail_msg("fog b=%g, y=%g, dir.y=%g, s=%g: tau %.7g, quadrature %.7g", falloffs[f], (double)pts[i * 3],
                         (double)pts[i * 3 + 1], (double)pts[i * 3 + 2], (double)out[2 * i], want[i]);
            worst = fmax(worst, fabs(T - Tref));
            double Tn = exp(-(double)naive[2 * i]);
            naive_wrong += !isfinite(naive[2 * i]) || fabs(Tn - Tref) > 2e-5 + 1e-4 * Tref;
        }
        fprintf(stderr, "fog falloff %g: %d rays match quadrature (worst transmittance error %.2g); the lab's "
                "closed form as written gets %d wrong\n", falloffs[f], n, worst, naive_wrong);
        assert_true(naive_wrong > 0); /* level rays give it 0/0 */
        scene_free(&s);
    }
}

static void load_text_file(const char *name, const char *const *sets, int n, scene *s)
{
    err_t e;
    if (!scene_load(name, sets, n, s, &e))
        fail_msg("%s", e.msg);
}

/* ---- ridges: no black dashes ------------------------------------------------------------------------
 * The shading normal comes from ±1-texel differences; on a ridge seen from its back slope it can face
 * away from the viewer by 9–13°. Flipped to face the viewer (what the shared main does for a camera
 * inside a solid) it pointed into the ground: no sun, no sky, a black dash along the ridge. Lit
 * terrain has no pixel that dark: count pixels that hit the ground and are darker than 10 % of the
 * median hit pixel, and those of them in runs of two or more with lit ground above and below (dashes),
 * at the shipped terrains' own views, 1280x720 (13 and 90 dashes before the normal was bent instead of
 * flipped, 0 after). The Himalaya 640 km from the origin also from two cameras moved by 0.3 m and 4 m:
 * there ambient-occlusion probes nearer than the position's float step read rounding as occlusion,
 * dark speckles that moved with every rounding (0–64 dark pixels, 0–6 in dashes as the camera moved;
 * 4 dashes on an NVIDIA H100 at the shipped view, 0 here); with the probes kept off the floor, 0. */
static void ridges_have_no_black_dashes(void **st)
{
    (void)st;
    enum { RW = 1280, RH = 720 };
    static float aov[RW * RH * AOV], rgba[RW * RH * 4];
    static const struct {
        const char *scene;
        double move[3];
    } SHOTS[] = {{"jacksboro", {0, 0, 0}}, {"himalaya", {0, 0, 0}}, {"himalaya", {0, 0, 0.3}}, {"himalaya", {3, 0, -3}}};
    int total = 0;
    for (size_t k = 0; k < 2 * sizeof SHOTS / sizeof SHOTS[0]; k++) { /* smooth normals, then the patches' own */
        size_t v = k % (sizeof SHOTS / sizeof SHOTS[0]);
        bool patch = k >= sizeof SHOTS / sizeof SHOTS[0];
        scene s;
        const char *sets[] = {"quality.spp=1", patch ? "terrain.normals=patch" : "terrain.normals=smooth"};
        load_text_file(SHOTS[v].scene, sets, 2, &s);
        double eye[3], at[3];
        for (int i = 0; i < 3; i++)
            eye[i] = s.cam_position[i] + SHOTS[v].move[i], at[i] = s.cam_look_at[i];
        camera cam = camera_look_at_deg(eye, at, s.cam_fov_deg);
        draw(&s, &cam, RW, RH, 1, NULL, aov, rgba);
        static float lum[RW * RH];
        static double vals[RW * RH];
        int n = 0;
        for (int i = 0; i < RW * RH; i++) {
            lum[i] = 0.2126f * rgba[4 * i] + 0.7152f * rgba[4 * i + 1] + 0.0722f * rgba[4 * i + 2];
            if (!isinf(aov[i * AOV + AOV_SLOT_DEPTH]))
                vals[n++] = lum[i];
        }
        double median = util_median(vals, n);
        int dark = 0, dashes = 0;
        for (int y = 2; y < RH - 2; y++)
            for (int x = 0; x < RW; x++) {
                int i = y * RW + x;
                if (isinf(aov[i * AOV + AOV_SLOT_DEPTH]) || lum[i] >= 0.1 * median)
                    continue;
                dark++;
                bool run = (x > 0 && lum[i - 1] < 0.1 * median) || (x + 1 < RW && lum[i + 1] < 0.1 * median);
                dashes += run && lum[i - 2 * RW] >= 0.25 * median && lum[i + 2 * RW] >= 0.25 * median;
            }
        fprintf(stderr, "  %s moved by (%g, %g, %g) m, %s normals: %d ground pixels, %d darker than 10 %% of the median, "
                "%d of them in thin dashes\n", SHOTS[v].scene, SHOTS[v].move[0], SHOTS[v].move[1], SHOTS[v].move[2],
                patch ? "patch" : "smooth", n, dark, dashes);
        assert_true(n > RW * RH / 10);
        total += dark;
        scene_free(&s);
    }
    assert_int_equal(total, 0);
}

/* ---- running out of steps is not a miss ---------------------------------------------------------------
 * At every preset, from the shipped camera and a grazing one, no pixel may be a miss where a march
 * with a budget a hundred times longer hits: a ray that exhausts its steps near the ground returns
 * its best candidate (flagged by negative steps) instead of the sky. */
/* A ray that runs out of steps is resolved (the tail: common/march.glsl, within its stated tolerance)
 * or flagged, never drawn as a guess: against a march with 100x the steps, every pixel whose hit, miss
 * or depth differs either went into the tail (more steps than max_steps) or is flagged unresolved
 * (negative steps); and the noise terrain, whose horizon ran out of steps by the thousand and showed a
 * false band there, leaves none unresolved at the interactive and final presets. */
static void out_of_steps_is_not_a_miss(void **st)
{
    (void)st;
    static const char *const SCENES[] = {"noise", "jacksboro", "himalaya"};
    static float test[W * H * AOV], longer[W * H * AOV];
    for (size_t k = 0; k < sizeof SCENES / sizeof SCENES[0]; k++)
        for (int p = 0; p < PRESET_COUNT; p++) {
            char preset[64], steps[64];
            snprintf(preset, sizeof preset, "quality.preset=%s", preset_name((quality_preset)p));
            snprintf(steps, sizeof steps, "quality.max_steps=%d", 100 * (int)fmin(preset_quality((quality_preset)p).max_steps, 1000));
            const char *sa[] = {preset, "quality.spp=1"}, *sb[] = {preset, "quality.spp=1", steps};
            scene a, b;
            load_text_file(SCENES[k], sa, 2, &a);
            load_text_file(SCENES[k], sb, 3, &b);
            double eye[3], at[3]; /* grazing: just above the ground at the look-at point, level */
            for (int i = 0; i < 3; i++)
                eye[i] = a.cam_position[i], at[i] = a.cam_look_at[i];
            camera cams[2] = {camera_look_at_deg(eye, at, a.cam_fov_deg)};
            at[1] = eye[1] = (float)(a.cam_position[1] * 0.25 + a.cam_look_at[1] * 0.75);
            cams[1] = camera_look_at_deg(eye, at, a.cam_fov_deg);
            int silent = 0, flagged = 0, differ = 0, tail = 0;
            for (int c = 0; c < 2; c++) {
                draw(&a, &cams[c], W, H, 1, NULL, test, NULL);
                draw(&b, &cams[c], W, H, 1, NULL, longer, NULL);
                for (int i = 0; i < W * H; i++) {
                    float za = test[i * AOV + AOV_SLOT_DEPTH], zb = longer[i * AOV + AOV_SLOT_DEPTH];
                    float used = test[i * AOV + AOV_SLOT_STEPS];
                    bool unresolved = used < 0, tailed = used > (float)a.quality.max_steps;
                    bool differs = isinf(za) != isinf(zb) || (!isinf(za) && fabsf(za - zb) > 0.01f * zb);
                    flagged += unresolved;
                    tail += tailed;
                    differ += differs;
                    silent += differs && !unresolved && !tailed;
                }
            }
            fprintf(stderr, "%s %s: %d rays went on past max_steps, %d were left unresolved; %d pixels differ from "
                    "100x the steps, %d of them neither\n", SCENES[k], preset_name((quality_preset)p), tail, flagged,
                    differ, silent);
            assert_int_equal(silent, 0);
            if (k == 0 && (p == PRESET_INTERACTIVE || p == PRESET_FINAL))
                assert_int_equal(flagged, 0);
            scene_free(&a);
            scene_free(&b);
        }
}

/* ---- the noise terrain against a double-precision reference of the same filtered surface ----------------
 * shaders/terrain/noise.glsl's surface written again in double: f(p) = y − base − A Σ wᵢ aᵢ nᵢ(p fᵢ + 17.31 i),
 * value noise on Teschner's spatial hash of the lattice and one multiply-xorshift round, with the quintic fade, each octave's weight wᵢ fading
 * from 1 at 4 pixel footprints a wavelength to 0 at 2 (the footprint at p: its distance to the eye times
 * the pixel's angle). The reference marches it with one global Lipschitz bound, safe everywhere:
 * |∇f| ≤ 1 + A Σ aᵢ fᵢ (S √3 + 8 α), S = 30/16 the quintic's steepest slope, 8 α fᵢ the steepest a
 * weight changes with the distance (α the pixel angle), so its first root is the true first crossing
 * (to 1e-6 m), found in as many steps as it takes. Against it the shader's local bounds, filtered
 * octaves and tail, at the shipped view and a low one across the valleys, at draft, interactive and final
 * (draft does not refine: it drew 2,049 pixels of false ground above the horizon before it marched on to
 * the crossing, and 135 depths short by up to a tail step before that crossing was refined). */
static double ref_hash3(int x, int y, int z)
{
    /* Teschner et al.'s spatial hash of the lattice point, then one multiply-xorshift round */
    uint32_t h = ((uint32_t)x * 73856093u ^ (uint32_t)y * 19349663u ^ (uint32_t)z * 83492791u) * 0x27d4eb2du;
    return (h ^ (h >> 15)) * (1.0 / 4294967295.0);
}

static double ref_value_noise(const double q[3])
{
    int i[3];
    double u[3];
    for (int k = 0; k < 3; k++) {
        double fl = floor(q[k]), f = q[k] - fl;
        i[k] = (int)fl;
        u[k] = f * f * f * (f * (f * 6 - 15) + 10);
    }
    double v = 0;
    for (int c = 0; c < 8; c++) { /* trilinear in the faded coordinates */
        int bx = c & 1, by = (c >> 1) & 1, bz = (c >> 2) & 1;
        v += ref_hash3(i[0] + bx, i[1] + by, i[2] + bz) * (bx ? u[0] : 1 - u[0]) * (by ? u[1] : 1 - u[1]) *
             (bz ? u[2] : 1 - u[2]);
    }
    return v;
}

typedef struct {
    double base, amplitude, frequency, pixel_angle, eye[3], lipschitz;
    int octaves;
} noise_ref;

static double noise_ref_f(const noise_ref *n, const double p[3])
{
    double e[3] = {p[0] - n->eye[0], p[1] - n->eye[1], p[2] - n->eye[2]};
    double footprint = fmax(n->pixel_angle * sqrt(ref_dot(e, e)), 1e-30), sum = 0, amp = 0.5, freq = n->frequency;
    for (int o = 0; o < n->octaves; o++, amp *= 0.5, freq *= 2) {
        double w = fmin(fmax((1 / (footprint * freq) - 2) / 2, 0), 1);
        if (w <= 0)
            break;
        double q[3] = {p[0] * freq + 17.31 * o, p[1] * freq + 17.31 * o, p[2] * freq + 17.31 * o};
        sum += amp * w * ref_value_noise(q);
    }
    return p[1] - n->base - n->amplitude * sum;
}

/* The first crossing along the ray within tmax (+inf: none); NAN when the march could not decide. */
static double noise_ref_hit(const noise_ref *n, const dray *r, double tmax)
{
    double t = 0;
    for (int i = 0; i < 2000000; i++) {
        double p[3] = {r->o[0] + r->d[0] * t, r->o[1] + r->d[1] * t, r->o[2] + r->d[2] * t};
        if (p[1] > n->base + n->amplitude && r->d[1] >= 0)
            return INFINITY; /* above every octave's reach, and rising */
        double f = noise_ref_f(n, p);
        if (f < 1e-6)
            return t;
        t += f / n->lipschitz;
        if (t > tmax)
            return INFINITY;
    }
    return NAN;
}

static void noise_against_double_reference(void **st)
{
    (void)st;
    static float aov[W * H * AOV];
    static double ref[W * H];
    for (int p = PRESET_DRAFT; p <= PRESET_FINAL; p++) {
        char preset[64];
        snprintf(preset, sizeof preset, "quality.preset=%s", preset_name((quality_preset)p));
        scene s;
        load_text_file("noise", (const char *const[]){preset, "quality.spp=1"}, 2, &s);
        double eye[3], at[3];
        for (int i = 0; i < 3; i++)
            eye[i] = s.cam_position[i], at[i] = s.cam_look_at[i];
        camera cams[2] = {camera_look_at_deg(eye, at, s.cam_fov_deg)};
        eye[1] = at[1] = 0.5 * s.terrain.amplitude; /* halfway up the hills, level: the far valleys */
        cams[1] = camera_look_at_deg(eye, at, s.cam_fov_deg);
        for (int c = 0; c < 2; c++) {
            noise_ref n = {s.terrain.base, s.terrain.amplitude, s.terrain.frequency, camera_pixel_angle(&cams[c], H),
                           {cams[c].position[0], cams[c].position[1], cams[c].position[2]}, 1, s.terrain.octaves};
            for (int o = 0; o < n.octaves; o++) {
                double freq = n.frequency * ldexp(1, o);
                n.lipschitz += n.amplitude * ldexp(0.5, -o) * freq * (30.0 / 16.0 * sqrt(3.0) + 8 * n.pixel_angle);
            }
            draw(&s, &cams[c], W, H, 1, NULL, aov, NULL);
            for (int row = 0; row < H; row++)
                for (int x = 0; x < W; x++) {
                    dray r = pixel_ray(&cams[c], x, row, W, H);
                    ref[row * W + x] = noise_ref_hit(&n, &r, s.quality.max_dist);
                }
            int hits = 0, wrong_class = 0, at_edges = 0, undecided = 0, deep = 0, thin = 0, grazes = 0;
            for (int i = 0; i < W * H; i++) {
                double zr = ref[i];
                float zt = aov[i * AOV + AOV_SLOT_DEPTH];
                if (isnan(zr) || fabs(zr - s.quality.max_dist) < 0.01 * s.quality.max_dist) {
                    undecided++; /* the reference gave up, or the crossing sits on max_dist itself */
                    continue;
                }
                hits += !isinf(zr);
                if (isinf(zr) != isinf(zt)) {
                    /* a silhouette pixel: a neighbour's reference depth jumps or misses */
                    bool edge = false;
                    for (int k = 0; k < 4 && !edge; k++) {
                        int u = i % W + (k == 0) - (k == 1), v = i / W + (k == 2) - (k == 3);
                        if (u >= 0 && v >= 0 && u < W && v < H)
                            edge = isinf(ref[v * W + u]) != isinf(zr) || fabs(ref[v * W + u] - zr) > 0.05 * zr;
                    }
                    at_edges += edge;
                    wrong_class += !edge;
                    continue;
                }
                if (!isinf(zr)) {
                    /* shorter: only a graze within float resolution of the surface (a touch the reference,
                     * stopping at 1e-6 m, went past); behind: only past a chord thinner than the march's
                     * stated tolerance, one threshold (a rim the ray crossed between two samples) */
                    double rel = (zt - zr) / zr;
                    dray r = pixel_ray(&cams[c], i % W, i / W, W, H);
                    double q[3] = {r.o[0] + r.d[0] * zt, r.o[1] + r.d[1] * zt, r.o[2] + r.d[2] * zt};
                    double eps = s.quality.hit_k * n.pixel_angle * zr, chord = 0;
                    if (rel < -0.01 && fabs(noise_ref_f(&n, q)) > 1e-3)
                        deep++;
                    else if (rel < -0.01)
                        grazes++;
                    else if (rel > 0.01) {
                        for (chord = 0; chord < 2 * eps; chord += eps / 64) {
                            double u = zr + chord + eps / 64;
                            double pu[3] = {r.o[0] + r.d[0] * u, r.o[1] + r.d[1] * u, r.o[2] + r.d[2] * u};
                            if (noise_ref_f(&n, pu) > 0)
                                break;
                        }
                        if (chord < eps)
                            thin++;
                        else
                            deep++;
                    }
                    if (fabs(rel) > 0.01)
                        fprintf(stderr, "    pixel (%d, %d): depth %.6g, the reference %.6g (steps %g), f there %.2g, "
                                "chord %.3g m (a threshold %.3g m)\n", i % W, i / W, zt, zr, aov[i * AOV + AOV_SLOT_STEPS],
                                noise_ref_f(&n, q), chord, eps);
                }
            }
            fprintf(stderr, "  noise %s view %d: %d hits in the double reference (%d undecided); %d hit or missed "
                    "against it off the silhouettes (%d on them); %d depths more than 1 %% off, %d of them past a chord "
                    "thinner than a threshold, %d short at a graze within 1 mm\n", preset_name((quality_preset)p), c, hits,
                    undecided, wrong_class, at_edges, deep + thin + grazes, thin, grazes);
            assert_true(hits > W * H / 4);
            assert_true(undecided < W * H / 100);
            assert_int_equal(wrong_class, 0);
            assert_int_equal(deep, 0);
            assert_true(thin <= hits / 1000);
            assert_true(at_edges <= W * H / 100);
        }
        scene_free(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(maxmip_first_hits),
        cmocka_unit_test(linear_first_hits),
        cmocka_unit_test(thin_ridge),
        cmocka_unit_test(no_wall_below_the_floor),
        cmocka_unit_test(big_and_odd_grids),
        cmocka_unit_test(nodata_holes),
        cmocka_unit_test(patch_normals_are_exact),
        cmocka_unit_test(tiled_grids),
        cmocka_unit_test(changed_file_is_read_again),
        cmocka_unit_test(ground_height_probe),
        cmocka_unit_test(ridges_have_no_black_dashes),
        cmocka_unit_test(fog_against_quadrature),
        cmocka_unit_test(out_of_steps_is_not_a_miss),
        cmocka_unit_test(noise_against_double_reference),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='far*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
