/* image_codecs — what image_io.c reads and writes without OpenImageIO: PNG through libpng (a writer's
 * rows into a temporary file, then every row decoded again to check it) and clean PNG and JPEG files
 * read at once (anything odd goes to OpenImageIO, which also words the errors). Internal to image_io.
 * No GL. */
#ifndef FATHOM_IMAGE_CODECS_H
#define FATHOM_IMAGE_CODECS_H

#include <png.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef struct image_png {
    png_structp png;
    png_infop info;
    FILE *f;
    char why[256]; /* libpng's message */
} image_png;


/* A decoded image: c channels of 8- or 16-bit values (native order), rows top first. */
typedef struct image_decoded {
    int w, h, c, bits;
    void *px;
} image_decoded;

/* A .png name (any case). */
bool image_is_png(const char *path);
/* Writing a PNG: opens tmp and writes the header and the text entries (key, value pairs, NULL-ended);
 * then rows; then the end. False with io->why; image_png_drop frees what a failed or dropped one holds. */
bool image_png_begin(image_png *io, const char *tmp, int width, int height, int channels, const char *const *texts);
bool image_png_rows(image_png *io, int rows, int width, int channels, const uint8_t *pixels);
bool image_png_end(image_png *io);
void image_png_drop(image_png *io);
/* Decodes every row of a written file: a truncated or corrupt one fails (why: libpng's words). */
bool image_png_verify(const char *file, int width, int height, int channels, char *why, size_t n);
/* A clean PNG (8- or 16-bit grey, grey+alpha, RGB or RGBA, no transparency chunk, not interlaced; u8:
 * 8-bit only) or JPEG of at most max_side a side, decoded; false leaves it to OpenImageIO. */
bool image_fast_decode(const char *path, int max_side, bool u8, image_decoded *d);

#endif
