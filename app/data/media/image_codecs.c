/* image_codecs — the two codecs image_io calls itself (image_codecs.h): libpng writes and checks PNG
 * files and reads clean ones, libjpeg-turbo reads clean JPEG files. */
#include "data/media/image_codecs.h"

#include <errno.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <jpeglib.h> /* after stdio.h: it uses FILE */

/* ---- PNG through libpng ----------------------------------------------------------------------------- */


static void png_fail(png_structp png, png_const_charp msg)
{
    image_png *io = png_get_error_ptr(png);
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

bool image_is_png(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && !strcasecmp(dot, ".png");
}

static const int PNG_COLOR[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                 PNG_COLOR_TYPE_RGBA};

/* Opens tmp and writes the header and the text entries; false with io->why. */
bool image_png_begin(image_png *io, const char *tmp, int width, int height, int channels, const char *const *texts)
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

bool image_png_rows(image_png *io, int rows, int width, int channels, const uint8_t *pixels)
{
    if (setjmp(png_jmpbuf(io->png)))
        return false;
    for (int y = 0; y < rows; y++)
        png_write_row(io->png, pixels + (size_t)y * (size_t)width * (size_t)channels);
    return true;
}

/* Ends the image and closes the file (write errors surface at the flush); false with io->why. */
bool image_png_end(image_png *io)
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

void image_png_drop(image_png *io)
{
    if (io->png)
        png_destroy_write_struct(&io->png, &io->info);
    if (io->f)
        fclose(io->f);
    io->f = NULL;
}

/* Opens path for libpng to read; false (io holding what it made) when it cannot. */
static bool png_open_read(const char *path, image_png *io)
{
    io->f = fopen(path, "rb");
    io->png = io->f ? png_create_read_struct(PNG_LIBPNG_VER_STRING, io, png_fail, png_quiet) : NULL;
    io->info = io->png ? png_create_info_struct(io->png) : NULL;
    return io->info != NULL;
}

static void png_close_read(image_png *io)
{
    if (io->png)
        png_destroy_read_struct(&io->png, &io->info, NULL);
    if (io->f)
        fclose(io->f);
    io->f = NULL;
}

/* Decodes every row: a truncated or corrupt file fails here. */
bool image_png_verify(const char *file, int width, int height, int channels, char *why, size_t n)
{
    image_png io = {0};
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


/* Taken here only while small: anything larger goes to OpenImageIO, whose reader checks it against the
 * machine's memory first. */
enum { FAST_MAX_PIXELS = 1 << 26 };

static bool fast_size_ok(int w, int h, int max_side)
{
    return w > 0 && h > 0 && w <= max_side && h <= max_side && (long)w * h <= FAST_MAX_PIXELS;
}

/* An 8- or 16-bit grey, grey+alpha, RGB or RGBA PNG without a transparency chunk; false leaves it to
 * OpenImageIO (which also words the errors). u8 takes 8-bit files only. */
static bool png_decode(const char *path, int max_side, bool u8, image_decoded *d)
{
    image_png io = {0};
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
static bool jpeg_decode(const char *path, int max_side, image_decoded *d)
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

bool image_fast_decode(const char *path, int max_side, bool u8, image_decoded *d)
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

