#include "jobs/capture/offline.h"

#include <epoxy/gl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "view/aov.h"
#include "cli/cli.h"
#include "gpu/gpu.h"
#include "data/media/image_io.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "gpu/render_programs.h"
#include "gpu/res_heightfield.h"
#include "view/shot.h"

/* A band: about 2 Mpixel by default; at most 16 Mpixel whatever --strip-rows asks (GPU targets 52 bytes
 * a pixel, the readback about 140), so 16384 columns always render. */
enum { BAR_WIDTH = 30, MAX_CHANNELS = 24, STRIP_PIXELS = 1 << 21, BAND_MAX_PIXELS = 1 << 24 };
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
    static const struct {
        unsigned flag;
        int slot;
        const char *names[3]; /* one channel, or three */
    } AOVS[] = {
        {AOV_DEPTH, AOV_SLOT_DEPTH, {"Z"}},
        {AOV_NORMAL, AOV_SLOT_NORMAL, {"N.X", "N.Y", "N.Z"}},
        {AOV_STEPS, AOV_SLOT_STEPS, {"steps"}},
        {AOV_EXIT, AOV_SLOT_EXIT, {"exit.X", "exit.Y", "exit.Z"}},
        {AOV_VARIANCE, AOV_SLOT_VARIANCE, {"variance.R", "variance.G", "variance.B"}},
        {AOV_SAMPLES, AOV_SLOT_SAMPLES, {"samples"}},
        {AOV_POSITION, AOV_SLOT_POSITION, {"P.X", "P.Y", "P.Z"}},
        {AOV_ALBEDO, AOV_SLOT_ALBEDO, {"albedo.R", "albedo.G", "albedo.B"}},
    };
    static const char *const RGBA[] = {"R", "G", "B", "A"};
    int nc = 0;
    for (; nc < 4; nc++)
        names[nc] = RGBA[nc];
    for (size_t a = 0; a < sizeof AOVS / sizeof AOVS[0]; a++)
        for (int k = 0; k < 3 && (aovs & AOVS[a].flag) && AOVS[a].names[k]; k++)
            names[nc] = AOVS[a].names[k], src[nc++] = AOVS[a].slot + k;
    return nc;
}

static bool is_png(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && !strcasecmp(dot, ".png");
}

/* The camera as OpenEXR's worldToCamera and worldToNDC (view/camera.h) for the whole image, which
 * compositors read: CAMERA_KEY's text, "16 numbers;16 numbers" (the second empty where there is no
 * such matrix), %.9g so each float is exact; a tile keeps it for the poster stitched from it. A stereo image
 * is the left eye's, then ";16;16" the right eye's (as rightWorldToCamera and rightWorldToNDC): each maps a
 * point to where its eye drew it (the centre's mapped a left-eye point ~156 px off). */
#define CAMERA_KEY "fathom_camera"
enum { CAMERA_TEXT_MAX = 1600 };
static void camera_text(const camera *cam, int width, int height, char out[CAMERA_TEXT_MAX])
{
    size_t at = 0;
    for (int eye = -1; eye <= (cam->lens.stereo != STEREO_NONE ? 1 : -1); eye += 2) {
        float m[2][16];
        bool ndc = camera_matrices(cam, width, height, eye, m[0], m[1]);
        for (int k = 0; k < 2; k++)
            for (int i = 0; i < 16 && (k == 0 || ndc); i++)
                at += (size_t)snprintf(out + at, CAMERA_TEXT_MAX - at, "%s%.9g", i ? " " : k || eye > 0 ? ";" : "",
                                       (double)m[k][i]);
        if (!ndc)
            at += (size_t)snprintf(out + at, CAMERA_TEXT_MAX - at, ";");
    }
}

/* cam_text: camera_text's, or NULL (none, and a PNG takes none). */
static image_writer *open_writer(const char *path, int width, int height, unsigned aovs, const char *description,
                                 const char *tile, const char *cam_text, err_t *err)
{
    const char *names[MAX_CHANNELS];
    int src[MAX_CHANNELS];
    char m[4][CAMERA_TEXT_MAX / 2] = {"", "", "", ""}; /* left (or only) eye's two matrices, the right eye's */
    const char *at = cam_text && !is_png(path) ? cam_text : NULL;
    for (int k = 0; at && k < 4; k++) {
        size_t n = strcspn(at, ";");
        if (n < sizeof m[k])
            snprintf(m[k], sizeof m[k], "%.*s", (int)n, at);
        at = at[n] ? at + n + 1 : NULL;
    }
    const char *texts[] = {SHOT_KEY, description, TILE_KEY, tile, CAMERA_KEY, m[0][0] ? cam_text : NULL,
                           "m44f:worldtocamera", m[0][0] ? m[0] : NULL, "m44f:worldtoNDC", m[1][0] ? m[1] : NULL,
                           "m44f:rightWorldToCamera", m[2][0] ? m[2] : NULL, "m44f:rightWorldToNDC",
                           m[3][0] ? m[3] : NULL, NULL};
    if (is_png(path))
        return image_writer_open_text(path, width, height, 3, false, NULL, texts, err);
    return image_writer_open_text(path, width, height, exr_channels(aovs, names, src), true, names, texts, err);
}

/* Appends rows [skip, skip + rows) of the current render target (top down: a band of the image, all of
 * it, or a band with margin rows above and below it) to w. */
static bool write_band(image_writer *w, const char *path, int width, int skip, int rows, unsigned aovs, err_t *err)
{
    int all_rows;
    render_active_size(&width, &all_rows);
    size_t n = (size_t)width * (size_t)all_rows, first = (size_t)width * (size_t)skip;
    bool ok;
    if (is_png(path)) {
        uint8_t *px = malloc(n * 4);
        if (!px)
            return err_set(err, "cannot write '%s': out of memory for a %dx%d band", path, width, rows);
        render_read_srgb8(px, EXPOSURE);
        for (size_t i = 0; i < n; i++) /* drop alpha: the image is opaque */
            memmove(px + i * 3, px + i * 4, 3);
        ok = image_writer_rows(w, rows, px + first * 3, err);
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
        ok = image_writer_rows(w, rows, out + first * (size_t)nc, err);
    }
    free(out);
    free(rgba);
    free(aov);
    return ok;
}

bool offline_write(const char *path, int width, int height, unsigned aovs, const char *description, err_t *err)
{
    image_writer *w = open_writer(path, width, height, aovs, description, NULL, NULL, err);
    if (!w)
        return false;
    if (!write_band(w, path, width, 0, height, aovs, err)) {
        image_writer_abort(w);
        return false;
    }
    return image_writer_finish(w, err);
}

/* Rows a band of an image `height` rows tall: all of them up to STRIP_PIXELS (or --strip-rows, at most
 * BAND_MAX_PIXELS), else an even count. Bands are cut from the bottom (GL's row 0), so each band's
 * offset is even and pixel quads keep their parity: screen-space derivatives, and so every pixel,
 * match an unbanded render. The top band takes the remainder. */
static int band_rows(const offline_desc *d, int height)
{
    int rows = d->strip_rows ? d->strip_rows : STRIP_PIXELS / d->width;
    if (rows > BAND_MAX_PIXELS / d->width)
        rows = BAND_MAX_PIXELS / d->width;
    if (rows >= height)
        return height;
    return rows > 2 ? rows & ~1 : 2;
}

void offline_tile_rows(int height, int index, int count, int *top, int *rows)
{
    int r = (height / count) & ~1;
    if (r < 2)
        r = 2;
    int bottom = (count - index) * r; /* tile `count` is at the bottom */
    *rows = index == 1 ? height - bottom : r;
    *top = height - bottom - *rows;
}

bool offline_tile_name(const char *output, int index, int count, char *out, size_t n, err_t *err)
{
    const char *dot = strrchr(output, '.');
    int digits = snprintf(NULL, 0, "%d", count);
    int len = snprintf(out, n, "%.*s.tile-%0*d-of-%d%s", (int)(dot - output), output, digits, index, count, dot);
    if (len < 0 || (size_t)len >= n)
        return err_set(err, "bad --output '%s': the tile's file name is too long", output);
    return true;
}

/* A streamed terrain (gpu/res_heightfield.h): passes of one sample until one asks for no tile the GPU lacks
 * (each loads what the last asked for). TERRAIN_OVER_BUDGET: the band needs more tiles than the cache. */
static res_heightfield_settled stream_in(const camera *cam, err_t *err)
{
    res_heightfield_watch();
    for (;;) {
        render_begin(cam);
        render_sample();
        res_heightfield_settled r = res_heightfield_settle(INT_MAX, err);
        if (r != TERRAIN_LOADED)
            return r;
    }
}

typedef struct band_run {
    const offline_desc *d;
    image_writer *w;
    int margin;
    long *unresolved;
    double *pixel_samples, t0;
    int done_rows, rows; /* the progress: rows written of the rows to render */
} band_run;

/* Rows [band_top, band_top + h) of the image, with margin rows above and below where adaptive sampling
 * needs them; a streamed terrain's band whose tiles do not fit the cache is cut in two (even rows). */
static bool render_band(band_run *b, int band_top, int h, err_t *err)
{
    const offline_desc *d = b->d;
    int below = d->height - band_top - h;
    int above = band_top < b->margin ? band_top : b->margin, under = below < b->margin ? below : b->margin;
    for (;;) {
        render_resize(d->width, above + h + under);
        render_set_window(d->width, d->height, 0, band_top - above);
        render_begin(&d->cam);
        res_heightfield_settled r = TERRAIN_SETTLED;
        if (res_heightfield_streamed() && (r = stream_in(&d->cam, err)) == TERRAIN_SETTLED)
            render_begin(&d->cam);
        for (int i = 0; r == TERRAIN_SETTLED && i < d->spp; i++) {
            render_sample();
            glFinish();
            if (!d->quiet)
                progress((int)((b->done_rows + (double)h * (i + 1) / d->spp) * d->spp / b->rows + 0.5), d->spp,
                         util_now() - b->t0);
        }
        if (r == TERRAIN_SETTLED && res_heightfield_streamed()) /* a jittered sample may have asked for more */
            r = res_heightfield_settle(INT_MAX, err);
        if (r == TERRAIN_SETTLED)
            break;
        if (r == TERRAIN_FAILED)
            return false;
        if (r == TERRAIN_OVER_BUDGET) {
            if (h <= 2)
                return err_set(err, "cannot render '%s': two rows of this view need more terrain tiles than "
                                    "terrain.cache_mb holds (%d); raise terrain.cache_mb", d->output,
                               res_heightfield_get_stats().slots);
            int top_rows = (h / 2) & ~1; /* even: pixel quads keep their parity */
            return render_band(b, band_top, top_rows, err) && render_band(b, band_top + top_rows, h - top_rows, err);
        }
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR)
        return err_set(err, "cannot render '%s': the GL failed on a %dx%d band (%s); try a smaller --strip-rows",
                       d->output, d->width, h, e == GL_OUT_OF_MEMORY ? "out of GPU memory" : "GL error");
    b->unresolved[0] += render_unresolved_pixels(&b->unresolved[1]); /* (margin rows counted too) */
    *b->pixel_samples += render_mean_samples() * d->width * h; /* (margin rows as many a pixel) */
    b->done_rows += h;
    return write_band(b->w, d->output, d->width, above, h, d->aovs, err);
}

/* Renders rows [top, top + height) of the d->width × d->height image (all of it, or one tile) into w.
 * Each band is rendered with margin rows of the image above and below it where adaptive sampling's
 * 3x3 blocks need them (render_adaptive_margin), so bands and tiles agree with the whole image. */
static bool render_bands(const offline_desc *d, int top, int height, image_writer *w, long unresolved[2],
                         double *pixel_samples, err_t *err)
{
    int rows = band_rows(d, height), bands = (height + rows - 1) / rows;
    band_run b = {.d = d, .w = w, .margin = render_adaptive_margin(d->scene, d->spp), .unresolved = unresolved,
                  .pixel_samples = pixel_samples, .t0 = util_now(), .rows = height};
    for (int k = 0; k < bands; k++) {
        int bottom = (bands - 1 - k) * rows, h = height - bottom < rows ? height - bottom : rows;
        if (!render_band(&b, top + height - bottom - h, h, err))
            return false;
    }
    if (res_heightfield_streamed() && !d->quiet) {
        res_heightfield_stats st = res_heightfield_get_stats();
        fprintf(stderr, "terrain: %ld tiles read from disk (%.0f MB of the DEM), %d of %d resident (%d slots)\n",
                st.loaded, (double)st.bytes_read / 1e6, st.resident, st.tiles, st.slots);
    }
    return true;
}

offline_desc offline_desc_defaults(const offline_desc *d)
{
    offline_desc o = *d;
    o.width = o.width ? o.width : GPU_DEFAULT_WIDTH;
    o.height = o.height ? o.height : GPU_DEFAULT_HEIGHT;
    o.spp = o.spp ? o.spp : o.scene->quality.spp;
    return o;
}

offline_desc offline_shot(offline_desc base, const scene *s, camera cam, const char *output, const char *const *sets,
                          int nsets, strbuf *description)
{
    base.scene = s;
    base.cam = cam;
    base.output = output;
    offline_desc d = offline_desc_defaults(&base);
    const char *formulas[SHOT_FORMULA_MAX];
    scene_formula_files(s, formulas);
    shot_describe_fractal(s->path, sets, nsets, formulas, &d.cam, d.width, d.height, description);
    d.description = description->data;
    return d;
}

bool offline_render_current(const offline_desc *desc, err_t *err)
{
    offline_desc dd = offline_desc_defaults(desc);
    const offline_desc *d = &dd;
    scene fit = *d->scene; /* a deep zoom: the precision the view needs (render_fit_precision) */
    if (!render_set_scene(d->scene, NULL, err) || /* the output was checked by the caller, before the GPU */
        !render_fit_precision(&fit, &d->cam, d->height, err))
        return false;
    const char *precision = fit.fractal.deep_now ? ", double precision" : "";
    double t0 = util_now();
    int top = 0, rows = d->height;
    char tile[128] = "";
    if (d->tile_count) {
        offline_tile_rows(d->height, d->tile_index, d->tile_count, &top, &rows);
        snprintf(tile, sizeof tile, "%d %d %d %d %d %u", d->tile_index, d->tile_count, d->width, d->height, top, d->aovs);
    }
    char renderer[320];
    snprintf(renderer, sizeof renderer, "fathom %s, %s backend, %s", FATHOM_VERSION,
             render_backend_name(render_backend_used()), gpu_describe());
    strbuf described = {0};
    if (d->description)
        shot_note_renderer(d->description, renderer, &described);
    char cam_text[CAMERA_TEXT_MAX];
    camera_text(&d->cam, d->width, d->height, cam_text);
    image_writer *w = open_writer(d->output, d->width, rows, d->aovs, described.data, tile[0] ? tile : NULL, cam_text, err);
    sb_free(&described);
    if (!w)
        return false;
    long unresolved[2] = {0, 0}; /* all, and those out of the loop budget */
    double pixel_samples = 0;
    if (!render_bands(d, top, rows, w, unresolved, &pixel_samples, err)) {
        image_writer_abort(w);
        return false;
    }
    if (unresolved[1] == (long)d->width * rows) { /* not one pixel finished: no image, whatever was drawn */
        image_writer_abort(w);
        return err_set(err, "every pixel ran out of the loop budget (%s): the scene's loops do not end (a formula "
                            "whose loop never stops?); nothing written", render_programs_loop_budget_text());
    }
    if (!image_writer_finish(w, err))
        return false;
    char spp[64]; /* adaptive sampling: the samples the pixels took, on average */
    double mean = pixel_samples / ((double)d->width * rows);
    int len = snprintf(spp, sizeof spp, "%d spp", d->spp);
    if (mean < d->spp - 0.05)
        snprintf(spp + len, sizeof spp - (size_t)len, ", %.1f a pixel", mean);
    if (!d->quiet && d->tile_count)
        fprintf(stderr, "wrote %s (tile %d of %d: rows %d-%d of %dx%d, %s%s, %.2f s, %s, %s)\n", d->output,
                d->tile_index, d->tile_count, top, top + rows - 1, d->width, d->height, spp, precision,
                util_now() - t0, render_backend_name(render_backend_used()), gpu_describe());
    else if (!d->quiet)
        fprintf(stderr, "wrote %s (%dx%d, %s%s, %.2f s, %s, %s)\n", d->output, d->width, d->height, spp,
                precision, util_now() - t0, render_backend_name(render_backend_used()), gpu_describe());
    long steps = unresolved[0] - unresolved[1], loops = unresolved[1];
    double share = 100.0 / ((double)d->width * rows);
    if (!d->quiet && steps)
        fprintf(stderr, "note: %ld pixel%s (%.3g%%) ran out of steps and are drawn as misses (the steps AOV marks them "
                        "negative); raise quality.max_steps or use --quality final\n",
                steps, steps == 1 ? "" : "s", share * (double)steps);
    if (!d->quiet && loops)
        fprintf(stderr, "note: %ld pixel%s (%.3g%%) ran out of the loop budget (%s): a ray that had found nothing "
                        "is drawn as a miss, else the shading may be cut short (the steps AOV marks them -(steps + "
                        "0.5)); lower fractal.iterations, quality.max_steps or quality.shadow_steps, or render on a "
                        "GPU\n",
                loops, loops == 1 ? "" : "s", share * (double)loops, render_programs_loop_budget_text());
    return true;
}

bool offline_render(const offline_desc *d, err_t *err)
{
    if ((d->aovs & AOV_POSITION) && d->cam.lens.aperture > 0)
        return err_set(err, "--aov position needs a pinhole camera: with camera.aperture > 0 each lens sample sees "
                            "another point (render the pass with --set camera.aperture=0)");
    if (!image_can_write(d->output, err))
        return false;
    if (!gpu_open(&(gpu_desc){.headless = true}, err))
        return false;
    bool ok = render_init(err) && offline_render_current(d, err);
    render_shutdown();
    gpu_close();
    return ok;
}

/* ---- stitching tiles ---- */

typedef struct tile_info {
    const char *file;
    int index, count, width, height, top;
    unsigned aovs;
} tile_info;

bool offline_tile_record(const char *text, bool png, tile_record *r)
{
    char end;
    *r = (tile_record){0};
    return sscanf(text, "%d %d %d %d %d %u%c", &r->index, &r->count, &r->width, &r->height, &r->top, &r->aovs,
                  &end) == 6 &&
           r->count >= 1 && r->count <= TILE_MAX && r->index >= 1 && r->index <= r->count && r->width >= 1 &&
           r->width <= IMAGE_MAX_SIDE && r->height >= 1 && r->height <= IMAGE_MAX_SIDE && r->count <= r->height &&
           r->top >= 0 && r->top < r->height && !(r->aovs & ~(unsigned)AOV_ALL) && !(png && r->aovs);
}

static int by_index(const void *a, const void *b)
{
    return ((const tile_info *)a)->index - ((const tile_info *)b)->index;
}

/* True (with err) when the poster would replace one of its own tiles. */
static bool same_file_as_a_tile(const char *output, const char *const *tiles, int n, err_t *err)
{
    struct stat o, t;
    if (stat(output, &o) != 0)
        return false; /* a new file: no tile can be it */
    for (int i = 0; i < n; i++)
        if (stat(tiles[i], &t) == 0 && t.st_dev == o.st_dev && t.st_ino == o.st_ino) {
            err_set(err, "stitch: --output '%s' is one of the tiles; name a new file for the poster", output);
            return true;
        }
    return false;
}

/* A tile file's record (TILE_KEY), checked against what fathom writes: counts and sizes in range, AOV
 * bits fathom knows (PNG tiles carry none). */
static bool read_tile_record(tile_info *t, const char *output, err_t *err)
{
    char *text = NULL;
    tile_record rec;
    bool ok = false;
    if (!util_file_exists(t->file))
        err_set(err, "tile '%s' not found: check the path (stitch takes every tile of the poster)", t->file);
    else if (is_png(t->file) != is_png(output))
        err_set(err, "tile '%s': its format differs from '%s' (tiles and poster are all .png or all .exr)", t->file,
                output);
    else if (!image_read_text(t->file, TILE_KEY, &text, err))
        err_set(err, "'%s' is not a fathom tile (render tiles with --tile I/N)", t->file);
    else if (!offline_tile_record(text, is_png(t->file), &rec))
        err_set(err, "tile '%s': its record is damaged (render the tile again)", t->file);
    else
        ok = true;
    if (ok)
        t->index = rec.index, t->count = rec.count, t->width = rec.width, t->height = rec.height, t->top = rec.top,
        t->aovs = rec.aovs;
    free(text);
    return ok;
}

bool offline_stitch(const char *output, const char *const *tiles, int n, bool quiet, err_t *err)
{
    if (n < 1)
        return err_set(err, "stitch: no tile files given (e.g. fathom stitch --output poster.png poster.tile-*.png)");
    if (!image_can_write(output, err))
        return false;
    tile_info *t = util_calloc((size_t)n, sizeof *t, "tiles");
    bool ok = !same_file_as_a_tile(output, tiles, n, err);
    for (int i = 0; i < n && ok; i++) {
        t[i].file = tiles[i];
        ok = read_tile_record(&t[i], output, err);
        if (ok && i > 0 && (t[i].count != t[0].count || t[i].width != t[0].width || t[i].height != t[0].height ||
                            t[i].aovs != t[0].aovs))
            ok = err_set(err, "tile '%s' belongs to another poster than '%s' (%d tiles of %dx%d against %d of %dx%d)",
                         tiles[i], tiles[0], t[i].count, t[i].width, t[i].height, t[0].count, t[0].width, t[0].height);
    }
    if (ok) {
        qsort(t, (size_t)n, sizeof *t, by_index);
        for (int i = 0; i < n && ok; i++)
            if (i > 0 && t[i].index == t[i - 1].index)
                ok = err_set(err, "tiles '%s' and '%s' are both tile %d", t[i - 1].file, t[i].file, t[i].index);
        if (ok && n != t[0].count) {
            enum { LISTED = 16 }; /* the missing tiles named; the rest counted */
            strbuf missing = {0};
            int absent = 0;
            for (int k = 1, j = 0; k <= t[0].count; k++) {
                while (j < n && t[j].index < k)
                    j++;
                if ((j >= n || t[j].index != k) && absent++ < LISTED)
                    sb_printf(&missing, "%s%d", missing.len ? ", " : "", k);
            }
            if (absent > LISTED)
                sb_printf(&missing, " and %d more", absent - LISTED);
            ok = err_set(err, "%d of %d tiles given: missing %s", n, t[0].count, missing.data);
            sb_free(&missing);
        }
    }
    char *shot = NULL, *cam = NULL;
    err_t ignore;
    if (ok) { /* the poster remembers the shot and (an EXR) the camera, as the tiles do */
        image_read_text(t[0].file, SHOT_KEY, &shot, &ignore);
        if (!is_png(output))
            image_read_text(t[0].file, CAMERA_KEY, &cam, &ignore);
    }
    image_writer *w = ok ? open_writer(output, t[0].width, t[0].height, t[0].aovs, shot, NULL, cam, err) : NULL;
    ok = ok && w;
    const char *names[MAX_CHANNELS];
    int src[MAX_CHANNELS];
    int nc = exr_channels(t[0].aovs, names, src);
    for (int i = 0; i < n && ok; i++) {
        int top, rows, width, height, got;
        offline_tile_rows(t[0].height, t[i].index, t[0].count, &top, &rows);
        void *px = NULL;
        if (is_png(output))
            ok = image_read_u8(t[i].file, 3, TILE_MAX * 4, &width, &height, (uint8_t **)&px, err);
        else
            ok = image_read_f32(t[i].file, 0, TILE_MAX * 4, &width, &height, &got, (float **)&px, err) &&
                 (got == nc || err_set(err, "tile '%s' has %d channels; its record's AOVs make %d: it is damaged",
                                       t[i].file, got, nc));
        if (ok && (width != t[0].width || height != rows || t[i].top != top))
            ok = err_set(err, "tile '%s' is %dx%d at row %d; tile %d of %d of a %dx%d poster is %dx%d at row %d",
                         t[i].file, width, height, t[i].top, t[i].index, t[0].count, t[0].width, t[0].height,
                         t[0].width, rows, top);
        ok = ok && image_writer_rows(w, rows, px, err);
        free(px);
    }
    free(shot);
    free(cam);
    if (w && !ok)
        image_writer_abort(w);
    else if (w)
        ok = image_writer_finish(w, err);
    if (ok && !quiet)
        fprintf(stderr, "wrote %s (%dx%d from %d tiles)\n", output, t[0].width, t[0].height, n);
    free(t);
    return ok;
}
