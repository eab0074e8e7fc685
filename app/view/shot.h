/* shot — what a written image remembers of how it was made: the scene file, the --set overrides and
 * the camera, as a small JSON text stored in the PNG or EXR (image_io's text entry SHOT_KEY).
 * `fathom --scene shot.png` reopens it: same scene, same overrides, same view (the way fractal users
 * share their finds). Pure C. */
#ifndef FATHOM_SHOT_H
#define FATHOM_SHOT_H

#include <stdbool.h>

#include "view/camera.h"
#include "util.h"

#define SHOT_KEY "fathom_shot"
enum { SHOT_SET_MAX = 64 }; /* overrides a shot carries (cli.h takes as many) */

typedef struct shot_desc {
    char scene[PATH_MAX_LEN];
    char sets[SHOT_SET_MAX][256];
    int set_count;
    camera cam;
    int width, height;
} shot_desc;

/* The JSON text for a shot of scene_path (made absolute) with these overrides, camera and size. */
void shot_describe(const char *scene_path, const char *const *sets, int set_count, const camera *cam, int width,
                   int height, strbuf *out);

/* Parses a shot text read from `source` (for messages). */
bool shot_parse(const char *text, const char *source, shot_desc *d, err_t *err);

/* True when a --scene argument names an image (.png or .exr) rather than a scene. */
bool shot_is_image(const char *name);

#endif
