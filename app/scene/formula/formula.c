/* formula — a formula's declarations, read from its GLSL file (formula.h). */
/* realpath() is XSI */
#define _XOPEN_SOURCE 700
#include "scene/formula/formula.h"

#include <ctype.h>
#include <limits.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/formula/frag.h"

static const char *const TYPE_NAMES[] = {[FORMULA_FLOAT] = "float", [FORMULA_INT] = "int", [FORMULA_BOOL] = "bool",
                                         [FORMULA_VEC3] = "vec3", [FORMULA_COLOR] = "colour",
                                         [FORMULA_VEC2] = "vec2", [FORMULA_VEC4] = "vec4", [FORMULA_COLOR4] = "colour4"};

static const char *skip_space(const char *p)
{
    while (*p == ' ' || *p == '\t')
        p++;
    return p;
}

/* "uMinRadius" -> "min_radius" (false when it does not start with 'u' and a capital). */
static bool key_of(const char *uniform, char *key, size_t n)
{
    if (uniform[0] != 'u' || !isupper((unsigned char)uniform[1]))
        return false;
    size_t k = 0;
    for (const char *p = uniform + 1; *p && k + 2 < n; p++) {
        if (isupper((unsigned char)*p) && p > uniform + 1)
            key[k++] = '_';
        key[k++] = (char)tolower((unsigned char)*p);
    }
    key[k] = '\0';
    return k > 0;
}

/* Up to `count` numbers separated by commas; false unless exactly `count` finite ones. */
static bool numbers(const char **p, float *v, int count)
{
    for (int i = 0; i < count; i++) {
        char *end;
        double x = strtod(skip_space(*p), &end);
        if (end == skip_space(*p) || !isfinite((float)x)) /* 1e39 is a finite double but an infinite float */
            return false;
        v[i] = (float)x;
        *p = skip_space(end);
        if (i + 1 < count) {
            if (**p != ',')
                return false;
            (*p)++;
        }
    }
    return true;
}

/* "[LO, HI]" and an optional "not (A, B)". */
static bool range(const char **p, formula_param *q)
{
    float r[2];
    if (**p != '[')
        return false;
    (*p)++;
    if (!numbers(p, r, 2) || **p != ']' || r[0] > r[1])
        return false;
    q->lo = r[0], q->hi = r[1];
    *p = skip_space(*p + 1);
    if (!strncmp(*p, "not (", 5)) {
        *p += 5;
        if (!numbers(p, r, 2) || **p != ')' || r[0] >= r[1])
            return false;
        q->has_gap = true, q->gap_lo = r[0], q->gap_hi = r[1];
        *p = skip_space(*p + 1);
    }
    return true;
}

/* "uniform TYPE uName; // @param DEFAULT [LO, HI] description" (or @color). */
static bool param_line(const char *line, const char *at, formula_param *q, char *why, size_t n)
{
    char type[16], name[FORMULA_KEY_MAX];
    int end = 0;
    if (sscanf(line, " uniform %15s %47[A-Za-z0-9_]%n", type, name, &end) != 2 || end == 0)
        return snprintf(why, n, "expected 'uniform TYPE uName; // @param ...'") < 0;
    if (isalnum((unsigned char)line[end]) || line[end] == '_') /* cut at 47: the shader would never get it */
        return snprintf(why, n, "a parameter's uniform name is at most %d characters", FORMULA_KEY_MAX - 1) < 0;
    if (*skip_space(line + end) != ';')
        return snprintf(why, n, "expected 'uniform TYPE uName; // @param ...'") < 0;
    bool color = !strncmp(at, "@color", 6);
    *q = (formula_param){0};
    snprintf(q->uniform, sizeof q->uniform, "%s", name);
    if (!key_of(name, q->key, sizeof q->key))
        return snprintf(why, n, "'%s': a parameter's uniform is named uName (uPower, uMinRadius)", name) < 0;
    const char *p = skip_space(at + (color ? 6 : 6));
    if (!strcmp(type, "float") || !strcmp(type, "int"))
        q->type = type[0] == 'f' ? FORMULA_FLOAT : FORMULA_INT;
    else if (!strcmp(type, "bool"))
        q->type = FORMULA_BOOL;
    else if (!strcmp(type, "vec3"))
        q->type = color ? FORMULA_COLOR : FORMULA_VEC3;
    else
        return snprintf(why, n, "'%s': a parameter is a float, int, bool or vec3", type) < 0;
    if (color && q->type != FORMULA_COLOR)
        return snprintf(why, n, "@color is for a vec3") < 0;
    if (q->type == FORMULA_BOOL) {
        bool t = !strncmp(p, "true", 4), f = !strncmp(p, "false", 5);
        if (!t && !f)
            return snprintf(why, n, "a bool's default is true or false") < 0;
        q->def[0] = t ? 1.0f : 0.0f, q->lo = 0, q->hi = 1;
        p = skip_space(p + (t ? 4 : 5));
    } else if (q->type == FORMULA_COLOR) {
        if (!numbers(&p, q->def, 3))
            return snprintf(why, n, "a colour's default is R,G,B") < 0;
        q->lo = 0, q->hi = 1;
    } else {
        if (!numbers(&p, q->def, q->type == FORMULA_VEC3 ? 3 : 1) || !range(&p, q))
            return snprintf(why, n, "expected DEFAULT [LO, HI] (a vec3's default is X,Y,Z)") < 0;
    }
    for (int i = 0; i < formula_components(q->type); i++)
        if (q->def[i] < q->lo || q->def[i] > q->hi || (q->type == FORMULA_INT && q->def[i] != floorf(q->def[i])))
            return snprintf(why, n, "the default is outside its range") < 0;
    snprintf(q->description, sizeof q->description, "%s", p);
    return true;
}

/* The directives of a formula's estimate: @escape, @de, @trap, @exact, @deep (formula.h). *handled: the
 * directive was one of them; then a problem is written to why (empty: none). */
static void estimate_directive(formula *f, const char *at, char *why, size_t n, bool *handled)
{
    const char *p;
    *handled = true;
    why[0] = '\0';
    if (!strncmp(at, "@escape", 7)) {
        snprintf(f->escape, sizeof f->escape, "%s", skip_space(at + 7));
        if (!f->escape[0])
            snprintf(why, n, "expected @escape EXPR: the radius beyond which orbits only grow");
    } else if (!strncmp(at, "@de", 3) && (at[3] == ' ' || at[3] == '\t' || !at[3])) {
        p = skip_space(at + 3);
        if (strcmp(p, "log") && strcmp(p, "linear"))
            snprintf(why, n, "expected @de log (orbits grow like a power) or @de linear (like a scale)");
        f->step_formula = true;
        f->de_log = !strcmp(p, "log");
    } else if (!strncmp(at, "@trap", 5)) {
        /* two expressions: split at the first space outside parentheses */
        const char *q = skip_space(at + 5), *c = q;
        for (int depth = 0; *c && (depth > 0 || (*c != ' ' && *c != '\t')); c++)
            depth += *c == '(' ? 1 : *c == ')' ? -1 : 0;
        const char *hi = skip_space(c);
        if (c == q || !*hi || c - q >= FORMULA_EXPR_MAX) {
            snprintf(why, n, "expected @trap LO HI: the orbit trap's values spread over the palette");
            return;
        }
        snprintf(f->trap[0], sizeof f->trap[0], "%.*s", (int)(c - q), q);
        snprintf(f->trap[1], sizeof f->trap[1], "%s", hi);
    } else if (!strncmp(at, "@loops", 6)) {
        snprintf(f->loops, sizeof f->loops, "%s", skip_space(at + 6));
        if (!f->loops[0])
            snprintf(why, n, "expected @loops EXPR: the loop iterations one estimate runs (e.g. iterations * 3)");
    } else if (!strncmp(at, "@exact", 6) && !at[6 + strspn(at + 6, " \t")]) {
        f->exact = true;
    } else if (!strncmp(at, "@deep", 5)) {
        f->deep = true;
        p = skip_space(at + 5);
        if (*p && strncmp(p, "whole ", 6))
            snprintf(why, n, "expected @deep, or @deep whole KEY... (parameters that must be whole numbers there)");
        else if (*p)
            snprintf(f->deep_whole, sizeof f->deep_whole, "%s", skip_space(p + 6));
    } else {
        *handled = false;
    }
}

/* One "// @..." directive on line `line` (text from the '@'). */
static bool directive(formula *f, const char *line, const char *at, char *why, size_t n)
{
    bool handled;
    estimate_directive(f, at, why, n, &handled);
    if (handled)
        return why[0] == '\0';
    const char *p;
    if (!strncmp(at, "@param", 6) || !strncmp(at, "@color", 6)) {
        if (f->param_count == FORMULA_MAX_PARAMS)
            return snprintf(why, n, "more than %d parameters", FORMULA_MAX_PARAMS) < 0;
        formula_param *q = &f->params[f->param_count];
        if (!param_line(line, at, q, why, n))
            return false;
        for (int i = 0; i < f->param_count; i++)
            if (!strcmp(f->params[i].key, q->key))
                return snprintf(why, n, "'%s' is declared twice", q->key) < 0;
        static const char *const reserved[] = {FORMULA_COMMON_KEYS};
        for (size_t i = 0; i < sizeof reserved / sizeof *reserved; i++)
            if (!strcmp(reserved[i], q->key))
                return snprintf(why, n, "'%s' is a key of every fractal block: name the parameter otherwise", q->key) < 0;
        f->param_count++;
    } else if (!strncmp(at, "@formula", 8)) {
        snprintf(f->summary, sizeof f->summary, "%s", skip_space(at + 8));
    } else if (!strncmp(at, "@iterations", 11)) {
        formula_param q = {0};
        p = at + 11;
        if (!numbers(&p, q.def, 1) || !range(&p, &q) || q.def[0] < q.lo || q.def[0] > q.hi || q.lo < 1 || q.hi > 1000 ||
            q.def[0] != floorf(q.def[0]) || q.lo != floorf(q.lo) || q.hi != floorf(q.hi))
            return snprintf(why, n, "expected @iterations DEFAULT [LO, HI], whole numbers from 1 to 1000") < 0;
        f->iterations = (int)q.def[0], f->iterations_lo = (int)q.lo, f->iterations_hi = (int)q.hi;
    } else if (!strncmp(at, "@bound", 6)) {
        snprintf(f->bound, sizeof f->bound, "%s", skip_space(at + 6));
    } else if (!strncmp(at, "@step", 5)) {
        snprintf(f->step, sizeof f->step, "%s", skip_space(at + 5));
        if (!f->step[0])
            return snprintf(why, n, "expected @step FACTOR (an expression), above 0 and at most 1") < 0;
    } else if (!strncmp(at, "@require", 8)) {
        if (f->require_count == FORMULA_MAX_REQUIRES)
            return snprintf(why, n, "more than %d @require lines", FORMULA_MAX_REQUIRES) < 0;
        formula_require *r = &f->requires[f->require_count];
        const char *q = skip_space(at + 8), *op = strpbrk(q, "<>"), *msg = op ? strchr(op, '"') : NULL;
        const char *close = msg ? strchr(msg + 1, '"') : NULL;
        if (!op || !msg || !close || op - q >= FORMULA_EXPR_MAX || msg - op >= FORMULA_EXPR_MAX)
            return snprintf(why, n, "expected @require EXPR < EXPR \"message\" (or >)") < 0;
        *r = (formula_require){.less = *op == '<'};
        const char *rhs = skip_space(op + 1), *lhs_end = op, *rhs_end = msg;
        while (lhs_end > q && (lhs_end[-1] == ' ' || lhs_end[-1] == '\t'))
            lhs_end--;
        while (rhs_end > rhs && (rhs_end[-1] == ' ' || rhs_end[-1] == '\t'))
            rhs_end--;
        snprintf(r->lhs, sizeof r->lhs, "%.*s", (int)(lhs_end - q), q);
        snprintf(r->rhs, sizeof r->rhs, "%.*s", (int)(rhs_end - rhs), rhs);
        snprintf(r->message, sizeof r->message, "%.*s", (int)(close - msg - 1), msg + 1);
        f->require_count++;
    } else {
        return snprintf(why, n, "unknown directive (known: @formula @iterations @bound @step @escape @de @trap @loops "
                                "@exact @deep @require @param @color)") < 0;
    }
    return true;
}

bool formula_parse(const char *text, const char *source, formula *f, err_t *err)
{
    *f = (formula){.iterations = 1, .iterations_lo = 1, .iterations_hi = 1};
    snprintf(f->bound, sizeof f->bound, "2");
    snprintf(f->trap[0], sizeof f->trap[0], "0");
    snprintf(f->trap[1], sizeof f->trap[1], "1");
    snprintf(f->loops, sizeof f->loops, "iterations + 1");
    int line = 1;
    if (!strncmp(text, UTF8_BOM, 3)) /* an editor's byte-order mark: not text (shader.c skips it too) */
        text += 3;
    for (const char *p = text; *p; line++) {
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p), full = len;
        if (len && p[len - 1] == '\r') /* a CRLF file's lines end in \r */
            len--;
        for (size_t i = 0; i < len; i++)
            if (((unsigned char)p[i] < 0x20 && p[i] != '\t') || p[i] == 0x7f)
                return err_set(err, "%s:%d: a control character (0x%02x) in the text: a formula file is plain "
                                    "text", source, line, (unsigned char)p[i]);
        char buf[512];
        snprintf(buf, sizeof buf, "%.*s", (int)(len < sizeof buf ? len : sizeof buf - 1), p);
        const char *c = strstr(buf, "//");
        const char *at = c ? skip_space(c + 2) : NULL;
        if (at && *at == '@' && isalpha((unsigned char)at[1])) {
            char why[160] = "";
            if (!directive(f, buf, at, why, sizeof why))
                return err_set(err, "%s:%d: %s", source, line, why);
        }
        p = eol ? eol + 1 : p + full;
    }
    if (!f->summary[0])
        return err_set(err, "%s: no '// @formula' line: a formula file says what it is there", source);
    if (f->step_formula != (f->escape[0] != 0))
        return err_set(err, "%s: a step formula (formulaStep) declares both @de and @escape; a formula with its "
                            "own formulaDE declares neither", source);
    for (const char *k = f->deep_whole; *k;) { /* every key @deep names is a parameter */
        size_t len = strcspn(k, " \t");
        bool found = false;
        for (int i = 0; i < f->param_count; i++)
            found |= strlen(f->params[i].key) == len && !strncmp(f->params[i].key, k, len);
        if (!found)
            return err_set(err, "%s: @deep whole %.*s: no such parameter", source, (int)len, k);
        k = skip_space(k + len);
    }
    return true;
}

void formula_user_dir(char *out, size_t n)
{
    const char *dir = getenv("FATHOM_FORMULAS"), *xdg = getenv("XDG_CONFIG_HOME"), *home = getenv("HOME");
    if (dir && *dir)
        snprintf(out, n, "%s", dir);
    else if (xdg && *xdg)
        snprintf(out, n, "%s/fathom/formulas", xdg);
    else
        snprintf(out, n, "%s/.config/fathom/formulas", home ? home : ".");
}

/* Whether shaders/fractal/NAME.glsl is one of fathom's own formulas */
static bool shipped(const char *name, char *file, size_t fn, char *path, size_t pn)
{
    int a = snprintf(file, fn, "fractal/%s.glsl", name);
    int b = snprintf(path, pn, "%s/shaders/%s", util_data_dir(), file);
    return a < (int)fn && b < (int)pn && util_file_exists(path);
}

bool formula_load(const char *name_or_path, const char *dir, formula *f, err_t *err)
{
    char path[PATH_MAX_LEN], file[PATH_MAX_LEN], user[PATH_MAX_LEN], name[FORMULA_NAME_MAX], joined[PATH_MAX_LEN];
    bool is_path = strchr(name_or_path, '/') || strstr(name_or_path, ".glsl") || frag_is_fragment(name_or_path);
    if (is_path) {
        char abs[PATH_MAX]; /* realpath writes up to PATH_MAX */
        if (dir && name_or_path[0] != '/' && util_join(dir, name_or_path, joined, sizeof joined))
            name_or_path = joined; /* a scene's formula file lies beside it, as its textures do */
        if (!realpath(name_or_path, abs))
            return err_set(err, "formula file '%s' not found: check the path%s", name_or_path,
                           dir ? " (relative to the scene file's folder)" : "");
        if (strlen(abs) >= sizeof path)
            return err_set(err, "formula file '%s': its path is too long", name_or_path);
        memcpy(path, abs, strlen(abs) + 1);
        memcpy(file, path, sizeof file);
    } else {
        for (const char *c = name_or_path; *c; c++)
            if (!isalnum((unsigned char)*c) && *c != '_' && *c != '-')
                return err_set(err, "formula '%s': a name is letters, digits, '_' and '-' (or give a .glsl path)",
                               name_or_path);
        if (strlen(name_or_path) >= FORMULA_NAME_MAX)
            return err_set(err, "formula '%.64s…': the name is too long", name_or_path);
        /* a shipped name always means the shipped formula: a user's file of that name never replaces it
         * (formula_list says it is ignored); the user's folder holds only new names */
        formula_user_dir(user, sizeof user);
        if (!shipped(name_or_path, file, sizeof file, path, sizeof path)) {
            if (snprintf(path, sizeof path, "%s/%s.glsl", user, name_or_path) >= (int)sizeof path ||
                !util_file_exists(path)) {
                strbuf names = {0};
                formula_list(&names);
                char *notes = names.data ? strstr(names.data, "note: ") : NULL;
                if (notes) /* the names alone, on one line */
                    *notes = '\0';
                for (char *c = names.data; c && *c; c++)
                    if (*c == '\n')
                        *c = c[1] ? ' ' : '\0';
                err_set(err, "unknown formula '%s' (known: %s); or give a .glsl file, or put %s.glsl in %s (your "
                             "formula folder, $FATHOM_FORMULAS)", name_or_path, names.data ? names.data : "none",
                        name_or_path, user);
                sb_free(&names);
                return false;
            }
            memcpy(file, path, sizeof file);
        }
    }
    for (const char *c = file; *c; c++)
        if (*c == '"' || *c == '\\' || (unsigned char)*c < 0x20 || *c == 0x7f)
            return err_set(err, "formula file '%s': its path has a '\"', '\\' or control character, which GLSL's "
                                "#include cannot carry: rename it", file);
    if (frag_is_fragment(path)) /* a Fragmentarium fragment: read as data, translated (frag.h) */
        return frag_load(path, f, err);
    char *text;
    if (!util_read_file_max(path, UTIL_SOURCE_FILE_MAX, &text, NULL, err))
        return false;
    bool ok = formula_parse(text, path, f, err);
    free(text);
    const char *base = strrchr(path, '/');
    snprintf(name, sizeof name, "%.*s", (int)strcspn(base ? base + 1 : path, "."), base ? base + 1 : path);
    if (ok) {
        snprintf(f->name, sizeof f->name, "%s", name);
        snprintf(f->file, sizeof f->file, "%s", file);
    }
    return ok;
}

/* The .glsl files of a folder that declare a formula, sorted, appended one a line; with shadowed, a
 * file whose name is also a shipped formula's goes to notes instead, as ignored. */
static void list_dir(const char *dir, bool shadowed, strbuf *out, strbuf *notes)
{
    struct dirent **list;
    int n = scandir(dir, &list, NULL, alphasort);
    for (int i = 0; i < n; i++) {
        const char *d = list[i]->d_name, *dot = strrchr(d, '.');
        char path[PATH_MAX_LEN], *text, name[FORMULA_NAME_MAX], sf[PATH_MAX_LEN], sp[PATH_MAX_LEN];
        err_t e;
        formula f;
        if (dot && !strcmp(dot, ".glsl") && dot - d < FORMULA_NAME_MAX &&
            snprintf(path, sizeof path, "%s/%s", dir, d) < (int)sizeof path && util_read_file(path, &text, NULL, &e)) {
            snprintf(name, sizeof name, "%.*s", (int)(dot - d), d);
            if (strstr(text, "@formula") && formula_parse(text, path, &f, &e)) {
                if (shadowed && shipped(name, sf, sizeof sf, sp, sizeof sp))
                    sb_printf(notes, "note: %s is ignored: the shipped formula %s has its name; rename it\n", path,
                              name);
                else
                    sb_printf(out, "%s\n", name);
            }
            free(text);
        }
        free(list[i]);
    }
    if (n >= 0)
        free(list);
}

void formula_list(strbuf *out)
{
    char dir[PATH_MAX_LEN];
    snprintf(dir, sizeof dir, "%s/shaders/fractal", util_data_dir());
    strbuf notes = {0};
    list_dir(dir, false, out, NULL);
    formula_user_dir(dir, sizeof dir);
    list_dir(dir, true, out, &notes);
    if (notes.data)
        sb_append(out, notes.data);
    sb_free(&notes);
}

void formula_describe(const formula *f, strbuf *out)
{
    sb_printf(out, "formula %s (%s)\n  %s\n  each key as --set KEY=VALUE takes it (a vec3 as x,y,z):\n", f->name, f->file,
              f->summary);
    sb_printf(out, "  fractal.%-14s int    %d [%d, %d]  iterations of the formula\n", "iterations", f->iterations,
              f->iterations_lo, f->iterations_hi);
    sb_printf(out, "  fractal.%-14s float  %s  a sphere about the origin that holds the set\n", "bound_radius", f->bound);
    if (f->step[0])
        sb_printf(out, "  (its estimate needs quality.step_factor <= %s: a larger one is capped at it)\n", f->step);
    for (int i = 0; i < f->param_count; i++) {
        const formula_param *q = &f->params[i];
        char def[64];
        if (q->type == FORMULA_BOOL)
            snprintf(def, sizeof def, "%s", q->def[0] != 0 ? "true" : "false");
        else
            for (int k = 0, at = 0; k < formula_components(q->type); k++)
                at += snprintf(def + at, sizeof def - (size_t)at, "%s%g", k ? "," : "", (double)q->def[k]);
        sb_printf(out, "  fractal.%-14s %-6s %s", q->key, TYPE_NAMES[q->type], def);
        if (q->type != FORMULA_BOOL)
            sb_printf(out, " [%g, %g]", (double)q->lo, (double)q->hi);
        if (q->has_gap)
            sb_printf(out, " not (%g, %g)", (double)q->gap_lo, (double)q->gap_hi);
        sb_printf(out, "  %s\n", q->description);
    }
    for (int i = 0; i < f->require_count; i++)
        sb_printf(out, "  requires %s %c %s\n", f->requires[i].lhs, f->requires[i].less ? '<' : '>', f->requires[i].rhs);
    if (f->step_formula)
        sb_printf(out, "  a step formula (z -> f(z) + c, estimate %s, escape radius %s): fractal.julia and "
                       "fractal.julia_c draw its Julia sets; fractal.hybrid alternates it with another step formula\n",
                  f->de_log ? "1/2 ln r r / dr" : "r / dr", f->escape);
    if (f->deep)
        sb_printf(out, "  compiles in double for a deep zoom (fractal.precision auto)%s%s\n",
                  f->deep_whole[0] ? " with whole " : "", f->deep_whole);
}

const formula_param *formula_find(const formula *f, const char *key)
{
    for (int i = 0; i < f->param_count; i++)
        if (!strcmp(f->params[i].key, key))
            return &f->params[i];
    return NULL;
}

/* ---- expressions: recursive descent over + - * / ( ) numbers, names (NAME.x .y .z: a vector's
 * component), abs sqrt min max pow floor ---- */

typedef struct expr {
    const char *p;
    const formula *f;
    const float (*values)[4];
    int iterations;
    bool bad;
    char why[96];
} expr;

static double sum(expr *e);

/* Takes `c` (after spaces) if it is next; never steps past the end of the text. */
static bool take(expr *e, char c)
{
    e->p = skip_space(e->p);
    if (*e->p != c)
        return false;
    e->p++;
    return true;
}

static double atom(expr *e)
{
    e->p = skip_space(e->p);
    if (take(e, '(')) {
        double v = sum(e);
        e->bad |= !take(e, ')');
        return v;
    }
    if (take(e, '-'))
        return -atom(e);
    if (isdigit((unsigned char)*e->p) || *e->p == '.') {
        char *end;
        double v = strtod(e->p, &end);
        e->p = end;
        return v;
    }
    char name[FORMULA_KEY_MAX];
    int n = 0;
    while ((isalnum((unsigned char)*e->p) || *e->p == '_') && n + 1 < (int)sizeof name)
        name[n++] = *e->p++;
    name[n] = '\0';
    if (n == 0) {
        e->bad = true;
        return 0;
    }
    static const char *const FUNCS[] = {"abs", "sqrt", "min", "max", "pow", "floor"};
    for (int k = 0; k < 6; k++)
        if (!strcmp(name, FUNCS[k])) {
            if (!take(e, '(')) {
                e->bad = true;
                return 0;
            }
            double a = sum(e), b = 0;
            if (k >= 2 && k <= 4) /* min, max and pow take two */
                e->bad |= !take(e, ','), b = sum(e);
            e->bad |= !take(e, ')');
            return k == 0 ? fabs(a) : k == 1 ? sqrt(a) : k == 2 ? fmin(a, b) : k == 3 ? fmax(a, b) : k == 4 ? pow(a, b) : floor(a);
        }
    if (!strcmp(name, "iterations"))
        return e->iterations;
    int comp = -1; /* NAME.x .y .z .w: a vector's component; NAME alone its first */
    if (e->p[0] == '.' && strchr("xyzw", e->p[1]) && e->p[1] && !isalnum((unsigned char)e->p[2]))
        comp = e->p[1] == 'w' ? 3 : e->p[1] - 'x', e->p += 2;
    for (int i = 0; i < e->f->param_count; i++)
        if (!strcmp(e->f->params[i].key, name)) {
            int comps = formula_components(e->f->params[i].type);
            if (comp >= 0 && (comps == 1 || comp >= comps))
                snprintf(e->why, sizeof e->why, "'%s' %s no .%c", name, comps == 1 ? "is a number: it has" : "has",
                         "xyzw"[comp]), e->bad = true;
            return e->values[i][comp > 0 ? comp : 0];
        }
    snprintf(e->why, sizeof e->why, "unknown name '%s'", name);
    e->bad = true;
    return 0;
}

static double product(expr *e)
{
    double v = atom(e);
    for (;;) {
        if (take(e, '*'))
            v *= atom(e);
        else if (take(e, '/'))
            v /= atom(e);
        else
            return v;
    }
}

static double sum(expr *e)
{
    double v = product(e);
    for (;;) {
        if (take(e, '+'))
            v += product(e);
        else if (take(e, '-'))
            v -= product(e);
        else
            return v;
    }
}

bool formula_eval(const formula *f, const char *text, const float (*values)[4], int iterations, double *out, err_t *err)
{
    expr e = {.p = text, .f = f, .values = values, .iterations = iterations};
    *out = sum(&e);
    if (e.bad || *skip_space(e.p) != '\0' || !isfinite(*out))
        return err_set(err, "formula %s: '%s': %s", f->name, text,
                       e.why[0] ? e.why : isfinite(*out) ? "malformed expression" : "not a finite number");
    return true;
}
