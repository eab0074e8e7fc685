/* render_scene — the scene the renderer draws: its own copy of the caller's scene (by value, so the
 * caller may free or change its scene at once) and the GPU resources it needs, by kind
 * (render_resource.h), uploaded in order and bound together. */
#ifndef FATHOM_RENDER_SCENE_H
#define FATHOM_RENDER_SCENE_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "scene/scene.h"
#include "util.h"

/* Copies s and makes every resource kind hold what s needs. On error no scene is set. */
bool render_scene_set(const scene *s, err_t *err);
const scene *render_scene_current(void); /* NULL before the first scene */
/* Uploads s's uniforms to prog (glUseProgram'd); for the current scene also its resources' units and
 * sizes (another scene, a probe's, gets only its own values). */
void render_scene_uniforms(GLuint prog, const scene *s);
void render_scene_bind(void);
/* The first texture unit after the resource kinds' (render_resource.h): free for the renderer's own. */
int render_scene_units_end(void);
void render_scene_release(void); /* frees every resource; no scene is current */
void render_scene_shutdown(void);

#endif
