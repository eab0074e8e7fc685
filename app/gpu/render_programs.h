/* render_programs — the renderer's program cache: one GL program per (fragment shader, preamble, map),
 * so two scenes share a program exactly when they would compile the same one; and the vertex array
 * every full-screen draw binds (the core profile draws nothing without one). */
#ifndef FATHOM_RENDER_PROGRAMS_H
#define FATHOM_RENDER_PROGRAMS_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "scene/scene.h"
#include "util.h"

void render_programs_init(void);
void render_programs_shutdown(void);
const char *render_programs_shader_root(void);
GLuint render_programs_vao(void);
/* The cached program for (s's preamble + extra_defines, s's map, frag), compiled on first use. */
GLuint render_programs_get(const scene *s, const char *frag, const char *extra_defines, err_t *err);
/* Rebuilds every cached program from disk; on any error keeps them all. *current follows its program. */
bool render_programs_reload(GLuint *current, err_t *err);

/* The loop budget in words, for messages: "57343 loop iterations a pixel: llvmpipe ends every loop
 * after 65535" (shaders/common/budget.glsl). */
const char *render_programs_loop_budget_text(void);
/* The driver's loop limit of an invocation, all loops together (llvmpipe: 65535), or 0 where it has none. */
int render_programs_loop_limit(void);

#endif
