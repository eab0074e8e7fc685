/* explore_app — the window's state, shared by the files of the explore module: explore.c (the frame
 * loop), explore_keys.c (what each key asks) and explore_hud.c (the text over the image). The state
 * of each concern is its own module's (window/session.h, flycam.h, costs.h, framestats.h, recorder.h);
 * what is here is what the keys ask and how the window shows it. GL and GLFW. */
#ifndef FATHOM_EXPLORE_APP_H
#define FATHOM_EXPLORE_APP_H

#include <stdbool.h>

#include "cli/cli.h"
#include "gpu/render.h"
#include "scene/quality.h"
#include "view/resolution.h"
#include "window/costs.h"
#include "window/flycam.h"
#include "window/framestats.h"
#include "window/recorder.h"
#include "window/session.h"

struct GLFWwindow;

enum { MAX_SCENES = 9, DEFAULT_FPS = 30 };
typedef enum hud_mode { HUD_LINE, HUD_FULL, HUD_HIDDEN } hud_mode;

typedef struct explore_app {
    const cli_options *opt;
    session s;       /* the scene and its edits */
    flycam fly;      /* the camera and how it moves */
    edit_costs cost; /* what each edit cost */
    frame_stats stats;
    recorder flight;
    char names[MAX_SCENES][SCENE_NAME_MAX]; /* the number keys' scenes */
    int scene_count;
    struct { /* what the keys asked, done in the frame's order */
        bool reload, screenshot, mesh, go_home, save_view, add_key, clear_keys, toggle_play;
        bool undo, redo, save_preset, copy_preset, paste_preset;
        bool focus; /* F: focus the lens on the point under the cursor */
        int recall_view;   /* Ctrl+1…9: 1…9; 0 none */
        int pending_scene; /* a number key's scene; −1 none */
        int knob_step;     /* =/-: +1 or −1 */
        int fragment_preset; /* J, Shift+J: +1, −1 */
    } ask;
    int fragment_preset; /* the fragment's preset J last opened (−1: none) */
    bool panel, focus_field;
    hud_mode hud;
    render_view view;
    float exposure;
    knob_id knob; /* the knob that =/- step */
    char message[ERR_MSG_MAX];
    char cursor_info[256];
    char preset_path[PATH_MAX_LEN];
    res_controller res;     /* the internal resolution while moving */
    bool scaled;            /* the last frame was rendered below full size */
    double band_rows;       /* rows of a still image's sample per display frame (0: not yet known) */
    double frame_sample_ms; /* this frame's sample */
    long unresolved;        /* the converged image's pixels out of steps (drawn as misses); −1: not counted */
} explore_app;

/* explore_keys.c: the keys' callbacks write into a (its ask, and the toggles they own). */
void explore_keys_install(struct GLFWwindow *win, explore_app *a);
/* The next knob the window steps after k (QUALITY_KNOBS' step column; only those the scene uses). */
knob_id explore_next_knob(const explore_app *a, knob_id k);
/* explore_hud.c: one line, all of it, or nothing. */
void explore_hud(const explore_app *a, int w, int h);
/* What the converged image could not resolve (its pixels out of steps), for the HUD and the panel. */
const char *explore_unresolved_text(const explore_app *a);

#endif
