/* res_imagery — a terrain's draped imagery (terrain.imagery): every layer warped by GDAL onto the DEM's
 * extent in its CRS (data/geo.h), composited in order with its opacity ("over"), one sRGB texture with
 * mipmaps and the driver's anisotropic filtering where it has it. Alpha is the imagery's coverage:
 * shaders/terrain/layers.glsl shows the terrain's own layers where it is 0. Kept while the next scene
 * drapes the same unchanged files on the same DEM. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/geo.h"
#include "gpu/render_resource.h"
#include "gpu/texture.h"

enum { IMAGERY_MAX_SIDE = 8192 }; /* 256 MB of RGBA with mipmaps at most */

static struct {
    GLuint tex;
    char key[SCENE_MAX_IMAGERY * (PATH_MAX_LEN + 96) + PATH_MAX_LEN + 96];
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

static bool set(const scene *s, err_t *err)
{
    const struct scene_terrain *t = &s->terrain;
    if (!t->imagery_count || !t->heightmap[0]) {
        release();
        return true;
    }
    char key[sizeof state.key] = "";
    render_file_key(t->heightmap, key, sizeof key);
    for (int i = 0; i < t->imagery_count; i++) {
        size_t n = strlen(key);
        snprintf(key + n, sizeof key - n, "%.4f;", (double)t->imagery_opacity[i]);
        render_file_key(t->imagery[i], key, sizeof key);
    }
    if (state.tex && !strcmp(key, state.key))
        return true;
    release();
    GLint most = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &most);
    int side = most < IMAGERY_MAX_SIDE ? most : IMAGERY_MAX_SIDE, w = 0, h = 0;
    unsigned char *all = NULL;
    bool ok = true;
    for (int i = 0; ok && i < t->imagery_count; i++) { /* the first layer sets the size; the rest match it */
        unsigned char *layer = NULL;
        ok = geo_drape(t->heightmap, t->imagery[i], side, &layer, &w, &h, err);
        if (ok && !all) {
            all = calloc(4 * (size_t)w * (size_t)h, 1);
            ok = all || err_set(err, "out of memory for the imagery (%d x %d)", w, h);
        }
        if (ok)
            over(all, layer, (size_t)w * (size_t)h, t->imagery_opacity[i]);
        free(layer);
    }
    err_t fault;
    ok = ok && (upload(all, w, h) || err_set(err, "the GPU driver refused the imagery's %d x %d texture: give a smaller "
                                                  "one (gdal_translate -outsize)", w, h));
    if (ok && render_resource_fault(res_imagery.name, &fault))
        ok = err_set(err, "%s", fault.msg);
    free(all);
    if (!ok) {
        release();
        return false;
    }
    fprintf(stderr, "fathom: imagery: %d layer%s draped at %d x %d\n", t->imagery_count, t->imagery_count > 1 ? "s" : "",
            w, h);
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
