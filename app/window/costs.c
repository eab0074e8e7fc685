/* costs — what each edit of the scene costs (costs.h). */
#include "window/costs.h"

#include <stdio.h>
#include <string.h>

void costs_init(edit_costs *c)
{
    memset(c, 0, sizeof *c);
    c->pending = -1;
    c->reference_rmse = -1;
}

void costs_clear(edit_costs *c) { c->count = 0; }

void costs_grabbed(edit_costs *c) { c->reference_rmse = 0; }

/* The median of this image's full-size sample times, but its first. */
static double median_full_ms(const edit_costs *c)
{
    double v[COSTS_HISTORY];
    int skip = c->full_count > 1; /* the first also compiled the program (llvmpipe: 200-400 ms more) */
    int n = c->full_count - skip;
    memcpy(v, c->full_ms + skip, sizeof v[0] * (size_t)n);
    for (int i = 1; i < n; i++) /* a handful: insertion sort */
        for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
            double t = v[j];
            v[j] = v[j - 1], v[j - 1] = t;
        }
    return n == 0 ? 0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void costs_note_edit(edit_costs *c, const char *kv)
{
    char key[PARAM_KEY_MAX];
    snprintf(key, sizeof key, "%.*s", (int)strcspn(kv, "="), kv);
    int i = 0;
    while (i < c->count && strcmp(c->entries[i].key, key))
        i++;
    if (i < c->count) { /* the newest edit is the last entry */
        memmove(c->entries + i, c->entries + i + 1, sizeof c->entries[0] * (size_t)(c->count - i - 1));
        i = --c->count;
    }
    if (i == c->count) {
        if (c->count == COSTS_MAX) { /* the oldest goes */
            memmove(c->entries, c->entries + 1, sizeof c->entries[0] * (COSTS_MAX - 1));
            i = --c->count;
        }
        c->count++;
        snprintf(c->entries[i].key, sizeof c->entries[i].key, "%s", key);
    }
    c->entries[i].ms_before = c->full_count ? median_full_ms(c) : c->sample_ms;
    c->entries[i].ms_after = 0;
    c->entries[i].rmse_before = c->reference_rmse;
    c->entries[i].rmse_after = -1;
    c->pending = i;
}

void costs_note_sample(edit_costs *c, double ms, int iw, int ih, int w, int h, bool complete, bool first)
{
    if (iw != w || ih != h) {
        c->sample_ms = ms * ((double)w * h) / ((double)iw * ih);
        c->band_ms = 0;
    } else {
        c->band_ms += ms;
        if (complete)
            c->sample_ms = c->band_ms, c->band_ms = 0;
    }
    if (!complete || iw != w || ih != h)
        return;
    if (first) /* a new image: its samples' times start again */
        c->full_count = 0;
    if (c->full_count < COSTS_HISTORY)
        c->full_ms[c->full_count++] = c->sample_ms;
    if (c->pending >= 0) /* the median so far: one sample that also compiled or met a busy core is not the cost */
        c->entries[c->pending].ms_after = median_full_ms(c);
}

void costs_note_converged(edit_costs *c, double rmse)
{
    if (c->pending >= 0 && c->reference_rmse < 0) { /* no reference: the time is all there is */
        c->pending = -1;
        return;
    }
    if (c->reference_rmse < 0 || rmse < 0)
        return;
    c->reference_rmse = rmse;
    if (c->pending >= 0) {
        c->entries[c->pending].rmse_after = rmse;
        c->pending = -1;
    }
}
