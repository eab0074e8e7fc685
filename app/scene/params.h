/* params — every value of a scene a user can tune, as the parser read it: its key path (the way
 * --set names it), type, range, current value and, where the scene knows one, a description. The
 * window's panel is generated from this list (a section per block, a control per parameter), so a
 * key any block reads — a formula's declared parameter, a quality knob, a material's roughness, a
 * CSG primitive's radius — shows up there with its range and needs no panel code. An edit goes back
 * as a "key=value" override and meets exactly the checks --set does. Pure C.
 *
 * Recorded: numbers, whole numbers, vectors, colours, booleans and names from a list (scene_get_num,
 * scene_get_int, scene_get_vec3, scene_get_enum and the fractal block's own reads). Not recorded: files (textures,
 * heightmaps: not a slider's business) and the camera's position and look-at (the window edits its
 * live camera instead). */
#ifndef FATHOM_PARAMS_H
#define FATHOM_PARAMS_H

#include <stdbool.h>

#include "util.h"

enum { PARAM_KEY_MAX = 160, PARAM_NAMES_MAX = 256, PARAM_HELP_MAX = 320 };

typedef enum param_type { PARAM_FLOAT, PARAM_INT, PARAM_BOOL, PARAM_VEC3, PARAM_COLOR, PARAM_ENUM } param_type;

typedef struct scene_param {
    char key[PARAM_KEY_MAX]; /* "materials.glass.roughness", "fractal.power", "lights.0.direction" */
    param_type type;
    double value[4];         /* a number, a vector, 0/1, or an enum's index */
    int comps;               /* a vector's or colour's components: 2 to 4 (0: 3); a colour's 4th is an intensity */
    double lo, hi;           /* the accepted range (each component); a bool 0..1, an enum 0..count-1 */
    char names[PARAM_NAMES_MAX]; /* an enum's names, each followed by '\0' ("auto\0on\0off\0") */
    int name_count;
    char help[PARAM_HELP_MAX]; /* a description (a formula's declaration, a knob's help), or "" */
    int array_len, array_index; /* one element of an array value (the palette's colours), else 0, 0 */
    char group[48];          /* a heading inside its section (a fragment's #group), or "" */
} scene_param;

/* What a group of keys is, for its heading: "objects.3" is "box (red)". */
typedef struct param_label {
    char key[PARAM_KEY_MAX];
    char text[64];
} param_label;

typedef struct param_list {
    scene_param *items;
    int count, cap;
    param_label *labels;
    int label_count, label_cap;
} param_list;

#ifdef __cplusplus
extern "C" { /* the panel (window/panel.cpp) reads the list */
#endif

/* Adds (or, for a key already there, replaces) a parameter; returns where it is kept. */
scene_param *params_add(param_list *l, const scene_param *p);
const scene_param *params_find(const param_list *l, const char *key);
/* Names the group of keys under key ("objects.3" -> "box (red)"); NULL when none is named. */
void params_label(param_list *l, const char *key, const char *text);
const char *params_label_of(const param_list *l, const char *key);
void params_free(param_list *l);

/* The block a key belongs to (its first segment: "materials", "fractal"...), into out. */
void params_section(const char *key, char *out, size_t n);

/* The override that sets p (one of l's) to v (components as p's type has them): "fractal.power=6",
 * "lights.0.direction=0.5,0.7,0.4", "effects.fog=off"; an element of an array sets the whole array
 * from its siblings in l ("fractal.palette=[[...],[...],[...]]"). Numbers are written so that they
 * read back exactly (%.9g). */
void params_override(const param_list *l, const scene_param *p, const double *v, char *out, size_t n);

/* The components p's value has (1 for a number, 2 to 4 for a vector or colour). */
int params_components(const scene_param *p);

#ifdef __cplusplus
}
#endif

#endif
