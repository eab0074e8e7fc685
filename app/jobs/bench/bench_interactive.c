/* bench --interactive: what flying the window costs and looks like. A scripted flight of FLIGHT_FRAMES
 * frames (a dolly toward the scene's look-at point while turning) at the --size window, each frame one
 * sample at the internal resolution the window's controller (app/view/resolution.h) picks for --fps; then
 * the camera stops and the window's still path runs (full size). Reports the median and p95 frame time,
 * the median internal size, the error of moving frames (stretched as the window shows them) against
 * the full-size frame of the same camera, and the time from stopping to the first full-size frame and
 * to the preset's spp, every pixel and adaptively. Two measurements of what the window does not do:
 * depth-aware upsampling, and reprojection (the last shown image carried to the new camera by depth
 * and blended with the new frame; FATHOM_BENCH_JITTER=1 gives each moving frame a new sub-pixel point
 * so the history can gather detail). */
#include "jobs/bench/bench.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/aov.h"
#include "view/camera.h"
#include "gpu/gpu.h"
#include "data/media/image_io.h"
#include "jobs/bench/metrics.h"
#include "gpu/render.h"
#include "view/resolution.h"
#include "scene/scene.h"

enum { FLIGHT_FRAMES = 100, ERROR_EVERY = 10, DEFAULT_FPS = 30 };
static const float DOLLY = 0.35f;     /* of the way to the look-at point */
static const float TURN_DEG = 25.0f;  /* yaw over the flight */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static camera flight_camera(const scene *s, int frame)
{
    double f = (double)frame / (FLIGHT_FRAMES - 1), eye[3];
    for (int i = 0; i < 3; i++)
        eye[i] = s->cam_position[i] + DOLLY * f * (s->cam_look_at[i] - s->cam_position[i]);
    camera c = scene_camera(s, eye, s->cam_look_at, s->cam_fov_deg);
    c.yaw += glm_rad(TURN_DEG) * (float)f;
    return c;
}

/* Reprojection, measured (not in the window): the last shown image, carried to the new camera by the
 * depth of each pixel, blended with the new stretched frame (80 % history where the depths agree).
 * full-resolution history rgba8 + depth (along the unit ray; INFINITY: sky), from camera `prev`. */
typedef struct history {
    uint8_t *rgba;
    float *depth;
    camera cam;
    bool valid;
} history;

enum { HISTORY_WEIGHT_PERCENT = 80 };

/* Pixel (x, y) (row 0 at the top) of a w × h image: its unit ray. */
static void pixel_dir(const camera *c, const camera_basis *b, int x, int y, int w, int h, float d[3])
{
    float t = tanf(0.5f * c->fov_y), sx = (2.0f * ((float)x + 0.5f) / (float)w - 1.0f) * t * (float)w / (float)h;
    float sy = (2.0f * ((float)(h - 1 - y) + 0.5f) / (float)h - 1.0f) * t, len = 0;
    for (int i = 0; i < 3; i++) {
        d[i] = b->forward[i] + sx * b->right[i] + sy * b->up[i];
        len += d[i] * d[i];
    }
    for (int i = 0; i < 3; i++)
        d[i] /= sqrtf(len);
}

/* Blends `now` (the stretched frame, depth from the low-resolution AOVs) with the history carried to
 * `cam`; writes the result to out and makes it the history. */
static void reproject(history *hs, const camera *cam, const uint8_t *now, const float *aov, int iw, int ih, int w,
                      int h, uint8_t *out, float *depth_now)
{
    camera_basis b = camera_get_basis(cam), pb = camera_get_basis(&hs->cam);
    float pt = tanf(0.5f * hs->cam.fov_y), aspect = (float)w / (float)h;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            /* the nearest low-resolution texel's depth (AOV rows top first) */
            int ax = x * iw / w, ay = y * ih / h;
            float z = aov[((size_t)ay * (size_t)iw + (size_t)ax) * AOV_FLOATS + AOV_SLOT_DEPTH];
            depth_now[i] = z;
            memcpy(out + 4 * i, now + 4 * i, 4);
            if (!hs->valid)
                continue;
            float d[3], v[3];
            pixel_dir(cam, &b, x, y, w, h, d);
            bool sky = isinf(z);
            for (int k = 0; k < 3; k++) /* the point seen, relative to the old camera (sky: a direction) */
                v[k] = sky ? d[k] : (float)(cam->position[k] - hs->cam.position[k]) + d[k] * z;
            float zf = glm_vec3_dot(v, pb.forward);
            if (zf <= 0)
                continue;
            float sx = glm_vec3_dot(v, pb.right) / (zf * pt * aspect), sy = glm_vec3_dot(v, pb.up) / (zf * pt);
            int px = (int)floorf((sx + 1) * 0.5f * (float)w), py = h - 1 - (int)floorf((sy + 1) * 0.5f * (float)h);
            if (px < 0 || py < 0 || px >= w || py >= h)
                continue;
            size_t j = (size_t)py * (size_t)w + (size_t)px;
            float zh = hs->depth[j], dist = sky ? INFINITY : glm_vec3_norm(v);
            bool same = sky ? isinf(zh) : !isinf(zh) && fabsf(zh - dist) < 0.05f * dist;
            if (!same)
                continue; /* disoccluded: only the new frame */
            for (int c = 0; c < 3; c++)
                out[4 * i + (size_t)c] = (uint8_t)((HISTORY_WEIGHT_PERCENT * hs->rgba[4 * j + (size_t)c] +
                                                    (100 - HISTORY_WEIGHT_PERCENT) * now[4 * i + (size_t)c] + 50) / 100);
        }
    memcpy(hs->rgba, out, (size_t)w * (size_t)h * 4);
    memcpy(hs->depth, depth_now, sizeof(float) * (size_t)w * (size_t)h);
    hs->cam = *cam;
    hs->valid = true;
}

static double one_sample(void)
{
    glFinish();
    double t0 = util_now();
    render_sample();
    glFinish();
    return (util_now() - t0) * 1000.0;
}

/* --out DIR: what the window shows, as DIR/SCENE-WHAT.png (RGBA8 → RGB). */
static bool save(const bench_desc *opt, const scene *s, const char *what, uint8_t *rgba, int w, int h, err_t *err)
{
    if (!opt->out)
        return true;
    char path[PATH_MAX_LEN];
    snprintf(path, sizeof path, "%s/%s-%s.png", opt->out, s->name, what);
    for (size_t i = 0, n = (size_t)w * (size_t)h; i < n; i++)
        memmove(rgba + i * 3, rgba + i * 4, 3);
    return image_write_u8(path, w, h, 3, rgba, err);
}

/* RMSE (0..1) between two sRGB8 RGBA images. */
static double rmse(const uint8_t *a, const uint8_t *b, size_t pixels)
{
    double sum = 0;
    for (size_t i = 0; i < pixels; i++)
        for (int c = 0; c < 3; c++) {
            double d = (a[i * 4 + (size_t)c] - b[i * 4 + (size_t)c]) / 255.0;
            sum += d * d;
        }
    return sqrt(sum / (3.0 * (double)pixels));
}

/* One run of the bench: the flight's buffers and what it measured. */
typedef struct interactive_run {
    const bench_desc *opt;
    const scene *s;
    int w, h, fps;
    size_t n; /* pixels of the window */
    bool jittered;
    res_controller res;
    double ms[FLIGHT_FRAMES], side[FLIGHT_FRAMES];
    double err_sum, err_max, edge_sum, edge_max, reproj_sum, reproj_max, reproj_ms;
    int err_n;
    uint8_t *moving, *full, *edge, *shown, *reproj, *one, *adapt; /* RGBA8 images of the window's size */
    history hs;
    float *depth_now, *aov;
    double first_ms, spp_ms, adaptive_ms, adaptive_rmse, one_rmse, kept;
} interactive_run;

/* What the window shows after frame `cam` (moving, bilinear and depth-aware, and reprojected) against
 * the full-size frame of the same camera. */
static void compare_moving(interactive_run *R, const camera *cam)
{
    render_set_edge_aware(false);
    render_read_stretched_srgb8(R->moving, R->w, R->h, 1.0f);
    render_set_edge_aware(true);
    render_read_stretched_srgb8(R->edge, R->w, R->h, 1.0f);
    render_set_active(R->w, R->h);
    render_begin(cam);
    render_sample();
    render_read_stretched_srgb8(R->full, R->w, R->h, 1.0f);
    double e = rmse(R->moving, R->full, R->n), ee = rmse(R->edge, R->full, R->n), er = rmse(R->reproj, R->full, R->n);
    R->err_sum += e, R->err_max = fmax(R->err_max, e), R->err_n++;
    R->edge_sum += ee, R->edge_max = fmax(R->edge_max, ee);
    R->reproj_sum += er, R->reproj_max = fmax(R->reproj_max, er);
}

/* The scripted flight: each frame one sample at the controller's internal size. */
static void fly(interactive_run *R)
{
    for (int f = 0; f < FLIGHT_FRAMES; f++) {
        camera cam = flight_camera(R->s, f);
        int iw = res_side(R->w, R->res.scale), ih = res_side(R->h, R->res.scale);
        render_set_active(iw, ih);
        render_begin(&cam);
        if (R->jittered)
            render_set_first_jitter(1 + f % 16); /* a new sub-pixel point each frame, for the history */
        R->ms[f] = one_sample();
        render_set_first_jitter(0);
        R->side[f] = (double)ih / R->h;
        res_update(&R->res, R->ms[f], (double)iw * ih, (double)R->n);
        /* reprojection of what was shown, as a measurement: its CPU time is not a GPU's */
        render_read_stretched_srgb8(R->shown, R->w, R->h, 1.0f);
        render_read_aovs(R->aov);
        double t0 = util_now();
        reproject(&R->hs, &cam, R->shown, R->aov, iw, ih, R->w, R->h, R->reproj, R->depth_now);
        R->reproj_ms += (util_now() - t0) * 1000.0;
        if (f % ERROR_EVERY == ERROR_EVERY - 1)
            compare_moving(R, &cam);
        if (!R->opt->quiet)
            fprintf(stderr, "\rbench --interactive %s: frame %d/%d", R->s->name, f + 1, FLIGHT_FRAMES);
    }
}

/* The camera stops: the window's still path, every pixel sampled to the preset's spp, then with
 * adaptive sampling as the window does it (further samples only on the edge mask). */
static bool stop(interactive_run *R, err_t *err)
{
    bool ok = true;
    for (int pass = 0; ok && pass < 2; pass++) {
        render_set_active(R->w, R->h);
        render_set_adaptive(pass == 1);
        camera cam = flight_camera(R->s, FLIGHT_FRAMES - 1);
        render_begin(&cam);
        double t0 = util_now();
        for (int i = 0; i < R->s->quality.spp; i++) {
            one_sample();
            if (i == 0 && pass == 0) {
                R->first_ms = (util_now() - t0) * 1000.0;
                double t1 = util_now();
                render_read_stretched_srgb8(R->one, R->w, R->h, 1.0f);
                t0 += util_now() - t1; /* the readback is the bench's, not the window's */
            }
        }
        *(pass ? &R->adaptive_ms : &R->spp_ms) = (util_now() - t0) * 1000.0;
        render_read_stretched_srgb8(pass ? R->adapt : R->full, R->w, R->h, 1.0f);
        if (pass) {
            R->kept = (double)render_adaptive_pixels() / (double)R->n;
            R->adaptive_rmse = rmse(R->adapt, R->full, R->n);
            R->one_rmse = rmse(R->one, R->full, R->n);
        }
        render_set_adaptive(false);
        ok = glGetError() == GL_NO_ERROR || err_set(err, "GL error during the flight");
    }
    return ok;
}

static void report(const interactive_run *R)
{
    const scene *s = R->s;
    int w = R->w, h = R->h;
    double sorted[FLIGHT_FRAMES], sides[FLIGHT_FRAMES];
    memcpy(sorted, R->ms, sizeof sorted);
    memcpy(sides, R->side, sizeof sides);
    qsort(sorted, FLIGHT_FRAMES, sizeof *sorted, cmp_double);
    qsort(sides, FLIGHT_FRAMES, sizeof *sides, cmp_double);
    double med = sorted[FLIGHT_FRAMES / 2], p95 = sorted[FLIGHT_FRAMES * 95 / 100];
    int mw = res_side(w, (float)sides[FLIGHT_FRAMES / 2]), mh = res_side(h, (float)sides[FLIGHT_FRAMES / 2]);
    double err_mean = R->err_n ? R->err_sum / R->err_n : 0.0, edge_mean = R->err_n ? R->edge_sum / R->err_n : 0.0;
    double reproj_mean = R->err_n ? R->reproj_sum / R->err_n : 0.0;
    if (!R->opt->quiet)
        fputc('\n', stderr);
    printf("%s, window %dx%d, target %d fps, %s\n", s->name, w, h, R->fps, gpu_describe());
    printf("  moving (%d frames): median %.1f ms (%.1f fps), p95 %.1f ms; median inside %dx%d; "
           "error vs full size RMSE %.4f mean, %.4f worst bilinear; %.4f, %.4f depth-aware\n",
           FLIGHT_FRAMES, med, 1000.0 / med, p95, mw, mh, err_mean, R->err_max, edge_mean, R->edge_max);
    printf("  reprojection (measured here, not in the window): %d %% history carried by depth, RMSE %.4f mean, "
           "%.4f worst (%.0f ms a frame on the CPU)\n", HISTORY_WEIGHT_PERCENT, reproj_mean, R->reproj_max,
           R->reproj_ms / FLIGHT_FRAMES);
    printf("  stopped: first full-size frame after %.0f ms, the preset's %d spp after %.0f ms; adaptive (%.1f %% of "
           "pixels on edges) after %.0f ms, RMSE %.4f to every pixel's %d spp (1 spp: %.4f)\n", R->first_ms,
           s->quality.spp, R->spp_ms, 100 * R->kept, R->adaptive_ms, R->adaptive_rmse, s->quality.spp, R->one_rmse);
    printf("csv,%s,%d,%d,%d,%.2f,%.2f,%d,%d,%.5f,%.5f,%.0f,%d,%.0f,%.4f,%.0f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f\n", s->name,
           w, h, R->fps, med, p95, mw, mh, err_mean, R->err_max, R->first_ms, s->quality.spp, R->spp_ms, R->kept,
           R->adaptive_ms, R->adaptive_rmse, R->one_rmse, edge_mean, R->edge_max, reproj_mean, R->reproj_max);
}

static void run_free(interactive_run *R)
{
    uint8_t *images[] = {R->moving, R->full, R->edge, R->shown, R->reproj, R->one, R->adapt, R->hs.rgba};
    for (size_t i = 0; i < sizeof images / sizeof images[0]; i++)
        free(images[i]);
    free(R->hs.depth);
    free(R->depth_now);
    free(R->aov);
}

bool bench_interactive(const bench_desc *opt, int w, int h, err_t *err)
{
    scene s;
    if (!scene_load(opt->scene, opt->sets, opt->set_count, &s, err))
        return false;
    if (!gpu_open(&(gpu_desc){.headless = true}, err)) {
        scene_free(&s);
        return false;
    }
    static interactive_run R; /* big: the frame times */
    size_t n = (size_t)w * (size_t)h;
    R = (interactive_run){.opt = opt, .s = &s, .w = w, .h = h, .n = n, .fps = opt->fps ? opt->fps : DEFAULT_FPS,
                          .jittered = getenv("FATHOM_BENCH_JITTER") != NULL};
    R.res = res_init((float)R.fps, RES_MIN_SCALE);
    uint8_t **images[] = {&R.moving, &R.full, &R.edge, &R.shown, &R.reproj, &R.one, &R.adapt, &R.hs.rgba};
    for (size_t i = 0; i < sizeof images / sizeof images[0]; i++)
        *images[i] = util_alloc(n * 4, "a bench image");
    R.hs.depth = util_alloc(sizeof(float) * n, "the history");
    R.depth_now = util_alloc(sizeof(float) * n, "a depth image");
    R.aov = util_alloc(sizeof(float) * n * AOV_FLOATS, "the AOVs");
    bool ok = render_init(err) && render_set_scene(&s, NULL, err);
    if (ok) {
        render_resize(w, h);
        fly(&R);
        ok = stop(&R, err);
    }
    /* the last moving frame as the window showed it, and the converged one */
    if (ok && opt->out)
        ok = save(opt, &s, "still", R.adapt, w, h, err) && save(opt, &s, "moving", R.moving, w, h, err);
    if (ok)
        report(&R);
    run_free(&R);
    render_shutdown();
    gpu_close();
    scene_free(&s);
    return ok;
}
