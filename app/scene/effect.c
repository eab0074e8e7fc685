#include "scene/effect.h"

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

void effect_preamble(unsigned effects, strbuf *out)
{
    for (int e = 0; e < EFFECT_COUNT; e++)
        sb_printf(out, "#define %s %d\n#define %s_BIT %du\n", EFFECT_DEFINES[e], (effects >> e) & 1u,
                  EFFECT_DEFINES[e], 1 << e);
}
