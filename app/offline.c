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
#include "shot.h"

/* A band: about 2 Mpixel by default; at most 16 Mpixel whatever --strip-rows asks (GPU targets 52 bytes
 * a pixel, the readback about 140), so 16384 columns always render. */
enum { BAR_WIDTH = 30, MAX_CHANNELS = 12, STRIP_PIXELS = 1 << 21, BAND_MAX_PIXELS = 1 << 24 };
static const float EXPOSURE = 1.0f;

static void progress(int done, int total, double elapsed)
{
    int fill = total > 0 ? done * BAR_WIDTH / total : BAR_WIDTH;
    char bar[BAR_WIDTH + 1];
    for (int i = 0; i < BAR_WIDTH; i++)
        bar[i] = i < fill ? '#' : '-';
    bar[BAR_WIDTH] = '\0';
    double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
    fprintf(stderr, "\rrendering [%s] %d/%d samples  %.1f s  (eta %.1f s) ", bar, done, total, elapsed, eta);
    if (done == total)
        fputc('\n', stderr);
    fflush(stderr);
}

/* EXR channels: RGBA, then the requested AOVs; src[c] is the AOV slot of channel c >= 4. */
static int exr_channels(unsigned aovs, const char *names[MAX_CHANNELS], int src[MAX_CHANNELS])
{
    static const char *const RGBA[] = {"R", "G", "B", "A"};
    int nc = 0;
    for (; nc < 4; nc++)
        names[nc] = RGBA[nc];
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
    return nc;
}

static bool is_png(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && !strcmp(dot, ".png");
}

static image_writer *open_writer(const char *path, int width, int height, unsigned aovs, const char *description,
                                 err_t *err)
{
    const char *names[MAX_CHANNELS];
    int src[MAX_CHANNELS];
    if (is_png(path))
        return image_writer_open_text(path, width, height, 3, false, NULL, SHOT_KEY, description, err);
    return image_writer_open_text(path, width, height, exr_channels(aovs, names, src), true, names, SHOT_KEY,
                                  description, err);
}

/* Appends the current render target (width × rows, a band of the image or all of it) to w. */
static bool write_band(image_writer *w, const char *path, int width, int rows, unsigned aovs, err_t *err)
{
    size_t n = (size_t)width * (size_t)rows;
    bool ok;
    if (is_png(path)) {
        uint8_t *px = malloc(n * 4);
        if (!px)
            return err_set(err, "cannot write '%s': out of memory for a %dx%d band", path, width, rows);
        render_read_srgb8(px, EXPOSURE);
        for (size_t i = 0; i < n; i++) /* drop alpha: the image is opaque */
            memmove(px + i * 3, px + i * 4, 3);
        ok = image_writer_rows(w, rows, px, err);
        free(px);
        return ok;
    }
    const char *names[MAX_CHANNELS];
    int src[MAX_CHANNELS];
    int nc = exr_channels(aovs, names, src);
    float *rgba = malloc(sizeof(float) * 4 * n), *aov = malloc(sizeof(float) * AOV_FLOATS * n);
    float *out = malloc(sizeof(float) * (size_t)nc * n);
    ok = rgba && aov && out;
    if (!ok) {
        err_set(err, "cannot write '%s': out of memory for a %dx%d band", path, width, rows);
    } else {
        render_read_linear(rgba);
        render_read_aovs(aov);
        for (size_t i = 0; i < n; i++) {
            memcpy(out + i * (size_t)nc, rgba + i * 4, sizeof(float) * 4);
            for (int c = 4; c < nc; c++)
                out[i * (size_t)nc + (size_t)c] = aov[i * AOV_FLOATS + (size_t)src[c]];
        }
        ok = image_writer_rows(w, rows, out, err);
    }
    free(out);
    free(rgba);
    free(aov);
    return ok;
}

bool offline_write(const char *path, int width, int height, unsigned aovs, const char *description, err_t *err)
{
    image_writer *w = open_writer(path, width, height, aovs, description, err);
    if (!w)
        return false;
    if (!write_band(w, path, width, height, aovs, err)) {
        image_writer_abort(w);
        return false;
    }
    return image_writer_finish(w, err);
}

/* Rows a band: all of them up to STRIP_PIXELS (or --strip-rows, at most BAND_MAX_PIXELS), else an even
 * count. Bands are cut from the bottom (GL's row 0), so each band's offset is even and pixel quads keep
 * their parity: screen-space derivatives, and so every pixel, match an unbanded render. The top band
 * takes the remainder. */
static int band_rows(const offline_desc *d)
{
    int rows = d->strip_rows ? d->strip_rows : STRIP_PIXELS / d->width;
    if (rows > BAND_MAX_PIXELS / d->width)
        rows = BAND_MAX_PIXELS / d->width;
    if (rows >= d->height)
        return d->height;
    return rows > 2 ? rows & ~1 : 2;
}

static bool render_bands(const offline_desc *d, image_writer *w, err_t *err)
{
    int rows = band_rows(d), bands = (d->height + rows - 1) / rows;
    double t0 = util_now();
    for (int k = 0; k < bands; k++) {
        int bottom = (bands - 1 - k) * rows, h = d->height - bottom < rows ? d->height - bottom : rows;
        render_resize(d->width, h);
        render_set_window(d->width, d->height, 0, d->height - bottom - h);
        render_begin(&d->cam);
        for (int i = 0; i < d->spp; i++) {
            render_sample();
            glFinish();
            if (!d->quiet)
                progress(k * d->spp + i + 1, bands * d->spp, util_now() - t0);
        }
        GLenum e = glGetError();
        if (e != GL_NO_ERROR)
            return err_set(err, "cannot render '%s': the GL failed on a %dx%d band (%s); try a smaller --strip-rows",
                           d->output, d->width, h, e == GL_OUT_OF_MEMORY ? "out of GPU memory" : "GL error");
        if (!write_band(w, d->output, d->width, h, d->aovs, err))
            return false;
    }
    return true;
}

bool offline_render_current(const offline_desc *d, err_t *err)
{
    if (!render_set_scene(d->scene, NULL, err)) /* the output was checked by the caller, before the GPU */
        return false;
    double t0 = util_now();
    image_writer *w = open_writer(d->output, d->width, d->height, d->aovs, d->description, err);
    if (!w)
        return false;
    if (!render_bands(d, w, err)) {
        image_writer_abort(w);
        return false;
    }
    if (!image_writer_finish(w, err))
        return false;
    if (!d->quiet)
        fprintf(stderr, "wrote %s (%dx%d, %d spp, %.2f s, %s)\n", d->output, d->width, d->height, d->spp,
                util_now() - t0, gpu_describe());
    return true;
}

bool offline_render(const offline_desc *d, err_t *err)
{
    if (!image_can_write(d->output, err))
        return false;
    if (!gpu_open(&(gpu_desc){.headless = true}, err))
        return false;
    bool ok = render_init(err) && offline_render_current(d, err);
    render_shutdown();
    gpu_close();
    return ok;
}
