/* image_io's functions in the binary: each loads fathom_image.so (image_io.cpp and OpenImageIO) on
 * first use and calls its own (data/lazy.h), so a run that reads and writes no image never maps
 * OpenImageIO's libraries. image_can_write needs none of them and is here whole. */
#include "data/image_io.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "data/lazy.h"

static bool cleanup_wanted, cleanup_installed;

/* The module's `name`, once the module is loaded with the signal cleanup main() asked for. */
static void *image_fn(const char *name, err_t *err)
{
    void *f = lazy_symbol(LAZY_IMAGE, name, err);
    if (f && cleanup_wanted && !cleanup_installed) {
        void (*install)(void);
        *(void **)&install = lazy_symbol(LAZY_IMAGE, "image_io_install_signal_cleanup", NULL);
        if (install)
            install();
        cleanup_installed = true;
    }
    return f;
}

/* The temporary files to remove on a fatal signal exist only once the module writes: its handlers
 * are installed when it loads. */
void image_io_install_signal_cleanup(void) { cleanup_wanted = true; }

image_writer *image_writer_open(const char *path, int width, int height, int channels, bool f32,
                                const char *const *names, err_t *err)
{
    LAZY_FN(image_writer *(*f)(const char *, int, int, int, bool, const char *const *, err_t *),
            image_fn("image_writer_open", err));
    return f ? f(path, width, height, channels, f32, names, err) : NULL;
}

image_writer *image_writer_open_text(const char *path, int width, int height, int channels, bool f32,
                                     const char *const *names, const char *const *texts, err_t *err)
{
    LAZY_FN(image_writer *(*f)(const char *, int, int, int, bool, const char *const *, const char *const *, err_t *),
            image_fn("image_writer_open_text", err));
    return f ? f(path, width, height, channels, f32, names, texts, err) : NULL;
}

bool image_writer_rows(image_writer *w, int rows, const void *pixels, err_t *err)
{
    LAZY_FN(bool (*f)(image_writer *, int, const void *, err_t *), image_fn("image_writer_rows", err));
    return f && f(w, rows, pixels, err);
}

bool image_writer_finish(image_writer *w, err_t *err)
{
    LAZY_FN(bool (*f)(image_writer *, err_t *), image_fn("image_writer_finish", err));
    return f && f(w, err);
}

void image_writer_abort(image_writer *w)
{
    if (!w) /* nothing opened: nothing to load */
        return;
    LAZY_FN(void (*f)(image_writer *), image_fn("image_writer_abort", NULL));
    if (f)
        f(w);
}

bool image_write_u8(const char *path, int width, int height, int channels, const uint8_t *pixels, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, int, int, int, const uint8_t *, err_t *), image_fn("image_write_u8", err));
    return f && f(path, width, height, channels, pixels, err);
}

bool image_write_f32(const char *path, int width, int height, int channels, const char *const *names,
                     const float *pixels, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, int, int, int, const char *const *, const float *, err_t *),
            image_fn("image_write_f32", err));
    return f && f(path, width, height, channels, names, pixels, err);
}

int image_remove_stale_temps(const char *path)
{
    LAZY_FN(int (*f)(const char *), image_fn("image_remove_stale_temps", NULL));
    return f ? f(path) : 0;
}

bool image_read_u8(const char *path, int channels, int max_side, int *width, int *height, uint8_t **pixels,
                   err_t *err)
{
    LAZY_FN(bool (*f)(const char *, int, int, int *, int *, uint8_t **, err_t *), image_fn("image_read_u8", err));
    return f && f(path, channels, max_side, width, height, pixels, err);
}

bool image_read_text(const char *path, const char *key, char **value, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, const char *, char **, err_t *), image_fn("image_read_text", err));
    return f && f(path, key, value, err);
}

bool image_read_f32(const char *path, int channels, int max_side, int *width, int *height, int *channels_out,
                    float **pixels, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, int, int, int *, int *, int *, float **, err_t *), image_fn("image_read_f32", err));
    return f && f(path, channels, max_side, width, height, channels_out, pixels, err);
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
    if (access(dir, W_OK) != 0)
        return err_set(err, "cannot write '%s': folder '%s' %s; choose another --output path", path, dir,
                       errno == ENOENT ? "does not exist" : "is not writable");
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
