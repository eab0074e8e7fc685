/* A DEM larger than the cache, streamed from disk in tiles (gpu/res_heightfield.c, data/geo/terrain_tiles.h,
 * data/geo/terrain_stream.h): the tiles' pyramid equals the whole grid's, node for node; a streamed shot
 * equals the in-core shot of the same DEM bit for bit, through eviction and bands cut to fit the cache; the
 * summary is kept in the cache folder and rebuilt when the DEM changes; a cache too small says so. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>
#include <gdal.h>

#include "check.h"
#include "gltest.h"
#include "data/geo/dem.h"
#include "data/geo/terrain.h"
#include "data/geo/terrain_tiles.h"
#include "data/media/image_io.h"
#include "gpu/render.h"
#include "view/aov.h"
#include "gpu/res_heightfield.h"
#include "jobs/capture/offline.h"

static uint32_t rng = 12345;
static float rnd(void)
{
    rng = rng * 1664525u + 1013904223u;
    return (float)(rng >> 8) / 16777216.0f;
}

/* Every node of every tile's levels and of the top pyramid against heightfield_from's pyramid (terrain.c's
 * build(), written for the whole grid), and the tiles' stats against its range, slope and holes: odd sizes,
 * long strips both ways, a grid of one cell, holes, tiles from 4 cells to one for all. */
static void tiles_equal_the_whole_pyramid(void **st)
{
    (void)st;
    static const int SIZES[][2] = {{301, 173}, {1000, 150}, {150, 1000}, {2, 2}, {65, 65}, {513, 257}, {3, 40}};
    static const int TILES[] = {4, 16, 64, 0};
    for (size_t s = 0; s < sizeof SIZES / sizeof *SIZES; s++) {
        int cols = SIZES[s][0], rows = SIZES[s][1];
        float *v = malloc(sizeof(float) * (size_t)cols * (size_t)rows);
        for (int i = 0; i < cols * rows; i++)
            v[i] = rnd() < 0.03f ? NAN : 100.0f * rnd() + 20.0f * sinf((float)(i % cols) * 0.05f);
        heightfield hf;
        heightfield_from(v, cols, rows, 2.0f, 3.0f, &hf); /* (NaN becomes TERRAIN_HOLE in hf.h) */
        for (size_t t = 0; t < sizeof TILES / sizeof *TILES; t++) {
            terrain_grid g;
            terrain_grid_plan(cols, rows, TILES[t], &g);
            assert_int_equal(g.levels, hf.levels);
            assert_int_equal(g.pw, hf.pw);
            int n = g.tiles_x * g.tiles_y;
            float *tile_max = malloc(sizeof(float) * (size_t)n), *win = malloc(sizeof(float) * (size_t)(size_t)g.slot_w * (size_t)g.slot_h);
            float *lv = malloc(sizeof(float) * (terrain_tile_level_floats(&g) + 1));
            terrain_tile_stats all = {.hmin = INFINITY, .hmax = -INFINITY};
            for (int k = 0; k < n; k++) {
                int tx = k % g.tiles_x, ty = k / g.tiles_x, x0, y0, w, h;
                terrain_tile_window(&g, tx, ty, &x0, &y0, &w, &h);
                for (int j = 0; j < h; j++)
                    memcpy(win + (size_t)j * (size_t)w, hf.h + (size_t)(y0 + j) * (size_t)cols + (size_t)x0, sizeof(float) * (size_t)w);
                terrain_tile_stats ts;
                terrain_tile_build(&g, tx, ty, win, hf.dx, hf.dz, lv, &ts);
                tile_max[k] = ts.max;
                all.hmin = fminf(all.hmin, ts.hmin), all.hmax = fmaxf(all.hmax, ts.hmax);
                all.lipschitz = fmaxf(all.lipschitz, ts.lipschitz), all.holes += ts.holes;
                const float *p = lv;
                for (int lvl = 1; lvl < g.tile_level; lvl++) {
                    int nx, ny, gw = hf.pw >> lvl;
                    gw = gw > 0 ? gw : 1;
                    terrain_tile_level_size(&g, lvl, &nx, &ny);
                    int sx = g.shift_x - lvl > 0 ? g.shift_x - lvl : 0, sy = g.shift_y - lvl > 0 ? g.shift_y - lvl : 0;
                    for (int j = 0; j < ny; j++)
                        for (int i = 0; i < nx; i++) {
                            int gx = (tx << sx) + i, gy = (ty << sy) + j; /* the node in the whole level */
                            float want = hf.max[lvl][(size_t)gy * (size_t)gw + (size_t)gx];
                            if (!(p[(size_t)j * (size_t)nx + (size_t)i] == want))
                                fail_msg("%dx%d, tiles of %d: level %d node (%d, %d) is %g, the whole grid's %g", cols, rows,
                                         TILES[t], lvl, gx, gy, (double)p[(size_t)j * (size_t)nx + (size_t)i], (double)want);
                        }
                    p += (size_t)nx * (size_t)ny;
                }
            }
            assert_true(all.hmin == hf.hmin && all.hmax == hf.hmax && all.lipschitz == hf.lipschitz);
            assert_int_equal(all.holes, hf.holes);
            float **top = terrain_top_build(&g, tile_max);
            for (int lvl = g.tile_level > 0 ? g.tile_level : 1; lvl < g.levels; lvl++) {
                int nx, ny;
                terrain_top_size(&g, lvl, &nx, &ny);
                for (int i = 0; i < nx * ny; i++)
                    if (!(top[lvl - g.tile_level][i] == hf.max[lvl][i]))
                        fail_msg("%dx%d, tiles of %d: top level %d node %d is %g, the whole grid's %g", cols, rows, TILES[t],
                                 lvl, i, (double)top[lvl - g.tile_level][i], (double)hf.max[lvl][i]);
            }
            terrain_top_free(&g, top);
            free(tile_max), free(win), free(lv);
        }
        heightfield_free(&hf);
        free(v);
    }
}

static char dir[] = "/tmp/fathom-stream-XXXXXX";
static char dem[300];

/* The shot of `json` with `sets` as float RGBA, depth and normal (EXR): *px, w × h × 8. */
static void shot(const char *json, const char *const *sets, int nsets, const camera *cam, float **px, const char *tag)
{
    scene s;
    load_text(json, sets, nsets, &s);
    char out[400];
    snprintf(out, sizeof out, "%s/%s.exr", dir, tag);
    offline_desc d = {.scene = &s, .cam = *cam, .width = 160, .height = 96, .spp = 2, .output = out,
                      .aovs = AOV_DEPTH | AOV_NORMAL, .quiet = true};
    err_t e = {{0}};
    if (!offline_render_current(&d, &e))
        fail_msg("%s: %s", tag, e.msg);
    int w, h, nc;
    if (!image_read_f32(out, 0, 4096, &w, &h, &nc, px, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(nc, 8);
    unlink(out);
    scene_free(&s);
}

static const char *JSON = "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"lights\": [{\"type\": "
                          "\"directional\", \"direction\": [-0.5, 0.4, 0.45], \"intensity\": 3, \"shadow\": \"soft\"}], "
                          "\"terrain\": {\"heightmap\": \"%s\", \"exaggeration\": 2}, \"quality\": {\"preset\": \"final\", \"max_dist\": 200000}}";

/* The in-core shot and streamed ones, bit for bit: a cache holding about two thirds of the tiles (tiles
 * evicted and read again), one holding a third (the image also cut into bands that fit), over three views. */
static void streamed_equals_in_core(void **st)
{
    (void)st;
    char json[1024];
    snprintf(json, sizeof json, JSON, dem);
    const camera views[] = {
        cam_at(-16000, 9000, -16000, 5000, 0, 4000, 50),      /* oblique, across the whole DEM */
        cam_at(-15000, 4800, 14000, 14000, 4000, -14000, 30), /* grazing, corner to corner (hills to 4.3 km) */
        cam_at(9000, 12000, 9000, 9500, 0, 9400, 40),         /* down on a corner: a few tiles */
    };
    setenv("FATHOM_TERRAIN_TILE", "64", 1); /* 16 × 16 tiles of 64 cells: many seams, 17 KB a tile */
    for (size_t v = 0; v < sizeof views / sizeof *views; v++) {
        float *core, *streamed;
        const char *in_core[] = {"terrain.cache_mb=4000"};
        shot(json, in_core, 1, &views[v], &core, "core");
        assert_false(res_heightfield_streamed());
        static const char *const CACHES[] = {"terrain.cache_mb=3", "terrain.cache_mb=2"};
        for (int c = 0; c < 2; c++) {
            shot(json, &CACHES[c], 1, &views[v], &streamed, "streamed");
            res_heightfield_stats s = res_heightfield_get_stats();
            assert_true(res_heightfield_streamed());
            print_message("view %zu, %s: %ld tiles read, %ld evicted, %d slots of %d tiles\n", v, CACHES[c], s.loaded,
                          s.evicted, s.slots, s.tiles);
            assert_true(s.slots < s.tiles);
            assert_true(s.loaded > 0);
            size_t n = 160 * 96 * 8, differ = 0;
            for (size_t i = 0; i < n; i++)
                differ += memcmp(&core[i], &streamed[i], sizeof(float)) != 0;
            if (differ)
                fail_msg("view %zu, %s: %zu of %zu values differ from the in-core shot", v, CACHES[c], differ, n);
            free(streamed);
            render_release_scene(); /* the next shot opens the DEM afresh (its tile counts from 0) */
        }
        free(core);
    }
    unsetenv("FATHOM_TERRAIN_TILE");
}

/* The window's way (res_heightfield_settle_async): frames go on while a loader thread reads the tiles they
 * asked for; once it has caught up (a frame asks for nothing), the frame equals the in-core one, bit for bit,
 * and the frames before it said they were waiting (TERRAIN_PENDING) rather than stalling. */
static void loader_thread_catches_up(void **st)
{
    (void)st;
    enum { FW = 120, FH = 72, FRAMES = 4000 };
    char json[1024];
    snprintf(json, sizeof json, JSON, dem);
    camera cam = cam_at(-15000, 4800, 14000, 14000, 4000, -14000, 30);
    setenv("FATHOM_TERRAIN_TILE", "64", 1);
    float *core = malloc(sizeof(float) * FW * FH * (AOV_FLOATS + 4)), *streamed = malloc(sizeof(float) * FW * FH * (AOV_FLOATS + 4));
    scene s;
    const char *in_core[] = {"terrain.cache_mb=4000"}, *small[] = {"terrain.cache_mb=3"};
    load_text(json, in_core, 1, &s);
    draw(&s, &cam, FW, FH, 1, NULL, core, core + FW * FH * AOV_FLOATS);
    scene_free(&s);
    render_release_scene();
    load_text(json, small, 1, &s);
    err_t e = {{0}};
    if (!render_set_scene(&s, NULL, &e))
        fail_msg("%s", e.msg);
    int frames = 0, pending = 0;
    for (res_heightfield_settled r = TERRAIN_LOADED; r != TERRAIN_SETTLED; frames++) {
        assert_true(frames < FRAMES);
        render_resize(FW, FH);
        render_begin(&cam);
        render_sample();
        r = res_heightfield_settle_async(4, &e);
        assert_int_not_equal(r, TERRAIN_FAILED);
        pending += r == TERRAIN_PENDING;
        if (r == TERRAIN_PENDING)
            nanosleep(&(struct timespec){0, 1000000}, NULL); /* a millisecond for the loader */
    }
    draw(&s, &cam, FW, FH, 1, NULL, streamed, streamed + FW * FH * AOV_FLOATS);
    print_message("loader: %d frames (%d waiting for it), %ld tiles read\n", frames, pending,
                  res_heightfield_get_stats().loaded);
    assert_memory_equal(core, streamed, sizeof(float) * FW * FH * (AOV_FLOATS + 4));
    scene_free(&s);
    render_release_scene();
    unsetenv("FATHOM_TERRAIN_TILE");
    free(core), free(streamed);
}

/* The summary: built the first time, read from the cache folder the next, built again when the DEM changes
 * (and its new heights drawn: the range follows them). */
static void summary_is_kept_and_rebuilt(void **st)
{
    (void)st;
    char json[1024];
    snprintf(json, sizeof json, JSON, dem);
    const char *sets[] = {"terrain.cache_mb=2"};
    setenv("FATHOM_TERRAIN_TILE", "64", 1);
    char cache[400]; /* a cache folder of its own: the other tests built this DEM's summary already */
    snprintf(cache, sizeof cache, "%s/cache-kept", dir);
    setenv("XDG_CACHE_HOME", cache, 1);
    scene s;
    err_t e = {{0}};
    bool cached[3];
    float hmax[3];
    for (int k = 0; k < 3; k++) {
        if (k == 2) { /* the DEM changed in place: a 10 × 10 block of 5 km peaks, same size and name */
            GDALAllRegister();
            GDALDatasetH ds = GDALOpen(dem, GA_Update);
            assert_non_null(ds);
            int16_t peak[100];
            for (int i = 0; i < 100; i++)
                peak[i] = 5000;
            assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 100, 100, 10, 10, peak, 10, 10, GDT_Int16,
                                          0, 0), CE_None);
            GDALClose(ds);
        }
        load_text(json, sets, 1, &s);
        if (!render_set_scene(&s, NULL, &e))
            fail_msg("%s", e.msg);
        cached[k] = res_heightfield_get_stats().summary_cached;
        hmax[k] = res_heightfield_loaded(NULL, NULL)->hmax;
        scene_free(&s);
        render_release_scene();
    }
    unsetenv("FATHOM_TERRAIN_TILE");
    snprintf(cache, sizeof cache, "%s/cache", dir);
    setenv("XDG_CACHE_HOME", cache, 1);
    assert_false(cached[0]);
    assert_true(cached[1]);
    assert_false(cached[2]);
    assert_true(hmax[0] == hmax[1]);
    assert_true(hmax[2] == 10000.0f); /* 5 km times the exaggeration */
    if (!dem_write_hills(dem, 1024, &e)) /* back as the other tests expect it */
        fail_msg("%s", e.msg);
}

/* A cache that cannot hold four tiles: one message naming terrain.cache_mb, no file written. */
static void too_small_a_cache_says_so(void **st)
{
    (void)st;
    char json[1024], out[400];
    snprintf(json, sizeof json, JSON, dem);
    snprintf(out, sizeof out, "%s/none.png", dir);
    const char *sets[] = {"terrain.cache_mb=1"}; /* tiles of 512 cells: 1.4 MB each */
    scene s;
    load_text(json, sets, 1, &s);
    offline_desc d = {.scene = &s, .cam = cam_at(-16000, 9000, -16000, 5000, 0, 4000, 50), .width = 64, .height = 36,
                      .spp = 1, .output = out, .quiet = true};
    err_t e = {{0}};
    assert_false(offline_render_current(&d, &e));
    print_message("%s\n", e.msg);
    assert_non_null(strstr(e.msg, "terrain.cache_mb"));
    assert_false(util_file_exists(out));
    scene_free(&s);
}

static int setup(void **st)
{
    if (!mkdtemp(dir))
        return -1;
    char cache[400];
    snprintf(cache, sizeof cache, "%s/cache", dir);
    setenv("XDG_CACHE_HOME", cache, 1); /* the summaries go here, not to the user's cache */
    snprintf(dem, sizeof dem, "%s/hills.tif", dir);
    err_t e;
    if (!dem_write_hills(dem, 1024, &e)) /* 30 m texels: 30.7 km square, hills 0 to 2.4 km */
        return -1;
    return gl_setup(st);
}

static int teardown(void **st)
{
    int r = gl_teardown(st);
    remove_tree(dir);
    return r;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(tiles_equal_the_whole_pyramid),
        cmocka_unit_test(streamed_equals_in_core),
        cmocka_unit_test(loader_thread_catches_up),
        cmocka_unit_test(summary_is_kept_and_rebuilt),
        cmocka_unit_test(too_small_a_cache_says_so),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
