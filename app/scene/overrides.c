/* overrides — the user's edits to a scene, with undo (overrides.h). */
#include "scene/overrides.h"

#include <stdio.h>
#include <string.h>

/* The index of key's edit in s, or −1; key ends at '=' or '\0'. */
static int find(const override_state *s, const char *key)
{
    size_t n = strcspn(key, "=");
    for (int i = 0; i < s->count; i++)
        if (strcspn(s->sets[i], "=") == n && !strncmp(s->sets[i], key, n))
            return i;
    return -1;
}

bool overrides_set(overrides *o, const char *kv)
{
    const char *eq = strchr(kv, '=');
    if (!eq || eq == kv || strlen(kv) >= OVERRIDE_LEN)
        return false;
    int i = find(&o->now, kv);
    if (i < 0) {
        if (o->now.count == OVERRIDES_MAX)
            return false;
        i = o->now.count++;
    }
    snprintf(o->now.sets[i], OVERRIDE_LEN, "%s", kv);
    return true;
}

const char *overrides_get(const overrides *o, const char *key)
{
    int i = find(&o->now, key);
    return i < 0 ? NULL : strchr(o->now.sets[i], '=') + 1;
}

/* Pushes s onto a stack of `cap` states, dropping the oldest when full. */
static void push(override_state *stack, int *count, const override_state *s)
{
    if (*count == OVERRIDES_UNDO) {
        memmove(stack, stack + 1, sizeof *stack * (OVERRIDES_UNDO - 1));
        (*count)--;
    }
    stack[(*count)++] = *s;
}

void overrides_checkpoint(overrides *o)
{
    push(o->undo, &o->undo_count, &o->now);
    o->redo_count = 0;
}

bool overrides_undo(overrides *o)
{
    if (!o->undo_count)
        return false;
    push(o->redo, &o->redo_count, &o->now);
    o->now = o->undo[--o->undo_count];
    return true;
}

bool overrides_redo(overrides *o)
{
    if (!o->redo_count)
        return false;
    push(o->undo, &o->undo_count, &o->now);
    o->now = o->redo[--o->redo_count];
    return true;
}

const char *const *overrides_list(const overrides *o, const char **out, int *n)
{
    for (int i = 0; i < o->now.count; i++)
        out[i] = o->now.sets[i];
    *n = o->now.count;
    return out;
}

void overrides_clear(overrides *o)
{
    o->now.count = 0;
    o->undo_count = o->redo_count = 0;
}
