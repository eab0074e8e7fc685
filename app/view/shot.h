/* shot — what a written image remembers of how it was made: the scene, the --set overrides and the
 * camera, as a small JSON text stored in the PNG or EXR (image_io's text entry SHOT_KEY), or saved
 * alone as a preset (a .fathom file, the window's panel writes one). `fathom --scene shot.png` (or
 * `--scene view.fathom`) reopens it: same scene, same overrides, same view — on any machine: a
 * shipped scene is named ("scene": "mandelbulb"), a user's own scene is carried whole ("scene_text",
 * with the path it had), so a shot travels as Mandelbulber's .fract text does. Pure C. */
#ifndef FATHOM_SHOT_H
#define FATHOM_SHOT_H

#include <stdbool.h>

#include "view/camera.h"
#include "util.h"

#define SHOT_KEY "fathom_shot"
enum { SHOT_SET_MAX = 64 }; /* overrides a shot carries (cli.h takes as many) */

typedef struct shot_desc {
    char scene[PATH_MAX_LEN]; /* a shipped scene's name, or a file's absolute path */
    char *scene_text;         /* that file's text when it is not shipped (malloc'd: shot_free), or NULL */
    char sets[SHOT_SET_MAX][256];
    int set_count;
    camera cam;
    int width, height;
} shot_desc;

/* The JSON text for a shot of the scene at scene_path with these overrides, camera and size: the scene
 * by name when it is one of fathom's own (under <data>/scenes), else its absolute path and its text. */
void shot_describe(const char *scene_path, const char *const *sets, int set_count, const camera *cam, int width,
                   int height, strbuf *out);

/* A shot text with "renderer": what rendered it (the backend and the GPU), for the record: nothing
 * reads it back. Copies text unchanged when it is no JSON object. */
void shot_note_renderer(const char *text, const char *renderer, strbuf *out);

/* Parses a shot text read from `source` (for messages). */
bool shot_parse(const char *text, const char *source, shot_desc *d, err_t *err);
void shot_free(shot_desc *d);

#define SHOT_PRESET_EXT ".fathom"
/* True when a --scene argument names an image (.png or .exr) rather than a scene. */
bool shot_is_image(const char *name);
/* True when it names a preset (.fathom: a shot's text alone). */
bool shot_is_preset(const char *name);

#endif
