/* res_imagery — a terrain's drape: its imagery (terrain.imagery), every layer warped by GDAL onto the
 * DEM's extent in its CRS (data/geo/geo.h), then its vectors (terrain.vectors: tracks, paths, places burnt
 * in their colour and width), composited in order with their opacity ("over"), one sRGB texture with
 * mipmaps and the driver's anisotropic filtering where it has it. Alpha is the imagery's coverage:
 * shaders/terrain/layers.glsl shows the terrain's own layers where it is 0. Kept while the next scene
 * drapes the same unchanged files on the same DEM. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/geo/geo.h"
#include "gpu/render_resource.h"
#include "gpu/texture.h"

enum { IMAGERY_MAX_SIDE = 8192 }; /* 256 MB of RGBA with mipmaps at most */

static struct {
    GLuint tex;
    char key[2 * SCENE_MAX_IMAGERY * (PATH_MAX_LEN + 128) + PATH_MAX_LEN + 96];
} state;

static void release(void)
{
    glDeleteTextures(1, &state.tex);
    memset(&state, 0, sizeof state);
}

static int held(void) { return state.tex != 0; }

/* dst = src over dst, src's alpha scaled by opacity (straight, not premultiplied, alpha). */
static void over(unsigned char *dst, const unsigned char *src, size_t n, float opacity)
{
    for (size_t k = 0; k < n; k++) {
        const unsigned char *s = src + 4 * k;
        unsigned char *d = dst + 4 * k;
        float a = s[3] / 255.0f * opacity, b = d[3] / 255.0f, out = a + b * (1 - a);
        for (int c = 0; c < 3 && out > 0; c++)
            d[c] = (unsigned char)lrintf((s[c] * a + d[c] * b * (1 - a)) / out);
        d[3] = (unsigned char)lrintf(out * 255);
    }
}

static bool upload(const unsigned char *rgba, int w, int h)
{
    state.tex = texture_mipmapped_2d(GL_SRGB8_ALPHA8, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba, 4, GL_CLAMP_TO_EDGE);
    if (epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic") ||
        epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic")) {
        GLfloat most = 1;
        glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &most);
        glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY_EXT, fminf(most, 16));
    }
    return glGetError() != GL_OUT_OF_MEMORY;
}

/* The cache key: the DEM and every layer's file, opacity, colour and width. */
static void drape_key(const struct scene_terrain *t, char *key, size_t n)
{
    key[0] = '\0';
    render_file_key(t->heightmap, key, n);
    for (int i = 0; i < t->imagery_count; i++) {
        size_t k = strlen(key);
        snprintf(key + k, n - k, "%.4f;", (double)t->imagery_opacity[i]);
        render_file_key(t->imagery[i], key, n);
    }
    for (int i = 0; i < t->vector_count; i++) {
        const float *c = t->vector_color[i];
        size_t k = strlen(key);
        snprintf(key + k, n - k, "v%.4f,%.4f,%.4f,%.4f,%.3f;", (double)c[0], (double)c[1], (double)c[2], (double)c[3],
                 (double)t->vector_width[i]);
        render_file_key(t->vectors[i], key, n);
    }
}

/* Every layer composited at one size (geo_layers_size): the first imagery's own, or finer where a vector layer
 * needs two texels across its lines. */
static unsigned char *composite(const struct scene_terrain *t, int side, int *w, int *h, err_t *err)
{
    if (!geo_layers_size(t->heightmap, t->imagery_count ? t->imagery[0] : NULL, t->vector_width, t->vector_count,
                         side, w, h, err))
        return NULL;
    unsigned char *all = NULL, *layer = NULL;
    bool ok = true;
    for (int i = 0; ok && i < t->imagery_count; i++) {
        int lw = *w, lh = *h;
        ok = geo_drape(t->heightmap, t->imagery[i], side, &layer, &lw, &lh, err);
        if (ok && !all)
            all = util_calloc(4 * (size_t)*w * (size_t)*h, 1, "the draped imagery");
        if (ok)
            over(all, layer, (size_t)*w * (size_t)*h, t->imagery_opacity[i]);
        free(layer);
        layer = NULL;
    }
    if (ok && !all)
        all = util_calloc(4 * (size_t)*w * (size_t)*h, 1, "the draped vectors");
    layer = ok && t->vector_count ? util_alloc(4 * (size_t)*w * (size_t)*h, "a vector layer") : NULL;
    for (int i = 0; ok && i < t->vector_count; i++) {
        const float *c = t->vector_color[i];
        ok = geo_vectors(t->heightmap, t->vectors[i], t->vector_width[i], (const float[4]){c[0], c[1], c[2], 1}, *w,
                         *h, layer, err);
        if (ok)
            over(all, layer, (size_t)*w * (size_t)*h, c[3]);
    }
    free(layer);
    if (!ok) {
        free(all);
        return NULL;
    }
    return all;
}

static bool set(const scene *s, err_t *err)
{
    const struct scene_terrain *t = &s->terrain;
    if ((!t->imagery_count && !t->vector_count) || !t->heightmap[0]) {
        release();
        return true;
    }
    char key[sizeof state.key];
    drape_key(t, key, sizeof key);
    if (state.tex && !strcmp(key, state.key))
        return true;
    release();
    GLint most = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &most);
    int side = most < IMAGERY_MAX_SIDE ? most : IMAGERY_MAX_SIDE, w, h;
    unsigned char *all = composite(t, side, &w, &h, err);
    err_t fault;
    bool ok = all && (upload(all, w, h) || err_set(err, "the GPU driver refused the imagery's %d x %d texture: give a "
                                                        "smaller one (gdal_translate -outsize)", w, h));
    if (ok && render_resource_fault(res_imagery.name, &fault))
        ok = err_set(err, "%s", fault.msg);
    free(all);
    if (!ok) {
        release();
        return false;
    }
    fprintf(stderr, "fathom: drape: %d imagery and %d vector layer%s at %d x %d\n", t->imagery_count, t->vector_count,
            t->vector_count == 1 ? "" : "s", w, h);
    snprintf(state.key, sizeof state.key, "%s", key);
    return true;
}

static void uniforms(const scene *s, const uniform_sink *u, int unit)
{
    (void)s;
    uniform_i(u, "uImagery", unit);
}

static void bind(int unit)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, state.tex);
}

const render_resource res_imagery = {"imagery", set, 1, uniforms, bind, release, held};
