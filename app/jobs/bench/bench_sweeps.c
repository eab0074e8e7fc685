/* bench_sweeps — which sweeps a bench runs, with which values (bench_sweeps.h). */
#include "jobs/bench/bench_sweeps.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jobs/bench/bench_report.h"
#include "scene/effect.h"
#include "scene/program.h"


/* A fractal's iterations from a third of its default to a third past it (within the range its formula
 * declares, formula.h), the default among them: where detail stops paying for its time. */
static void fractal_iterations_sweep(const formula *f, bench_sweep *out)
{
    enum { POINTS = 5 };
    *out = (bench_sweep){.name = "iterations", .key = "fractal.iterations"};
    int lo = f->iterations / 3 > f->iterations_lo ? f->iterations / 3 : f->iterations_lo;
    int hi = f->iterations + f->iterations / 3 < f->iterations_hi ? f->iterations + f->iterations / 3 : f->iterations_hi;
    int last = 0;
    bool def_done = false;
    for (int i = 0; i < POINTS; i++) {
        int v = lo + (int)lround((double)(hi - lo) * i / (POINTS - 1));
        for (int pass = 0; pass < 2; pass++) { /* the default in its place */
            int w = pass == 0 && !def_done && f->iterations <= v ? f->iterations : v;
            def_done |= w == f->iterations;
            if (w > last) {
                size_t len = strlen(out->values);
                snprintf(out->values + len, sizeof out->values - len, "%s%d", len ? "," : "", w);
                last = w;
            }
        }
    }
}

/* Every sweep the bench knows for scene s; `applies` says which run by default. */
int bench_list_sweeps(const scene *s, bench_sweep *out, bool *applies)
{
    int n = 0;
    for (int k = 0; k < KNOB_COUNT; k++) {
        const knob_def *d = knob_get_def((knob_id)k);
        if (!d->sweep)
            continue;
        out[n] = (bench_sweep){0};
        snprintf(out[n].name, sizeof out[n].name, "%s", d->name);
        snprintf(out[n].key, sizeof out[n].key, "quality.%s", d->name);
        snprintf(out[n].values, sizeof out[n].values, "%s", d->sweep);
        applies[n++] = scene_knob_applies(s, (knob_id)k);
    }
    /* the program's own: "key=v1,v2;key2=…", named by the key's last part */
    const char *own = program_get(s->program)->bench;
    for (const char *p = own; p && *p && n < BENCH_MAX_SWEEPS - 1;) {
        size_t len = strcspn(p, ";"), eq = strcspn(p, "=");
        assert(eq < len);
        out[n] = (bench_sweep){0};
        snprintf(out[n].key, sizeof out[n].key, "%.*s", (int)eq, p);
        const char *dot = strrchr(out[n].key, '.');
        snprintf(out[n].name, sizeof out[n].name, "%s", dot ? dot + 1 : out[n].key);
        snprintf(out[n].values, sizeof out[n].values, "%.*s", (int)(len - eq - 1), p + eq + 1);
        applies[n++] = true;
        p += len + (p[len] == ';');
    }
    if (program_is_fractal(s->program) && n < BENCH_MAX_SWEEPS - 3) {
        fractal_iterations_sweep(&s->fractal.formula, &out[n]), applies[n++] = true;
        /* the hit rules side by side (a fragment's by default; any fractal's with --knob), and the
         * Fragmentarium rule's Detail where it is the rule */
        out[n] = (bench_sweep){.name = "hit_rule", .key = "fractal.hit_rule", .values = "footprint,fragment"};
        applies[n++] = s->fractal.formula.fragment;
        out[n] = (bench_sweep){.name = "detail", .key = "fractal.detail", .values = "-4,-3.5,-3,-2.5,-2"};
        applies[n++] = s->fractal.hit_rule == HIT_RULE_FRAGMENT;
    }
    /* the model's approximations of light transport that are effects (fx_NAME), off and on (each
     * priced against the path tracer by bench --truth path): only those the scene uses */
    static const bench_approximation MODEL[] = {
#define X(knob, off, on, what) {knob, off, on, what},
        BENCH_APPROXIMATIONS(X)
#undef X
    };
    for (size_t i = 0; i < sizeof MODEL / sizeof MODEL[0] && n < BENCH_MAX_SWEEPS - 1; i++) {
        effect e;
        if (strncmp(MODEL[i].knob, "fx_", 3) || !effect_from_name(MODEL[i].knob + 3, &e))
            continue; /* a quality knob: swept with the others */
        out[n] = (bench_sweep){0};
        snprintf(out[n].name, sizeof out[n].name, "%s", MODEL[i].knob);
        snprintf(out[n].key, sizeof out[n].key, "effects.%s", effect_name(e));
        snprintf(out[n].values, sizeof out[n].values, "%s,%s", MODEL[i].off, MODEL[i].on);
        applies[n++] = (s->effects & (1u << e)) != 0;
    }
    out[n] = (bench_sweep){.name = "resolution_scale", .values = "0.25,0.5,0.75,1", .own = true};
    applies[n++] = true;
    return n;
}

/* A default sweep's values with the scene's own value among them, so each panel rings its operating
 * point: v as it is where it holds keep (or keep is ""), else keep put where it falls in v's order
 * (appended where v is not numbers in order). With quick, three of them: the first, keep (or the
 * middle) and the last. Into out. */
const char *bench_sweep_values(const char *v, const char *keep, bool quick, char *out, size_t n)
{
    char list[512];
    snprintf(list, sizeof list, "%s", v);
    const char *vals[65];
    int k = 0, at = -1;
    char *save = NULL;
    for (char *t = strtok_r(list, ",", &save); t && k < 64; t = strtok_r(NULL, ",", &save)) {
        if (*keep && bench_same_value(t, keep))
            at = k;
        vals[k++] = t;
    }
    if (*keep && at < 0) {
        char *e;
        double x = strtod(keep, &e);
        double dir = k > 1 ? strtod(vals[k - 1], NULL) - strtod(vals[0], NULL) : 1;
        at = k;
        for (int i = 0; !*e && i < k; i++) { /* before the first value it precedes, in v's direction */
            double a = strtod(vals[i], NULL);
            if ((dir >= 0 && x < a) || (dir < 0 && x > a)) {
                at = i;
                break;
            }
        }
        memmove(&vals[at + 1], &vals[at], sizeof vals[0] * (size_t)(k - at));
        vals[at] = keep;
        k++;
    }
    if (quick && k > 3) {
        int mid = at > 0 && at < k - 1 ? at : k / 2;
        snprintf(out, n, "%s,%s,%s", vals[0], vals[mid], vals[k - 1]);
        return out;
    }
    out[0] = '\0';
    for (int i = 0; i < k; i++) {
        size_t len = strlen(out);
        snprintf(out + len, n - len, "%s%s", i ? "," : "", vals[i]);
    }
    return out;
}

int bench_count_values(const char *v)
{
    int n = 1;
    for (; *v; v++)
        n += *v == ',';
    return n;
}

