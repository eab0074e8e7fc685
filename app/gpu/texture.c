#include "gpu/texture.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "data/media/image_io.h"

GLuint texture_mipmapped_2d(GLint internal, int w, int h, GLenum format, GLenum type, const void *px, GLint align,
                            GLint wrap)
{
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, align);
    glTexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, type, px);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
    return tex;
}

/* The GL's limit (16384 on llvmpipe), and never more than image_io reads. */
static int max_side(void)
{
    GLint n = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &n);
    return n > 0 && n < IMAGE_MAX_SIDE ? n : IMAGE_MAX_SIDE;
}

GLuint texture_load_2d(const char *path, err_t *err)
{
    int w, h;
    uint8_t *px;
    if (!image_read_u8(path, 4, max_side(), &w, &h, &px, err))
        return 0;
    /* Row order does not matter for a tiling texture; keep the file's. */
    GLuint tex = texture_mipmapped_2d(GL_SRGB8_ALPHA8, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px, 1, GL_REPEAT);
    free(px);
    return tex;
}

GLuint texture_load_height(const char *path, int *width, err_t *err)
{
    int w, h, c;
    float *px;
    if (!image_read_f32(path, 1, max_side(), &w, &h, &c, &px, err))
        return 0;
    float *one = util_alloc(sizeof(float) * (size_t)w * (size_t)h, "a relief heightmap");
    float lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < w * h; i++) {
        one[i] = px[(size_t)i * (size_t)c];
        lo = one[i] < lo ? one[i] : lo;
        hi = one[i] > hi ? one[i] : hi;
    }
    for (int i = 0; i < w * h; i++) /* 0 deepest, 1 the surface */
        one[i] = hi > lo ? (one[i] - lo) / (hi - lo) : 1.0f;
    free(px);
    GLuint tex = texture_mipmapped_2d(GL_R32F, w, h, GL_RED, GL_FLOAT, one, 4, GL_REPEAT);
    free(one);
    *width = w;
    return tex;
}

GLuint texture_load_cube(const char (*faces)[PATH_MAX_LEN], int *size, err_t *err)
{
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_CUBE_MAP, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    int first = 0;
    for (int i = 0; i < 6; i++) {
        int w, h;
        uint8_t *px;
        if (!image_read_u8(faces[i], 4, max_side(), &w, &h, &px, err)) {
            glDeleteTextures(1, &tex);
            return 0;
        }
        if (w != h || (i > 0 && w != first)) {
            free(px);
            glDeleteTextures(1, &tex);
            err_set(err, "cube-map face '%s' is %dx%d: faces must be square and all the same size", faces[i], w, h);
            return 0;
        }
        first = w;
        /* GL reads the first row as t = 0, which the cube-map convention puts at the top of each side
         * face: image files (top row first) load as they are. */
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)i, 0, GL_SRGB8_ALPHA8, w, h, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, px);
        free(px);
    }
    glGenerateMipmap(GL_TEXTURE_CUBE_MAP);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    *size = first;
    return tex;
}

bool texture_buffer(GLenum format, const void *data, size_t bytes, GLuint *buf, GLuint *tex)
{
    glGenBuffers(1, buf);
    glBindBuffer(GL_TEXTURE_BUFFER, *buf);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)bytes, data, GL_STATIC_DRAW);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    if (glGetError() == GL_OUT_OF_MEMORY) {
        glDeleteBuffers(1, buf);
        *buf = 0;
        return false;
    }
    glGenTextures(1, tex);
    glBindTexture(GL_TEXTURE_BUFFER, *tex);
    glTexBuffer(GL_TEXTURE_BUFFER, format, *buf);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    return true;
}

void texture_flip_rows(void *data, int height, size_t row_bytes)
{
    uint8_t *p = data, *tmp = util_alloc(row_bytes, "a row of the image");
    for (int y = 0; y < height / 2; y++) {
        uint8_t *a = p + (size_t)y * row_bytes, *b = p + (size_t)(height - 1 - y) * row_bytes;
        memcpy(tmp, a, row_bytes);
        memcpy(a, b, row_bytes);
        memcpy(b, tmp, row_bytes);
    }
    free(tmp);
}
