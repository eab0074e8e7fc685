/* flight — see flight.h. */
#include "jobs/capture/flight.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gpu/gpu.h"
#include "data/media/image_io.h"
#include "jobs/capture/flight_video.h"
#include "jobs/capture/offline.h"
#include "view/path.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "scene/formula/frag.h"
#include "scene/scene.h"
#include "view/shot.h"

enum { DEFAULT_FPS = 30 };

static bool exists(const char *file)
{
    struct stat st;
    return stat(file, &st) == 0 && S_ISREG(st.st_mode);
}

/* A frame on disk counts as done only if it decodes whole and is fathom's (it carries a shot record):
 * an empty or cut file, or someone else's image of that name, is rendered again. */
static bool frame_done(const char *file)
{
    char *text = NULL;
    err_t e;
    int w, h, c;
    float *px = NULL;
    bool ok = exists(file) && image_read_text(file, SHOT_KEY, &text, &e) &&
              image_read_f32(file, 0, IMAGE_MAX_SIDE, &w, &h, &c, &px, &e);
    free(text);
    free(px);
    return ok;
}

/* The scene for one frame: the command line's overrides, then the path's parameter tracks. */
static bool frame_scene(const flight_desc *opt, const path *p, const path_sample *smp, scene *s, const char **sets,
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

/* Whether a point float cannot tell from the surface is clear in double (a deep zoom's frames render
 * in double): the distance there, probed relative to the point itself, above a double's resolution. */
static bool clear_in_double(scene *deep, const double p[3], err_t *err, bool *clear)
{
    float zero[3] = {0, 0, 0}, d[2];
    render_set_origin(p);
    bool ok = render_probe(deep, NULL, zero, 1, d, err);
    render_set_origin((double[3]){0, 0, 0});
    *clear = ok && d[0] > 0 && (double)d[0] > 8 * DBL_EPSILON * (1 + fabs(p[0]) + fabs(p[1]) + fabs(p[2]));
    return ok;
}

/* The camera must never enter a solid (or a fractal's set): map() along the path, at 4 points a
 * frame, in the first frame's scene. A path that dips inside is refused with where and when. Inside: a
 * negative distance, or (a fractal's estimate, which need not turn negative in its set) one below
 * float resolution at that point, unless the formula compiles in double (a deep zoom) and the point
 * is clear there. */
static bool check_clearance(const flight_desc *opt, const path *p, int first, int last, int fps, err_t *err)
{
    enum { PER_FRAME = 4, MAX_POINTS = 1 << 17 };
    long long want = (long long)(last - first) * PER_FRAME + 1;
    int n = want > MAX_POINTS ? MAX_POINTS : (int)want;
    double t0 = p->keys[0].time + (double)first / fps, t1 = p->keys[0].time + (double)last / fps;
    float *pts = util_alloc(sizeof(float) * 3 * (size_t)n, "path clearance"), *d = util_alloc(sizeof(float) * 2 * (size_t)n, "path clearance");
    double *at = util_alloc(sizeof(double) * 3 * (size_t)n, "path clearance");
    for (int i = 0; i < n; i++) {
        path_sample smp;
        path_eval(p, n > 1 ? t0 + (t1 - t0) * i / (n - 1) : t0, &smp);
        for (int k = 0; k < 3; k++)
            pts[3 * i + k] = (float)(at[3 * i + k] = smp.position[k]);
    }
    scene s = {0};
    const char *sets[CLI_MAX_SETS + PATH_MAX_PARAMS + 1];
    char track[PATH_MAX_PARAMS][PATH_PARAM_NAME + 32];
    int nsets;
    path_sample smp;
    path_eval(p, t0, &smp);
    bool ok = frame_scene(opt, p, &smp, &s, sets, &nsets, track, err) && render_set_scene(&s, NULL, err) &&
              render_probe(&s, NULL, pts, n, d, err);
    scene deep = s;
    deep.fractal.deep_now = true;
    bool can_deep = s.program == PROGRAM_FRACTAL && s.fractal.deep_ok && render_has_fp64(), deep_set = false;
    for (int i = 0; ok && i < n; i++) {
        const double *q = at + 3 * i;
        bool clear = d[2 * i] >= 0 && d[2 * i] >= PRECISION_REL * (1 + fabs(q[0]) + fabs(q[1]) + fabs(q[2]));
        if (!clear && d[2 * i] >= 0 && can_deep && (deep_set || (deep_set = render_set_scene(&deep, NULL, err))))
            ok = clear_in_double(&deep, q, err, &clear);
        if (ok && !clear) {
            double t = n > 1 ? t0 + (t1 - t0) * i / (n - 1) : t0;
            int key = 0;
            while (key + 1 < p->count && p->keys[key + 1].time <= t)
                key++;
            ok = err_set(err, "path '%s': at t = %.3f s (frame %d) the camera is inside the scene's surface at (%.17g, "
                              "%.17g, %.17g), between keys %d and %d: move them or add a key that goes around",
                         opt->path, t, (int)floor((t - p->keys[0].time) * fps), q[0], q[1], q[2], key,
                         key + 1 < p->count ? key + 1 : key);
        }
    }
    scene_free(&s);
    free(pts);
    free(d);
    free(at);
    return ok;
}

/* The frames to render, [*first, *last]: --frames or the whole path; a range reaching past the end is
 * cut there (a farm's last chunk), one starting past it is refused. */
static bool frame_range(const flight_desc *opt, const path *p, int fps, int *first, int *last, err_t *err)
{
    int last_frame = (int)floor(path_duration(p) * fps + 1e-9);
    *first = opt->has_frames ? opt->frame_first : 0;
    *last = opt->has_frames ? opt->frame_last : last_frame;
    if (*first > last_frame)
        return err_set(err, "--frames %d-%d: the path '%s' ends at frame %d (%.3f s at %d frames a second)", *first,
                       *last, opt->path, last_frame, path_duration(p), fps);
    if (*last > last_frame) { /* a farm's last chunk may reach past the end: render what there is */
        if (!opt->shot.quiet)
            fprintf(stderr, "frames %d-%d: the path ends at frame %d; rendering %d-%d\n", *first, *last, last_frame,
                    *first, last_frame);
        *last = last_frame;
    }
    return true;
}

typedef struct flight_state {
    const flight_desc *opt;
    const path *p;
    const char *video; /* the frames' pattern of a video, else "" */
    int fps, rendered, skipped;
    bool loaded; /* s holds the scene for every frame (a path without parameter tracks) */
    scene s;
    const char *sets[CLI_MAX_SETS + PATH_MAX_PARAMS + 1];
    char track[PATH_MAX_PARAMS][PATH_PARAM_NAME + 32];
    int nsets;
} flight_state;

/* Frame f to its file, unless a file is there already (resume). */
static bool render_frame(flight_state *F, int f, err_t *err)
{
    const flight_desc *opt = F->opt;
    char name[PATH_MAX_LEN];
    if (!path_frame_name(opt->output, f, name, sizeof name, err))
        return false;
    bool video = F->video[0] != '\0'; /* the frames of a video: fathom's folder, fathom's frames only */
    /* a video's frame is fathom's by the manifest before any decoder reads it */
    if ((!video || flight_video_frame_trusted(F->video, f, name)) && frame_done(name)) {
        F->skipped++;
        if (!opt->shot.quiet)
            fprintf(stderr, "frame %d: %s is there, skipped\n", f, name);
        return true;
    }
    if (exists(name) && !opt->shot.quiet)
        fprintf(stderr, "frame %d: %s does not decode or is not fathom's: rendered again\n", f, name);
    double t = F->p->keys[0].time + (double)f / F->fps;
    path_sample smp;
    path_eval(F->p, t, &smp);
    /* a path without parameter tracks keeps one scene (and its textures on the GPU) */
    if (!F->loaded && !frame_scene(opt, F->p, &smp, &F->s, F->sets, &F->nsets, F->track, err))
        return false;
    F->loaded = F->p->param_count == 0;
    /* the position in double (a deep zoom's digits); the lens is the scene's at this frame ("set" may
     * track camera.focus: a rack focus) */
    camera cam = {.position = {smp.position[0], smp.position[1], smp.position[2]},
                  .yaw = (float)smp.yaw,
                  .pitch = (float)smp.pitch,
                  .roll = (float)smp.roll,
                  .fov_y = (float)(smp.fov_deg * 3.14159265358979323846 / 180.0),
                  .lens = scene_lens(&F->s)};
    strbuf description = {0};
    offline_desc d = offline_shot(opt->shot, &F->s, cam, name, F->sets, F->nsets, &description);
    d.quiet = true;
    double tf = util_now();
    bool ok = image_can_write(name, err) && offline_render_current(&d, err);
    sb_free(&description);
    if (!F->loaded)
        scene_free(&F->s);
    ok = ok && (!video || flight_video_frame_record(F->video, f, name, err));
    if (ok) {
        F->rendered++;
        if (!opt->shot.quiet)
            fprintf(stderr, "frame %d (t = %.3f s): %s, %.2f s\n", f, t, name, util_now() - tf);
    }
    return ok;
}

/* A video output: the frames go to its folder (flight_video.h); an empty folder is taken back on failure. */
static bool frames_of_video(const flight_desc **opt, flight_desc *framed, char *pattern, size_t n, video_options *vo,
                            err_t *err)
{
    if (!video_is_file((*opt)->output))
        return true;
    if (!flight_video_prepare((*opt)->output, (*opt)->video, pattern, n, vo, err))
        return false;
    int w = (*opt)->shot.width, h = (*opt)->shot.height;
    if (!vo->yuv444 && (w % 2 || h % 2)) /* before the first frame, not after the last */
        return err_set(err, "--output %s: yuv420p needs an even width and height (this is %dx%d): change --size, or "
                            "--video pix_fmt=yuv444p", (*opt)->output, w, h);
    *framed = **opt;
    framed->output = pattern;
    *opt = framed;
    return true;
}

static void drop_empty_folder(const char *pattern)
{
    char folder[PATH_MAX_LEN];
    if (pattern[0] && util_dirname(pattern, folder, sizeof folder))
        rmdir(folder); /* only when empty: nothing rendered yet */
}

/* The flight: the path file, or a fragment's KeyFrame presets over FragM's default length (frag.h). */
static bool load_flight(const char *file, path *p, err_t *err)
{
    enum { FRAGM_SECONDS = 10 }; /* FragM's default animation length (its settings' timeMax) */
    if (!frag_is_fragment(file))
        return path_load(file, p, err);
    strbuf text = {0};
    bool ok = frag_keyframes_flight(file, FRAGM_SECONDS, &text, err) && path_parse(text.data, file, p, err);
    sb_free(&text);
    return ok;
}

bool flight_render(const flight_desc *opt, err_t *err)
{
    path p;
    static flight_desc framed;
    char pattern[PATH_MAX_LEN] = "";
    const char *video = opt->output;
    video_options vo;
    if (!frames_of_video(&opt, &framed, pattern, sizeof pattern, &vo, err) || !load_flight(opt->path, &p, err)) {
        drop_empty_folder(pattern);
        return false;
    }
    static flight_state F; /* big: the overrides' text */
    F = (flight_state){.opt = opt, .p = &p, .video = pattern, .fps = opt->fps ? opt->fps : DEFAULT_FPS};
    int first, last;
    bool ok = frame_range(opt, &p, F.fps, &first, &last, err);
    /* the scene and the output folder are checked before the GPU opens */
    char name[PATH_MAX_LEN];
    path_sample smp;
    path_eval(&p, p.keys[0].time, &smp);
    camera_lens lens = {0};
    if (ok && (ok = frame_scene(opt, &p, &smp, &F.s, F.sets, &F.nsets, F.track, err))) {
        lens = scene_lens(&F.s);
        scene_free(&F.s);
    }
    ok = ok && path_frame_name(opt->output, first, name, sizeof name, err) && image_can_write(name, err);
    if (!ok || !gpu_open(&(gpu_desc){.headless = true}, err)) {
        drop_empty_folder(pattern);
        path_free(&p);
        return false;
    }
    ok = render_init(err) && check_clearance(opt, &p, first, last, F.fps, err);
    int stale = util_remove_stale_temps(name); /* what a killed run left half-written */
    if (stale && !opt->shot.quiet)
        fprintf(stderr, "removed %d temporary file%s a killed run left\n", stale, stale > 1 ? "s" : "");
    double t0 = util_now();
    for (int f = first; ok && f <= last; f++)
        ok = render_frame(&F, f, err);
    if (F.loaded)
        scene_free(&F.s);
    double secs = util_now() - t0;
    if (ok && !opt->shot.quiet)
        fprintf(stderr, "flight %s: %d frames rendered, %d skipped (already there), %.1f s: %.1f frames a minute (%s)\n",
                opt->path, F.rendered, F.skipped, secs, F.rendered ? 60.0 * F.rendered / secs : 0.0, gpu_describe());
    render_shutdown();
    gpu_close();
    if (!ok && pattern[0])
        drop_empty_folder(pattern);
    if (ok && pattern[0]) {
        video_view view = {.equirectangular = lens.projection == PROJECTION_EQUIRECTANGULAR, .stereo = (int)lens.stereo};
        ok = flight_video_assemble(video, pattern, (int)floor(path_duration(&p) * F.fps + 1e-9), F.fps, &vo, &view,
                                   opt->shot.quiet, err);
    }
    path_free(&p);
    return ok;
}
