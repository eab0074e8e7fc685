/* bench_frames — bench --frame-times (bench.h): start-up as a user meets it, and each preset's frame
 * time on both backends side by side. */
#include "jobs/bench/bench.h"
#include "jobs/bench/bench_load.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "data/droplets/droplets.h"
#include "view/aov.h"
#include "gpu/gpu.h"
#include "gpu/render.h"
#include "jobs/bench/metrics.h"

/* One preset's frame times on each backend, taken in turn (fragment, compute, fragment, ...) after a
 * warm-up of each, so both see the same machine load. */
static bool time_backends(const scene *s, const camera *cam, int w, int h, int nb, const render_backend *backends,
                          double *ms, int runs, err_t *err)
{
    for (int r = -1; r < runs; r++) /* r = -1: the warm-up (compiles) */
        for (int b = 0; b < nb; b++) {
            if (!render_switch_backend(backends[b], err) || !render_set_scene(s, NULL, err))
                return false;
            double t = bench_image_ms(s, cam, w, h);
            if (r >= 0)
                ms[b * runs + r] = t;
        }
    return true;
}

/* Start-up as a user meets it: whole-process times of `fathom --version` and of a 64x36 shot of the
 * scene, taken in turn (the image and DEM libraries load only when a run needs them: data/lazy/lazy.h). */
static void startup_times(const bench_desc *opt)
{
    char dir[] = "/tmp/fathom-bench-startup-XXXXXX", shot[sizeof dir + 16];
    if (!mkdtemp(dir))
        return;
    snprintf(shot, sizeof shot, "%s/shot.png", dir);
    char *version[] = {"fathom", "--version", NULL};
    char *image[] = {"fathom", "--scene", (char *)opt->scene, "--size", "64x36", "--quiet", "--output", shot, NULL};
    double *ms = util_alloc(sizeof *ms * 2 * (size_t)opt->runs, "bench timings");
    bool ok = bench_process_ms(image, NULL) >= 0; /* a warm-up: the shader cache and the page cache */
    for (int r = 0; ok && r < opt->runs; r++) {
        ms[r] = bench_process_ms(version, NULL);
        ms[opt->runs + r] = bench_process_ms(image, NULL);
        ok = ms[r] >= 0 && ms[opt->runs + r] >= 0;
    }
    unlink(shot);
    rmdir(dir);
    double lo[2], hi[2], med[2];
    for (int k = 0; ok && k < 2; k++)
        med[k] = metrics_median_interval(ms + k * opt->runs, opt->runs, &lo[k], &hi[k]);
    if (ok)
        printf("start-up (whole process, median [95 %% interval] of %d): fathom --version %.0f ms [%.0f-%.0f], "
               "a 64x36 shot of %s %.0f ms [%.0f-%.0f]\n",
               opt->runs, med[0], lo[0], hi[0], opt->scene, med[1], lo[1], hi[1]);
    else
        printf("start-up: a whole fathom process failed to run\n");
    free(ms);
}

/* Each preset's frame time (one sample per pixel) at the start view: what the window costs, on both
 * backends side by side where the GL has compute shaders. */
bool bench_frame_times(const bench_desc *opt, int w, int h, err_t *err)
{
    startup_times(opt);
    if (!gpu_open(&(gpu_desc){.headless = true}, err))
        return false;
    bool ok = render_init(err);
    render_backend backends[2] = {BACKEND_FRAGMENT, BACKEND_COMPUTE};
    int nb = render_has_compute() ? 2 : 1;
    printf("%s, %dx%d, %s: ms per frame (1 sample per pixel), median [95 %% interval] of %d, the backends "
           "taken in turn after a warm-up; auto takes %s\n",
           opt->scene, w, h, gpu_describe(), opt->runs, render_backend_name(render_backend_used()));
    printf("  %-12s %-24s %-24s %-22s %s\n", "preset", "fragment ms", nb > 1 ? "compute ms" : "(no compute)",
           "compute / fragment", "steps per pixel");
    for (int p = 0; ok && p < PRESET_COUNT; p++) {
        char set[64];
        snprintf(set, sizeof set, "quality.preset=%s", preset_name((quality_preset)p));
        const char *sets[] = {set, "quality.spp=1"};
        scene s;
        ok = bench_load(opt, sets, 2, &s, err) && render_set_scene(&s, NULL, err);
        if (!ok)
            break;
        double read_s, grid_s;
        const droplets *d = render_droplets(&read_s, &grid_s);
        if (d && p == 0 && d->nodes)
            printf("  droplets     %d: read %.3f s, bvh %.3f s (%d nodes, %zu listings, %.1f MB)\n", d->count, read_s,
                   grid_s, d->node_count, d->refs, (double)droplets_bytes(d) / 1e6);
        else if (d && p == 0)
            printf("  droplets     %d: read %.3f s, grid %.3f s (%dx%dx%d cells, %zu listings, %.1f MB)\n", d->count,
                   read_s, grid_s, d->dims[0], d->dims[1], d->dims[2], d->refs, (double)droplets_bytes(d) / 1e6);
        camera cam = scene_camera(&s, s.cam_position, s.cam_look_at, s.cam_fov_deg);
        double *ms = util_alloc(sizeof *ms * (size_t)opt->runs * 2, "bench timings");
        ok = time_backends(&s, &cam, w, h, nb, backends, ms, opt->runs, err);
        if (ok) {
            float *aov = util_alloc(sizeof(float) * (size_t)w * (size_t)h * AOV_FLOATS, "a bench image");
            render_read_aovs(aov);
            double steps = 0;
            for (int i = 0; i < w * h; i++)
                steps += fabsf(aov[(size_t)i * AOV_FLOATS + AOV_SLOT_STEPS]); /* negative: ran out of steps */
            free(aov);
            char cell[2][64], ratio[64] = "";
            double med[2], lo[2], hi[2];
            for (int b = 0; b < nb; b++) {
                med[b] = metrics_median_interval(ms + b * opt->runs, opt->runs, &lo[b], &hi[b]);
                snprintf(cell[b], sizeof cell[b], "%.1f [%.1f-%.1f]", med[b], lo[b], hi[b]);
            }
            if (nb > 1 && (lo[1] > hi[0] || lo[0] > hi[1]))
                snprintf(ratio, sizeof ratio, "%.2f", med[1] / med[0]);
            else if (nb > 1)
                snprintf(ratio, sizeof ratio, "not measurable");
            printf("  %-12s %-24s %-24s %-22s %.1f\n", preset_name((quality_preset)p), cell[0], nb > 1 ? cell[1] : "",
                   ratio, steps / (w * h));
        }
        free(ms);
        scene_free(&s);
    }
    render_shutdown();
    gpu_close();
    return ok;
}

