/* costs — what each edit of the scene costs: the full-size sample's time (the median of the image's
 * samples, its first left out: it also compiled the program) and the converged image's difference to
 * the grabbed reference, before and after the edit, for the panel. Its state is the caller's. No GL. */
#ifndef FATHOM_COSTS_H
#define FATHOM_COSTS_H

#include <stdbool.h>

#include "window/panel.h"

enum { COSTS_MAX = 32, COSTS_HISTORY = 16 };

typedef struct edit_costs {
    panel_cost entries[COSTS_MAX]; /* the newest edit last */
    int count;
    int pending;                     /* the entry waiting for its samples and its converged image, −1: none */
    double full_ms[COSTS_HISTORY];   /* this image's full-size sample times */
    int full_count;
    double sample_ms;      /* the last full-size sample's time (or the moving frames' estimate of it) */
    double band_ms;        /* the current full-size sample's bands so far */
    double reference_rmse; /* the converged image against the grabbed reference; −1: none grabbed */
} edit_costs;

void costs_init(edit_costs *c);
/* An edit of key=value: the time and reference error before it; the after comes with the samples. */
void costs_note_edit(edit_costs *c, const char *kv);
/* A sample of iw × ih (bands add up to a full-size one; a smaller moving frame is scaled up to w × h);
 * complete: the sample is whole; first: it is the image's first. */
void costs_note_sample(edit_costs *c, double ms, int iw, int ih, int w, int h, bool complete, bool first);
/* The image converged; rmse: its difference to the grabbed reference (negative: unknown). */
void costs_note_converged(edit_costs *c, double rmse);
/* A reference was grabbed (the difference is 0), or the scene changed (the entries go). */
void costs_grabbed(edit_costs *c);
void costs_clear(edit_costs *c);

#endif
