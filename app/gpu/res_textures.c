/* res_textures — the materials' 2D textures (colour maps, relief heightmaps), units 0 … 3. */
#include <stdio.h>
#include <string.h>

#include "gpu/render_resource.h"
#include "gpu/texture.h"

/* what each texture was read from (path, size, mtime; the heights' flag): the next scene reuses a
 * texture read from the same unchanged file (a flight's every frame, preset and knob switches), and a
 * file changed on disk (R reload) is read again */
static struct {
    GLuint tex[SCENE_MAX_TEXTURES];
    char key[SCENE_MAX_TEXTURES][PATH_MAX_LEN + 64];
    int width[SCENE_MAX_TEXTURES]; /* heightmaps: texels across (relief step size) */
} state;

/* Each texture reused from the last scene when read from the same unchanged file, else read; the
 * last scene's others are freed. */
static bool set(const scene *s, err_t *err)
{
    GLuint old[SCENE_MAX_TEXTURES];
    char old_key[SCENE_MAX_TEXTURES][sizeof state.key[0]];
    int old_width[SCENE_MAX_TEXTURES];
    memcpy(old, state.tex, sizeof old);
    memcpy(old_key, state.key, sizeof old_key);
    memcpy(old_width, state.width, sizeof old_width);
    memset(state.tex, 0, sizeof state.tex);
    memset(state.key, 0, sizeof state.key);
    bool ok = true;
    for (int i = 0; ok && i < s->texture_count; i++) {
        char key[sizeof state.key[0]] = "";
        snprintf(key, sizeof key, "%d;", s->texture_linear[i]);
        render_file_key(s->textures[i], key, sizeof key);
        for (int j = 0; j < SCENE_MAX_TEXTURES && !state.tex[i]; j++)
            if (old[j] && !strcmp(old_key[j], key)) {
                state.tex[i] = old[j], state.width[i] = old_width[j];
                old[j] = 0;
            }
        if (!state.tex[i]) {
            int w = 0;
            state.tex[i] = i == 1 && render_resource_fault(res_textures.name, err) ? 0 /* as a read that failed */
                           : s->texture_linear[i]                                  ? texture_load_height(s->textures[i], &w, err)
                                                                                  : texture_load_2d(s->textures[i], err);
            state.width[i] = w;
            ok = state.tex[i] != 0;
        }
        if (ok)
            snprintf(state.key[i], sizeof state.key[i], "%s", key);
    }
    for (int j = 0; j < SCENE_MAX_TEXTURES; j++)
        if (old[j])
            glDeleteTextures(1, &old[j]);
    if (!ok) { /* nothing of s is held: the textures read before the one that failed go too */
        glDeleteTextures(SCENE_MAX_TEXTURES, state.tex);
        memset(&state, 0, sizeof state);
    }
    return ok;
}

/* Units, and the relief heightmaps' widths (a relief step is one texel). */
static void uniforms(const scene *s, const uniform_sink *u, int unit)
{
    static const char *const names[SCENE_MAX_TEXTURES] = {"uTex0", "uTex1", "uTex2", "uTex3"};
    for (int i = 0; i < SCENE_MAX_TEXTURES; i++)
        uniform_i(u, names[i], unit + i);
    float texels[SCENE_MAX_MATERIALS];
    for (int i = 0; i < s->material_count; i++)
        texels[i] = s->materials[i].relief >= 0 ? (float)state.width[s->materials[i].relief] : 1.0f;
    uniform_fv(u, "uMatReliefTexels", 1, s->material_count, texels);
}

static void bind(int unit)
{
    for (int i = 0; i < SCENE_MAX_TEXTURES; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)(unit + i));
        glBindTexture(GL_TEXTURE_2D, state.tex[i]);
    }
}

static void release(void)
{
    glDeleteTextures(SCENE_MAX_TEXTURES, state.tex);
    memset(&state, 0, sizeof state);
}

static int held(void)
{
    int n = 0;
    for (int i = 0; i < SCENE_MAX_TEXTURES; i++)
        n += state.tex[i] != 0;
    return n;
}

const render_resource res_textures = {"textures", set, SCENE_MAX_TEXTURES, uniforms, bind, release, held};
