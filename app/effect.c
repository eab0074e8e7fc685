#include "effect.h"

#include <assert.h>
#include <string.h>

#include "scene.h"

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

/* An effect is compiled in when the scene's content calls for it ("auto"), then "on"/"off" force it. */
unsigned effect_derive(const scene *s)
{
    bool shadows = false, soft = false, mirror = false, glass = false, relief = false;
    for (int i = 0; i < s->light_count; i++) {
        shadows |= s->lights[i].shadow != SHADOW_NONE;
        soft |= s->lights[i].shadow == SHADOW_SOFT;
    }
    for (int i = 0; i < s->material_count; i++) {
        const scene_material *m = &s->materials[i];
        glass |= m->transmission > 0;
        relief |= m->relief >= 0;
        mirror |= m->transmission == 0 && m->roughness <= MIRROR_ROUGHNESS;
    }
    bool want[EFFECT_COUNT] = {
        [EFFECT_SHADOWS] = shadows,
        [EFFECT_SOFT_SHADOWS] = soft,
        [EFFECT_AO] = s->env_intensity > 0 && s->quality.ao_samples > 0,
        [EFFECT_REFLECTIONS] = mirror && s->quality.bounces > 0,
        [EFFECT_REFRACTION] = glass && s->quality.bounces > 0,
        [EFFECT_FOG] = s->has_fog,
        [EFFECT_ENVMAP] = s->has_cubemap,
        [EFFECT_TEXTURES] = s->texture_count > 0 && !(s->texture_count == 1 && s->texture_linear[0]),
        [EFFECT_AA] = s->quality.spp > 1,
        [EFFECT_GLOW] = s->fractal.glow > 0,
        [EFFECT_RELIEF] = relief,
        [EFFECT_DROPLETS] = s->has_droplets,
    };
    unsigned fx = 0;
    for (int e = 0; e < EFFECT_COUNT; e++) {
        bool on = s->effect_modes[e] == EFFECT_ON || (s->effect_modes[e] == EFFECT_AUTO && want[e]);
        fx |= (unsigned)on << e;
    }
    /* penumbrae are a kind of shadow: without shadow rays there is nothing to soften */
    if (!(fx & (1u << EFFECT_SHADOWS)))
        fx &= ~(1u << EFFECT_SOFT_SHADOWS);
    /* droplets come from a file: a scene without one has none to draw */
    if (!s->has_droplets)
        fx &= ~(1u << EFFECT_DROPLETS);
    /* terrain programs run the lab's search themselves, over their own surface: no relief there */
    if (program_get(s->program)->family == FAMILY_TERRAIN)
        fx &= ~(1u << EFFECT_RELIEF);
    return fx;
}


void effect_preamble(unsigned effects, strbuf *out)
{
    for (int e = 0; e < EFFECT_COUNT; e++)
        sb_printf(out, "#define %s %d\n#define %s_BIT %du\n", EFFECT_DEFINES[e], (effects >> e) & 1u,
                  EFFECT_DEFINES[e], 1 << e);
}
