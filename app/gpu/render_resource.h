/* render_resource — what a scene puts on the GPU besides its program, by kind. Each kind (material
 * textures, cube map, heightfield, CSG primitive list, droplets) is one file (res_textures.c,
 * res_heightfield.c, …) that owns its GL objects, the key that says when the next scene can keep them (same file, unchanged on disk), its
 * upload, its texture units and its uniforms, behind the one interface below; render_scene.c runs the
 * kinds in order. A new kind is one new file and a row in render_scene.c's RESOURCES table.
 *
 * Texture units: the scene's material textures take 0 … SCENE_MAX_TEXTURES-1, the kinds' own units
 * follow (RENDER_UNIT_*); uniforms name the unit, so shaders never number them. */
#ifndef FATHOM_RENDER_RESOURCE_H
#define FATHOM_RENDER_RESOURCE_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stddef.h>

#include "scene/scene.h"
#include "scene/uniforms.h"
#include "util.h"

enum {
    RENDER_UNIT_ENVMAP = SCENE_MAX_TEXTURES,
    RENDER_UNIT_ENV_CDF, /* the path tracer's sky distribution (res_envmap.c) */
    RENDER_UNIT_HEIGHT,
    RENDER_UNIT_HEIGHT_MAX,
    RENDER_UNIT_CSG_LIST,
    RENDER_UNIT_CSG_NODES,
    RENDER_UNIT_DROPLETS,
    RENDER_UNIT_DROPLET_CELLS,
    RENDER_UNIT_DROPLET_INDEX,
    RENDER_UNIT_DROPLET_NODES,
    RENDER_UNIT_HEIGHT_TOP, /* the terrain's upper pyramid levels, above its tiles */
    RENDER_UNIT_EDGE_MASK   /* adaptive sampling's mask (render.c) */
};

typedef struct render_resource {
    const char *name;
    /* Makes the GPU hold what s needs of this kind, keeping what an earlier scene loaded from the same
     * unchanged files, or frees it when s needs none. On error the kind holds nothing of s. */
    bool (*set)(const scene *s, err_t *err);
    /* Its sampler units (always: a program's samplers must not share a unit across types) and, when it
     * holds something, the uniforms only the loaded data knows (sizes, grids). s is the current scene. */
    void (*uniforms)(const scene *s, const uniform_sink *u);
    void (*bind)(void);    /* its textures to its units */
    void (*release)(void); /* frees everything it holds */
} render_resource;

extern const render_resource res_textures, res_envmap, res_heightfield, res_csg_list, res_droplets;

/* Appends "path|bytes|mtime;" of a file to a cache key: a file changed on disk makes a new key. */
void render_file_key(const char *path, char *key, size_t n);

#endif
