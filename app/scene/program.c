/* program — the registry of scene programs (program.h). */
#include "scene/program.h"

#include <assert.h>
#include <string.h>

#include "util.h"

static const program_def PROGRAMS[PROGRAM_COUNT] = {
#define X(id, name, map, block, family, parse, frame, frame_from, adaptive, defines, uniforms, bench)                 \
    [PROGRAM_##id] = {name, map, block, family, parse, frame, frame_from, adaptive, defines, uniforms, bench},
    PROGRAM_LIST(X)
#undef X
};

const program_def *program_get(program_kind p)
{
    assert(p < PROGRAM_COUNT);
    return &PROGRAMS[p];
}

const char *program_name(program_kind p) { return program_get(p)->name; }
bool program_is_fractal(program_kind p) { return program_get(p)->family == FAMILY_FRACTAL; }

bool program_from_name(const char *name, program_kind *p)
{
    for (int i = 0; i < PROGRAM_COUNT; i++)
        if (!strcmp(name, PROGRAMS[i].name)) {
            *p = (program_kind)i;
            return true;
        }
    return false;
}

void program_names(strbuf *out)
{
    for (int i = 0; i < PROGRAM_COUNT; i++)
        sb_printf(out, "%s%s", i ? ", " : "", PROGRAMS[i].name);
}
