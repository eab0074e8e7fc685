/* bench --interactive: what flying the window costs and looks like. A scripted flight of FLIGHT_FRAMES
 * frames (a dolly toward the scene's look-at point while turning) at the --size window, each frame one
 * sample at the internal resolution the window's controller (app/resolution.h) picks for --fps; then
 * the camera stops and the window's still path runs (full size). Reports the median and p95 frame time,
 * the median internal size, the error of moving frames (stretched as the window shows them) against
 * the full-size frame of the same camera, and the time from stopping to the first full-size frame and
 * to the preset's spp. */
#include "bench.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "gpu.h"
#include "image_io.h"
#include "metrics.h"
#include "render.h"
#include "resolution.h"
#include "scene.h"

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
    float f = (float)frame / (FLIGHT_FRAMES - 1), eye[3];
    for (int i = 0; i < 3; i++)
        eye[i] = s->cam_position[i] + DOLLY * f * (s->cam_look_at[i] - s->cam_position[i]);
    camera c = camera_look_at_deg(eye, s->cam_look_at, s->cam_fov_deg);
    c.yaw += glm_rad(TURN_DEG) * f;
    return c;
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
static bool save(const cli_options *opt, const scene *s, const char *what, uint8_t *rgba, int w, int h, err_t *err)
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

bool bench_interactive(const cli_options *opt, int w, int h, err_t *err)
{
    scene s;
    if (!scene_load(opt->scene, opt->sets, opt->set_count, &s, err))
        return false;
    if (!gpu_open(&(gpu_desc){.headless = true}, err)) {
        scene_free(&s);
        return false;
    }
    bool ok = render_init(err) && render_set_scene(&s, NULL, err);
    int fps = opt->fps ? opt->fps : DEFAULT_FPS;
    res_controller res = res_init((float)fps, RES_MIN_SCALE);
    double ms[FLIGHT_FRAMES], side[FLIGHT_FRAMES], err_sum = 0, err_max = 0;
    int err_n = 0;
    size_t n = (size_t)w * (size_t)h;
    uint8_t *moving = util_alloc(n * 4, "a bench image"), *full = util_alloc(n * 4, "a bench image");
    uint8_t *edge = util_alloc(n * 4, "a bench image");
    double edge_sum = 0, edge_max = 0;
    if (ok)
        render_resize(w, h);
    for (int f = 0; ok && f < FLIGHT_FRAMES; f++) {
        camera cam = flight_camera(&s, f);
        int iw = res_side(w, res.scale), ih = res_side(h, res.scale);
        render_set_active(iw, ih);
        render_begin(&cam);
        ms[f] = one_sample();
        side[f] = (double)ih / h;
        res_update(&res, ms[f], (double)iw * ih, (double)n);
        if (f % ERROR_EVERY == ERROR_EVERY - 1) { /* what the window shows against the full-size frame */
            render_set_edge_aware(false);
            render_read_stretched_srgb8(moving, w, h, 1.0f);
            render_set_edge_aware(true);
            render_read_stretched_srgb8(edge, w, h, 1.0f);
            render_set_active(w, h);
            render_begin(&cam);
            render_sample();
            render_read_stretched_srgb8(full, w, h, 1.0f);
            double e = rmse(moving, full, n), ee = rmse(edge, full, n);
            err_sum += e, err_max = fmax(err_max, e), err_n++;
            edge_sum += ee, edge_max = fmax(edge_max, ee);
        }
        if (!opt->quiet)
            fprintf(stderr, "\rbench --interactive %s: frame %d/%d", s.name, f + 1, FLIGHT_FRAMES);
    }
    /* the camera stops: the window's still path, every pixel sampled to the preset's spp, then with
     * adaptive sampling as the window does it (further samples only on the edge mask) */
    double first_ms = 0, spp_ms = 0, adaptive_ms = 0, adaptive_rmse = 0, one_rmse = 0, kept = 0;
    uint8_t *one = util_alloc(n * 4, "a bench image"), *adapt = util_alloc(n * 4, "a bench image");
    for (int pass = 0; ok && pass < 2; pass++) {
        render_set_active(w, h);
        render_set_adaptive(pass == 1);
        camera cam = flight_camera(&s, FLIGHT_FRAMES - 1);
        render_begin(&cam);
        double t0 = util_now();
        for (int i = 0; i < s.quality.spp; i++) {
            one_sample();
            if (i == 0 && pass == 0) {
                first_ms = (util_now() - t0) * 1000.0;
                double t1 = util_now();
                render_read_stretched_srgb8(one, w, h, 1.0f);
                t0 += util_now() - t1; /* the readback is the bench's, not the window's */
            }
        }
        *(pass ? &adaptive_ms : &spp_ms) = (util_now() - t0) * 1000.0;
        render_read_stretched_srgb8(pass ? adapt : full, w, h, 1.0f);
        if (pass) {
            kept = (double)render_adaptive_pixels() / (double)n;
            adaptive_rmse = rmse(adapt, full, n);
            one_rmse = rmse(one, full, n);
        }
        render_set_adaptive(false);
        ok = glGetError() == GL_NO_ERROR || err_set(err, "GL error during the flight");
    }
    /* the last moving frame as the window showed it, and the converged one */
    if (ok && opt->out)
        ok = save(opt, &s, "still", adapt, w, h, err) && save(opt, &s, "moving", edge, w, h, err);
    free(one);
    free(adapt);
    if (ok) {
        double sorted[FLIGHT_FRAMES], sides[FLIGHT_FRAMES];
        memcpy(sorted, ms, sizeof sorted);
        memcpy(sides, side, sizeof sides);
        qsort(sorted, FLIGHT_FRAMES, sizeof *sorted, cmp_double);
        qsort(sides, FLIGHT_FRAMES, sizeof *sides, cmp_double);
        double med = sorted[FLIGHT_FRAMES / 2], p95 = sorted[FLIGHT_FRAMES * 95 / 100];
        if (!opt->quiet)
            fputc('\n', stderr);
        printf("%s, window %dx%d, target %d fps, %s\n", s.name, w, h, fps, gpu_describe());
        printf("  moving (%d frames): median %.1f ms (%.1f fps), p95 %.1f ms; median inside %dx%d; "
               "error vs full size RMSE %.4f mean, %.4f worst bilinear; %.4f, %.4f depth-aware\n",
               FLIGHT_FRAMES, med, 1000.0 / med, p95, res_side(w, (float)sides[FLIGHT_FRAMES / 2]),
               res_side(h, (float)sides[FLIGHT_FRAMES / 2]), err_n ? err_sum / err_n : 0.0, err_max,
               err_n ? edge_sum / err_n : 0.0, edge_max);
        printf("  stopped: first full-size frame after %.0f ms, the preset's %d spp after %.0f ms; adaptive (%.1f %% of "
               "pixels on edges) after %.0f ms, RMSE %.4f to every pixel's %d spp (1 spp: %.4f)\n", first_ms,
               s.quality.spp, spp_ms, 100 * kept, adaptive_ms, adaptive_rmse, s.quality.spp, one_rmse);
        printf("csv,%s,%d,%d,%d,%.2f,%.2f,%d,%d,%.5f,%.5f,%.0f,%d,%.0f,%.4f,%.0f,%.5f,%.5f,%.5f,%.5f\n", s.name, w, h, fps, med,
               p95, res_side(w, (float)sides[FLIGHT_FRAMES / 2]), res_side(h, (float)sides[FLIGHT_FRAMES / 2]),
               err_n ? err_sum / err_n : 0.0, err_max, first_ms, s.quality.spp, spp_ms, kept, adaptive_ms, adaptive_rmse,
               one_rmse, err_n ? edge_sum / err_n : 0.0, edge_max);
    }
    free(moving);
    free(full);
    free(edge);
    render_shutdown();
    gpu_close();
    scene_free(&s);
    return ok;
}
