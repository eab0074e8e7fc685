/* res_envmap — the environment cube map (six files), kept while they are unchanged. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gpu/render_resource.h"
#include "gpu/texture.h"

static struct {
    GLuint tex;
    char key[6 * (PATH_MAX_LEN + 64)];
    int size; /* texels across a face */
} state;

static void release(void)
{
    if (state.tex)
        glDeleteTextures(1, &state.tex);
    memset(&state, 0, sizeof state);
}

static bool set(const scene *s, err_t *err)
{
    if (!s->has_cubemap || !(s->effects & (1u << EFFECT_ENVMAP))) {
        release();
        return true;
    }
    char key[sizeof state.key] = "";
    for (int f = 0; f < 6; f++)
        render_file_key(s->cubemap[f], key, sizeof key);
    if (state.tex && !strcmp(key, state.key))
        return true;
    if (state.tex)
        glDeleteTextures(1, &state.tex);
    state.tex = texture_load_cube(s->cubemap, &state.size, err);
    snprintf(state.key, sizeof state.key, "%s", state.tex ? key : "");
    return state.tex != 0;
}

/* The unit, and the mip count that rough reflections blur over. */
static void uniforms(const scene *s, const uniform_sink *u)
{
    (void)s;
    uniform_i(u, "uEnvMap", RENDER_UNIT_ENVMAP);
    uniform_f(u, "uEnvMaxLod", state.size > 0 ? log2f((float)state.size) : 0.0f);
}

static void bind(void)
{
    glActiveTexture(GL_TEXTURE0 + RENDER_UNIT_ENVMAP);
    glBindTexture(GL_TEXTURE_CUBE_MAP, state.tex);
}

const render_resource res_envmap = {"cube map", set, uniforms, bind, release};
