/* views — bookmarked views: per scene, named shot descriptions (shot.h: camera, overrides) in a JSON
 * file { "NAME": {shot}, ... } under the user's config folder, so shipped (read-only) scenes can have
 * them too: $FATHOM_VIEWS_DIR, else $XDG_CONFIG_HOME/fathom/views, else ~/.config/fathom/views; the
 * file is SCENE-NAME.json. The window's B saves, Ctrl+1…9 recalls; `--view NAME` renders one. Pure C. */
#ifndef FATHOM_VIEWS_H
#define FATHOM_VIEWS_H

#include <stdbool.h>

#include "util.h"

/* The views file of the scene named scene_name. */
bool views_file(const char *scene_name, char *out, size_t n, err_t *err);

/* Stores shot_json (shot_describe's text) as view `name`, replacing one of that name; the file is
 * written atomically (temporary file, then rename), its folder created if needed. */
bool views_save(const char *file, const char *name, const char *shot_json, err_t *err);

/* The shot text of view `name` (*shot_json malloc'd). Unknown: the error lists the names there are. */
bool views_load(const char *file, const char *name, char **shot_json, err_t *err);

/* The window's recorded flight of the scene (N adds a keyframe): SCENE-NAME.flight.json beside the views
 * file (its folder created if needed). */
bool views_flight_file(const char *scene_name, char *out, size_t n, err_t *err);

/* The first of "1" … "9" not yet used (0 when all are). */
int views_next_free(const char *file);

#endif
