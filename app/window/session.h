/* session — the scene the window shows and the user's edits of it. Every edit is a "key=value"
 * override (scene/overrides.h) parsed as --set is, on top of the base overrides the scene was opened
 * with (the command line's, or a recalled view's or preset's); loading hands the scene to the
 * renderer, and a scene that fails to load leaves the last good one in place. GL (the renderer). */
#ifndef FATHOM_SESSION_H
#define FATHOM_SESSION_H

#include <stdbool.h>

#include "cli/cli.h"
#include "data/geo/dem.h"
#include "scene/overrides.h"
#include "scene/params.h"
#include "scene/scene.h"
#include "util.h"
#include "view/camera.h"

typedef struct session {
    const cli_options *opt;
    scene scene;
    bool have_scene;
    param_list params; /* what the panel shows: every tunable value of the scene */
    overrides edits;   /* the panel's and the knob keys' edits, after the base overrides */
    char base[CLI_MAX_SETS][OVERRIDE_LEN];
    int base_count;
    dem_geo *geo; /* the DEM's georeferencing (latitude and longitude under the cursor), or NULL */
    char geo_path[PATH_MAX_LEN];
} session;

/* The command line's overrides as the base; no scene yet. */
void session_init(session *s, const cli_options *opt);
void session_free(session *s);
/* Loads `name` with the base overrides and the edits. *new_file: another scene file than before (the
 * camera starts again). On failure the last good scene stays, in the renderer too. */
bool session_load(session *s, const char *name, bool *new_file, err_t *err);
/* Applies an edit ("key=value"), checked by the parser like --set; a rejected one is taken back. */
bool session_edit(session *s, const char *kv, err_t *err);
/* Another scene by its name: the base overrides and edits belong to the last one and go. */
bool session_switch(session *s, const char *name, bool *new_file, err_t *err);
/* The view as a shot description (view/shot.h): the scene, its overrides, its formulas, the camera. */
void session_describe(const session *s, const camera *cam, int w, int h, strbuf *out);
/* Opens a shot description: its scene (carried or shipped), its overrides as the base (the edits go)
 * and its camera (into *cam). On failure what was in force stays. */
bool session_open_shot(session *s, const char *text, const char *source, camera *cam, bool *new_file, err_t *err);

#endif
