/* params — the tunable values of a scene (params.h). */
#include "scene/params.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

scene_param *params_add(param_list *l, const scene_param *p)
{
    for (int i = 0; i < l->count; i++)
        if (!strcmp(l->items[i].key, p->key)) {
            l->items[i] = *p;
            return &l->items[i];
        }
    if (l->count == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 64;
        l->items = util_realloc(l->items, (size_t)l->cap * sizeof *l->items, "scene parameters");
    }
    l->items[l->count] = *p;
    return &l->items[l->count++];
}

const scene_param *params_find(const param_list *l, const char *key)
{
    for (int i = 0; i < l->count; i++)
        if (!strcmp(l->items[i].key, key))
            return &l->items[i];
    return NULL;
}

void params_label(param_list *l, const char *key, const char *text)
{
    if (l->label_count == l->label_cap) {
        l->label_cap = l->label_cap ? 2 * l->label_cap : 16;
        l->labels = util_realloc(l->labels, (size_t)l->label_cap * sizeof *l->labels, "scene parameter labels");
    }
    param_label *b = &l->labels[l->label_count++];
    snprintf(b->key, sizeof b->key, "%s", key);
    snprintf(b->text, sizeof b->text, "%s", text);
}

const char *params_label_of(const param_list *l, const char *key)
{
    for (int i = l->label_count - 1; i >= 0; i--)
        if (!strcmp(l->labels[i].key, key))
            return l->labels[i].text;
    return NULL;
}

void params_free(param_list *l)
{
    free(l->items);
    free(l->labels);
    *l = (param_list){0};
}

void params_section(const char *key, char *out, size_t n)
{
    size_t len = strcspn(key, ".");
    snprintf(out, n, "%.*s", (int)len, key);
}

/* The name of an enum's value i. */
static const char *enum_name(const scene_param *p, int i)
{
    const char *s = p->names;
    for (int k = 0; k < i && k < p->name_count; k++)
        s += strlen(s) + 1;
    return s;
}

/* The components of a value, comma-separated. */
static int components(const scene_param *p, const double *v, char *out, size_t n)
{
    int at = 0;
    for (int i = 0; i < params_components(p) && at >= 0 && (size_t)at < n; i++)
        at += snprintf(out + at, n - (size_t)at, "%s%.9g", i ? "," : "", v[i]);
    return at;
}

int params_components(const scene_param *p)
{
    return p->type == PARAM_VEC3 || p->type == PARAM_COLOR ? (p->comps ? p->comps : 3) : 1;
}

void params_override(const param_list *l, const scene_param *p, const double *v, char *out, size_t n)
{
    if (p->array_len > 0) { /* the whole array: "a.b=[[..],[..]]" */
        size_t key_len = strlen(p->key) - strlen(strrchr(p->key, '.'));
        int at = snprintf(out, n, "%.*s=[", (int)key_len, p->key);
        for (int i = 0; i < p->array_len && at > 0 && (size_t)at < n; i++) {
            char sibling[PARAM_KEY_MAX + 16], value[128];
            snprintf(sibling, sizeof sibling, "%.*s.%d", (int)key_len, p->key, i);
            const scene_param *q = i == p->array_index ? p : params_find(l, sibling);
            components(p, i == p->array_index || !q ? v : q->value, value, sizeof value);
            at += snprintf(out + at, n - (size_t)at, "%s[%s]", i ? ", " : "", value);
        }
        if (at > 0 && (size_t)at < n)
            snprintf(out + at, n - (size_t)at, "]");
        return;
    }
    switch (p->type) {
    case PARAM_INT: snprintf(out, n, "%s=%d", p->key, (int)v[0]); break;
    case PARAM_BOOL: snprintf(out, n, "%s=%s", p->key, v[0] != 0 ? "true" : "false"); break;
    case PARAM_ENUM: snprintf(out, n, "%s=%s", p->key, enum_name(p, (int)v[0])); break;
    default: {
        char value[160];
        components(p, v, value, sizeof value);
        snprintf(out, n, "%s=%s", p->key, value);
    }
    }
}
