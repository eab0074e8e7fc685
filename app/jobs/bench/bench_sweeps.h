/* bench_sweeps — which sweeps a bench runs: every quality knob with a sweep column (QUALITY_KNOBS), the
 * program's own (PROGRAM_LIST's bench column), a fractal's iterations, the model's approximations
 * that are effects, and the bench's own resolution_scale; each with its values, the scene's own
 * operating point among them. Internal to bench. No GL. */
#ifndef FATHOM_BENCH_SWEEPS_H
#define FATHOM_BENCH_SWEEPS_H

#include <stdbool.h>
#include <stddef.h>

#include "scene/quality.h"
#include "scene/scene.h"

/* A sweep: a knob's --set key (NULL: the bench's own resolution_scale) and its values. Built at run
 * time from QUALITY_KNOBS, the program's row of PROGRAM_LIST, and resolution_scale. */
typedef struct bench_sweep {
    char name[32], key[64], values[256];
    bool own; /* resolution_scale: rendered smaller and upscaled, no --set */
} bench_sweep;
enum { BENCH_MAX_SWEEPS = KNOB_COUNT + 10 };

/* Every sweep the bench knows for scene s (at most BENCH_MAX_SWEEPS); `applies` says which run by default. */
int bench_list_sweeps(const scene *s, bench_sweep *out, bool *applies);
/* A sweep's values v with `keep` (the scene's own value, "" for none) among them in order; quick: three
 * of them (the ends and keep, or the middle). Into out; returns out. */
const char *bench_sweep_values(const char *v, const char *keep, bool quick, char *out, size_t n);
/* The number of comma-separated values in v. */
int bench_count_values(const char *v);

#endif
