/* image_io — see image_io.h. The atomic-write protocol (a temporary file beside the target, removed on
 * a fatal signal; close, fsync, decode it all again, rename) is here for every format. PNG files are
 * written and checked, and clean PNG and JPEG files read, by image_codecs.c (libpng, libjpeg-turbo);
 * everything else goes to OpenImageIO in fathom_image.so, loaded on first use
 * (data/lazy/lazy.h, data/media/image_oiio.h): its ~260 libraries cost 0.2 s, which a run of the shipped scenes
 * writing PNG files never pays. */
#include "data/media/image_io.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "data/media/image_codecs.h"
#include "data/media/image_oiio.h"
#include "data/lazy/lazy.h"

/* ---- the temporary file of the write in progress, for the signal handler ------------------------- */

enum { TEMP_MAX = PATH_MAX_LEN + 64 };     /* a target's path and ".tmpPID-N.EXT" */
static char g_temp[TEMP_MAX];             /* written only while no signal can see it half done: */
static volatile sig_atomic_t g_temp_live; /* the handler reads g_temp only when this is 1 */

static void set_temp(const char *path)
{
    g_temp_live = 0;
    snprintf(g_temp, sizeof g_temp, "%s", path);
    g_temp_live = 1;
}

static void clear_temp(void) { g_temp_live = 0; }

static void on_fatal_signal(int sig)
{
    if (g_temp_live)
        unlink(g_temp); /* async-signal-safe */
    signal(sig, SIG_DFL);
    raise(sig);
}

static void at_exit(void)
{
    if (g_temp_live)
        unlink(g_temp);
}

void image_io_install_signal_cleanup(void)
{
    atexit(at_exit); /* util_alloc's exit on out-of-memory */
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++)
        signal(sigs[i], on_fatal_signal);
    signal(SIGXFSZ, SIG_IGN); /* over a file-size limit, write() fails with EFBIG instead */
}

/* ---- the writer ------------------------------------------------------------------------------------- */

struct image_writer {
    char path[PATH_MAX_LEN], tmp[TEMP_MAX];
    int width, height, channels, next_row;
    oiio_writer *oiio; /* everything but a PNG; NULL: png */
    image_png png;
};

static bool oiio_close(oiio_writer *w, err_t *err)
{
    LAZY_FN(bool (*f)(oiio_writer *, err_t *), lazy_symbol(LAZY_IMAGE, "oiio_writer_close", err));
    return f && f(w, err);
}

static void discard(image_writer *w)
{
    err_t ignored;
    if (w->oiio)
        oiio_close(w->oiio, &ignored);
    else
        image_png_drop(&w->png);
    remove(w->tmp);
    clear_temp();
    free(w);
}

image_writer *image_writer_open(const char *path, int width, int height, int channels, bool f32,
                                const char *const *names, err_t *err)
{
    return image_writer_open_text(path, width, height, channels, f32, names, NULL, err);
}

image_writer *image_writer_open_text(const char *path, int width, int height, int channels, bool f32,
                                     const char *const *names, const char *const *texts, err_t *err)
{
    if (strlen(path) >= PATH_MAX_LEN) {
        err_set(err, "cannot write '%.64s...': the path is longer than %d bytes", path, PATH_MAX_LEN - 1);
        return NULL;
    }
    bool png = image_is_png(path) && !f32;
    if (image_is_png(path) && (channels < 1 || channels > 4 || width < 1 || height < 1)) {
        err_set(err, "cannot write '%s': a PNG of %dx%d with %d channels", path, width, height, channels);
        return NULL;
    }
    LAZY_FN_NAMED(open_fn,
                  oiio_writer * (*open_fn)(const char *, const char *, int, int, int, bool, const char *const *,
                                           const char *const *, err_t *),
                  png ? NULL : lazy_symbol(LAZY_IMAGE, "oiio_writer_open", err));
    if (!png && !open_fn)
        return NULL;
    image_writer *w = util_calloc(1, sizeof *w, "an image writer");
    snprintf(w->path, sizeof w->path, "%s", path);
    util_remove_stale_temps(path); /* what an earlier write killed mid-way (SIGKILL) left */
    if (!util_temp_path(path, w->tmp, sizeof w->tmp)) {
        err_set(err, "cannot write '%.200s...': the path is too long", path);
        free(w);
        return NULL;
    }
    w->width = width, w->height = height, w->channels = channels;
    /* the temporary file is made new here (O_EXCL, O_NOFOLLOW): whatever was planted at its name, a
     * link to another file included, is refused rather than written through */
    int fd = open(w->tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) {
        err_set(err, "cannot write '%s': its temporary file '%s': %s", path, w->tmp, strerror(errno));
        free(w);
        return NULL;
    }
    close(fd);
    set_temp(w->tmp);
    bool ok = png ? image_png_begin(&w->png, w->tmp, width, height, channels, texts)
                  : (w->oiio = open_fn(path, w->tmp, width, height, channels, f32, names, texts, err)) != NULL;
    if (!ok) {
        if (png)
            err_set(err, "cannot write '%s': %s", path, w->png.why);
        discard(w);
        return NULL;
    }
    return w;
}

bool image_writer_rows(image_writer *w, int rows, const void *pixels, err_t *err)
{
    if (w->next_row + rows > w->height)
        return err_set(err, "cannot write '%s': %d rows past the image's %d", w->path, w->next_row + rows - w->height,
                       w->height);
    if (w->oiio) {
        LAZY_FN(bool (*f)(oiio_writer *, int, int, const void *, err_t *),
                lazy_symbol(LAZY_IMAGE, "oiio_writer_rows", err));
        if (!f || !f(w->oiio, w->next_row, rows, pixels, err))
            return false;
    } else if (!image_png_rows(&w->png, rows, w->width, w->channels, pixels)) {
        return err_set(err, "cannot write '%s': %s", w->path, w->png.why);
    }
    w->next_row += rows;
    return true;
}

/* Closes the file and reads it all back; false with err's message (no "cannot write" prefix). */
static bool close_and_check(image_writer *w, err_t *err)
{
    bool closed;
    if (w->oiio) {
        closed = oiio_close(w->oiio, err);
        w->oiio = NULL;
    } else if (!(closed = image_png_end(&w->png))) {
        err_set(err, "%s", w->png.why);
    }
    errno = 0;
    if (closed && !util_fsync_path(w->tmp, O_RDONLY))
        return err_set(err, "%s", strerror(errno));
    if (!closed)
        return false;
    if (image_is_png(w->path)) {
        char why[256];
        return image_png_verify(w->tmp, w->width, w->height, w->channels, why, sizeof why) ||
               err_set(err, "the file did not read back after writing (disk full or file too large?): %s", why);
    }
    err_t why;
    LAZY_FN(bool (*f)(const char *, int, int, int, err_t *), lazy_symbol(LAZY_IMAGE, "oiio_verify", &why));
    return (f && f(w->tmp, w->width, w->height, w->channels, &why)) ||
           err_set(err, "the file did not read back after writing (disk full or file too large?): %s", why.msg);
}

bool image_writer_finish(image_writer *w, err_t *err)
{
    if (w->next_row != w->height) {
        err_set(err, "cannot write '%s': only %d of %d rows were rendered", w->path, w->next_row, w->height);
        discard(w);
        return false;
    }
    err_t why;
    if (!close_and_check(w, &why)) {
        err_set(err, "cannot write '%s': %s", w->path, why.msg[0] ? why.msg : "write failed");
        discard(w);
        return false;
    }
    if (rename(w->tmp, w->path) != 0) {
        err_set(err, "cannot write '%s': %s", w->path, strerror(errno));
        discard(w);
        return false;
    }
    clear_temp();
    if (!util_sync_folder_of(w->path)) { /* the new name may not outlive a crash: no file, not a maybe */
        err_set(err, "cannot write '%s': its folder could not be synced to the disk: %s", w->path, strerror(errno));
        unlink(w->path);
        free(w);
        return false;
    }
    free(w);
    return true;
}

void image_writer_abort(image_writer *w)
{
    if (w)
        discard(w);
}

static bool write_whole(const char *path, int width, int height, int channels, bool f32, const char *const *names,
                        const void *pixels, err_t *err)
{
    image_writer *w = image_writer_open(path, width, height, channels, f32, names, err);
    if (!w)
        return false;
    if (!image_writer_rows(w, height, pixels, err)) {
        image_writer_abort(w);
        return false;
    }
    return image_writer_finish(w, err);
}

bool image_write_u8(const char *path, int width, int height, int channels, const uint8_t *pixels, err_t *err)
{
    return write_whole(path, width, height, channels, false, NULL, pixels, err);
}

bool image_write_f32(const char *path, int width, int height, int channels, const char *const *names,
                     const float *pixels, err_t *err)
{
    return write_whole(path, width, height, channels, true, names, pixels, err);
}

bool image_can_write(const char *path, err_t *err)
{
    char dir[PATH_MAX_LEN];
    const char *slash = strrchr(path, '/');
    if (!slash)
        strcpy(dir, ".");
    else if (slash == path)
        strcpy(dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    if (access(dir, W_OK) != 0 && errno == ENOENT)
        return err_set(err, "cannot write '%s': folder '%s' does not exist: make it (mkdir -p '%s') or choose another "
                            "--output path", path, dir, dir);
    if (access(dir, W_OK) != 0)
        return err_set(err, "cannot write '%s': folder '%s' is not writable; choose another --output path", path, dir);
    struct stat st;
    if (stat(path, &st) == 0) {
        if (!S_ISREG(st.st_mode))
            return err_set(err, "cannot write '%s': it exists and is not a regular file; choose another --output path",
                           path);
        if (!(st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)))
            return err_set(err, "cannot write '%s': the file is read-only; make it writable (chmod u+w) or choose "
                                "another --output path", path);
    }
    return true;
}

/* ---- reading: clean PNG and JPEG files by image_codecs.c, anything else (or anything odd) through
 * OpenImageIO ---- */

/* The file's channels as `want` channels (0: as many as the file has), as image_io.cpp's reader maps
 * them: grey fills colour, a missing alpha is one, a grey file's second channel is alpha. Floats are
 * OpenImageIO's conversion, v · (1 / max). Frees d->px. */
static void *convert(image_decoded *d, int want, bool f32, int *channels_out)
{
    int nc = want > 0 ? want : d->c, nread = nc < d->c ? nc : d->c;
    if (d->c == 2 && nc >= 3)
        nread = 2;
    size_t n = (size_t)d->w * (size_t)d->h;
    void *out = util_alloc((f32 ? sizeof(float) : 1) * n * (size_t)nc, "an image");
    float scale = d->bits == 16 ? 1.0f / 65535.0f : 1.0f / 255.0f;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < nc; c++) {
            int k = d->c <= 2 ? (c < 3 ? 0 : (nread == 2 ? 1 : -1)) : (c < nread ? c : (c == 3 ? -1 : 0));
            size_t at = i * (size_t)d->c + (size_t)k;
            unsigned v = k < 0 ? (d->bits == 16 ? 65535u : 255u)
                               : d->bits == 16 ? ((uint16_t *)d->px)[at] : ((uint8_t *)d->px)[at];
            if (f32)
                ((float *)out)[i * (size_t)nc + (size_t)c] = (float)v * scale;
            else
                ((uint8_t *)out)[i * (size_t)nc + (size_t)c] = (uint8_t)v;
        }
    free(d->px);
    d->px = NULL;
    if (channels_out)
        *channels_out = nc;
    return out;
}

bool image_read_u8(const char *path, int channels, int max_side, int *width, int *height, uint8_t **pixels,
                   err_t *err)
{
    image_decoded d;
    if (image_fast_decode(path, max_side, true, &d)) {
        *width = d.w, *height = d.h;
        *pixels = convert(&d, channels, false, NULL);
        return true;
    }
    LAZY_FN(bool (*f)(const char *, int, int, int *, int *, uint8_t **, err_t *),
            lazy_symbol(LAZY_IMAGE, "oiio_read_u8", err));
    return f && f(path, channels, max_side, width, height, pixels, err);
}

bool image_read_text(const char *path, const char *key, char **value, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, const char *, char **, err_t *), lazy_symbol(LAZY_IMAGE, "oiio_read_text", err));
    return f && f(path, key, value, err);
}

bool image_read_f32(const char *path, int channels, int max_side, int *width, int *height, int *channels_out,
                    float **pixels, err_t *err)
{
    image_decoded d;
    if (image_fast_decode(path, max_side, false, &d)) {
        *width = d.w, *height = d.h;
        *pixels = convert(&d, channels, true, channels_out);
        return true;
    }
    LAZY_FN(bool (*f)(const char *, int, int, int *, int *, int *, float **, err_t *),
            lazy_symbol(LAZY_IMAGE, "oiio_read_f32", err));
    return f && f(path, channels, max_side, width, height, channels_out, pixels, err);
}
