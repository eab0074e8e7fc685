/* bench — what accuracy costs in time. Headless: for each quality preset of a scene, the time of one
 * sample per pixel (a window frame), median of `runs` frames after two warm-up frames, measured as
 * wall clock around glFinish (GL timer queries are wrong on llvmpipe). */
#ifndef FATHOM_BENCH_H
#define FATHOM_BENCH_H

#include <stdbool.h>

#include "cli.h"
#include "util.h"

bool bench_run(const cli_options *opt, err_t *err);

#endif
