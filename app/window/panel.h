/* panel — the window's parameter panel: Dear ImGui (Debian's libimgui-dev, its GLFW and OpenGL 3
 * backends) behind a C interface, like image_io.cpp for OpenImageIO. It owns no scene state: each
 * frame the window hands it a model (the scene's tunable parameters as scene/params.h lists them,
 * the camera, what the image costs) and it hands back what the user did. Every control is generated
 * from the parameter list — a section per block, a control per key, its range from the parser; all
 * it knows of the keys is that the program's block and "quality" open first, that "camera" has a
 * section of its own and that a key ending in "direction" is a unit vector. GL and GLFW. */
#ifndef FATHOM_PANEL_H
#define FATHOM_PANEL_H

#include <stdbool.h>

#include "scene/params.h"
#include "util.h"

struct GLFWwindow;

enum { PANEL_SET_MAX = 2048, PANEL_PATH_MAX = 512, PANEL_TEXT_MAX = 1024 };

typedef enum panel_camera_mode { CAMERA_FLY, CAMERA_ORBIT, CAMERA_WALK, CAMERA_MODE_COUNT } panel_camera_mode;

/* What it costs to draw with a parameter at its last two values (the window measures it). */
typedef struct panel_cost {
    char key[PARAM_KEY_MAX];
    double ms_before, ms_after;     /* ms per full-size sample before and after the last edit (0: not yet) */
    double rmse_before, rmse_after; /* the image against the grabbed reference (−1: none grabbed) */
} panel_cost;

typedef struct panel_model {
    const param_list *params;
    const char *scene_title;
    const char *program_block; /* the section of the scene's program ("fractal", "terrain", "objects"): first */
    /* the live camera */
    double position[3], look_at[3];
    float fov_deg;
    panel_camera_mode camera_mode;
    bool can_walk; /* a terrain: walking has a ground */
    /* the image */
    double ms_per_sample, fps;
    int samples, spp, width, height, internal_width, internal_height;
    bool double_precision;
    const char *unresolved; /* what the converged image could not resolve, or NULL */
    double reference_rmse; /* the image against the grabbed reference; −1: none grabbed */
    const panel_cost *costs;
    int cost_count;
    float exposure;
    int view; /* render.h's render_view */
    float heat_max;
    bool can_undo, can_redo;
    const char *message;
    const char *cursor_info; /* a DEM's latitude, longitude and height under the cursor, or NULL */
    const char *preset_path; /* where "Save preset" writes */
    bool focus_set_field;    /* the key=value field takes the keyboard (Enter was pressed) */
} panel_model;

typedef struct panel_actions {
    char set[PANEL_SET_MAX]; /* "key=value" to apply (as --set), or "" */
    bool edit_started;       /* the user took hold of a control: the state before it is an undo step */
    bool undo, redo, grab_reference;
    bool camera_typed;       /* position, look_at and fov below were typed */
    double position[3], look_at[3];
    float fov_deg;
    int camera_mode;         /* −1: unchanged */
    bool exposure_changed;   /* display only: the image does not restart */
    float exposure;
    int view;                /* −1: unchanged */
    bool heat_changed;
    float heat_max;
    bool save_preset, copy_preset, paste_preset, load_preset;
    char preset_path[PANEL_PATH_MAX];
} panel_actions;

#ifdef __cplusplus
extern "C" {
#endif

/* Dear ImGui on this window. Install the window's own GLFW callbacks first: ImGui's chain to them. */
bool panel_init(struct GLFWwindow *window, err_t *err);
void panel_shutdown(void);
/* Draws the panel (when shown) over the current framebuffer and fills *out. Call once a frame. */
void panel_frame(bool shown, const panel_model *m, panel_actions *out);
/* Whether ImGui uses the keyboard (a text field has focus) or the mouse (the cursor is over the panel):
 * then the window does not fly with them. */
bool panel_wants_keyboard(void);
bool panel_wants_mouse(void);

#ifdef __cplusplus
}
#endif

#endif
