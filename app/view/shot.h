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
enum { SHOT_SET_MAX = 160 }; /* overrides a shot carries (cli.h takes more): a fragment's preset sets up to ~130 */

/* The formulas that drew a fractal shot, so that it reopens as it was or says why not: a shipped one
 * by its file under shaders/ and the hash of its text; a user's own by its path, hash and whole text
 * (as a user's scene is carried). */
enum { SHOT_FORMULA_MAX = 2, SHOT_FORMULA_TEXT_MAX = 64 * 1024 };
typedef struct shot_formula {
    char key[32];            /* the override that names it: "fractal.formula" or "fractal.hybrid.formula" */
    char file[PATH_MAX_LEN]; /* "fractal/NAME.glsl" (shipped) or the user's file's absolute path */
    char hash[17];           /* FNV-1a 64 of its text, 16 hex digits */
    char *text;              /* a user's formula's text (malloc'd), NULL for a shipped one */
} shot_formula;

typedef struct shot_desc {
    char scene[PATH_MAX_LEN]; /* a shipped scene's name, or a file's absolute path */
    char *scene_text;         /* that file's text when it is not shipped (malloc'd: shot_free), or NULL */
    char sets[SHOT_SET_MAX][256];
    int set_count;
    shot_formula formulas[SHOT_FORMULA_MAX];
    int formula_count;
    char *notes; /* shot_resolve_formulas's notes through cli_apply_shot (malloc'd), or NULL */
    camera cam;
    int width, height;
} shot_desc;

/* The JSON text for a shot of the scene at scene_path with these overrides, camera and size: the scene
 * by name when it is one of fathom's own (under <data>/scenes), else its absolute path and its text. */
void shot_describe(const char *scene_path, const char *const *sets, int set_count, const camera *cam, int width,
                   int height, strbuf *out);
/* The same with the formulas that drew it: formula_files[i] is the fractal's formula (i = 0) and its
 * hybrid's (i = 1) as formula.h's `file` gives it ("fractal/NAME.glsl" or an absolute path), or NULL. */
void shot_describe_fractal(const char *scene_path, const char *const *sets, int set_count,
                           const char *const formula_files[SHOT_FORMULA_MAX], const camera *cam, int width, int height,
                           strbuf *out);

/* A reopened shot's formulas, checked against what this machine has: a shipped formula whose text
 * changed since is named in notes (the image may differ); a user's formula that is missing here or
 * changed is drawn from the text the shot carries, copied to the cache folder
 * ($XDG_CACHE_HOME/fathom/formulas/HASH/NAME.glsl) and named by an override appended to d->sets, and
 * notes say so. False with err when a carried text does not match its own hash (a damaged shot). */
bool shot_resolve_formulas(shot_desc *d, strbuf *notes, err_t *err);

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
