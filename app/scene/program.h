/* program — the registry of scene programs: what draws a scene, one row each.
 *
 * A program supplies only its shape (`vec2 map(vec3 p)`) and optionally its colouring and its own
 * marcher (see the contract at the top of shaders/common/contract.glsl); everything else is shared.
 * PROGRAM_LIST is the one place a program is described: adding one is a row here, its GLSL file and
 * the hooks the row names (its block parser, and the uniforms, #defines and framing it has; the
 * parsed values live in its part of the scene struct, scene.h). Every other place that differs by
 * program reads the row: which block a scene file gives its shape in (and the error for another
 * program's block), whether "camera": "auto" frames it, how fast the window flies, the panel's
 * first section, the bench's sweeps. Columns:
 *   ID        enum suffix (PROGRAM_ID)
 *   name      "program" in scene files, --scene names, the `PROGRAM_name` #define
 *   map       its GLSL under shaders/ (NULL: generated from the scene: csg's CSG tree, the fractal's
 *             #include of its formula file, shaders/fractal/NAME.glsl or the user's: formula.h)
 *   block     the scene file's block that holds its shape (and the panel's first section)
 *   family    what kind of field it is: CSG (exact distances of solids: coverage AA applies),
 *             FRACTAL (a formula: iterations, deep zoom, check-formula), TERRAIN (a ground: layers
 *             by slope and height, walking)
 *   parse     reads that block into the scene (and writes map() for a generated program)
 *   frame     "camera": "auto": frames the camera from the shape's extent (NULL: the scene gives
 *             its camera), and what it frames from, for the message when it cannot
 *   adaptive  the window flies at a speed proportional to the distance to the surface (a fractal's
 *             detail at every scale), else at a fixed speed
 *   defines   what it adds to the #define preamble (NULL: nothing)
 *   uniforms  its named uniforms (NULL: none)
 *   bench     its own bench sweeps, "key=v1,v2,…" separated by ';' (NULL: none)
 */
#ifndef FATHOM_PROGRAM_H
#define FATHOM_PROGRAM_H

#include <stdbool.h>

/* clang-format off */
#define PROGRAM_LIST(X)                                                                                                 \
    X(CSG,     "csg",     NULL,                   "objects", FAMILY_CSG,     scene_csg_parse,       NULL, NULL, false,                \
      NULL,                    NULL,                    NULL)                                                            \
    X(FRACTAL, "fractal", NULL,                   "fractal", FAMILY_FRACTAL, scene_fractal_parse,   scene_fractal_frame,           \
      "the formula's bound", true, scene_fractal_defines, scene_fractal_uniforms, NULL)                                   \
    X(TERRAIN, "terrain", "terrain/terrain.glsl", "terrain", FAMILY_TERRAIN, scene_heightmap_parse, scene_terrain_frame,           \
      "the DEM", false, scene_heightmap_defines, scene_layer_uniforms, "terrain.method=linear,maxmip")                     \
    X(NOISE,   "noise",   "terrain/noise.glsl",   "terrain", FAMILY_TERRAIN, scene_noise_parse,     NULL, NULL, false,                \
      NULL,                    scene_noise_uniforms,    NULL)                                                            \
    X(TORUS,   "torus",   "shapes/torus.glsl",    "torus",   FAMILY_CSG,     scene_torus_parse,     NULL, NULL, false,                \
      NULL,                    scene_torus_uniforms,    "torus.minor=0.05,0.15,0.3")
/* clang-format on */

typedef enum program_kind {
#define X(id, ...) PROGRAM_##id,
    PROGRAM_LIST(X)
#undef X
    PROGRAM_COUNT
} program_kind;

typedef enum program_family { FAMILY_CSG, FAMILY_FRACTAL, FAMILY_TERRAIN } program_family;

struct scene;
struct strbuf;
struct uniform_sink;
struct scene_ctx;
struct cJSON;
struct err_t;

/* The programs' hooks named in PROGRAM_LIST: block parsers, #defines, uniforms (scene_programs.c). */
bool scene_csg_parse(struct scene_ctx *c, const struct cJSON *root); /* scene_csg.c: "objects" → map() */
bool scene_fractal_frame(struct scene *s, struct err_t *err);
bool scene_terrain_frame(struct scene *s, struct err_t *err);
bool scene_fractal_parse(struct scene_ctx *c, const struct cJSON *root);
bool scene_heightmap_parse(struct scene_ctx *c, const struct cJSON *root);
bool scene_noise_parse(struct scene_ctx *c, const struct cJSON *root);
void scene_fractal_defines(const struct scene *s, struct strbuf *out);
void scene_heightmap_defines(const struct scene *s, struct strbuf *out);
void scene_fractal_uniforms(const struct scene *s, const struct uniform_sink *u);
void scene_layer_uniforms(const struct scene *s, const struct uniform_sink *u);
void scene_noise_uniforms(const struct scene *s, const struct uniform_sink *u);
bool scene_torus_parse(struct scene_ctx *c, const struct cJSON *root);
void scene_torus_uniforms(const struct scene *s, const struct uniform_sink *u);

typedef struct program_def {
    const char *name, *map_file, *block;
    program_family family;
    bool (*parse)(struct scene_ctx *c, const struct cJSON *root);
    bool (*frame)(struct scene *s, struct err_t *err);
    const char *frame_from;
    bool adaptive;
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
