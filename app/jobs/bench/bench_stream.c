/* bench --terrain-stream: what a DEM past memory costs, streamed from disk (gpu/res_heightfield.c). For each
 * side N (4096 … 65536, or --knob side=A,B,...) a VRT mosaic of one generated 4096² Int16 tile (30 m texels
 * in UTM 33N, bench --terrain-scale's hills) repeated (N/4096)² times, so no run writes gigabytes; then, in
 * a process of its own with an empty cache folder, as a user opens it with the default terrain.cache_mb
 * (64 MB for 4096² and 8192², which fit the default and would not stream):
 *   open cold   the summary built by reading the whole DEM once (every core), the textures allocated;
 *   open warm   the same with the summary in the cache folder;
 *   first       the first image, nothing resident yet (missing tiles stand as plateaus);
 *   shot        passes until no pixel asks for a tile, then the image: what an offline shot waits for;
 *   frame       median of --runs frames once warm, against the same view in core where it fits (≤ 16384²: a
 *               streamed block, the in-core one, a streamed one again);
 * and the peak resident memory of the process (VmHWM, reset after the GL context is made), the tiles and
 * bytes read, and the GPU's share (the slots). The view is a flight's: 2.6 km up, looking 40 km ahead. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "data/geo/dem.h"
#include "gpu/gpu.h"
#include "gpu/render.h"
#include "gpu/res_heightfield.h"
#include "jobs/bench/bench.h"

enum { TILE = 4096 };

/* The mosaic: n/TILE × n/TILE references to tile.tif, georeferenced as one DEM. */
static bool write_mosaic(const char *dir, int n, char *path, size_t len, err_t *err)
{
    snprintf(path, len, "%s/mosaic%d.vrt", dir, n);
    FILE *f = fopen(path, "w");
    if (!f)
        return err_set(err, "cannot write '%s'", path);
    fprintf(f, "<VRTDataset rasterXSize=\"%d\" rasterYSize=\"%d\">\n  <SRS>EPSG:32633</SRS>\n"
               "  <GeoTransform>500000, 30, 0, 5000000, 0, -30</GeoTransform>\n"
               "  <VRTRasterBand dataType=\"Int16\" band=\"1\">\n", n, n);
    for (int y = 0; y < n; y += TILE)
        for (int x = 0; x < n; x += TILE)
            fprintf(f, "    <SimpleSource><SourceFilename relativeToVRT=\"1\">tile.tif</SourceFilename>"
                       "<SourceBand>1</SourceBand><SourceProperties RasterXSize=\"%d\" RasterYSize=\"%d\" "
                       "DataType=\"Int16\" BlockXSize=\"256\" BlockYSize=\"256\"/><SrcRect xOff=\"0\" yOff=\"0\" "
                       "xSize=\"%d\" ySize=\"%d\"/><DstRect xOff=\"%d\" yOff=\"%d\" xSize=\"%d\" ySize=\"%d\"/>"
                       "</SimpleSource>\n", TILE, TILE, TILE, TILE, x, y, TILE, TILE);
    fprintf(f, "  </VRTRasterBand>\n</VRTDataset>\n");
    return fclose(f) == 0 || err_set(err, "cannot write '%s' (disk full?)", path);
}

static bool set_dem(const char *dem, int cache_mb, scene *s, camera *cam, err_t *err)
{
    char json[PATH_MAX_LEN + 1024];
    snprintf(json, sizeof json,
             "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"lights\": [{\"type\": \"directional\", "
             "\"direction\": [-0.5, 0.5, 0.45], \"intensity\": 3, \"shadow\": \"soft\"}], \"camera\": {\"position\": "
             "[0, 2600, 20000], \"look_at\": [0, 1200, -20000], \"fov\": 60}, \"terrain\": {\"heightmap\": \"%s\", "
             "\"cache_mb\": %d}, \"quality\": {\"preset\": \"interactive\", \"spp\": 1, \"max_dist\": 45000}}",
             dem, cache_mb);
    if (!scene_load_text(json, dem, NULL, 0, s, err))
        return false;
    *cam = scene_camera(s, s->cam_position, s->cam_look_at, s->cam_fov_deg);
    return render_set_scene(s, NULL, err);
}

typedef struct row {
    bool streamed;
    double open_cold, open_warm, first_ms, shot_s, frame_ms, core_ms, peak_mb, gpu_mb, read_mb;
    double frame_range[2], core_range[2]; /* the frames' fastest and slowest: the spread around the median */
    long loaded;
    int tiles, slots, passes;
} row;

/* Passes of one sample until one asks for no tile (then the frame is exact); false when the view's tiles do
 * not fit the cache (the offline shot cuts bands then; the bench's view is chosen to fit). */
static bool settle(const camera *cam, int w, int h, int *passes, err_t *err)
{
    render_resize(w, h);
    res_heightfield_watch();
    for (*passes = 1;; ++*passes) {
        render_begin(cam);
        render_sample();
        res_heightfield_settled r = res_heightfield_settle(1 << 30, err);
        if (r == TERRAIN_SETTLED)
            return true;
        if (r != TERRAIN_LOADED)
            return r == TERRAIN_FAILED ? false : err_set(err, "the view's tiles do not fit terrain.cache_mb");
    }
}

/* The streamed view's frames once its tiles are in: passes until none asks for one, then runs frames into t. */
static bool streamed_frames(const char *dem, int cache_mb, int w, int h, int runs, double *t, row *r, err_t *err)
{
    scene s;
    camera cam;
    bool ok = set_dem(dem, cache_mb, &s, &cam, err) && settle(&cam, w, h, &r->passes, err);
    bench_frame_ms(w, h, &cam);
    for (int i = 0; ok && i < runs; i++)
        t[i] = bench_frame_ms(w, h, &cam);
    scene_free(&s);
    render_release_scene();
    return ok;
}

static void range(const double *t, int n, double out[2])
{
    out[0] = out[1] = t[0];
    for (int i = 1; i < n; i++)
        out[0] = t[i] < out[0] ? t[i] : out[0], out[1] = t[i] > out[1] ? t[i] : out[1];
}

/* Streamed frames, in-core frames where it fits (≤ 16384²), streamed again: each median over both blocks of
 * its kind, so the order costs neither side. */
static bool compare_frames(const char *dem, int n, int cache_mb, int w, int h, int runs, row *r, err_t *err)
{
    double *t = util_alloc(sizeof(double) * 4 * (size_t)runs, "bench timings"), *core = t + 2 * runs;
    bool ok = streamed_frames(dem, cache_mb, w, h, runs, t, r, err);
    if (ok && n <= 16384) {
        scene s;
        camera cam;
        ok = set_dem(dem, 16384, &s, &cam, err);
        bench_frame_ms(w, h, &cam);
        for (int i = 0; ok && i < runs; i++)
            core[i] = bench_frame_ms(w, h, &cam);
        scene_free(&s);
        render_release_scene();
        ok = ok && streamed_frames(dem, cache_mb, w, h, runs, t + runs, r, err);
        r->core_ms = ok ? util_median(core, runs) : 0;
        range(core, runs, r->core_range);
    }
    r->frame_ms = util_median(t, n <= 16384 ? 2 * runs : runs);
    range(t, n <= 16384 ? 2 * runs : runs, r->frame_range);
    free(t);
    return ok;
}

static bool measure(const char *dem, int n, int w, int h, int runs, row *r, err_t *err)
{
    int cache_mb = n <= 8192 ? 64 : 0; /* streamed: 4096² and 8192² fit the default cache, so a smaller one */
    long base = bench_status_kb("VmRSS:");
    bench_reset_peak();
    scene s;
    camera cam;
    double t0 = util_now();
    if (!set_dem(dem, cache_mb, &s, &cam, err))
        return false;
    glFinish();
    r->open_cold = util_now() - t0;
    render_release_scene();
    scene_free(&s);
    t0 = util_now();
    if (!set_dem(dem, cache_mb, &s, &cam, err))
        return false;
    glFinish();
    r->open_warm = util_now() - t0;
    r->streamed = res_heightfield_streamed();
    r->first_ms = bench_frame_ms(w, h, &cam); /* nothing resident: plateaus */
    t0 = util_now();
    bool ok = settle(&cam, w, h, &r->passes, err);
    if (ok) {
        render_begin(&cam);
        render_sample();
        glFinish();
    }
    r->shot_s = util_now() - t0;
    res_heightfield_stats st = res_heightfield_get_stats();
    r->loaded = st.loaded, r->tiles = st.tiles, r->slots = st.slots;
    r->read_mb = (double)st.bytes_read / 1e6;
    r->gpu_mb = st.gpu_bytes / 1048576.0;
    r->peak_mb = (double)(bench_status_kb("VmHWM:") - base) / 1024.0; /* before the in-core comparison */
    scene_free(&s);
    render_release_scene();
    return ok && compare_frames(dem, n, cache_mb, w, h, runs, r, err);
}

static bool one_side(int n, const char *dir, int w, int h, int runs, const char *csv_path, err_t *err)
{
    char dem[PATH_MAX_LEN], cache[PATH_MAX_LEN];
    if (!write_mosaic(dir, n, dem, sizeof dem, err))
        return false;
    snprintf(cache, sizeof cache, "%s/cache%d", dir, n); /* cold: no summary kept from before */
    setenv("XDG_CACHE_HOME", cache, 1);
    if (!gpu_open(&(gpu_desc){.headless = true}, err) || !render_init(err))
        return false;
    row r = {0};
    bool ok = measure(dem, n, w, h, runs, &r, err);
    render_shutdown();
    gpu_close();
    util_remove_tree(cache); /* the summary, and Mesa's shader cache (it follows XDG_CACHE_HOME too) */
    if (util_file_exists(cache) || unlink(dem) != 0)
        fprintf(stderr, "fathom: could not remove '%s' or '%s'\n", cache, dem);
    if (!ok)
        return false;
    char frame[48], core[48] = "-", ratio[32] = "-";
    snprintf(frame, sizeof frame, "%.1f (%.0f-%.0f)", r.frame_ms, r.frame_range[0], r.frame_range[1]);
    if (r.core_ms > 0) {
        snprintf(core, sizeof core, "%.1f (%.0f-%.0f)", r.core_ms, r.core_range[0], r.core_range[1]);
        snprintf(ratio, sizeof ratio, "%.2f", r.frame_ms / r.core_ms);
    }
    printf("%7d %9s %10.2f %9.2f %9.0f %7.2f %6d %18s %18s %6s %8.0f %8.0f %8ld %9.0f %7d\n", n,
           r.streamed ? "streamed" : "in core", r.open_cold, r.open_warm, r.first_ms, r.shot_s, r.passes, frame,
           core, ratio, r.peak_mb, r.gpu_mb, r.loaded, r.read_mb, r.tiles);
    fflush(stdout);
    FILE *csv = csv_path ? fopen(csv_path, "a") : NULL;
    if (csv) {
        fprintf(csv, "%d,%s,%.0f,%.3f,%.3f,%.1f,%.3f,%d,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.0f,%.0f,%ld,%.0f,%d,%d\n", n,
                r.streamed ? "streamed" : "in core", (double)n * n, r.open_cold, r.open_warm, r.first_ms, r.shot_s,
                r.passes, r.frame_ms, r.frame_range[0], r.frame_range[1], r.core_ms, r.core_range[0], r.core_range[1],
                r.peak_mb, r.gpu_mb, r.loaded, r.read_mb, r.tiles, r.slots);
        fclose(csv);
    }
    return true;
}

static bool stream_side(int n, const bench_side_run *r, err_t *err)
{
    return one_side(n, r->dir, r->w, r->h, r->runs, r->csv, err);
}

bool bench_terrain_stream(const bench_desc *opt, int w, int h, err_t *err)
{
    const char *sides;
    char csv_path[PATH_MAX_LEN];
    if (!bench_sides(opt, "--terrain-stream", "4096,16384,65536", TILE, DEM_STREAM_MAX_SIDE, TILE, &sides,
                     "terrain-stream.csv", "side,mode,texels,open_cold_s,open_warm_s,first_ms,shot_s,passes,frame_ms,"
                     "frame_min_ms,frame_max_ms,in_core_ms,in_core_min_ms,in_core_max_ms,peak_mb,gpu_mb,tiles_read,read_mb,tiles,slots", csv_path, err))
        return false;
    char dir[] = "/tmp/fathom-stream-XXXXXX", tile[PATH_MAX_LEN];
    if (!mkdtemp(dir))
        return err_set(err, "cannot make a temporary folder in /tmp");
    snprintf(tile, sizeof tile, "%s/tile.tif", dir);
    if (!dem_write_hills(tile, TILE, err)) {
        rmdir(dir);
        return false;
    }
    printf("DEMs past memory, streamed: %dx%d, 1 sample per pixel at the interactive preset, frames the median of %d;\n"
           "each side in a process of its own with an empty cache folder and the default terrain.cache_mb (64 MB up to\n"
           "8192², which fit the default); frame ms: the median of two blocks around the in-core one (fastest-slowest)\n"
           "%7s %9s %10s %9s %9s %7s %6s %18s %18s %6s %8s %8s %8s %9s %7s\n", w, h, opt->runs, "side", "mode", "open cold", "open warm",
           "first ms", "shot s", "passes", "frame ms", "core ms", "ratio", "peak MB", "GPU MB", "tiles rd", "read MB",
           "tiles");
    fflush(stdout);
    bench_side_run run = {dir, w, h, opt->runs, opt->out ? csv_path : NULL};
    bool ok = bench_fork_sides(sides, "--terrain-stream", stream_side, &run, err);
    unlink(tile);
    rmdir(dir);
    return ok;
}
