/* shots — the window's view as a shot description (view/shot.h) in a file: B saves it into the first
 * free numbered slot and Ctrl+1…9 recall one (view/views.h); a preset is the same text on its own,
 * saved, loaded, copied or pasted; J walks a fragment's own presets; P writes the image with its description inside;
 * M writes the scene's surface as a mesh. Opening one goes
 * through session_open_shot; the caller moves its camera (shots_opened). GL and GLFW. */
#ifndef FATHOM_SHOTS_H
#define FATHOM_SHOTS_H

#include <stdbool.h>
#include <stddef.h>

#include "view/camera.h"
#include "window/session.h"

struct GLFWwindow;

/* What opening a view or preset gave: the camera, and whether the scene file changed. */
typedef struct shots_opened {
    bool opened, new_file;
    camera cam;
} shots_opened;

/* What was asked of presets this frame (the keys' and the panel's). */
typedef struct shots_preset_ask {
    bool save, copy, load, paste;
} shots_preset_ask;

/* B (save: the view into the first free slot) or Ctrl+recall (1…9). message: what happened. */
shots_opened shots_views(session *s, const camera *cam, bool save, int recall, int w, int h, char *message, size_t n);
/* Saves to, copies, loads from `path` or pastes a preset. */
shots_opened shots_presets(struct GLFWwindow *win, session *s, const camera *cam, shots_preset_ask ask, const char *path,
                           int w, int h, char *message, size_t n);
/* J (step +1) or Shift+J (−1): a fragment's next or previous preset (scene/formula/frag.h), *current its index
 * (−1 before the first); nothing for another scene. */
shots_opened shots_fragment_preset(session *s, int step, int *current, char *message, size_t n);
/* P: the converged image (finished first, or drawn once at full size) to fathom-DATE-TIME.png. */
void shots_screenshot(const session *s, const camera *cam, int w, int h, char *message, size_t n);
/* M: the scene's surface as a mesh, fathom-DATE-TIME.glb (`fathom mesh` at its defaults: jobs/mesh/mesh_job.h),
 * its report and progress in the terminal. */
void shots_mesh(const session *s, char *message, size_t n);

#endif
