/* check-formula over a formula's parameter ranges: its defaults, then each parameter at the ends of
 * its range (check.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/gpu.h"
#include "gpu/render.h"
#include "jobs/check/check.h"

/* Whether the user's overrides set fractal.KEY already (then its corners are not varied). */
static bool user_sets(const check_desc *d, const char *key)
{
    char prefix[FORMULA_KEY_MAX + 16];
    int n = snprintf(prefix, sizeof prefix, "fractal.%s=", key);
    for (int i = 0; i < d->set_count; i++)
        if (!strncmp(d->sets[i], prefix, (size_t)n))
            return true;
    return false;
}

static int add(char (*out)[CHECK_SET_MAX], int n, int max, const char *key, const char *value)
{
    if (n < max)
        snprintf(out[n], CHECK_SET_MAX, "fractal.%s=%s", key, value);
    return n + 1;
}

/* The shortest text that reads back as x: 0.01, not 0.00999999978. */
static const char *shortest(float x, char out[32])
{
    for (int digits = 6; digits <= 9; digits++) {
        snprintf(out, 32, "%.*g", digits, (double)x);
        if ((float)strtod(out, NULL) == x)
            break;
    }
    return out;
}

int check_corners(const formula *f, const check_desc *d, char (*out)[CHECK_SET_MAX], int max)
{
    int n = 0;
    char v[96];
    if (!user_sets(d, "iterations") && f->iterations_lo < f->iterations_hi) {
        snprintf(v, sizeof v, "%d", f->iterations_lo), n = add(out, n, max, "iterations", v);
        snprintf(v, sizeof v, "%d", f->iterations_hi), n = add(out, n, max, "iterations", v);
    }
    for (int i = 0; i < f->param_count; i++) {
        const formula_param *p = &f->params[i];
        if (p->type == FORMULA_COLOR || p->type == FORMULA_COLOR4 || user_sets(d, p->key))
            continue;
        if (p->type == FORMULA_BOOL) {
            n = add(out, n, max, p->key, p->def[0] != 0 ? "false" : "true");
            continue;
        }
        /* the ends (a gap's ends too); a vector's components one at a time, the others at their defaults */
        float ends[4] = {p->lo, p->hi, p->gap_lo, p->gap_hi};
        int comps = formula_components(p->type);
        for (int k = 0; k < comps; k++)
            for (int e = 0; e < (p->has_gap ? 4 : 2); e++) {
                float x[4] = {p->def[0], p->def[1], p->def[2], p->def[3]};
                x[k] = ends[e];
                if (p->type == FORMULA_INT) {
                    snprintf(v, sizeof v, "%d", (int)x[0]);
                } else {
                    char c[32];
                    for (int j = 0, at = 0; j < comps; j++)
                        at += snprintf(v + at, sizeof v - (size_t)at, "%s%s", j ? "," : "", shortest(x[j], c));
                }
                n = add(out, n, max, p->key, v);
            }
    }
    return n < max ? n : max;
}

/* How far a check is from passing: a failure outranks any pass, then the step times the worst ratio. */
static double badness(const formula_check *c)
{
    return (c->ok ? 0 : 1e6) + (c->contained ? 0 : 1e3) + c->step * c->worst;
}

bool check_formula_run(const check_desc *d, err_t *err)
{
    scene s;
    if (!scene_load(d->scene, d->sets, d->set_count, &s, err))
        return false;
    if (!gpu_open(&(gpu_desc){.headless = true}, err)) {
        scene_free(&s);
        return false;
    }
    formula_check c;
    bool ok = render_init(err) && check_formula(&s, 1u, CHECK_RAYS, &c, err);
    char (*corners)[CHECK_SET_MAX] = util_alloc(sizeof *corners * CHECK_CORNERS_MAX, "corners");
    int n = ok && !d->defaults_only ? check_corners(&s.fractal.formula, d, corners, CHECK_CORNERS_MAX) : 0, failed = !c.ok, refused = 0;
    const char *worst = NULL;
    double worst_badness = ok ? badness(&c) : 0;
    if (ok) {
        const formula *f = &s.fractal.formula;
        strbuf text = {0};
        bool given = false; /* parameters the user set (beside the formula check-formula names) */
        for (int i = 0; i < d->set_count; i++)
            given |= strncmp(d->sets[i], "fractal.formula=", strlen("fractal.formula=")) != 0;
        sb_printf(&text, "formula %s (%s)%s%s%s at %s: %s\n", f->name, f->file, s.fractal.julia ? ", Julia set" : "",
                  s.fractal.has_hybrid ? ", hybrid with " : "", s.fractal.has_hybrid ? s.fractal.hybrid.name : "",
                  given ? "the values given" : "its defaults", c.ok ? "passes" : "FAILS");
        check_describe(&s, &c, &text);
        if (n)
            sb_printf(&text, "each parameter at the ends of its range, the others at their defaults:\n");
        fputs(text.data, stdout);
        fflush(stdout);
        sb_free(&text);
    }
    const char **sets = util_alloc(sizeof *sets * (size_t)(d->set_count + 1), "corner overrides");
    for (int i = 0; i < d->set_count; i++)
        sets[i] = d->sets[i];
    for (int k = 0; ok && k < n; k++) {
        sets[d->set_count] = corners[k];
        scene t;
        err_t why;
        if (!scene_load(d->scene, sets, d->set_count + 1, &t, &why)) { /* a @require the corner breaks */
            const char *what = strstr(why.msg, ": fractal: "); /* past the scene file's name */
            printf("  %-30s refused: %s\n", corners[k] + strlen("fractal."), what ? what + strlen(": fractal: ") : why.msg);
            refused++;
            continue;
        }
        formula_check ck;
        ok = check_formula(&t, 1u, CHECK_CORNER_RAYS, &ck, err);
        ck.ok = check_passes(&ck, false);
        if (ok) {
            printf("  %-30s %s  estimate/distance at worst %.3f (at step %.2g: %.3f)%s%s%s%s\n",
                   corners[k] + strlen("fractal."), ck.ok ? "passes" : "FAILS ", ck.worst, ck.step, ck.step * ck.worst,
                   ck.crossing ? "" : "; no ray met the set (dust, or empty)", ck.contained ? "" : "; the set crosses its bounding sphere",
                   ck.nonfinite ? "; NaN or Inf" : "", ck.loops_measured && ck.loops > ck.loops_declared ? "; loops past @loops" : "");
            fflush(stdout);
            failed += !ck.ok;
            if (badness(&ck) > worst_badness)
                worst_badness = badness(&ck), worst = corners[k];
        }
        scene_free(&t);
    }
    if (ok && n)
        printf("worst parameter set: %s; %d of %d range ends fail%s\n", worst ? worst : "the defaults", failed - !c.ok,
               n - refused, refused ? " (the rest are refused by the formula's @require)" : "");
    fflush(stdout);
    if (ok && failed)
        ok = err_set(err, "formula %s fails its check (above)", s.fractal.formula.name);
    free(sets);
    free(corners);
    render_shutdown();
    gpu_close();
    scene_free(&s);
    return ok;
}
