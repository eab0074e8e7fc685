#include "offline.h"

#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "aov.h"
#include "cli.h"
#include "gpu.h"
#include "image_io.h"
#include "render.h"

enum { BAR_WIDTH = 30, MAX_CHANNELS = 12 };
static const float EXPOSURE = 1.0f;

static void progress(int done, int total, double elapsed)
{
    int fill = total > 0 ? done * BAR_WIDTH / total : BAR_WIDTH;
    char bar[BAR_WIDTH + 1];
    for (int i = 0; i < BAR_WIDTH; i++)
        bar[i] = i < fill ? '#' : '-';
    bar[BAR_WIDTH] = '\0';
    double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
    fprintf(stderr, "\rrendering [%s] %d/%d spp  %.1f s  (eta %.1f s) ", bar, done, total, elapsed, eta);
    if (done == total)
        fputc('\n', stderr);
    fflush(stderr);
}

bool offline_write(const char *path, int width, int height, unsigned aovs, err_t *err)
{
    const char *dot = strrchr(path, '.');
    size_t n = (size_t)width * (size_t)height;
    if (dot && !strcmp(dot, ".png")) {
        uint8_t *px = malloc(n * 4);
        render_read_srgb8(px, EXPOSURE);
        /* drop alpha: the image is opaque */
        for (size_t i = 0; i < n; i++)
            memmove(px + i * 3, px + i * 4, 3);
        bool ok = image_write_u8(path, width, height, 3, px, err);
        free(px);
        return ok;
    }
    float *rgba = malloc(sizeof(float) * 4 * n), *aov = malloc(sizeof(float) * AOV_FLOATS * n);
    render_read_linear(rgba);
    render_read_aovs(aov);
    const char *names[MAX_CHANNELS] = {"R", "G", "B", "A"};
    int src[MAX_CHANNELS]; /* index into aov for channels past RGBA */
    int nc = 4;
    if (aovs & AOV_DEPTH) names[nc] = "Z", src[nc++] = AOV_SLOT_DEPTH;
    if (aovs & AOV_NORMAL) {
        names[nc] = "N.X", src[nc++] = AOV_SLOT_NORMAL;
        names[nc] = "N.Y", src[nc++] = AOV_SLOT_NORMAL + 1;
        names[nc] = "N.Z", src[nc++] = AOV_SLOT_NORMAL + 2;
    }
    if (aovs & AOV_STEPS) names[nc] = "steps", src[nc++] = AOV_SLOT_STEPS;
    if (aovs & AOV_EXIT) {
        names[nc] = "exit.X", src[nc++] = AOV_SLOT_EXIT;
        names[nc] = "exit.Y", src[nc++] = AOV_SLOT_EXIT + 1;
        names[nc] = "exit.Z", src[nc++] = AOV_SLOT_EXIT + 2;
    }
    float *out = malloc(sizeof(float) * (size_t)nc * n);
    for (size_t i = 0; i < n; i++) {
        memcpy(out + i * (size_t)nc, rgba + i * 4, sizeof(float) * 4);
        for (int c = 4; c < nc; c++)
            out[i * (size_t)nc + (size_t)c] = aov[i * AOV_FLOATS + (size_t)src[c]];
    }
    bool ok = image_write_f32(path, width, height, nc, names, out, err);
    free(out);
    free(rgba);
    free(aov);
    return ok;
}

bool offline_render(const offline_desc *d, err_t *err)
{
    if (!image_can_write(d->output, err))
        return false;
    if (!gpu_open(&(gpu_desc){.headless = true}, err))
        return false;
    bool ok = render_init(err) && render_set_scene(d->scene, NULL, err);
    if (ok) {
        render_resize(d->width, d->height);
        render_begin(&d->cam);
        double t0 = util_now();
        for (int i = 0; i < d->spp; i++) {
            render_sample();
            glFinish();
            if (!d->quiet)
                progress(i + 1, d->spp, util_now() - t0);
        }
        ok = offline_write(d->output, d->width, d->height, d->aovs, err);
        if (ok && !d->quiet)
            fprintf(stderr, "wrote %s (%dx%d, %d spp, %.2f s, %s)\n", d->output, d->width, d->height, d->spp,
                    util_now() - t0, gpu_describe());
    }
    render_shutdown();
    gpu_close();
    return ok;
}
