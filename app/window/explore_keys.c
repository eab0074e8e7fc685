/* explore_keys — what each key asks of the window (explore_app.h). Letters by their position: GLFW
 * names keys after the US layout's places. */
#include "window/explore_app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <stdio.h>

#include "window/panel.h"

static explore_app *app_of_keys; /* GLFW's callbacks carry no pointer of ours */

knob_id explore_next_knob(const explore_app *a, knob_id k)
{
    for (int tries = 0; tries < KNOB_COUNT; tries++) {
        k = (knob_id)((k + 1) % KNOB_COUNT);
        if (knob_window_steps(k) && (!a->s.have_scene || scene_knob_applies(&a->s.scene, k)))
            break;
    }
    return k;
}

/* Keys with the Ctrl modifier: saved views, undo and presets. True when handled. */
static bool ctrl_key(explore_app *a, int key, int mods)
{
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9)
        a->ask.recall_view = key - GLFW_KEY_0;
    else if (key == GLFW_KEY_Z && (mods & GLFW_MOD_SHIFT))
        a->ask.redo = true;
    else if (key == GLFW_KEY_Z)
        a->ask.undo = true;
    else if (key == GLFW_KEY_Y)
        a->ask.redo = true;
    else if (key == GLFW_KEY_S)
        a->ask.save_preset = true;
    else if (key == GLFW_KEY_C)
        a->ask.copy_preset = true;
    else if (key == GLFW_KEY_V)
        a->ask.paste_preset = true;
    else
        return false;
    return true;
}

/* The window's own keys (letters by their position: GLFW names keys after the US layout's places). */
static void plain_key(explore_app *a, GLFWwindow *w, int key, int mods)
{
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    case GLFW_KEY_F1:
    case GLFW_KEY_TAB: a->panel = !a->panel; break;
    case GLFW_KEY_ENTER:
    case GLFW_KEY_KP_ENTER: a->panel = a->focus_field = true; break;
    case GLFW_KEY_F2: a->hud = a->hud == HUD_FULL ? HUD_LINE : HUD_FULL; break;
    case GLFW_KEY_F3: a->hud = a->hud == HUD_HIDDEN ? HUD_LINE : HUD_HIDDEN; break;
    case GLFW_KEY_R: a->ask.reload = true; break;
    case GLFW_KEY_P:
    case GLFW_KEY_F12: a->ask.screenshot = true; break;
    case GLFW_KEY_M: a->ask.mesh = true; break;
    case GLFW_KEY_H: a->view = a->view == VIEW_STEPS ? VIEW_COLOR : VIEW_STEPS; break;
    case GLFW_KEY_G:
        render_grab_reference(), costs_grabbed(&a->cost);
        snprintf(a->message, sizeof a->message, "grabbed this frame as the reference: V shows the difference");
        break;
    case GLFW_KEY_V: a->view = a->view == VIEW_DIFFERENCE ? VIEW_COLOR : VIEW_DIFFERENCE; break;
    case GLFW_KEY_O: a->fly.mode = a->fly.mode == CAMERA_ORBIT ? CAMERA_FLY : CAMERA_ORBIT; break;
    case GLFW_KEY_T: a->fly.mode = a->fly.mode == CAMERA_WALK ? CAMERA_FLY : CAMERA_WALK; break;
    case GLFW_KEY_U: flycam_toggle_level(&a->fly); break;
    case GLFW_KEY_F: a->ask.focus = true; break;
    case GLFW_KEY_HOME:
    case GLFW_KEY_BACKSPACE: a->ask.go_home = true; break;
    case GLFW_KEY_B: a->ask.save_view = true; break;
    case GLFW_KEY_J: a->ask.fragment_preset = mods & GLFW_MOD_SHIFT ? -1 : +1; break;
    case GLFW_KEY_N: *(mods & GLFW_MOD_SHIFT ? &a->ask.clear_keys : &a->ask.add_key) = true; break;
    case GLFW_KEY_L: a->ask.toggle_play = true; break;
    case GLFW_KEY_K: a->knob = explore_next_knob(a, a->knob); break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD: a->ask.knob_step = +1; break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT: a->ask.knob_step = -1; break;
    default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && key - GLFW_KEY_1 < a->scene_count)
            a->ask.pending_scene = key - GLFW_KEY_1;
    }
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    if (action != GLFW_PRESS || panel_wants_keyboard()) /* typing into the panel */
        return;
    if (!(mods & GLFW_MOD_CONTROL) || !ctrl_key(app_of_keys, key, mods))
        plain_key(app_of_keys, w, key, mods);
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)w;
    (void)dx;
    if (!panel_wants_mouse())
        app_of_keys->fly.scroll += (float)dy;
}

void explore_keys_install(GLFWwindow *win, explore_app *a)
{
    app_of_keys = a;
    glfwSetKeyCallback(win, on_key);
    glfwSetScrollCallback(win, on_scroll);
}
