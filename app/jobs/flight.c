/* flight — see flight.h. */
#include "jobs/flight.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "gpu/gpu.h"
#include "data/image_io.h"
#include "jobs/offline.h"
#include "view/path.h"
#include "gpu/render.h"
#include "scene/scene.h"
#include "view/shot.h"

enum { DEFAULT_FPS = 30, DEFAULT_WIDTH = 1280, DEFAULT_HEIGHT = 720 };

static bool exists(const char *file)
{
    struct stat st;
    return stat(file, &st) == 0 && S_ISREG(st.st_mode);
}

/* The scene for one frame: the command line's overrides, then the path's parameter tracks. */
static bool frame_scene(const cli_options *opt, const path *p, const path_sample *smp, scene *s, const char **sets,
                        int *nsets, char (*track)[PATH_PARAM_NAME + 32], err_t *err)
{
    int n = 0;
    for (int i = 0; i < opt->set_count; i++)
        sets[n++] = opt->sets[i];
    for (int k = 0; k < p->param_count && n < CLI_MAX_SETS + PATH_MAX_PARAMS; k++) {
        snprintf(track[k], sizeof track[k], "%s=%.9g", p->params[k], smp->values[k]);
        sets[n++] = track[k];
    }
    static char spp[48]; /* --spp as the override it stands for: the frame's file remembers it */
    if (opt->spp) {
        snprintf(spp, sizeof spp, "quality.spp=%d", opt->spp);
        sets[n++] = spp;
    }
    *nsets = n;
    return scene_load(opt->scene, sets, n, s, err);
}

/* The camera must never enter a solid (or a fractal's set): map() along the path, at 4 points a
 * frame, in the first frame's scene. A path that dips inside is refused with where and when. */
static bool check_clearance(const cli_options *opt, const path *p, int first, int last, int fps, err_t *err)
{
    enum { PER_FRAME = 4, MAX_POINTS = 1 << 17 };
    int n = (last - first) * PER_FRAME + 1;
    if (n > MAX_POINTS)
        n = MAX_POINTS;
    double t0 = p->keys[0].time + (double)first / fps, t1 = p->keys[0].time + (double)last / fps;
    float *pts = util_alloc(sizeof(float) * 3 * (size_t)n, "path clearance"), *d = util_alloc(sizeof(float) * 2 * (size_t)n, "path clearance");
    for (int i = 0; i < n; i++) {
        path_sample smp;
        path_eval(p, n > 1 ? t0 + (t1 - t0) * i / (n - 1) : t0, &smp);
        for (int k = 0; k < 3; k++)
            pts[3 * i + k] = (float)smp.position[k];
    }
    scene s = {0};
    const char *sets[CLI_MAX_SETS + PATH_MAX_PARAMS + 1];
    char track[PATH_MAX_PARAMS][PATH_PARAM_NAME + 32];
    int nsets;
    path_sample smp;
    path_eval(p, t0, &smp);
    bool ok = frame_scene(opt, p, &smp, &s, sets, &nsets, track, err) && render_set_scene(&s, NULL, err) &&
              render_probe(&s, NULL, pts, n, d, err);
    /* inside: a negative distance, or (a fractal's estimate, which need not turn negative in its set) one
     * below float resolution at that point */
    for (int i = 0; ok && i < n; i++)
        if (d[2 * i] < 0 || d[2 * i] < PRECISION_REL * (1 + fabsf(pts[3 * i]) + fabsf(pts[3 * i + 1]) + fabsf(pts[3 * i + 2]))) {
            double t = n > 1 ? t0 + (t1 - t0) * i / (n - 1) : t0;
            int key = 0;
            while (key + 1 < p->count && p->keys[key + 1].time <= t)
                key++;
            ok = err_set(err, "path '%s': at t = %.3f s (frame %d) the camera is inside the scene's surface at (%.4g, "
                              "%.4g, %.4g), between keys %d and %d: move them or add a key that goes around",
                         opt->path, t, (int)floor((t - p->keys[0].time) * fps), (double)pts[3 * i],
                         (double)pts[3 * i + 1], (double)pts[3 * i + 2], key, key + 1 < p->count ? key + 1 : key);
        }
    scene_free(&s);
    free(pts);
    free(d);
    return ok;
}

bool flight_render(const cli_options *opt, err_t *err)
{
    path p;
    if (!path_load(opt->path, &p, err))
        return false;
    int fps = opt->fps ? opt->fps : DEFAULT_FPS;
    int last_frame = (int)floor(path_duration(&p) * fps + 1e-9);
    int first = opt->has_frames ? opt->frame_first : 0, last = opt->has_frames ? opt->frame_last : last_frame;
    bool ok = true;
    if (first > last_frame)
        ok = err_set(err, "--frames %d-%d: the path '%s' ends at frame %d (%.3f s at %d frames a second)", first, last,
                     opt->path, last_frame, path_duration(&p), fps);
    if (ok && last > last_frame) { /* a farm's last chunk may reach past the end: render what there is */
        if (!opt->quiet)
            fprintf(stderr, "frames %d-%d: the path ends at frame %d; rendering %d-%d\n", first, last, last_frame, first,
                    last_frame);
        last = last_frame;
    }
    /* the scene and the output folder are checked before the GPU opens */
    scene s;
    const char *sets[CLI_MAX_SETS + PATH_MAX_PARAMS + 1];
    char track[PATH_MAX_PARAMS][PATH_PARAM_NAME + 32];
    char name[PATH_MAX_LEN];
    int nsets;
    path_sample smp;
    path_eval(&p, p.keys[0].time, &smp);
    if (ok && (ok = frame_scene(opt, &p, &smp, &s, sets, &nsets, track, err)))
        scene_free(&s);
    ok = ok && path_frame_name(opt->output, first, name, sizeof name, err) && image_can_write(name, err);
    if (!ok || !gpu_open(&(gpu_desc){.headless = true}, err)) {
        path_free(&p);
        return false;
    }
    ok = render_init(err) && check_clearance(opt, &p, first, last, fps, err);
    int rendered = 0, skipped = 0;
    bool loaded = false; /* s holds the scene for every frame */
    double t0 = util_now();
    for (int f = first; ok && f <= last; f++) {
        if (!(ok = path_frame_name(opt->output, f, name, sizeof name, err)))
            break;
        if (exists(name)) {
            skipped++;
            if (!opt->quiet)
                fprintf(stderr, "frame %d: %s is there, skipped\n", f, name);
            continue;
        }
        double t = p.keys[0].time + (double)f / fps;
        path_eval(&p, t, &smp);
        /* a path without parameter tracks keeps one scene (and its textures on the GPU) */
        if (!loaded && !(ok = frame_scene(opt, &p, &smp, &s, sets, &nsets, track, err)))
            break;
        loaded = p.param_count == 0;
        camera cam = {.position = {(float)smp.position[0], (float)smp.position[1], (float)smp.position[2]},
                      .yaw = (float)smp.yaw,
                      .pitch = (float)smp.pitch,
                      .fov_y = (float)(smp.fov_deg * 3.14159265358979323846 / 180.0)};
        offline_desc d = {.scene = &s,
                          .cam = cam,
                          .width = opt->width ? opt->width : DEFAULT_WIDTH,
                          .height = opt->height ? opt->height : DEFAULT_HEIGHT,
                          .spp = s.quality.spp,
                          .output = name,
                          .aovs = opt->aovs,
                          .strip_rows = opt->strip_rows,
                          .quiet = true};
        strbuf description = {0};
        shot_describe(s.path, sets, nsets, &d.cam, d.width, d.height, &description);
        d.description = description.data;
        double tf = util_now();
        ok = image_can_write(name, err) && offline_render_current(&d, err);
        sb_free(&description);
        if (!loaded)
            scene_free(&s);
        if (ok) {
            rendered++;
            if (!opt->quiet)
                fprintf(stderr, "frame %d (t = %.3f s): %s, %.2f s\n", f, t, name, util_now() - tf);
        }
    }
    if (loaded)
        scene_free(&s);
    double secs = util_now() - t0;
    if (ok && !opt->quiet)
        fprintf(stderr, "flight %s: %d frames rendered, %d skipped (already there), %.1f s: %.1f frames a minute (%s)\n",
                opt->path, rendered, skipped, secs, rendered ? 60.0 * rendered / secs : 0.0, gpu_describe());
    render_shutdown();
    gpu_close();
    path_free(&p);
    return ok;
}
