/* variant — which GLSL program a scene compiles: the scene kind, the effect set and the quality knobs.
 *
 * One table (EFFECT_LIST) names every optional effect. The renderer compiles one program per
 * distinct variant, built from a `#define` preamble that variant_preamble() writes; shader code
 * tests `#if FX_NAME`. An effect that a scene does not use is not in its program at all.
 */
#ifndef FATHOM_VARIANT_H
#define FATHOM_VARIANT_H

#include <stdbool.h>

#include "util.h"

/*        id            name in scene files  what it simulates */
#define EFFECT_LIST(X)                                                                              \
    X(SHADOWS, "shadows", "hard shadow rays toward the lights, started off the surface")            \
    X(SOFT_SHADOWS, "soft_shadows", "penumbrae from the closest miss of shadow rays")                \
    X(AO, "ao", "ambient occlusion: distance samples along the normal")                              \
    X(REFLECTIONS, "reflections", "traced mirror reflections on smooth materials")                   \
    X(REFRACTION, "refraction", "glass: exact Fresnel, Snell, total internal reflection, Beer")      \
    X(FOG, "fog", "exponential fog along primary rays")                                              \
    X(ENVMAP, "envmap", "cube-map environment (else a constant colour)")                             \
    X(TEXTURES, "textures", "filtered material textures (mipmaps, anisotropic)")                     \
    X(AA, "aa", "jittered sub-pixel samples, accumulated progressively")                             \
    X(GLOW, "glow", "fractals: light that grows with the march steps near the surface")               \
    X(RELIEF, "relief", "parallax occlusion mapping of a heightmap on a material (the lab's search)")

typedef enum effect {
#define X(id, name, what) EFFECT_##id,
    EFFECT_LIST(X)
#undef X
    EFFECT_COUNT
} effect;

const char *effect_name(effect e);
const char *effect_summary(effect e);
bool effect_from_name(const char *name, effect *e);

/* Positions are float: near |p| no step below about 4 ulps (|p| · 2⁻²¹) resolves anything, so hit
 * thresholds never go below PRECISION_REL · (|camera| + t); the window says when a zoom reaches it. */
#define PRECISION_REL 4.76837158e-7f

/* A smooth opaque material reflects a traced mirror image when its roughness is at most this. */
#define MIRROR_ROUGHNESS 0.25f

/* Scene kinds. Each supplies only `vec2 map(vec3 p)` (distance, material) and optionally
 * `vec3 programAlbedo(vec3 p)` (colouring): csg from the scene's CSG tree (generated), a fractal from
 * shaders/fractal/NAME.glsl. Everything else (marching, lighting, effects) is shared. */
typedef enum program_kind {
    PROGRAM_CSG,
    PROGRAM_MANDELBULB,
    PROGRAM_MENGER,
    PROGRAM_MANDELBOX,
    PROGRAM_TERRAIN,
    PROGRAM_NOISE,
    PROGRAM_COUNT
} program_kind;
const char *program_name(program_kind p);
const char *program_map_file(program_kind p); /* under shaders/; NULL when generated (csg) */
bool program_is_fractal(program_kind p);
bool program_from_name(const char *name, program_kind *p);

/* Accuracy knobs. Each is a compile-time constant in the shader (loops unroll, dead code goes). */
typedef struct quality {
    int max_steps;     /* sphere-tracing steps per ray */
    float hit_k;       /* hit threshold = hit_k * t * pixel angle (pixel footprints at distance t) */
    float step_factor; /* fraction of the distance bound taken per step (1 for exact distances) */
    float max_dist;    /* rays give up beyond this distance */
    int shadow_steps;  /* steps per shadow ray */
    int ao_samples;    /* distance samples along the normal */
    int bounces;       /* reflection / refraction path segments after the primary hit */
    int aniso_taps;    /* texture taps along the footprint's long axis (anisotropic filtering) */
    float over_relax;  /* sphere-tracing over-relaxation ω (Keinert et al. 2014); 1 = plain */
    float linear_step; /* terrain, the lab's method: first step of the linear search, texels */
    float step_growth; /* terrain: each linear step is this much longer than the last */
    int binary_steps;  /* terrain: binary-search refinements after the linear search brackets a hit */
    int spp;           /* samples per pixel for offline shots and a still window */
} quality;

typedef enum quality_preset { PRESET_DRAFT, PRESET_INTERACTIVE, PRESET_FINAL, PRESET_REFERENCE, PRESET_COUNT } quality_preset;
const char *preset_name(quality_preset p);
bool preset_from_name(const char *name, quality_preset *p);
quality preset_quality(quality_preset p);

typedef struct variant {
    program_kind program;
    unsigned effects; /* bit (1u << effect) */
    quality q;
    int num_lights, num_materials;
    int fractal_iterations; /* iterations (Menger: levels) compiled into a fractal's map; 0 for csg */
    bool terrain_maxmip;    /* terrain: the max-mipmap traversal instead of the lab's linear search */
} variant;

/* The `#define` block (no #version) for v. Appends to out. Two variants compile to the same
 * program exactly when their preambles are equal. */
void variant_preamble(const variant *v, strbuf *out);

#endif
