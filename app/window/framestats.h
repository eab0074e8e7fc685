/* framestats — what the window's frames cost: the last FRAMESTATS_HISTORY frames' times (the frame
 * rate the HUD shows), the smoothed time a frame spends besides its sample, and for --frames N every
 * frame's time, the panel's and the swap's share, moving or still, summed up in one line at the end.
 * Its state is the caller's. No GL. */
#ifndef FATHOM_FRAMESTATS_H
#define FATHOM_FRAMESTATS_H

#include <stdbool.h>

enum { FRAMESTATS_HISTORY = 30, FRAMESTATS_MAX = 100000 };

typedef struct frame_stats {
    double frame_ms[FRAMESTATS_HISTORY]; /* the last samples' times (0: none) */
    int frame_index;
    double overhead_ms; /* a frame's time besides its sample (display, HUD, panel, swap, probes): smoothed */
    /* --frames: each frame */
    double *all_ms, *panel_ms, *swap_ms;
    bool *moving;
    int count, cap;
} frame_stats;

/* Keeps every one of the first `frames` frames' times (0: none). */
void framestats_init(frame_stats *s, int frames);
void framestats_free(frame_stats *s);
/* A sample's time; the mean of the last ones; and forgetting them (another scene's say nothing). */
void framestats_note_sample(frame_stats *s, double ms);
double framestats_average_ms(const frame_stats *s);
void framestats_forget(frame_stats *s);
/* The frame's whole time and its sample's: the overhead is what is left. */
void framestats_note_overhead(frame_stats *s, double frame_ms, double sample_ms);
/* True while each frame's times are kept (then the caller waits for the GPU to measure them). */
bool framestats_recording(const frame_stats *s);
void framestats_note_frame(frame_stats *s, double frame_ms, double panel_ms, double swap_ms, bool moving);
/* --frames N: one line to stderr on what the frames cost, moving and still, and the panel's share;
 * `what` ends it (the backend and the GPU). */
void framestats_summary(const frame_stats *s, int w, int h, bool panel_open, const char *what);

#endif
