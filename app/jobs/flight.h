/* flight — a camera path (app/view/path.h) rendered frame by frame, headless: `fathom render --path F
 * --frames A-B --output out/frame_%04d.png`. Frame n shows the path at time first key + n / fps.
 * Each frame is an offline shot (verified, atomic write; its file remembers scene, overrides and
 * camera, so `--scene frame.png` renders it again). A frame whose file already exists is skipped, so
 * a run killed part way (a crash, a pre-empted farm job) resumes where it stopped, and several
 * processes can share one range. One GL context serves every frame. */
#ifndef FATHOM_FLIGHT_H
#define FATHOM_FLIGHT_H

#include <stdbool.h>

#include "cli.h"
#include "util.h"

bool flight_render(const cli_options *opt, err_t *err);

#endif
