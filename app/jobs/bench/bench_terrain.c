/* bench --terrain-scale: what a DEM's size costs. For each side N (256 … 32768, or --knob
 * side=A,B,...) an N × N Int16 GeoTIFF in metres is written (SRTM-like: 30 m texels in UTM, rolling
 * hills of several wavelengths), then timed as a user opens it: reading it through GDAL, building the
 * max pyramid and uploading the tiles; the peak memory that adds (VmHWM, reset before each load);
 * then frames at --size with the camera framed from the DEM's extent, for maxmip and linear: the
 * median of --runs frames (1 sample per pixel, interactive preset) and the height samples per pixel. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "view/aov.h"
#include "jobs/bench/bench.h"
#include "gpu/gpu.h"
#include "gpu/render.h"
#include "data/geo/dem.h"
#include "data/geo/terrain.h"

/* kB of the process's current (VmRSS) or peak (VmHWM) resident memory */
long bench_status_kb(const char *key)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    size_t n = strlen(key);
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, key, n))
            kb = atol(line + n + 1);
    if (f)
        fclose(f);
    return kb;
}

void bench_reset_peak(void)
{
    FILE *f = fopen("/proc/self/clear_refs", "w"); /* "5": reset the peak RSS to the current RSS */
    if (f) {
        fputs("5", f);
        fclose(f);
    }
}

double bench_frame_ms(int w, int h, const camera *cam)
{
    render_resize(w, h);
    render_begin(cam);
    glFinish();
    double t0 = util_now();
    render_sample();
    glFinish();
    return (util_now() - t0) * 1000.0;
}

/* One side, in a process of its own (forked: a fresh heap and GPU context, so the peak memory is this
 * DEM's alone): writes the DEM, loads it, times both methods, prints the row (and appends it to csv). */
static bool one_side(int n, const char *dir, int w, int h, int runs, const char *csv_path, err_t *err)
{
    char file[PATH_MAX_LEN], json[PATH_MAX_LEN * 2];
    snprintf(file, sizeof file, "%s/dem%d.tif", dir, n);
    if (!dem_write_hills(file, n, err))
        return false;
    FILE *f = fopen(file, "rb");
    double file_mb = 0;
    if (f) {
        fseek(f, 0, SEEK_END);
        file_mb = (double)ftell(f) / 1e6;
        fclose(f);
    }
    if (!gpu_open(&(gpu_desc){.headless = true}, err) || !render_init(err)) {
        unlink(file);
        return false;
    }
    double ms[2] = {0}, samples[2] = {0}, load_s = 0, peak_mb = 0, kept_mb = 0;
    int tx = 0, ty = 0;
    bool ok = true;
    for (int m = 0; ok && m < 2; m++) {
        snprintf(json, sizeof json,
                 "{\"program\": \"terrain\", \"camera\": \"auto\", \"materials\": {\"rock\": {}}, \"lights\": "
                 "[{\"type\": \"directional\", \"direction\": [-0.5, 0.5, 0.45], \"intensity\": 3, \"shadow\": \"soft\"}], "
                 "\"terrain\": {\"heightmap\": \"%s\", \"method\": \"%s\"}, \"quality\": {\"preset\": \"interactive\", "
                 "\"spp\": 1}}", file, m ? "linear" : "maxmip");
        scene s;
        if (!(ok = scene_load_text(json, file, NULL, 0, &s, err)))
            break;
        long base = bench_status_kb("VmRSS:");
        bench_reset_peak();
        double t0 = util_now();
        ok = render_set_scene(&s, NULL, err);
        glFinish();
        if (m == 0) { /* the second method reuses the loaded DEM */
            load_s = util_now() - t0;
            peak_mb = (double)(bench_status_kb("VmHWM:") - base) / 1024.0;
            kept_mb = (double)(bench_status_kb("VmRSS:") - base) / 1024.0; /* what stays once loaded */
            render_terrain_tiles(&tx, &ty);
        }
        if (ok) {
            camera cam = scene_camera(&s, s.cam_position, s.cam_look_at, s.cam_fov_deg);
            double *t = util_alloc(sizeof(double) * (size_t)runs, "bench timings");
            bench_frame_ms(w, h, &cam);
            for (int r = 0; r < runs; r++)
                t[r] = bench_frame_ms(w, h, &cam);
            ms[m] = util_median(t, runs);
            free(t);
            float *aov = util_alloc(sizeof(float) * (size_t)w * (size_t)h * AOV_FLOATS, "a bench image");
            render_read_aovs(aov);
            for (int i = 0; i < w * h; i++)
                samples[m] += fabsf(aov[(size_t)i * AOV_FLOATS + AOV_SLOT_STEPS]);
            samples[m] /= (double)w * h;
            free(aov);
        }
        scene_free(&s);
    }
    unlink(file);
    render_shutdown();
    gpu_close();
    if (!ok)
        return false;
    double texels = (double)n * n, bpt = peak_mb * 1048576.0 / texels, kpt = kept_mb * 1048576.0 / texels;
    printf("%7d %8.1f %8.2f %9.0f %10.2f %9.0f %10.2f %3dx%-2d %12.1f %10.1f %12.1f %10.1f\n", n, file_mb, load_s, peak_mb,
           bpt, kept_mb, kpt, tx, ty, ms[0], samples[0], ms[1], samples[1]);
    fflush(stdout);
    FILE *csv = csv_path ? fopen(csv_path, "a") : NULL;
    if (csv) {
        fprintf(csv, "%d,%.0f,%.1f,%.3f,%.0f,%.2f,%.0f,%.2f,%dx%d,%.1f,%.1f,%.1f,%.1f\n", n, texels, file_mb, load_s, peak_mb,
                bpt, kept_mb, kpt, tx, ty, ms[0], samples[0], ms[1], samples[1]);
        fclose(csv);
    }
    return true;
}

static bool scale_side(int n, const bench_side_run *r, err_t *err)
{
    return one_side(n, r->dir, r->w, r->h, r->runs, r->csv, err);
}

bool bench_sides(const bench_desc *opt, const char *mode, const char *sides, long lo, long hi, long step,
                 const char **out, const char *name, const char *header, char csv_path[PATH_MAX_LEN], err_t *err)
{
    for (int i = 0; i < opt->knob_count; i++) {
        if (strncmp(opt->knobs[i], "side=", 5))
            return err_set(err, "bench %s takes --knob side=N1,N2,... only", mode);
        sides = opt->knobs[i] + 5;
    }
    for (const char *p = sides; *p; p += strcspn(p, ","), p += *p == ',') {
        char *end;
        long n = strtol(p, &end, 10);
        if (end == p || (*end && *end != ',') || n < lo || n > hi || n % step)
            return err_set(err, "--knob side: expected whole numbers from %ld to %ld%s, e.g. side=%ld,%ld", lo, hi,
                           step > 1 ? ", multiples of the tile" : "", lo, lo * 4);
    }
    *out = sides;
    csv_path[0] = '\0';
    if (!opt->out)
        return true;
    snprintf(csv_path, PATH_MAX_LEN, "%s/%s", opt->out, name);
    FILE *csv = fopen(csv_path, "w");
    if (!csv)
        return err_set(err, "cannot write '%s'", csv_path);
    fprintf(csv, "%s\n", header);
    return fclose(csv) == 0 || err_set(err, "cannot write '%s' (disk full?)", csv_path);
}

bool bench_terrain_scale(const bench_desc *opt, int w, int h, err_t *err)
{
    const char *sides;
    char csv_path[PATH_MAX_LEN];
    if (!bench_sides(opt, "--terrain-scale", "256,1024,4096,8192,16384,32768", 2, TERRAIN_MAX_SIDE, 1, &sides,
                     "terrain-scale.csv", "side,texels,file_mb,load_s,peak_mb,peak_bytes_per_texel,kept_mb,"
                     "kept_bytes_per_texel,tiles,maxmip_ms,maxmip_samples,linear_ms,linear_samples", csv_path, err))
        return false;
    char dir[] = "/tmp/fathom-scale-XXXXXX";
    if (!mkdtemp(dir))
        return err_set(err, "cannot make a temporary folder in /tmp");
    printf("DEM scaling, %dx%d, 1 sample per pixel at the interactive preset, median of %d frames; each side in a\n"
           "process of its own; peak MB: resident memory the load added at its highest; kept MB: what stays\n"
           "once it is loaded (the raw Int16 file is 2 bytes a texel)\n%7s %8s %8s %9s %10s %9s %10s %6s %12s %10s %12s "
           "%10s\n", w, h, opt->runs, "side", "file MB", "load s", "peak MB", "B/texel", "kept MB", "B/texel", "tiles",
           "maxmip ms", "samples/px", "linear ms", "samples/px");
    fflush(stdout);
    bench_side_run run = {dir, w, h, opt->runs, opt->out ? csv_path : NULL};
    bool ok = bench_fork_sides(sides, "--terrain-scale", scale_side, &run, err);
    rmdir(dir);
    return ok;
}

bool bench_fork_sides(const char *sides, const char *mode, bool (*side)(int n, const bench_side_run *r, err_t *err),
                      const bench_side_run *r, err_t *err)
{
    bool ok = true;
    for (const char *p = sides; ok && *p; p += strcspn(p, ","), p += *p == ',') {
        int n = atoi(p);
        pid_t pid = fork();
        if (pid == 0) {
            err_t e;
            bool done = side(n, r, &e);
            if (!done)
                fprintf(stderr, "fathom: side %d: %s\n", n, e.msg);
            fflush(NULL);
            _exit(done ? 0 : 1);
        }
        int status = 0;
        if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
            ok = err_set(err, "bench %s: side %d failed%s", mode, n,
                         pid > 0 && WIFSIGNALED(status) ? " (killed: out of memory?)" : "");
    }
    return ok;
}
