/* texture — GL textures from image files: colour textures are sRGB, mipmapped and trilinear;
 * cube maps filter seamlessly. Anisotropic filtering is done in the shader (common/material.glsl):
 * llvmpipe's hardware-style anisotropic path measured 65× slower than trilinear at 256×144, and the
 * shader's taps give the same image on every driver. */
#ifndef FATHOM_TEXTURE_H
#define FATHOM_TEXTURE_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stddef.h>

#include "util.h"

/* 0 and err when the file cannot be read. */
GLuint texture_load_2d(const char *path, err_t *err);
/* A mipmapped, trilinear 2D texture from one level of pixels, wrapping as `wrap` says (GL_REPEAT for a
 * tiling texture, GL_CLAMP_TO_EDGE for one that covers something once). */
GLuint texture_mipmapped_2d(GLint internal, int w, int h, GLenum format, GLenum type, const void *px, GLint align,
                            GLint wrap);

/* A heightmap as linear float (first channel), mipmapped, repeating: for parallax occlusion. *width
 * gets its width in texels. */
GLuint texture_load_height(const char *path, int *width, err_t *err);

/* faces in GL order +X, -X, +Y, -Y, +Z, -Z; all square and the same size. *size gets the face size. */
GLuint texture_load_cube(const char (*faces)[PATH_MAX_LEN], int *size, err_t *err);

/* Reverses the order of `height` rows of row_bytes each, in place: GL's rows run bottom to top, files' top to
 * bottom. */
void texture_flip_rows(void *rows, int height, size_t row_bytes);

/* A texture buffer over `bytes` of data in `format` (shaders read it with texelFetch); false when the
 * GPU is out of memory (then nothing is left allocated). */
bool texture_buffer(GLenum format, const void *data, size_t bytes, GLuint *buf, GLuint *tex);

#endif
