/* res_frag_textures — a Fragmentarium fragment's own textures (uniform sampler2D NAME; file[IMAGE], or
 * samplerCube: scene/formula/frag.h), units 0 … 3 of this kind, loaded as FragM loads them
 * (DisplayWidget's loadQtTexture and setTextureParms, read from its source): an image's bytes as they are
 * (not decoded from sRGB: the fragment does its own arithmetic on them), bottom row first, so texture()
 * at (0, 0) is the image's lower-left corner; .hdr and .exr as 32-bit floats; linear filtering without
 * mipmaps unless the fragment's #TexParameter lines say otherwise (wrap: GL_REPEAT, GL's own). A cube map is
 * six square faces stacked top to bottom (+X, −X, +Y, −Y, +Z, −Z), linear and clamped. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "data/media/image_io.h"
#include "gpu/render_resource.h"
#include "gpu/texture.h"
#include "scene/program.h"

static struct {
    GLuint tex[FRAG_TEXTURES_MAX];
    bool cube[FRAG_TEXTURES_MAX];
    char key[FRAG_TEXTURES_MAX][PATH_MAX_LEN + 64];
} state;

/* The fragment's textures, when the scene is a fragment's. */
static const formula *fragment_of(const scene *s)
{
    return s && program_is_fractal(s->program) && s->fractal.formula.fragment ? &s->fractal.formula : NULL;
}

/* A #TexParameter's GL enum by its name (0: none fathom knows). */
static GLenum gl_name(const char *w)
{
    static const struct { const char *name; GLenum value; } NAMES[] = {
        {"GL_TEXTURE_WRAP_S", GL_TEXTURE_WRAP_S}, {"GL_TEXTURE_WRAP_T", GL_TEXTURE_WRAP_T},
        {"GL_TEXTURE_MIN_FILTER", GL_TEXTURE_MIN_FILTER}, {"GL_TEXTURE_MAG_FILTER", GL_TEXTURE_MAG_FILTER},
        {"GL_REPEAT", GL_REPEAT}, {"GL_CLAMP_TO_EDGE", GL_CLAMP_TO_EDGE}, {"GL_CLAMP", GL_CLAMP_TO_EDGE},
        {"GL_MIRRORED_REPEAT", GL_MIRRORED_REPEAT}, {"GL_NEAREST", GL_NEAREST}, {"GL_LINEAR", GL_LINEAR},
        {"GL_NEAREST_MIPMAP_NEAREST", GL_NEAREST_MIPMAP_NEAREST}, {"GL_LINEAR_MIPMAP_NEAREST", GL_LINEAR_MIPMAP_NEAREST},
        {"GL_NEAREST_MIPMAP_LINEAR", GL_NEAREST_MIPMAP_LINEAR}, {"GL_LINEAR_MIPMAP_LINEAR", GL_LINEAR_MIPMAP_LINEAR}};
    for (size_t i = 0; i < sizeof NAMES / sizeof *NAMES; i++)
        if (!strcmp(w, NAMES[i].name))
            return NAMES[i].value;
    return 0;
}

static GLuint load(const formula *f, const frag_texture *t, err_t *err)
{
    GLint side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &side);
    const char *dot = strrchr(t->path, '.');
    bool hdr = dot && (!strcasecmp(dot, ".hdr") || !strcasecmp(dot, ".exr"));
    int w, h, c;
    void *px = NULL;
    if (hdr ? !image_read_f32(t->path, 4, t->cube ? 6 * side : side, &w, &h, &c, (float **)&px, err)
            : !image_read_u8(t->path, 4, t->cube ? 6 * side : side, &w, &h, (uint8_t **)&px, err))
        return 0;
    if (t->cube && h != 6 * w) {
        free(px);
        return err_set(err, "%s: a cube map for %s must be six square faces stacked (%dx%d is not)", t->path,
                       t->name, w, h), 0;
    }
    GLenum target = t->cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D, type = hdr ? GL_FLOAT : GL_UNSIGNED_BYTE;
    size_t texel = hdr ? 16 : 4;
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(target, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (t->cube) {
        for (int k = 0; k < 6; k++)
            glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)k, 0, hdr ? GL_RGBA32F : GL_RGBA8, w, w, 0, GL_RGBA,
                         type, (const uint8_t *)px + (size_t)k * (size_t)w * (size_t)w * texel);
        glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    } else {
        texture_flip_rows(px, h, (size_t)w * texel); /* bottom row first */
        glTexImage2D(GL_TEXTURE_2D, 0, hdr ? GL_RGBA32F : GL_RGBA8, w, h, 0, GL_RGBA, type, px);
    }
    free(px);
    GLint min = GL_LINEAR, mag = GL_LINEAR, ws = t->cube ? GL_CLAMP_TO_EDGE : GL_REPEAT, wt = ws;
    for (int i = 0; i < f->frag_texparam_count && !t->cube; i++) {
        GLenum key = gl_name(f->frag_texparams[i][1]), value = gl_name(f->frag_texparams[i][2]);
        if (strcmp(f->frag_texparams[i][0], t->name) || !value)
            continue;
        *(key == GL_TEXTURE_WRAP_S ? &ws : key == GL_TEXTURE_WRAP_T ? &wt : key == GL_TEXTURE_MIN_FILTER ? &min
          : &mag) = (GLint)value;
    }
    bool mips = min != GL_LINEAR && min != GL_NEAREST;
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, min);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, mag == GL_NEAREST ? GL_NEAREST : GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, ws);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, wt);
    glTexParameteri(target, GL_TEXTURE_MAX_LEVEL, mips ? 1000 : 0);
    if (mips)
        glGenerateMipmap(target);
    glBindTexture(target, 0);
    if (glGetError() != GL_NO_ERROR) {
        glDeleteTextures(1, &tex);
        return err_set(err, "%s: the GPU cannot hold the texture %s (%dx%d)", t->path, t->name, w, h), 0;
    }
    return tex;
}

/* Each texture reused from the last scene when read from the same unchanged file with the same
 * parameters, else read; the last scene's others are freed. */
static bool set(const scene *s, err_t *err)
{
    const formula *f = fragment_of(s);
    int n = f ? f->frag_texture_count : 0;
    GLuint old[FRAG_TEXTURES_MAX];
    char old_key[FRAG_TEXTURES_MAX][sizeof state.key[0]];
    memcpy(old, state.tex, sizeof old);
    memcpy(old_key, state.key, sizeof old_key);
    memset(&state, 0, sizeof state);
    bool ok = true;
    for (int i = 0; ok && i < n; i++) {
        const frag_texture *t = &f->frag_textures[i];
        char key[sizeof state.key[0]] = "";
        for (int k = 0; k < f->frag_texparam_count; k++)
            if (!strcmp(f->frag_texparams[k][0], t->name))
                snprintf(key + strlen(key), sizeof key - strlen(key), "%s=%s;", f->frag_texparams[k][1],
                         f->frag_texparams[k][2]);
        render_file_key(t->path, key, sizeof key);
        for (int j = 0; j < FRAG_TEXTURES_MAX && !state.tex[i]; j++)
            if (old[j] && !strcmp(old_key[j], key))
                state.tex[i] = old[j], old[j] = 0;
        if (!state.tex[i])
            state.tex[i] = i == 0 && render_resource_fault(res_frag_textures.name, err) ? 0 : load(f, t, err);
        ok = state.tex[i] != 0;
        state.cube[i] = t->cube;
        snprintf(state.key[i], sizeof state.key[i], "%s", key);
    }
    for (int j = 0; j < FRAG_TEXTURES_MAX; j++)
        if (old[j])
            glDeleteTextures(1, &old[j]);
    if (!ok) { /* nothing of s is held */
        glDeleteTextures(FRAG_TEXTURES_MAX, state.tex);
        memset(&state, 0, sizeof state);
    }
    return ok;
}

static void uniforms(const scene *s, const uniform_sink *u, int unit)
{
    const formula *f = fragment_of(s);
    for (int i = 0; f && i < f->frag_texture_count; i++)
        uniform_i(u, f->frag_textures[i].name, unit + i);
}

static void bind(int unit)
{
    for (int i = 0; i < FRAG_TEXTURES_MAX; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)(unit + i));
        glBindTexture(state.cube[i] ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D, state.tex[i]);
    }
}

static void release(void)
{
    glDeleteTextures(FRAG_TEXTURES_MAX, state.tex);
    memset(&state, 0, sizeof state);
}

static int held(void)
{
    int n = 0;
    for (int i = 0; i < FRAG_TEXTURES_MAX; i++)
        n += state.tex[i] != 0;
    return n;
}

const render_resource res_frag_textures = {"fragment textures", set, FRAG_TEXTURES_MAX, uniforms, bind, release, held};
