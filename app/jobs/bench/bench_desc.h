/* bench_desc — what a bench run measures, as the command line's `fathom bench` options give it (main.c
 * fills it): zero fields are the defaults. Shared by the bench's files (bench.h). No GL. */
#ifndef FATHOM_BENCH_DESC_H
#define FATHOM_BENCH_DESC_H

#include <stdbool.h>

typedef struct bench_desc {
    const char *scene;         /* a name or a path */
    const char *const *sets;   /* its overrides, "key=value" */
    int set_count;
    int width, height;         /* 0: the mode's default size */
    int runs;                  /* images a setting is timed on (0: 5; --quick 3, --full 9) */
    const char *const *knobs;  /* "NAME=v1,v2,..." sweeps (none: every knob that applies) */
    int knob_count;
    const char *out, *name;    /* the folder for files (NULL: print only) and their prefix (NULL: the scene's) */
    bool quick, full, quiet;
    bool path_truth;           /* error against the path tracer, not the reference preset */
    bool frame_times, interactive, terrain_scale, terrain_stream, final_frame, viewshed; /* the other modes */
    int fps;                   /* --interactive: the frame rate to hold (0: 30) */
} bench_desc;

#endif
