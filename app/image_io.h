/* image_io — reading and writing images through OpenImageIO (the only C++ file, behind extern "C").
 *
 * Rows are stored top row first in memory, as image files are. Writes are atomic: the image goes
 * to a temporary file in the same folder, then is renamed over the target, so a failed or
 * interrupted write never leaves a partial file.
 */
#ifndef FATHOM_IMAGE_IO_H
#define FATHOM_IMAGE_IO_H

#include <stdbool.h>
#include <stdint.h>

#include "util.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 8-bit image (e.g. sRGB PNG) with `channels` interleaved channels. */
bool image_write_u8(const char *path, int width, int height, int channels, const uint8_t *pixels, err_t *err);

/* Float image (EXR: half is not used, channels stay 32-bit) with named channels (NULL: R,G,B,A). */
bool image_write_f32(const char *path, int width, int height, int channels, const char *const *names,
                     const float *pixels, err_t *err);

/* Reads any image OpenImageIO knows as 8-bit, converted to `channels` channels (missing ones
 * filled: alpha = 255, grey copied). *pixels is malloc'd. */
bool image_read_u8(const char *path, int channels, int *width, int *height, uint8_t **pixels, err_t *err);

/* Reads as 32-bit float, keeping the file's channel count; *pixels is malloc'd. */
bool image_read_f32(const char *path, int *width, int *height, int *channels, float **pixels, err_t *err);

/* True when `path`'s folder exists and is writable: checked before a long render. */
bool image_can_write(const char *path, err_t *err);

#ifdef __cplusplus
}
#endif

#endif
