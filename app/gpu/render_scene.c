/* render_scene — the current scene and its GPU resources (render_scene.h). */
#include "gpu/render_scene.h"

#include <stdlib.h>
#include <string.h>

#include "gpu/render_resource.h"

/* Upload order (and unit order: the material textures first, at 0): a failure leaves the later kinds
 * as they were. */
static const render_resource *const RESOURCES[] = {&res_textures, &res_heightfield, &res_imagery, &res_csg_list, &res_droplets,
                                                   &res_envmap, &res_frag_textures};
enum { RESOURCE_COUNT = sizeof RESOURCES / sizeof RESOURCES[0] };

static struct {
    scene scene; /* a copy, with map_glsl pointing to our own copy of the caller's */
    char *map_glsl;
    bool have_scene;
} state;

bool render_scene_set(const scene *s, err_t *err)
{
    state.have_scene = false;
    for (int i = 0; i < RESOURCE_COUNT; i++)
        if (!RESOURCES[i]->set(s, err))
            return false;
    state.scene = *s;
    free(state.map_glsl);
    state.map_glsl = s->map_glsl ? util_strdup(s->map_glsl) : NULL;
    state.scene.map_glsl = state.map_glsl; /* its own copy: probes of the current scene compile with it */
    state.scene.csg_list = state.scene.csg_nodes = NULL;
    state.have_scene = true;
    return true;
}

const scene *render_scene_current(void) { return state.have_scene ? &state.scene : NULL; }

/* A uniform_sink that uploads to one GL program; names the program does not use are skipped. */
static void gl_set(void *user, const char *name, uniform_type type, int comps, int count, const void *data)
{
    GLint loc = glGetUniformLocation(*(const GLuint *)user, name);
    if (loc < 0 || count <= 0)
        return;
    const float *f = data;
    const GLint *i = data;
    switch (comps * 2 + (type == UNIFORM_INT)) {
    case 2: glUniform1fv(loc, count, f); break;
    case 3: glUniform1iv(loc, count, i); break;
    case 4: glUniform2fv(loc, count, f); break;
    case 5: glUniform2iv(loc, count, i); break;
    case 6: glUniform3fv(loc, count, f); break;
    case 7: glUniform3iv(loc, count, i); break;
    case 8: glUniform4fv(loc, count, f); break;
    default: glUniform4iv(loc, count, i); break;
    }
}

void render_scene_uniforms(GLuint prog, const scene *s)
{
    glUseProgram(prog);
    uniform_sink u = {gl_set, &prog};
    scene_uniforms(s, &u);
    bool current = state.have_scene && !strcmp(state.scene.path, s->path) &&
                   !strcmp(state.scene.terrain.heightmap, s->terrain.heightmap);
    if (!current)
        return;
    for (int i = 0, unit = 0; i < RESOURCE_COUNT; unit += RESOURCES[i++]->units)
        RESOURCES[i]->uniforms(s, &u, unit);
}

void render_scene_bind(void)
{
    for (int i = 0, unit = 0; i < RESOURCE_COUNT; unit += RESOURCES[i++]->units)
        RESOURCES[i]->bind(unit);
    glActiveTexture(GL_TEXTURE0);
}

int render_scene_units_end(void)
{
    int unit = 0;
    for (int i = 0; i < RESOURCE_COUNT; i++)
        unit += RESOURCES[i]->units;
    return unit;
}

void render_scene_release(void)
{
    for (int i = 0; i < RESOURCE_COUNT; i++)
        RESOURCES[i]->release();
    state.have_scene = false;
}

void render_scene_shutdown(void)
{
    render_scene_release();
    free(state.map_glsl);
    memset(&state, 0, sizeof state);
}
