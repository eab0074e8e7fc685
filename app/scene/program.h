/* program — the registry of scene programs: what draws a scene, one row each.
 *
 * A program supplies only its shape (`vec2 map(vec3 p)`) and optionally its colouring and its own
 * marcher (see the contract at the top of shaders/common/contract.glsl); everything else is shared.
 * PROGRAM_LIST is the one place a program is described. Adding one is a row here, its GLSL file,
 * and its block parser (app/scene/scene_programs.c). Columns:
 *   ID        enum suffix (PROGRAM_ID)
 *   name      "program" in scene files, --scene names, the `PROGRAM_name` #define
 *   map       its GLSL under shaders/ (NULL: generated from the scene: csg's CSG tree, the fractal's
 *             #include of its formula file, shaders/fractal/NAME.glsl or the user's: formula.h)
 *   family    which block holds its shape: CSG "objects", FRACTAL "fractal", TERRAIN "terrain"
 *   parse     reads that block into the scene (and writes map() for a generated program)
 *   defines   what it adds to the #define preamble (NULL: nothing)
 *   uniforms  its named uniforms (NULL: none)
 *   bench     its own bench sweeps, "key=v1,v2,…" separated by ';' (NULL: none)
 */
#ifndef FATHOM_PROGRAM_H
#define FATHOM_PROGRAM_H

#include <stdbool.h>

/* clang-format off */
#define PROGRAM_LIST(X)                                                                                                 \
    X(CSG,        "csg",        NULL,                      FAMILY_CSG,     scene_csg_parse,        NULL,            NULL,               NULL) \
    X(FRACTAL,    "fractal",    NULL,                      FAMILY_FRACTAL, scene_fractal_parse,    scene_fractal_defines, scene_fractal_uniforms,   NULL) \
    X(TERRAIN,    "terrain",    "terrain/terrain.glsl",    FAMILY_TERRAIN, scene_heightmap_parse,  scene_heightmap_defines, scene_layer_uniforms,   "terrain.method=linear,maxmip") \
    X(NOISE,      "noise",      "terrain/noise.glsl",      FAMILY_TERRAIN, scene_noise_parse,      NULL,            scene_noise_uniforms,     NULL)
/* clang-format on */

typedef enum program_kind {
#define X(id, ...) PROGRAM_##id,
    PROGRAM_LIST(X)
#undef X
    PROGRAM_COUNT
} program_kind;

typedef enum program_family { FAMILY_CSG, FAMILY_FRACTAL, FAMILY_TERRAIN } program_family;

/* Where each family's shape lives in a scene file. */
const char *program_family_block(program_family f);

struct scene;
struct strbuf;
struct uniform_sink;
struct scene_ctx;
struct cJSON;

/* The programs' hooks named in PROGRAM_LIST: block parsers, #defines, uniforms (scene_programs.c). */
bool scene_csg_parse(struct scene_ctx *c, const struct cJSON *root); /* scene_csg.c: "objects" → map() */
bool scene_fractal_parse(struct scene_ctx *c, const struct cJSON *root);
bool scene_heightmap_parse(struct scene_ctx *c, const struct cJSON *root);
bool scene_noise_parse(struct scene_ctx *c, const struct cJSON *root);
void scene_fractal_defines(const struct scene *s, struct strbuf *out);
void scene_heightmap_defines(const struct scene *s, struct strbuf *out);
void scene_fractal_uniforms(const struct scene *s, const struct uniform_sink *u);
void scene_layer_uniforms(const struct scene *s, const struct uniform_sink *u);
void scene_noise_uniforms(const struct scene *s, const struct uniform_sink *u);

typedef struct program_def {
    const char *name, *map_file;
    program_family family;
    bool (*parse)(struct scene_ctx *c, const struct cJSON *root);
    void (*defines)(const struct scene *s, struct strbuf *out);
    void (*uniforms)(const struct scene *s, const struct uniform_sink *u);
    const char *bench;
} program_def;

const program_def *program_get(program_kind p);
const char *program_name(program_kind p);
bool program_from_name(const char *name, program_kind *p);
bool program_is_fractal(program_kind p);
/* The known names, ", "-separated (for messages). */
void program_names(struct strbuf *out);

#endif
