/* explore — the interactive window: free-fly camera, progressive refinement while still, HUD,
 * scene keys, shader reload and screenshots. */
#ifndef FATHOM_EXPLORE_H
#define FATHOM_EXPLORE_H

#include <stdbool.h>

#include "cli/cli.h"
#include "util.h"

/* Runs until Esc / window close (or opt->frames frames). False with err on a fatal error. */
bool explore_run(const cli_options *opt, err_t *err);

#endif
