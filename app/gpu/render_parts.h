/* render_parts — internal to the render module, which is split along its seams:
 *   render.c          targets, one sample, display, readback (the public API in render.h)
 *   render_programs.c the program cache: one GL program per (fragment shader, preamble, map)
 *   render_scene.c    scene upload: a copy of the scene by value, its textures, heightfield and uniforms
 *   render_probe.c    map() (or another probe shader) evaluated at points on the GPU
 * Each file keeps its own static state; they talk only through the functions below.
 */
#ifndef FATHOM_RENDER_PARTS_H
#define FATHOM_RENDER_PARTS_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "scene/scene.h"

/* Texture units: the scene's textures first, then these. */
enum {
    UNIT_ENVMAP = SCENE_MAX_TEXTURES,
    UNIT_HEIGHT,
    UNIT_HEIGHT_MAX,
    UNIT_CSG_LIST,
    UNIT_CSG_NODES,
    UNIT_DROPLETS,
    UNIT_DROPLET_CELLS,
    UNIT_DROPLET_INDEX,
    UNIT_DROPLET_NODES,
    UNIT_HEIGHT_TOP, /* the terrain's upper pyramid levels, above its tiles */
    UNIT_EDGE_MASK   /* adaptive sampling's mask (render.c) */
};

/* ---- render.c ---- */
GLuint render_vao(void); /* core profile draws nothing without a bound VAO */

/* ---- render_programs.c ---- */
void programs_init(void);
void programs_shutdown(void);
const char *programs_shader_root(void);
/* The cached program for (s's preamble + extra_defines, s's map, frag), compiled on first use. */
GLuint programs_get(const scene *s, const char *frag, const char *extra_defines, err_t *err);
/* Rebuilds every cached program from disk; on any error keeps them all. *current follows its program. */
bool programs_reload(GLuint *current, err_t *err);

/* ---- render_scene.c ---- */
/* Copies s, loads its textures, cube map and heightfield. On error no scene is set. */
bool scene_gpu_set(const scene *s, err_t *err);
void scene_gpu_shutdown(void);
const scene *scene_gpu_current(void); /* NULL before the first scene */
/* Uploads s's uniforms (and, for the current scene, its texture units and heightfield) to prog. */
void scene_gpu_uniforms(GLuint prog, const scene *s);
void scene_gpu_bind_textures(void);

#endif
