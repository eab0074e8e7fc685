/* image_io — see image_io.h. The atomic-write protocol (a temporary file beside the target, removed on
 * a fatal signal; close, fsync, decode it all again, rename) is here for every format. PNG files are
 * written and checked here with libpng, and clean PNG and JPEG files read with libpng and
 * libjpeg-turbo; everything else goes to OpenImageIO in fathom_image.so, loaded on first use
 * (data/lazy.h, data/image_oiio.h): its ~260 libraries cost 0.2 s, which a run of the shipped scenes
 * writing PNG files never pays. */
#include "data/image_io.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <png.h>
#include <setjmp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include <jpeglib.h> /* after stdio.h: it uses FILE */

#include "data/image_oiio.h"
#include "data/lazy.h"

/* ---- the temporary file of the write in progress, for the signal handler ------------------------- */

enum { TEMP_MAX = PATH_MAX_LEN + 32 };     /* a target's path and ".tmpPID" */
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

/* ".NAME.tmpPID.EXT" beside NAME.EXT: the same folder (rename stays atomic) and extension (the
 * format follows it). */
static void temp_path_for(const char *path, char *out, size_t n)
{
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path, *dot = strrchr(base, '.');
    snprintf(out, n, "%.*s.%s.tmp%ld%s", (int)(base - path), path, base, (long)getpid(), dot ? dot : "");
}

int image_remove_stale_temps(const char *path)
{
    const char *slash = strrchr(path, '/');
    char dir[PATH_MAX_LEN], file[PATH_MAX_LEN * 2];
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) + 1 : 2, slash ? path : "./");
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int removed = 0;
    for (struct dirent *e; (e = readdir(d));) {
        /* ".NAME.tmpPID.EXT", as temp_path_for makes it, whose writer is gone */
        const char *n = e->d_name, *t = n[0] == '.' ? strstr(n, ".tmp") : NULL;
        while (t && strstr(t + 1, ".tmp"))
            t = strstr(t + 1, ".tmp");
        if (!t || t == n)
            continue;
        char *end;
        long pid = strtol(t + 4, &end, 10);
        if (end == t + 4 || *end != '.' || pid <= 0 || strchr(end + 1, '.') || pid == (long)getpid())
            continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH)
            continue; /* its writer is alive (or not ours to ask): leave it */
        snprintf(file, sizeof file, "%s%s", dir, n);
        removed += remove(file) == 0;
    }
    closedir(d);
    return removed;
}

/* ---- PNG through libpng ----------------------------------------------------------------------------- */

typedef struct png_io {
    png_structp png;
    png_infop info;
    FILE *f;
    char why[256]; /* libpng's message */
} png_io;

static void png_fail(png_structp png, png_const_charp msg)
{
    png_io *io = png_get_error_ptr(png);
    int saved = errno;
    if (io->f && ferror(io->f) && saved) /* libpng says only "Write Error": say why (a full disk) */
        snprintf(io->why, sizeof io->why, "%s (is the disk full?)", strerror(saved));
    else
        snprintf(io->why, sizeof io->why, "%s", msg);
    png_longjmp(png, 1);
}

static void png_quiet(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

static bool is_png(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && !strcasecmp(dot, ".png");
}

static const int PNG_COLOR[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                 PNG_COLOR_TYPE_RGBA};

/* Opens tmp and writes the header and the text entries; false with io->why. */
static bool png_begin(png_io *io, const char *tmp, int width, int height, int channels, const char *const *texts)
{
    io->f = fopen(tmp, "wb");
    if (!io->f) {
        snprintf(io->why, sizeof io->why, "%s", strerror(errno));
        return false;
    }
    io->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, io, png_fail, png_quiet);
    io->info = io->png ? png_create_info_struct(io->png) : NULL;
    if (!io->info) {
        snprintf(io->why, sizeof io->why, "out of memory");
        return false;
    }
    if (setjmp(png_jmpbuf(io->png)))
        return false;
    png_init_io(io->png, io->f);
    png_set_IHDR(io->png, io->info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR[channels],
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(io->png, io->info, PNG_sRGB_INTENT_PERCEPTUAL);
    for (int i = 0; texts && texts[i]; i += 2)
        if (texts[i + 1]) { /* tEXt chunks: the bytes as they are (OpenImageIO reads them back) */
            png_text t = {.compression = PNG_TEXT_COMPRESSION_NONE, .key = (png_charp)texts[i],
                          .text = (png_charp)texts[i + 1], .text_length = strlen(texts[i + 1])};
            png_set_text(io->png, io->info, &t, 1);
        }
    png_write_info(io->png, io->info);
    return true;
}

static bool png_rows(png_io *io, int rows, int width, int channels, const uint8_t *pixels)
{
    if (setjmp(png_jmpbuf(io->png)))
        return false;
    for (int y = 0; y < rows; y++)
        png_write_row(io->png, pixels + (size_t)y * (size_t)width * (size_t)channels);
    return true;
}

/* Ends the image and closes the file (write errors surface at the flush); false with io->why. */
static bool png_end(png_io *io)
{
    volatile bool ok = true;
    if (setjmp(png_jmpbuf(io->png)))
        ok = false;
    else
        png_write_end(io->png, NULL);
    png_destroy_write_struct(&io->png, &io->info);
    ok = ok && fflush(io->f) == 0;
    if (!ok && !io->why[0])
        snprintf(io->why, sizeof io->why, "%s", strerror(errno));
    if (fclose(io->f) != 0 && ok) {
        snprintf(io->why, sizeof io->why, "%s", strerror(errno));
        ok = false;
    }
    io->f = NULL;
    return ok;
}

static void png_drop(png_io *io)
{
    if (io->png)
        png_destroy_write_struct(&io->png, &io->info);
    if (io->f)
        fclose(io->f);
    io->f = NULL;
}

/* Opens path for libpng to read; false (io holding what it made) when it cannot. */
static bool png_open_read(const char *path, png_io *io)
{
    io->f = fopen(path, "rb");
    io->png = io->f ? png_create_read_struct(PNG_LIBPNG_VER_STRING, io, png_fail, png_quiet) : NULL;
    io->info = io->png ? png_create_info_struct(io->png) : NULL;
    return io->info != NULL;
}

static void png_close_read(png_io *io)
{
    if (io->png)
        png_destroy_read_struct(&io->png, &io->info, NULL);
    if (io->f)
        fclose(io->f);
    io->f = NULL;
}

/* Decodes every row: a truncated or corrupt file fails here. */
static bool png_verify(const char *file, int width, int height, int channels, char *why, size_t n)
{
    png_io io = {0};
    bool opened = png_open_read(file, &io);
    uint8_t *row = malloc((size_t)width * (size_t)channels);
    volatile bool ok = opened && row;
    if (!ok) {
        /* nothing to read with */
    } else if (setjmp(png_jmpbuf(io.png))) {
        ok = false;
    } else {
        png_init_io(io.png, io.f);
        png_read_info(io.png, io.info);
        if (png_get_image_width(io.png, io.info) != (png_uint_32)width ||
            png_get_image_height(io.png, io.info) != (png_uint_32)height ||
            png_get_channels(io.png, io.info) != channels || png_get_bit_depth(io.png, io.info) != 8) {
            snprintf(io.why, sizeof io.why, "it reads back as %ux%u with %d channels",
                     png_get_image_width(io.png, io.info), png_get_image_height(io.png, io.info),
                     png_get_channels(io.png, io.info));
            ok = false;
        }
        for (int y = 0; ok && y < height; y++)
            png_read_row(io.png, row, NULL);
        if (ok)
            png_read_end(io.png, NULL);
    }
    snprintf(why, n, "%s", io.why[0] ? io.why : !io.f ? strerror(errno) : "out of memory");
    png_close_read(&io);
    free(row);
    return ok;
}

/* ---- the writer ------------------------------------------------------------------------------------- */

struct image_writer {
    char path[PATH_MAX_LEN], tmp[TEMP_MAX];
    int width, height, channels, next_row;
    oiio_writer *oiio; /* everything but a PNG; NULL: png */
    png_io png;
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
        png_drop(&w->png);
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
    bool png = is_png(path) && !f32;
    if (is_png(path) && (channels < 1 || channels > 4 || width < 1 || height < 1)) {
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
    temp_path_for(path, w->tmp, sizeof w->tmp);
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
    bool ok = png ? png_begin(&w->png, w->tmp, width, height, channels, texts)
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
    } else if (!png_rows(&w->png, rows, w->width, w->channels, pixels)) {
        return err_set(err, "cannot write '%s': %s", w->path, w->png.why);
    }
    w->next_row += rows;
    return true;
}

/* The bytes on the disk, not in a cache: a failure here (EIO, ENOSPC on some file systems) is the last
 * chance to hear of it. */
static bool sync_file(const char *path, int flags)
{
    int fd = open(path, flags);
    if (fd < 0)
        return false;
    bool ok = fsync(fd) == 0 || errno == EINVAL; /* EINVAL: a folder on a file system without fsync */
    close(fd);
    return ok;
}

/* Closes the file and reads it all back; false with err's message (no "cannot write" prefix). */
static bool close_and_check(image_writer *w, err_t *err)
{
    bool closed;
    if (w->oiio) {
        closed = oiio_close(w->oiio, err);
        w->oiio = NULL;
    } else if (!(closed = png_end(&w->png))) {
        err_set(err, "%s", w->png.why);
    }
    errno = 0;
    if (closed && !sync_file(w->tmp, O_RDONLY))
        return err_set(err, "%s", strerror(errno));
    if (!closed)
        return false;
    if (is_png(w->path)) {
        char why[256];
        return png_verify(w->tmp, w->width, w->height, w->channels, why, sizeof why) ||
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
    char dir[PATH_MAX_LEN];
    const char *slash = strrchr(w->path, '/');
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - w->path) + 1 : 1, slash ? w->path : ".");
    sync_file(dir, O_RDONLY | O_DIRECTORY);
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

/* ---- reading: clean PNG and JPEG files here, anything else (or anything odd) through OpenImageIO ---- */

/* A decoded image: c channels of 8- or 16-bit values (native order), rows top first. */
typedef struct decoded {
    int w, h, c, bits;
    void *px;
} decoded;

/* Taken here only while small: anything larger goes to OpenImageIO, whose reader checks it against the
 * machine's memory first. */
enum { FAST_MAX_PIXELS = 1 << 26 };

static bool fast_size_ok(int w, int h, int max_side)
{
    return w > 0 && h > 0 && w <= max_side && h <= max_side && (long)w * h <= FAST_MAX_PIXELS;
}

/* An 8- or 16-bit grey, grey+alpha, RGB or RGBA PNG without a transparency chunk; false leaves it to
 * OpenImageIO (which also words the errors). u8 takes 8-bit files only. */
static bool png_decode(const char *path, int max_side, bool u8, decoded *d)
{
    png_io io = {0};
    bool opened = png_open_read(path, &io);
    png_bytep *volatile rows = NULL; /* volatile: read again after libpng's longjmp */
    d->px = NULL;
    volatile bool ok = opened;
    if (!ok) {
        /* nothing to read with */
    } else if (setjmp(png_jmpbuf(io.png))) {
        ok = false;
    } else {
        png_init_io(io.png, io.f);
        png_read_info(io.png, io.info);
        int type = png_get_color_type(io.png, io.info), bits = png_get_bit_depth(io.png, io.info);
        d->w = (int)png_get_image_width(io.png, io.info);
        d->h = (int)png_get_image_height(io.png, io.info);
        ok = (bits == 8 || (bits == 16 && !u8)) && !(type & PNG_COLOR_MASK_PALETTE) &&
             !png_get_valid(io.png, io.info, PNG_INFO_tRNS) && fast_size_ok(d->w, d->h, max_side) &&
             png_get_interlace_type(io.png, io.info) == PNG_INTERLACE_NONE;
        if (ok) {
            if (bits == 16)
                png_set_swap(io.png); /* PNG is big-endian */
            d->c = png_get_channels(io.png, io.info);
            d->bits = bits;
            size_t row = (size_t)d->w * (size_t)d->c * (size_t)(bits / 8);
            d->px = malloc(row * (size_t)d->h);
            rows = malloc(sizeof *rows * (size_t)d->h);
            ok = d->px && rows;
            for (int y = 0; ok && y < d->h; y++)
                rows[y] = (png_bytep)d->px + row * (size_t)y;
            if (ok) {
                png_read_image(io.png, rows);
                png_read_end(io.png, NULL);
            }
        }
    }
    png_close_read(&io);
    free(rows);
    if (!ok) {
        free(d->px);
        d->px = NULL;
    }
    return ok;
}

typedef struct jpeg_fail {
    struct jpeg_error_mgr mgr;
    jmp_buf jump;
    bool warned; /* a corrupt stream libjpeg decodes on regardless: left to OpenImageIO */
} jpeg_fail;

static void jpeg_on_error(j_common_ptr c) { longjmp(((jpeg_fail *)c->err)->jump, 1); }

static void jpeg_on_message(j_common_ptr c, int level)
{
    if (level < 0)
        ((jpeg_fail *)c->err)->warned = true;
}

/* A grey or colour (YCbCr, RGB) baseline or progressive JPEG, as libjpeg-turbo decodes it by default
 * (what OpenImageIO's reader asks of it too); false leaves it to OpenImageIO. */
static bool jpeg_decode(const char *path, int max_side, decoded *d)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    struct jpeg_decompress_struct j;
    jpeg_fail fail = {0};
    j.err = jpeg_std_error(&fail.mgr);
    fail.mgr.error_exit = jpeg_on_error;
    fail.mgr.emit_message = jpeg_on_message;
    d->px = NULL;
    volatile bool ok = false;
    if (!setjmp(fail.jump)) {
        jpeg_create_decompress(&j);
        jpeg_stdio_src(&j, f);
        jpeg_read_header(&j, TRUE);
        bool colour = j.jpeg_color_space == JCS_YCbCr || j.jpeg_color_space == JCS_RGB;
        if ((colour || j.jpeg_color_space == JCS_GRAYSCALE) &&
            fast_size_ok((int)j.image_width, (int)j.image_height, max_side)) {
            j.out_color_space = colour ? JCS_RGB : JCS_GRAYSCALE;
            jpeg_start_decompress(&j);
            d->w = (int)j.output_width, d->h = (int)j.output_height, d->c = j.output_components, d->bits = 8;
            size_t row = (size_t)d->w * (size_t)d->c;
            d->px = malloc(row * (size_t)d->h);
            while (d->px && j.output_scanline < j.output_height) {
                JSAMPROW r = (JSAMPROW)d->px + row * j.output_scanline;
                jpeg_read_scanlines(&j, &r, 1);
            }
            if (d->px)
                jpeg_finish_decompress(&j);
            ok = d->px && !fail.warned;
        }
    }
    jpeg_destroy_decompress(&j);
    fclose(f);
    if (!ok) {
        free(d->px);
        d->px = NULL;
    }
    return ok;
}

static bool fast_decode(const char *path, int max_side, bool u8, decoded *d)
{
    const char *dot = strrchr(path, '.');
    if (!dot)
        return false;
    if (!strcasecmp(dot, ".png"))
        return png_decode(path, max_side, u8, d);
    if (!strcasecmp(dot, ".jpg") || !strcasecmp(dot, ".jpeg"))
        return jpeg_decode(path, max_side, d);
    return false;
}

/* The file's channels as `want` channels (0: as many as the file has), as image_io.cpp's reader maps
 * them: grey fills colour, a missing alpha is one, a grey file's second channel is alpha. Floats are
 * OpenImageIO's conversion, v · (1 / max). Frees d->px. */
static void *convert(decoded *d, int want, bool f32, int *channels_out)
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
    decoded d;
    if (fast_decode(path, max_side, true, &d)) {
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
    decoded d;
    if (fast_decode(path, max_side, false, &d)) {
        *width = d.w, *height = d.h;
        *pixels = convert(&d, channels, true, channels_out);
        return true;
    }
    LAZY_FN(bool (*f)(const char *, int, int, int *, int *, int *, float **, err_t *),
            lazy_symbol(LAZY_IMAGE, "oiio_read_f32", err));
    return f && f(path, channels, max_side, width, height, channels_out, pixels, err);
}
