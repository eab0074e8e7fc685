/* render_programs — the program cache and the full-screen VAO (render_programs.h). */
#include "gpu/render_programs.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/shader.h"

enum { MAX_PROGRAMS = 64 };

typedef struct cached_program {
    const char *frag;     /* sdf.frag or sdf.comp (the image), probe.frag (map() at points), fogprobe.frag */
    char *preamble, *map; /* the key */
    GLuint prog;
} cached_program;

static struct {
    char shader_root[PATH_MAX_LEN];
    GLuint vao;
    cached_program programs[MAX_PROGRAMS];
    int count;
} cache;

void render_programs_init(void)
{
    snprintf(cache.shader_root, sizeof cache.shader_root, "%s/shaders", util_data_dir());
    glGenVertexArrays(1, &cache.vao);
    glBindVertexArray(cache.vao);
}

GLuint render_programs_vao(void) { return cache.vao; }

const char *render_programs_shader_root(void) { return cache.shader_root; }

static void drop(cached_program *c)
{
    glDeleteProgram(c->prog);
    free(c->preamble);
    free(c->map);
}

void render_programs_shutdown(void)
{
    for (int i = 0; i < cache.count; i++)
        drop(&cache.programs[i]);
    glDeleteVertexArrays(1, &cache.vao);
    memset(&cache, 0, sizeof cache);
}

/* The loop budget of an invocation (shaders/common/budget.glsl): on llvmpipe below its loop limiter's
 * 65,535 iterations, with room for the loops fathom does not count (lights, AO samples, refinement, a
 * terrain's own traversal); elsewhere none (the shader's default). */
enum { LLVMPIPE_LOOP_LIMIT = 65535, LOOP_BUDGET_SLACK = 2048 };
static bool llvmpipe(void)
{
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    return renderer && strstr(renderer, "llvmpipe");
}

static void loop_budget(const char *preamble, strbuf *out)
{
    if (llvmpipe())
        sb_printf(out, "#define LOOP_BUDGET %d\n", LLVMPIPE_LOOP_LIMIT - LOOP_BUDGET_SLACK);
    sb_append(out, preamble ? preamble : "");
}

int render_programs_loop_limit(void) { return llvmpipe() ? LLVMPIPE_LOOP_LIMIT : 0; }

const char *render_programs_loop_budget_text(void)
{
    static char text[128];
    if (llvmpipe())
        snprintf(text, sizeof text, "%d loop iterations a pixel: llvmpipe ends every loop after %d",
                 LLVMPIPE_LOOP_LIMIT - LOOP_BUDGET_SLACK, LLVMPIPE_LOOP_LIMIT);
    else
        snprintf(text, sizeof text, "the driver cut the pixel's loops short");
    return text;
}

/* frag: a fragment shader drawn over fullscreen.vert, or a compute shader (a name ending in .comp). */
static GLuint build(const char *frag, const char *preamble, const char *map, err_t *err)
{
    shader_virtual virt[] = {{"program.glsl", map}};
    size_t n = strlen(frag);
    strbuf pre = {0};
    loop_budget(preamble, &pre);
    GLuint prog = n > 5 && !strcmp(frag + n - 5, ".comp")
                      ? shader_build_compute(cache.shader_root, frag, pre.data, virt, 1, err)
                      : shader_build(cache.shader_root, "fullscreen.vert", frag, pre.data, virt, 1, err);
    sb_free(&pre);
    return prog;
}

GLuint render_programs_get(const scene *s, const char *frag, const char *extra_defines, err_t *err)
{
    strbuf pre = {0};
    scene_preamble(s, &pre);
    if (extra_defines)
        sb_append(&pre, extra_defines);
    for (int i = 0; i < cache.count; i++) {
        cached_program *c = &cache.programs[i];
        if (!strcmp(c->frag, frag) && !strcmp(c->preamble, pre.data) && !strcmp(c->map, s->map_glsl)) {
            sb_free(&pre);
            return c->prog;
        }
    }
    GLuint prog = build(frag, pre.data, s->map_glsl, err);
    if (!prog) {
        sb_free(&pre);
        return 0;
    }
    if (cache.count == MAX_PROGRAMS) { /* evict the oldest */
        drop(&cache.programs[0]);
        memmove(cache.programs, cache.programs + 1, sizeof cache.programs[0] * (MAX_PROGRAMS - 1));
        cache.count--;
    }
    cache.programs[cache.count++] =
        (cached_program){.frag = frag, .preamble = pre.data, .map = util_strdup(s->map_glsl), .prog = prog};
    return prog;
}

bool render_programs_reload(GLuint *current, err_t *err)
{
    /* Build everything first: one failure keeps every old program. */
    GLuint fresh[MAX_PROGRAMS];
    for (int i = 0; i < cache.count; i++) {
        cached_program *c = &cache.programs[i];
        fresh[i] = build(c->frag, c->preamble, c->map, err);
        if (!fresh[i]) {
            for (int k = 0; k < i; k++)
                glDeleteProgram(fresh[k]);
            return false;
        }
    }
    for (int i = 0; i < cache.count; i++) {
        if (cache.programs[i].prog == *current)
            *current = fresh[i];
        glDeleteProgram(cache.programs[i].prog);
        cache.programs[i].prog = fresh[i];
    }
    return true;
}
