/* scene_parse — internal to the scene module: JSON reading with error context, shared by the block
 * parsers (scene_blocks.c, scene_csg.c, scene_programs.c). Every error names the file and the key
 * path, and the "allowed here" / "known" lists come from the tables they check against.
 */
#ifndef FATHOM_SCENE_PARSE_H
#define FATHOM_SCENE_PARSE_H

#include <cjson/cJSON.h>
#include <stdbool.h>

#include "scene/params.h"
#include "scene/scene.h"
#include "scene/uniforms.h"

enum { KEY_PATH_MAX = 512 };

/* Context for messages: every error names the file and the key path. */
typedef struct scene_ctx {
    const char *file;
    err_t *err;
    scene *s;
    strbuf code; /* generated GLSL: program.glsl */
    int next_var;
    const char *formula; /* "program": "NAME" naming a formula: the fractal program with that formula */
    param_list *params;  /* when not NULL, every tunable value read is recorded here (params.h) */
} scene_ctx;

/* Records a tunable value read by hand (the get_* functions record their own): its key path, type,
 * value (v[0] for a number or bool, v[0..2] for a vector) and range. Does nothing without c->params. */
scene_param *scene_record_param(scene_ctx *c, const char *path, const char *key, param_type type, const double *v,
                          double lo, double hi);

bool scene_fail(scene_ctx *c, const char *path, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* "parent.key" (cut when long: key paths only appear in messages). */
void scene_child_path(char *out, size_t n, const char *parent, const char *key);

/* Every object is checked against the keys it may hold, so a typo is an error, not a silent default. */
bool scene_check_keys(scene_ctx *c, const cJSON *obj, const char *path, const char *const *allowed);

/* Optional values: a missing key gives def; a present one must be of the type and in [lo, hi]. */
bool scene_get_num(scene_ctx *c, const cJSON *obj, const char *path, const char *key, float def, float lo, float hi,
             float *out);
bool scene_get_int(scene_ctx *c, const cJSON *obj, const char *path, const char *key, int def, int lo, int hi, int *out);
bool scene_get_vec3(scene_ctx *c, const cJSON *obj, const char *path, const char *key, const float def[3], float lo,
              float hi, float out[3]);
/* A vector of n (2 to 4) numbers, each in [lo, hi]; recorded as a colour (n = 4: RGB and an intensity) or
 * a vector of n components. */
bool scene_get_vecn(scene_ctx *c, const cJSON *obj, const char *path, const char *key, int n, const float *def,
                    float lo, float hi, bool colour, float *out);
/* The same in double (camera positions: a deep zoom needs more than a float's digits). */
bool scene_get_dvec3(scene_ctx *c, const cJSON *obj, const char *path, const char *key, const double def[3], double lo,
               double hi, double out[3]);
bool scene_get_str(scene_ctx *c, const cJSON *obj, const char *path, const char *key, const char *def, const char **out);

/* A string from a NULL-terminated list of names: *out = its index (def when the key is missing).
 * An unknown name is refused with the list ("unknown light type 'x' (known: point, directional)"). */
bool scene_get_enum(scene_ctx *c, const cJSON *obj, const char *path, const char *key, const char *what,
              const char *const *names, int def, int *out);

/* A file named in the scene: resolved against the scene file's folder and checked to exist. */
bool scene_resolve_file(scene_ctx *c, const char *path, const char *rel, char *out);

/* Blocks every program has (scene_blocks.c). */
bool scene_parse_materials(scene_ctx *c, const cJSON *root);
int scene_find_material(const scene *s, const char *name);
bool scene_parse_camera(scene_ctx *c, const cJSON *root);
bool scene_parse_fog(scene_ctx *c, const cJSON *root);
bool scene_parse_environment(scene_ctx *c, const cJSON *root);
bool scene_parse_lights(scene_ctx *c, const cJSON *root);
bool scene_parse_sun(scene_ctx *c, const cJSON *root); /* scene_sun.c */
bool scene_parse_quality(scene_ctx *c, const cJSON *root);
bool scene_parse_effects(scene_ctx *c, const cJSON *root);
bool scene_parse_droplets(scene_ctx *c, const cJSON *root);

/* "camera": "auto": frames the camera, distances, haze and layers from the DEM (heightfield_probe). */
bool scene_terrain_frame(scene *s, err_t *err);
/* "camera": "auto" for a fractal: a three-quarter view of its bounding sphere, whatever the formula. */
bool scene_fractal_frame(scene *s, err_t *err);

/* --set overrides (scene_set.c): "a.b.0.c=value" applied to the parsed JSON tree. */
bool scene_apply_set(cJSON *root, const char *kv, err_t *err);

/* The scene's text: the one a shot carried for this path (scene_provide_text), else the file's
 * (scene_files.c). */
bool scene_read_text(const char *path, char **text, err_t *err);

#endif
