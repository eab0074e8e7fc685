#include "variant.h"

#include <assert.h>
#include <string.h>

static const struct { const char *name, *summary; } EFFECTS[EFFECT_COUNT] = {
#define X(id, name, what) {name, what},
    EFFECT_LIST(X)
#undef X
};

static const char *const EFFECT_DEFINES[EFFECT_COUNT] = {
#define X(id, name, what) "FX_" #id,
    EFFECT_LIST(X)
#undef X
};

const char *effect_name(effect e) { assert(e < EFFECT_COUNT); return EFFECTS[e].name; }
const char *effect_summary(effect e) { assert(e < EFFECT_COUNT); return EFFECTS[e].summary; }

bool effect_from_name(const char *name, effect *e)
{
    for (int i = 0; i < EFFECT_COUNT; i++)
        if (!strcmp(name, EFFECTS[i].name)) {
            *e = (effect)i;
            return true;
        }
    return false;
}

static const struct { const char *name, *map_file; } PROGRAMS[PROGRAM_COUNT] = {
    [PROGRAM_CSG] = {"csg", NULL},
    [PROGRAM_MANDELBULB] = {"mandelbulb", "fractal/mandelbulb.glsl"},
    [PROGRAM_MENGER] = {"menger", "fractal/menger.glsl"},
    [PROGRAM_MANDELBOX] = {"mandelbox", "fractal/mandelbox.glsl"},
    [PROGRAM_TERRAIN] = {"terrain", "terrain/terrain.glsl"},
    [PROGRAM_NOISE] = {"noise", "terrain/noise.glsl"},
};

const char *program_name(program_kind p) { assert(p < PROGRAM_COUNT); return PROGRAMS[p].name; }
const char *program_map_file(program_kind p) { assert(p < PROGRAM_COUNT); return PROGRAMS[p].map_file; }
bool program_is_fractal(program_kind p) { return p == PROGRAM_MANDELBULB || p == PROGRAM_MENGER || p == PROGRAM_MANDELBOX; }

bool program_from_name(const char *name, program_kind *p)
{
    for (int i = 0; i < PROGRAM_COUNT; i++)
        if (!strcmp(name, PROGRAMS[i].name)) {
            *p = (program_kind)i;
            return true;
        }
    return false;
}

static const char *const PRESET_NAMES[PRESET_COUNT] = {"draft", "interactive", "final", "reference"};

/* draft: fastest usable look; interactive: the window's default; final: offline shots;
 * reference: far stricter than final, the ground truth the bench compares against. */
/* Picked from the measured fronts (docs/bench): the hit threshold buys the most accuracy per ms, so it
 * halves at each step; more than 16 shadow steps, 64 march steps or 2–4 texture taps bought nothing
 * measurable in any scene; samples per pixel (anti-aliasing) cost the most. */
static const quality PRESETS[PRESET_COUNT] = {
    [PRESET_DRAFT] = {.max_steps = 64, .hit_k = 2.0f, .step_factor = 1.0f, .max_dist = 100.0f,
                      .shadow_steps = 16, .ao_samples = 3, .bounces = 1, .aniso_taps = 1, .over_relax = 1.0f,
                      .linear_step = 2.0f, .step_growth = 1.05f, .binary_steps = 4, .spp = 1},
    [PRESET_INTERACTIVE] = {.max_steps = 128, .hit_k = 1.0f, .step_factor = 1.0f, .max_dist = 100.0f,
                            .shadow_steps = 32, .ao_samples = 5, .bounces = 3, .aniso_taps = 2, .over_relax = 1.0f,
                            .linear_step = 1.0f, .step_growth = 1.02f, .binary_steps = 6, .spp = 4},
    [PRESET_FINAL] = {.max_steps = 256, .hit_k = 0.5f, .step_factor = 1.0f, .max_dist = 100.0f,
                      .shadow_steps = 32, .ao_samples = 5, .bounces = 6, .aniso_taps = 4, .over_relax = 1.0f,
                      .linear_step = 0.5f, .step_growth = 1.01f, .binary_steps = 8, .spp = 16},
    [PRESET_REFERENCE] = {.max_steps = 1024, .hit_k = 0.25f, .step_factor = 1.0f, .max_dist = 100.0f,
                          .shadow_steps = 256, .ao_samples = 8, .bounces = 10, .aniso_taps = 16, .over_relax = 1.0f,
                          .linear_step = 0.25f, .step_growth = 1.0f, .binary_steps = 12, .spp = 256},
};

const char *preset_name(quality_preset p) { assert(p < PRESET_COUNT); return PRESET_NAMES[p]; }

bool preset_from_name(const char *name, quality_preset *p)
{
    for (int i = 0; i < PRESET_COUNT; i++)
        if (!strcmp(name, PRESET_NAMES[i])) {
            *p = (quality_preset)i;
            return true;
        }
    return false;
}

quality preset_quality(quality_preset p) { assert(p < PRESET_COUNT); return PRESETS[p]; }

void variant_preamble(const variant *v, strbuf *out)
{
    sb_printf(out, "#define PROGRAM_%s 1\n", program_name(v->program));
    for (int e = 0; e < EFFECT_COUNT; e++)
        sb_printf(out, "#define %s %d\n#define %s_BIT %du\n", EFFECT_DEFINES[e], (v->effects >> e) & 1u,
                  EFFECT_DEFINES[e], 1 << e);
    sb_printf(out,
              "#define MAX_STEPS %d\n#define HIT_K %.9g\n#define STEP_FACTOR %.9g\n#define MAX_DIST %.9g\n"
              "#define SHADOW_STEPS %d\n#define AO_SAMPLES %d\n#define BOUNCES %d\n#define ANISO_TAPS %d\n"
              "#define NUM_LIGHTS %d\n#define NUM_MATERIALS %d\n#define MIRROR_ROUGHNESS %.9g\n"
              "#define OVER_RELAX %.9g\n#define FRACTAL_ITERATIONS %d\n#define PRECISION_REL %.9g\n"
              "#define LINEAR_STEP %.9g\n#define STEP_GROWTH %.9g\n#define BINARY_STEPS %d\n#define TERRAIN_MAXMIP %d\n",
              v->q.max_steps, (double)v->q.hit_k, (double)v->q.step_factor, (double)v->q.max_dist,
              v->q.shadow_steps, v->q.ao_samples, v->q.bounces, v->q.aniso_taps, v->num_lights, v->num_materials, (double)MIRROR_ROUGHNESS,
              (double)v->q.over_relax, v->fractal_iterations, (double)PRECISION_REL,
              (double)v->q.linear_step, (double)v->q.step_growth, v->q.binary_steps, v->terrain_maxmip);
}
