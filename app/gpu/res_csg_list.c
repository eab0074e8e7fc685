/* res_csg_list — the csg program's primitive list and its BVH as RGBA32F texel rows
 * (shaders/csg/list.glsl), made from the scene itself (app/scene/scene_csg.c): no file, no key. */
#include <stdlib.h>
#include <string.h>

#include "gpu/render_resource.h"

static struct {
    GLuint list_tex, nodes_tex;
} state;

static void release(void)
{
    glDeleteTextures(1, &state.list_tex); /* each on its own: a half-made upload holds one */
    glDeleteTextures(1, &state.nodes_tex);
    memset(&state, 0, sizeof state);
}

static int held(void) { return (state.list_tex != 0) + (state.nodes_tex != 0); }

/* texels RGBA texels, row-major in rows CSG_TEXTURE_WIDTH wide (shaders/csg/list.glsl). */
static GLuint texel_texture(const float *data, int texels)
{
    int rows = (texels + CSG_TEXTURE_WIDTH - 1) / CSG_TEXTURE_WIDTH;
    float *padded = calloc((size_t)rows * CSG_TEXTURE_WIDTH * 4, sizeof(float));
    if (!padded)
        return 0;
    memcpy(padded, data, sizeof(float) * 4 * (size_t)texels);
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, CSG_TEXTURE_WIDTH, rows, 0, GL_RGBA, GL_FLOAT, padded);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    free(padded);
    return t;
}

static bool set(const scene *s, err_t *err)
{
    release();
    if (s->csg_list_count == 0)
        return true;
    state.list_tex = texel_texture(s->csg_list, s->csg_list_count * CSG_LIST_TEXELS);
    err_t fault;
    state.nodes_tex = render_resource_fault(res_csg_list.name, &fault)
                          ? 0
                          : texel_texture(s->csg_nodes, s->csg_node_count * CSG_NODE_TEXELS);
    if (!state.list_tex || !state.nodes_tex) {
        release(); /* nothing of s is held */
        return err_set(err, "%s: out of memory for %d primitives", s->path, s->csg_list_count);
    }
    return true;
}

static void uniforms(const scene *s, const uniform_sink *u, int unit)
{
    (void)s;
    uniform_i(u, "uCsgList", unit);
    uniform_i(u, "uCsgNodes", unit + 1);
}

static void bind(int unit)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, state.list_tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 1);
    glBindTexture(GL_TEXTURE_2D, state.nodes_tex);
}

const render_resource res_csg_list = {"csg primitive list", set, 2, uniforms, bind, release, held};
