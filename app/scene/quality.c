#include "scene/quality.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#define KNOB_TYPE_INT KNOB_INT
#define KNOB_TYPE_FLOAT KNOB_FLOAT

static const knob_def KNOBS[KNOB_COUNT] = {
#define X(name, TYPE, glsl, lo, hi, d, i, f, r, mul, add, sweep, scope, help)                                  \
    [KNOB_##name] = {#name, glsl, sweep, help, KNOB_TYPE_##TYPE, lo, hi, {d, i, f, r}, mul, add, scope},
    QUALITY_KNOBS(X)
#undef X
};

static const size_t OFFSETS[KNOB_COUNT] = {
#define X(name, ...) [KNOB_##name] = offsetof(quality, name),
    QUALITY_KNOBS(X)
#undef X
};

const knob_def *knob_get_def(knob_id k)
{
    assert(k < KNOB_COUNT);
    return &KNOBS[k];
}

bool knob_from_name(const char *name, knob_id *k)
{
    for (int i = 0; i < KNOB_COUNT; i++)
        if (!strcmp(name, KNOBS[i].name)) {
            *k = (knob_id)i;
            return true;
        }
    return false;
}

double knob_value(const quality *q, knob_id k)
{
    assert(k < KNOB_COUNT);
    const char *p = (const char *)q + OFFSETS[k];
    int i;
    float f;
    if (KNOBS[k].type == KNOB_INT) {
        memcpy(&i, p, sizeof i);
        return i;
    }
    memcpy(&f, p, sizeof f);
    return f;
}

void knob_set_value(quality *q, knob_id k, double v)
{
    assert(k < KNOB_COUNT);
    char *p = (char *)q + OFFSETS[k];
    if (KNOBS[k].type == KNOB_INT) {
        int i = (int)lround(v);
        memcpy(p, &i, sizeof i);
    } else {
        float f = (float)v;
        memcpy(p, &f, sizeof f);
    }
}

bool knob_window_steps(knob_id k) { return knob_get_def(k)->step_mul > 0; }

double knob_step(knob_id k, double v, int dir)
{
    const knob_def *d = knob_get_def(k);
    assert(d->step_mul > 0);
    v = dir > 0 ? v * d->step_mul + d->step_add : (v - d->step_add) / d->step_mul;
    if (d->type == KNOB_INT)
        v = round(v);
    return v < d->min ? d->min : v > d->max ? d->max : v;
}

static const char *const PRESET_NAMES[PRESET_COUNT] = {"draft", "interactive", "final", "reference"};

const char *preset_name(quality_preset p)
{
    assert(p < PRESET_COUNT);
    return PRESET_NAMES[p];
}

bool preset_from_name(const char *name, quality_preset *p)
{
    for (int i = 0; i < PRESET_COUNT; i++)
        if (!strcmp(name, PRESET_NAMES[i])) {
            *p = (quality_preset)i;
            return true;
        }
    return false;
}

quality preset_quality(quality_preset p)
{
    assert(p < PRESET_COUNT);
    quality q;
    memset(&q, 0, sizeof q);
    for (int k = 0; k < KNOB_COUNT; k++)
        knob_set_value(&q, (knob_id)k, KNOBS[k].preset[p]);
    return q;
}

void quality_preamble(const quality *q, strbuf *out)
{
    for (int k = 0; k < KNOB_COUNT; k++) {
        if (!KNOBS[k].glsl)
            continue;
        if (KNOBS[k].type == KNOB_INT)
            sb_printf(out, "#define %s %d\n", KNOBS[k].glsl, (int)knob_value(q, (knob_id)k));
        else
            sb_printf(out, "#define %s %.9g\n", KNOBS[k].glsl, knob_value(q, (knob_id)k));
    }
}

void quality_describe(strbuf *out)
{
    for (int k = 0; k < KNOB_COUNT; k++) {
        const knob_def *d = &KNOBS[k];
        sb_printf(out, "  %-13s %s [%g/%g/%g/%g]\n", d->name, d->help, d->preset[0], d->preset[1], d->preset[2],
                  d->preset[3]);
    }
}
