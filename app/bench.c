#include "bench.h"

#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "image_io.h"
#include "render.h"
#include "scene.h"

enum { WARMUP_FRAMES = 2, DEFAULT_WIDTH = 640, DEFAULT_HEIGHT = 360 };

typedef struct row {
    quality_preset preset;
    quality q;
    double median_ms, min_ms, max_ms;
} row;

static bool time_preset(const cli_options *opt, quality_preset p, int w, int h, row *out, err_t *err)
{
    const char *sets[CLI_MAX_SETS + 1];
    char preset[64];
    snprintf(preset, sizeof preset, "quality.preset=%s", preset_name(p));
    sets[0] = preset;
    for (int i = 0; i < opt->set_count; i++)
        sets[i + 1] = opt->sets[i];
    scene s;
    if (!scene_load(opt->scene, sets, opt->set_count + 1, &s, err))
        return false;
    bool ok = render_set_scene(&s, NULL, err);
    if (ok) {
        render_resize(w, h);
        camera cam = camera_look_at(s.cam_position, s.cam_look_at, s.cam_fov_deg * GLM_PIf / 180.0f);
        double *ms = malloc(sizeof *ms * (size_t)opt->runs);
        for (int i = -WARMUP_FRAMES; i < opt->runs; i++) {
            render_begin(&cam);
            glFinish();
            double t0 = util_now();
            render_sample();
            glFinish();
            if (i >= 0)
                ms[i] = (util_now() - t0) * 1000.0;
        }
        *out = (row){.preset = p, .q = s.quality, .median_ms = util_median(ms, opt->runs), .min_ms = ms[0],
                     .max_ms = ms[0]};
        for (int i = 1; i < opt->runs; i++) {
            out->min_ms = ms[i] < out->min_ms ? ms[i] : out->min_ms;
            out->max_ms = ms[i] > out->max_ms ? ms[i] : out->max_ms;
        }
        free(ms);
    }
    scene_free(&s);
    return ok;
}

bool bench_run(const cli_options *opt, err_t *err)
{
    int w = opt->width ? opt->width : DEFAULT_WIDTH, h = opt->height ? opt->height : DEFAULT_HEIGHT;
    if (opt->csv && !image_can_write(opt->csv, err))
        return false;
    if (!gpu_open(&(gpu_desc){.headless = true}, err))
        return false;
    row rows[PRESET_COUNT];
    bool ok = render_init(err);
    for (int p = 0; ok && p < PRESET_COUNT; p++) {
        if (!opt->quiet)
            fprintf(stderr, "\rbench %s: %s (%d/%d) ", opt->scene, preset_name((quality_preset)p), p + 1, PRESET_COUNT);
        ok = time_preset(opt, (quality_preset)p, w, h, &rows[p], err);
    }
    if (!opt->quiet)
        fputc('\n', stderr);
    if (ok) {
        printf("scene %s, %dx%d, %s, median of %d frames (1 sample per pixel each)\n\n", opt->scene, w, h,
               gpu_describe(), opt->runs);
        printf("| preset | max steps | hit k | shadow steps | AO | bounces | aniso | ms/frame (median) | min | max "
               "| spp | ms per image at that spp |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (int p = 0; p < PRESET_COUNT; p++) {
            const row *r = &rows[p];
            printf("| %s | %d | %g | %d | %d | %d | %d | %.1f | %.1f | %.1f | %d | %.0f |\n", preset_name(r->preset),
                   r->q.max_steps, (double)r->q.hit_k, r->q.shadow_steps, r->q.ao_samples, r->q.bounces,
                   r->q.aniso_taps, r->median_ms, r->min_ms, r->max_ms, r->q.spp, r->median_ms * r->q.spp);
        }
    }
    if (ok && opt->csv) {
        char tmp[PATH_MAX_LEN];
        snprintf(tmp, sizeof tmp, "%s.tmp", opt->csv);
        FILE *f = fopen(tmp, "w");
        if (!f) {
            ok = err_set(err, "cannot write '%s'", opt->csv);
        } else {
            fprintf(f, "scene,width,height,preset,max_steps,hit_k,shadow_steps,ao_samples,bounces,aniso_taps,spp,"
                       "runs,median_ms,min_ms,max_ms,renderer\n");
            for (int p = 0; p < PRESET_COUNT; p++) {
                const row *r = &rows[p];
                fprintf(f, "%s,%d,%d,%s,%d,%g,%d,%d,%d,%d,%d,%d,%.3f,%.3f,%.3f,\"%s\"\n", opt->scene, w, h,
                        preset_name(r->preset), r->q.max_steps, (double)r->q.hit_k, r->q.shadow_steps,
                        r->q.ao_samples, r->q.bounces, r->q.aniso_taps, r->q.spp, opt->runs, r->median_ms,
                        r->min_ms, r->max_ms, gpu_describe());
            }
            ok = fclose(f) == 0 && rename(tmp, opt->csv) == 0;
            if (!ok) {
                remove(tmp);
                err_set(err, "cannot write '%s'", opt->csv);
            }
        }
    }
    render_shutdown();
    gpu_close();
    return ok;
}
