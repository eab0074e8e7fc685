/* image_oiio — what fathom_image.so (image_io.cpp, over OpenImageIO) gives image_io.c, which loads it
 * on first use (data/lazy/lazy.h). Everything but a PNG written: EXR, reading any format. The module writes
 * only to the temporary file image_io.c names; closing, syncing, checking and renaming it over the
 * target are image_io.c's, for both codecs. */
#ifndef FATHOM_IMAGE_OIIO_H
#define FATHOM_IMAGE_OIIO_H

#include <stdbool.h>
#include <stdint.h>

#include "util.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct oiio_writer oiio_writer;

/* Opens tmp for writing in the format path's extension names (image_writer_open_text's arguments). */
oiio_writer *oiio_writer_open(const char *path, const char *tmp, int width, int height, int channels, bool f32,
                              const char *const *names, const char *const *texts, err_t *err);
bool oiio_writer_rows(oiio_writer *w, int first_row, int rows, const void *pixels, err_t *err);
/* Closes the file and frees w; false with err when the close failed. */
bool oiio_writer_close(oiio_writer *w, err_t *err);
/* Decodes every row of a written file: false with why when it does not read back as width × height ×
 * channels. */
bool oiio_verify(const char *file, int width, int height, int channels, err_t *err);

/* image_io.h's readers. */
bool oiio_read_u8(const char *path, int channels, int max_side, int *width, int *height, uint8_t **pixels, err_t *err);
bool oiio_read_f32(const char *path, int channels, int max_side, int *width, int *height, int *channels_out,
                   float **pixels, err_t *err);
bool oiio_read_text(const char *path, const char *key, char **value, err_t *err);

#ifdef __cplusplus
}
#endif

#endif
