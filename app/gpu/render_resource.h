/* render_resource — what a scene puts on the GPU besides its program, by kind. Each kind (material
 * textures, cube map, heightfield, CSG primitive list, droplets) is one file (res_textures.c,
 * res_heightfield.c, …; CMake builds every app/gpu/res_*.c) that owns its GL objects, the key that
 * says when the next scene can keep them (same file, unchanged on disk), its upload, how many texture
 * units it samples from and its uniforms, behind the one interface below; render_scene.c runs the
 * kinds in order. A new kind is one new file, its row in render_scene.c's RESOURCES table and its name
 * in the extern line at the end of this file.
 *
 * Texture units: render_scene.c gives each kind `units` consecutive units in table order (the
 * material textures first: 0 … SCENE_MAX_TEXTURES-1) and hands the first to uniforms() and bind();
 * uniforms name the unit, so shaders never number them. render_scene_units_end() is the first unit
 * after them (render.c's edge mask). */
#ifndef FATHOM_RENDER_RESOURCE_H
#define FATHOM_RENDER_RESOURCE_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stddef.h>

#include "scene/scene.h"
#include "scene/uniforms.h"
#include "util.h"

typedef struct render_resource {
    const char *name;
    /* Makes the GPU hold what s needs of this kind, keeping what an earlier scene loaded from the same
     * unchanged files, or frees it when s needs none. On error the kind holds nothing of s. */
    bool (*set)(const scene *s, err_t *err);
    int units; /* texture units it samples from: unit … unit + units − 1 below */
    /* Its sampler units (always: a program's samplers must not share a unit across types) and, when it
     * holds something, the uniforms only the loaded data knows (sizes, grids). s is the current scene. */
    void (*uniforms)(const scene *s, const uniform_sink *u, int unit);
    void (*bind)(int unit); /* its textures to its units */
    void (*release)(void); /* frees everything it holds */
    int (*held)(void);     /* the GL objects it holds (none after a failed set: tests check the promise) */
} render_resource;

extern const render_resource res_textures, res_envmap, res_heightfield, res_imagery, res_csg_list, res_droplets,
    res_frag_textures;

/* Fault injection for the tests: true when $FATHOM_RESOURCE_FAULT is this kind's name. Each kind then
 * fails halfway through its set, after its first GL object, as a refused allocation there would. */
bool render_resource_fault(const char *name, err_t *err);

/* Appends "path|bytes|mtime;" of a file to a cache key: a file changed on disk makes a new key. */
void render_file_key(const char *path, char *key, size_t n);

#endif
