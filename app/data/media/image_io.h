/* image_io — reading and writing images: PNG files are written, and clean PNG and JPEG files read,
 * with libpng and libjpeg-turbo (image_io.c); everything else goes through OpenImageIO (image_io.cpp
 * behind extern "C", no exception crossing it), loaded on first use (data/lazy/lazy.h).
 *
 * Rows are stored top row first in memory, as image files are.
 *
 * Writes are verified end to end: the image goes to a hidden temporary file in the target's folder
 * (streamed in bands of rows, so any size the format allows needs only a band in memory); after
 * close it is flushed to the disk (fsync), opened again and decoded in full, and only then renamed
 * over the target. A full disk, a file-size limit, an I/O error or a signal during the write gives
 * one error line and leaves neither the target nor the temporary file.
 *
 * Reads check the header before allocating: an image larger than the caller's limit is refused
 * with the limit in the message; decoders' own messages are folded into that one line.
 */
#ifndef FATHOM_IMAGE_IO_H
#define FATHOM_IMAGE_IO_H

#include <stdbool.h>
#include <stdint.h>

#include "util.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest image side read or written (GL_MAX_TEXTURE_SIZE on llvmpipe; outputs larger are tiled). */
enum { IMAGE_MAX_SIDE = 16384 };

/* ---- writing --------------------------------------------------------------------------------- */

typedef struct image_writer image_writer;

/* Starts writing a width × height image: 8-bit sRGB (f32 false) or 32-bit float (EXR) with named
 * channels (NULL: R, G, B, A). NULL on failure (err set). */
image_writer *image_writer_open(const char *path, int width, int height, int channels, bool f32,
                                const char *const *names, err_t *err);
/* The same with text entries stored in the file (PNG: tEXt chunks; EXR: string attributes): texts
 * holds key, value, key, value, …, NULL (NULL: none; a NULL value skips its key). fathom keeps the
 * scene, overrides and camera of a shot there, and where a tile sits in its poster. */
image_writer *image_writer_open_text(const char *path, int width, int height, int channels, bool f32,
                                     const char *const *names, const char *const *texts, err_t *err);
/* Appends `rows` rows (top first; uint8_t or float as opened, channels interleaved). */
bool image_writer_rows(image_writer *w, int rows, const void *pixels, err_t *err);
/* Closes, flushes, decodes the file again and renames it over the target. Frees w either way. */
bool image_writer_finish(image_writer *w, err_t *err);
/* Gives up: removes the temporary file and frees w. */
void image_writer_abort(image_writer *w);

/* Whole images in one call (the writer above, one band). */
bool image_write_u8(const char *path, int width, int height, int channels, const uint8_t *pixels, err_t *err);
bool image_write_f32(const char *path, int width, int height, int channels, const char *const *names,
                     const float *pixels, err_t *err);

/* Checked before a long render: the folder exists and is writable, and an existing target is a
 * regular file that is not read-only (mode without write bits: refused even for root). */
bool image_can_write(const char *path, err_t *err);

/* Removes the temporary file of a write in progress when SIGINT, SIGTERM, SIGHUP or SIGQUIT
 * arrives, then dies of the signal as it would have (and at exit()); SIGXFSZ is ignored so that a file-size limit
 * is an error the writer reports. Call once at start-up. */
void image_io_install_signal_cleanup(void);

/* ---- reading --------------------------------------------------------------------------------- */

/* Reads any image OpenImageIO knows as 8-bit, converted to `channels` channels (missing ones filled:
 * alpha = 255, grey copied). Images wider or taller than max_side are refused before allocating.
 * *pixels is malloc'd. */
bool image_read_u8(const char *path, int channels, int max_side, int *width, int *height, uint8_t **pixels,
                   err_t *err);

/* The text entry `key` of an image file (see image_writer_open_text): *value malloc'd, or false with
 * err set when the file cannot be read or has no such entry. */
bool image_read_text(const char *path, const char *key, char **value, err_t *err);

/* Reads as 32-bit float: `channels` channels, or the file's count when 0 (*channels_out). */
bool image_read_f32(const char *path, int channels, int max_side, int *width, int *height, int *channels_out,
                    float **pixels, err_t *err);

#ifdef __cplusplus
}
#endif

#endif
