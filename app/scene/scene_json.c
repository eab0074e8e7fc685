/* scene_json — JSON reading with error context for the scene parsers (see scene_parse.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "scene/scene_parse.h"

bool scene_fail(scene_ctx *c, const char *path, const char *fmt, ...)
{
    char what[1024];
    va_list ap;
    va_start(ap, fmt);
    if (vsnprintf(what, sizeof what, fmt, ap) >= (int)sizeof what)
        what[sizeof what - 1] = '\0';
    va_end(ap);
    return err_set(c->err, "%s: %s: %s", c->file, path[0] ? path : "(top level)", what);
}

/* Key paths only appear in messages: a long one is cut, which is fine there. */
void scene_child_path(char *out, size_t n, const char *parent, const char *key)
{
    if (snprintf(out, n, "%s%s%s", parent, parent[0] ? "." : "", key) >= (int)n)
        out[n - 1] = '\0';
}

/* Every object is checked against the keys it may hold, so a typo is an error, not a silent default. */
bool scene_check_keys(scene_ctx *c, const cJSON *obj, const char *path, const char *const *allowed)
{
    if (!cJSON_IsObject(obj))
        return scene_fail(c, path, "expected an object {...}");
    for (const cJSON *it = obj->child; it; it = it->next) {
        bool ok = false;
        for (const char *const *k = allowed; *k; k++)
            ok |= !strcmp(it->string, *k);
        if (!ok) {
            char p[512];
            scene_child_path(p, sizeof p, path, it->string);
            strbuf list = {0};
            for (const char *const *k = allowed; *k; k++)
                sb_printf(&list, "%s%s", k == allowed ? "" : ", ", *k);
            bool r = scene_fail(c, p, "unknown key '%s' (allowed here: %s)", it->string, list.data);
            sb_free(&list);
            return r;
        }
    }
    return true;
}

scene_param *scene_record_param(scene_ctx *c, const char *path, const char *key, param_type type, const double *v,
                          double lo, double hi)
{
    if (!c->params)
        return NULL;
    scene_param p = {.type = type, .lo = lo, .hi = hi};
    scene_child_path(p.key, sizeof p.key, path, key);
    for (int i = 0; i < (type == PARAM_VEC3 || type == PARAM_COLOR ? 3 : 1); i++)
        p.value[i] = v[i];
    return params_add(c->params, &p);
}

/* A finite number within [lo, hi], compared as the type it is stored in: a float's range ends are
 * floats (1.2 is 1.2f as a float, and below (double)1.2f: the declared end was refused). */
static bool in_range(const cJSON *v, double lo, double hi, bool as_float)
{
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble))
        return false;
    if (!as_float)
        return v->valuedouble >= lo && v->valuedouble <= hi;
    float f = (float)v->valuedouble;
    return isfinite(f) && f >= (float)lo && f <= (float)hi;
}

bool scene_get_num(scene_ctx *c, const cJSON *obj, const char *path, const char *key, float def, float lo,
                    float hi, float *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    scene_child_path(p, sizeof p, path, key);
    if (v && !in_range(v, lo, hi, true)) {
        char range[128];
        snprintf(range, sizeof range, "%g to %g", (double)lo, (double)hi);
        return scene_fail(c, p, "expected a number from %s", range);
    }
    *out = v ? (float)v->valuedouble : def;
    scene_record_param(c, path, key, PARAM_FLOAT, (const double[1]){*out}, lo, hi);
    return true;
}

bool scene_get_int(scene_ctx *c, const cJSON *obj, const char *path, const char *key, int def, int lo, int hi,
                    int *out)
{
    float f = 0; /* set by scene_get_num on success; GCC -O3 cannot see it */
    if (!scene_get_num(c, obj, path, key, (float)def, (float)lo, (float)hi, &f))
        return false;
    if (f != floorf(f)) {
        char p[512];
        scene_child_path(p, sizeof p, path, key);
        return scene_fail(c, p, "expected a whole number");
    }
    *out = (int)f;
    scene_record_param(c, path, key, PARAM_INT, (const double[1]){f}, lo, hi);
    return true;
}

static bool get_vecn_as(scene_ctx *c, const cJSON *obj, const char *path, const char *key, int n, const double *def,
                        double lo, double hi, bool as_float, double *out)
{
    static const char *const COUNT[] = {"", "one", "two", "three", "four"}, *const FORM[] = {"", "[x]", "[x, y]",
                                                                                          "[x, y, z]", "[x, y, z, w]"};
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    scene_child_path(p, sizeof p, path, key);
    if (!v) {
        memcpy(out, def, sizeof(double) * (size_t)n);
        return true;
    }
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n)
        return scene_fail(c, p, "expected %s numbers %s", COUNT[n], FORM[n]);
    for (int i = 0; i < n; i++) {
        const cJSON *e = cJSON_GetArrayItem(v, i);
        if (!in_range(e, lo, hi, as_float)) {
            char range[128];
            snprintf(range, sizeof range, "%g to %g", lo, hi);
            return scene_fail(c, p, "expected %s numbers, each from %s", COUNT[n], range);
        }
        out[i] = e->valuedouble;
    }
    return true;
}

bool scene_get_dvec3(scene_ctx *c, const cJSON *obj, const char *path, const char *key, const double def[3], double lo,
                     double hi, double out[3])
{
    return get_vecn_as(c, obj, path, key, 3, def, lo, hi, false, out);
}

bool scene_get_vec3(scene_ctx *c, const cJSON *obj, const char *path, const char *key, const float def[3],
                     float lo, float hi, float out[3])
{
    bool colour = strstr(key, "color") && lo >= 0 && hi <= 1;
    return scene_get_vecn(c, obj, path, key, 3, def, lo, hi, colour, out);
}

bool scene_get_vecn(scene_ctx *c, const cJSON *obj, const char *path, const char *key, int n, const float *def,
                    float lo, float hi, bool colour, float *out)
{
    double d[4] = {0}, v[4] = {0};
    for (int i = 0; i < n; i++)
        d[i] = def[i];
    if (!get_vecn_as(c, obj, path, key, n, d, lo, hi, true, v))
        return false;
    for (int i = 0; i < n; i++)
        out[i] = (float)v[i];
    scene_param *q = scene_record_param(c, path, key, colour ? PARAM_COLOR : PARAM_VEC3, v, lo, hi);
    for (int i = 0; q && i < n; i++)
        q->comps = n, q->value[i] = v[i];
    return true;
}

bool scene_get_str(scene_ctx *c, const cJSON *obj, const char *path, const char *key, const char *def,
                    const char **out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) {
        *out = def;
        return true;
    }
    if (!cJSON_IsString(v)) {
        char p[512];
        scene_child_path(p, sizeof p, path, key);
        return scene_fail(c, p, "expected a string in quotes");
    }
    *out = v->valuestring;
    return true;
}

bool scene_get_enum(scene_ctx *c, const cJSON *obj, const char *path, const char *key, const char *what,
              const char *const *names, int def, int *out)
{
    const char *v = NULL;
    if (!scene_get_str(c, obj, path, key, names[def], &v))
        return false;
    for (int i = 0; names[i]; i++)
        if (!strcmp(v, names[i])) {
            *out = i;
            int n = 0;
            while (names[n])
                n++;
            scene_param *p = scene_record_param(c, path, key, PARAM_ENUM, (const double[1]){i}, 0, n - 1);
            if (p) {
                size_t at = 0;
                for (int k = 0; k < n && at + strlen(names[k]) + 1 < sizeof p->names; k++, p->name_count++) {
                    memcpy(p->names + at, names[k], strlen(names[k]) + 1);
                    at += strlen(names[k]) + 1;
                }
            }
            return true;
        }
    char p[KEY_PATH_MAX];
    scene_child_path(p, sizeof p, path, key);
    strbuf known = {0};
    for (int i = 0; names[i]; i++)
        sb_printf(&known, "%s%s", i ? ", " : "", names[i]);
    bool r = scene_fail(c, p, "unknown %s '%s' (known: %s)", what, v, known.data);
    sb_free(&known);
    return r;
}

bool scene_resolve_file(scene_ctx *c, const char *path, const char *rel, char *out)
{
    if (!util_join(c->s->dir, rel, out, PATH_MAX_LEN))
        return scene_fail(c, path, "path '%s' is too long", rel);
    if (!util_file_exists(out))
        return scene_fail(c, path, "file '%s' not found (paths are relative to the scene file's folder)", out);
    return true;
}

