/* quality — the accuracy knobs and the four presets, all from one table.
 *
 * QUALITY_KNOBS is the only place a knob is described. From it come the `quality` struct, the
 * presets, the scene file's "quality" block (keys, ranges, whole-number checks), the `#define`
 * preamble, the window's stepped knobs, the bench's sweeps and the --help list. Adding a knob is one
 * row here plus the GLSL that reads its #define.
 *
 * Columns:
 *   name     key in the scene file's "quality" block and in --set quality.NAME=…
 *   TYPE     INT or FLOAT
 *   GLSL     the #define the shader reads (a compile-time constant: loops unroll, dead code goes);
 *            NULL: the knob is host-side only
 *   min,max  accepted range
 *   draft … reference   the presets' values: draft is the fastest usable look, interactive the
 *            window's default, final for offline shots, reference far stricter than final
 *   mul,add  the window's = key sets v·mul + add, − undoes it (mul 0: the window does not step it)
 *   sweep    the bench's default values (NULL: not swept)
 *   scope    where the knob has any effect (the bench sweeps it only there)
 *
 * The presets were picked from the measured fronts (docs/bench): the hit threshold buys the most
 * accuracy per ms, so it halves at each step; more than 16 shadow steps, 64 march steps or 2–4
 * texture taps bought nothing measurable in any scene; samples per pixel cost the most.
 */
#ifndef FATHOM_QUALITY_H
#define FATHOM_QUALITY_H

#include <stdbool.h>
#include <stddef.h>

#include "util.h"

/* Positions are float: near |p| no step below about 4 ulps (|p| · 2⁻²¹) resolves anything, so hit
 * thresholds never go below PRECISION_REL · (|camera| + t); the window says when a zoom reaches it. */
#define PRECISION_REL 4.76837158e-7f

/* Where a knob has any effect (the bench sweeps it only in such scenes). */
typedef enum knob_scope {
    SCOPE_ANY,      /* every program */
    SCOPE_SHADOWS,  /* scenes that compile shadow rays */
    SCOPE_AO,       /* scenes that compile ambient occlusion */
    SCOPE_BOUNCES,  /* scenes with mirrors or glass */
    SCOPE_TEXTURES, /* scenes with filtered colour textures */
    SCOPE_SEARCH,   /* the lab's linear + binary search runs: linear terrain, relief materials */
    SCOPE_REFINES,  /* sphere-traced programs whose distance is exact or a bound (not fractals' level-of-detail surfaces) */
    SCOPE_DROPLETS, /* scenes with droplets */
    SCOPE_EXACT,    /* programs whose distance is exact or a tight bound (csg): a cone's coverage needs it */
    SCOPE_ENVMAP,   /* scenes lit by a cube map */
} knob_scope;

/* clang-format off */
/*  name          TYPE   GLSL          min    max     draft interact final  ref   mul  add   sweep                    scope           help */
#define QUALITY_KNOBS(X)                                                                                                                    \
    X(max_steps,    INT,   "MAX_STEPS",    1,     100000, 64,   128,     256,   1024, 2,   0,    "16,32,64,128,256,512",  SCOPE_ANY,      \
      "sphere-tracing steps per ray")                                                                                                     \
    X(hit_k,        FLOAT, "HIT_K",        1e-3,  1e3,    2,    1,       0.5,   0.25, 2,   0,    "8,4,2,1,0.5",           SCOPE_ANY,      \
      "hit threshold in pixel footprints: a ray stops within hit_k * t * pixel angle of a surface")                                       \
    X(refine,       INT,   "REFINE_STEPS", 0,   64,     0,    8,       12,    24,   1,   4,    "0,2,4,8,16",            SCOPE_REFINES,  \
      "hits are surfaces: below the footprint threshold the march goes on to the zero crossing, located by up to this many regula-falsi steps (0: a ray within hit_k footprints has hit; on a slow distance bound, the noise terrain's, it still goes on to the crossing)") \
    X(step_factor,  FLOAT, "STEP_FACTOR",  0.05,  1,      1,    1,       1,     1,    1,   0.05, "0.6,0.8,0.9,1",         SCOPE_ANY,      \
      "fraction of the distance bound taken per step (1 for exact distances)")                                                            \
    X(max_dist,     FLOAT, "MAX_DIST",     1e-2,  1e7,    100,  100,     100,   100,  0,   0,    NULL,                    SCOPE_ANY,      \
      "rays give up beyond this distance (metres)")                                                                                       \
    X(shadow_steps, INT,   "SHADOW_STEPS", 1,     100000, 16,   32,      32,    256,  2,   0,    "8,16,32,64,128",        SCOPE_SHADOWS,  \
      "steps per shadow ray")                                                                                                             \
    X(ao_samples,   INT,   "AO_SAMPLES",   0,     64,     3,    5,       5,     8,    1,   1,    "0,2,3,5,8",             SCOPE_AO,       \
      "ambient-occlusion distance samples along the normal")                                                                              \
    X(bounces,      INT,   "BOUNCES",      0,     64,     1,    3,       6,     10,   1,   1,    "0,1,2,3,6",             SCOPE_BOUNCES,  \
      "reflection / refraction path segments after the primary hit")                                                                     \
    X(aniso_taps,   INT,   "ANISO_TAPS",   1,     64,     1,    2,       4,     16,   0,   0,    "1,2,4,8",               SCOPE_TEXTURES, \
      "texture taps along the footprint's long axis (anisotropic filtering)")                                                             \
    X(over_relax,   FLOAT, "OVER_RELAX",   1,     1.95,   1,    1,       1,     1,    1,   0.1,  "1,1.2,1.3,1.4,1.6",     SCOPE_ANY,      \
      "sphere-tracing over-relaxation factor (Keinert et al. 2014); 1 = plain")                                                           \
    X(linear_step,  FLOAT, "LINEAR_STEP",  0.01,  1000,   2,    1,       0.5,   0.25, 0,   0,    "4,2,1,0.5,0.25",        SCOPE_SEARCH,   \
      "the lab's search: first step of the linear search, in texels")                                                                     \
    X(step_growth,  FLOAT, "STEP_GROWTH",  1,     2,      1.05, 1.02,    1.01,  1,    0,   0,    "1.1,1.05,1.02,1",       SCOPE_SEARCH,   \
      "the lab's search: each linear step is this much longer than the last")                                                             \
    X(binary_steps, INT,   "BINARY_STEPS", 0,     40,     4,    6,       8,     12,   0,   0,    "0,2,4,8,12",            SCOPE_SEARCH,   \
      "the lab's search: binary-search refinements once the linear search brackets a hit")                                                \
    X(droplet_lod,  FLOAT, "DROPLET_LOD",  0,     1000,   1,    0.5,     0.25,  0,    2,   0,    "0,0.25,0.5,1,2",        SCOPE_DROPLETS, \
      "droplets smaller than this many pixel footprints (radius) are not traced: the ray goes straight on, dimmed by the droplet's mean transmittance (0: trace every droplet)") \
    X(droplet_events, INT, "DROPLET_EVENTS", 0,   1000,   4,    8,       16,    64,   2,   0,    "2,4,8,16,32",           SCOPE_DROPLETS, \
      "droplet surfaces a path may cross (entries, exits, internal reflections); then it goes on straight")        \
    X(droplet_cull, INT,   "DROPLET_CULL", 0,     1,      1,    1,       1,     1,    0,   0,    "0,1",                   SCOPE_DROPLETS, \
      "1: the droplets' grid walk stops at the scene's surface, so droplets behind it cost nothing; 0: it walks on (the same image, to measure the saving)") \
    X(coverage,     INT,   "COVERAGE",     0,     1,      0,    0,       0,     0,    0,   0,    "0,1",                   SCOPE_EXACT,    \
      "1: cone coverage anti-aliasing (csg): a surface the centre ray passes within half a pixel gets its share of the pixel [docs/bench/coverage]") \
    X(ambient,      INT,   "AMBIENT",      0,     1,      1,    1,       1,     1,    0,   0,    "0,1",                   SCOPE_ENVMAP,   \
      "diffuse ambient light under a cube map: 1 the sky around the normal (the map blurred over a hemisphere), 0 one constant, the sky's mean (as a renderer without image-based light has it)") \
    X(integrator,   INT,   "INTEGRATOR",   0,     1,      0,    0,       0,     0,    0,   0,    NULL,                    SCOPE_ANY,      \
      "0: the shading model (direct light, AO, one-level glass); 1: a path tracer through the same map() and materials, the Monte Carlo truth the model is priced against (common/pathtrace.glsl)") \
    X(tolerance,    FLOAT, NULL,          0,     1,      0.008, 0.008,  0.008, 0,    0,   0,    "0,0.004,0.008,0.016,0.032", SCOPE_ANY, \
      "adaptive sampling: after 2 samples a pixel stops once the standard error of its mean, as displayed (tone-mapped and sRGB-encoded, 0-1), is below this in its whole 3x3 block, none of its rays passed a surface by within the pixel, and it has the samples an edge in its block needs (contrast / 2.5 tolerances) (0, and under the path tracer: every pixel takes every sample)") \
    X(spp,          INT,   NULL,         1,     65536,  1,    4,       16,    256,  2,   0,    "1,2,4,8,16",            SCOPE_ANY,      \
      "samples per pixel for offline shots and a still window (progressive, jittered)")
/* clang-format on */

#define KNOB_CTYPE_INT int
#define KNOB_CTYPE_FLOAT float

typedef struct quality {
#define X(name, TYPE, ...) KNOB_CTYPE_##TYPE name;
    QUALITY_KNOBS(X)
#undef X
} quality;

typedef enum knob_id {
#define X(name, ...) KNOB_##name,
    QUALITY_KNOBS(X)
#undef X
    KNOB_COUNT
} knob_id;

typedef enum quality_preset { PRESET_DRAFT, PRESET_INTERACTIVE, PRESET_FINAL, PRESET_REFERENCE, PRESET_COUNT } quality_preset;

typedef enum knob_type { KNOB_INT, KNOB_FLOAT } knob_type;

typedef struct knob_def {
    const char *name, *glsl, *sweep, *help; /* glsl NULL: host-side only; sweep NULL: not swept */
    knob_type type;
    double min, max;
    double preset[PRESET_COUNT];
    double step_mul, step_add; /* the window's step rule; step_mul 0: not stepped */
    knob_scope scope;
} knob_def;

const knob_def *knob_get_def(knob_id k);
bool knob_from_name(const char *name, knob_id *k);
double knob_value(const quality *q, knob_id k);
void knob_set_value(quality *q, knob_id k, double v); /* rounds to the knob's type */
bool knob_window_steps(knob_id k);
/* The window's = (dir > 0) or − (dir < 0) applied to v, clamped to the knob's range. */
double knob_step(knob_id k, double v, int dir);

const char *preset_name(quality_preset p);
bool preset_from_name(const char *name, quality_preset *p);
quality preset_quality(quality_preset p);

/* "#define MAX_STEPS 64\n…" for every knob the shader reads, in table order. */
void quality_preamble(const quality *q, strbuf *out);

/* "name  help [draft/interactive/final/reference]" lines, for --help and the docs. */
void quality_describe(strbuf *out);

#endif
