/* bench_load — what the bench's files share, below them all (no bench file calls another's and is
 * called back: tests/tree/calls.sh). */
#ifndef FATHOM_BENCH_LOAD_H
#define FATHOM_BENCH_LOAD_H

#include <stdbool.h>

#include "jobs/bench/bench_desc.h"
#include "scene/scene.h"
#include "view/camera.h"
#include "util.h"

/* The wall time (ms) of one whole fathom process (this binary) with these arguments, stdout to
 * /dev/null and stderr to `log` (NULL: /dev/null); negative when it could not run or failed. */
double bench_process_ms(char *const *argv, const char *log);

/* For the bench's files: the scene with the command line's --set, then `extra` more; and the time (ms)
 * of all of s's samples from cam at w × h (wall clock around glFinish). */
bool bench_load(const bench_desc *opt, const char *const *extra, int n_extra, scene *s, err_t *err);
double bench_image_ms(const scene *s, const camera *cam, int w, int h);

#endif
