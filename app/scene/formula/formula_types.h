/* formula_types — what a formula is, as formula.c reads it from a formula file and frag.c from a
 * Fragmentarium fragment (formula.h has the file format). Types only. */
#ifndef FATHOM_FORMULA_TYPES_H
#define FATHOM_FORMULA_TYPES_H

#include <stdbool.h>

#include "util.h"

#define UTF8_BOM "\xef\xbb\xbf"

enum { FORMULA_MAX_PARAMS = 160, FORMULA_NAME_MAX = 64, FORMULA_KEY_MAX = 48, FORMULA_TEXT_MAX = 200,
       FORMULA_MAX_REQUIRES = 4, FORMULA_EXPR_MAX = 160, FORMULA_LOOPS_MAX = 1 << 20 };

/* The keys of the fractal block that are not a formula's parameters. */
#define FORMULA_COMMON_KEYS "formula", "iterations", "bound_radius", "palette", "glow", "glow_color", "julia", \
    "julia_c", "hybrid", "steps", "precision", "hit_distance", "hit_rule", "detail", "max_distance", "look"

/* FORMULA_VEC2 and FORMULA_VEC4 and FORMULA_COLOR4 (an RGB colour and an intensity in w, Fragmentarium's
 * color[LO,DEFAULT,HIGH,R,G,B]) come from fragments (frag.h). */
typedef enum formula_type { FORMULA_FLOAT, FORMULA_INT, FORMULA_BOOL, FORMULA_VEC3, FORMULA_COLOR, FORMULA_VEC2,
                            FORMULA_VEC4, FORMULA_COLOR4 } formula_type;

/* The components a value of this type has: 1 to 4. */
static inline int formula_components(formula_type t)
{
    return t == FORMULA_VEC2 ? 2 : t == FORMULA_VEC3 || t == FORMULA_COLOR ? 3 : t >= FORMULA_VEC4 ? 4 : 1;
}

typedef struct formula_param {
    char key[FORMULA_KEY_MAX];     /* scene key: min_radius */
    char uniform[FORMULA_KEY_MAX]; /* GLSL name: uMinRadius */
    char description[FORMULA_TEXT_MAX];
    formula_type type;
    float def[4], lo, hi;     /* default (a vector: its components) and range (each component; a COLOR4's w) */
    bool locked;              /* a fragment's Locked slider: a compile-time constant (frag.h) */
    char group[FORMULA_KEY_MAX]; /* a fragment's #group, or "" */
    bool has_gap;             /* values strictly inside (gap_lo, gap_hi) are refused */
    float gap_lo, gap_hi;
} formula_param;

typedef struct formula_require {
    char lhs[FORMULA_EXPR_MAX], rhs[FORMULA_EXPR_MAX], message[FORMULA_TEXT_MAX];
    bool less; /* lhs < rhs, else lhs > rhs */
} formula_require;

/* How a fragment's DE renderer lights (app/scene/formula/frag.c COMPAT, shaders/frag/look.glsl). */
typedef enum frag_light { FRAG_LIGHT_NONE, FRAG_LIGHT_DE, FRAG_LIGHT_PHONG, FRAG_LIGHT_PHONG_SHADOWS } frag_light;

/* A Fragmentarium fragment's texture (uniform sampler2D NAME; file[PATH], or samplerCube) and the host's
 * #TexParameter lines (frag.h). */
enum { FRAG_TEXTURES_MAX = 4, FRAG_TEXPARAMS_MAX = 16, FRAG_TEXPARAM_MAX = 40 };
typedef struct frag_texture {
    char name[FORMULA_KEY_MAX]; /* the sampler uniform's */
    char path[PATH_MAX_LEN];    /* the file's real path, inside the fragment's folder or its collection's Include */
    bool cube;                  /* samplerCube: six square faces stacked top to bottom, +X -X +Y -Y +Z -Z */
} frag_texture;

typedef struct formula {
    char name[FORMULA_NAME_MAX]; /* the file's name without .glsl */
    char file[PATH_MAX_LEN];     /* for #include: "fractal/NAME.glsl" under shaders/, or an absolute path */
    char summary[FORMULA_TEXT_MAX];
    int iterations, iterations_lo, iterations_hi;
    char bound[FORMULA_EXPR_MAX]; /* expression of the parameters */
    char step[FORMULA_EXPR_MAX];  /* @step: an expression of the parameters ("": not declared, 1) */
    char trap[2][FORMULA_EXPR_MAX]; /* the orbit trap's range: expressions of the parameters */
    char loops[FORMULA_EXPR_MAX]; /* @loops: loop iterations one estimate runs (an expression) */
    bool step_formula;            /* formulaStep and the loop (@de), not its own formulaDE */
    bool fragment;                /* a Fragmentarium fragment (frag.h): file is its absolute path */
    float frag_detail, frag_max_distance; /* its DE renderer's Detail and MaxDistance defaults (frag.h) */
    frag_light frag_light;        /* how its renderer lights (its own look is the default unless NONE: frag.c) */
    bool frag_syntopia; /* its collection is Syntopia's Fragmentarium's (its DE-Raytracer shadows the camera light
                           too, and its host takes a preset's value past a slider as it is: frag.c) */
    int frag_texture_count, frag_texparam_count;
    frag_texture frag_textures[FRAG_TEXTURES_MAX];
    char frag_texparams[FRAG_TEXPARAMS_MAX][3][FRAG_TEXPARAM_MAX]; /* sampler, GL_TEXTURE_..., value */
    bool de_log;                  /* @de log: ½ ln r · r / dr; else r / dr */
    char escape[FORMULA_EXPR_MAX]; /* @escape: an expression of the parameters */
    bool deep;                    /* @deep: compiles in double */
    bool exact;                   /* @exact: the estimate is the exact distance (fathom mesh meshes level 0) */
    char deep_whole[FORMULA_TEXT_MAX]; /* @deep whole KEY...: keys that must be whole numbers in double */
    int param_count;
    formula_param params[FORMULA_MAX_PARAMS];
    int require_count;
    formula_require requires[FORMULA_MAX_REQUIRES];
} formula;

#endif
