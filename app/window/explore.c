/* explore — the interactive window (explore.h). One frame: read input, move the camera (fly, orbit or
 * walk, never into a surface: camera_slide), apply what the keys and the panel asked, draw a sample
 * (moving: at the resolution the frame-rate controller picks; still: full size, refining), then the
 * HUD and the panel. Every edit of the scene is a "key=value" override (scene/overrides.h) and goes
 * through the same parser --set does. */
#include "window/explore.h"

#include <assert.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "data/dem.h"
#include "gpu/aov.h"
#include "gpu/gpu.h"
#include "gpu/render.h"
#include "gpu/res_heightfield.h"
#include "jobs/offline.h"
#include "scene/overrides.h"
#include "scene/params.h"
#include "scene/scene.h"
#include "view/camera.h"
#include "view/resolution.h"
#include "view/shot.h"
#include "view/views.h"
#include "window/hud.h"
#include "window/panel.h"
#include "window/recorder.h"

enum { MAX_SCENES = 9, FRAME_HISTORY = 30, FULL_HISTORY = 16, DEFAULT_FPS = 30, COST_MAX = 32, PROBE_MAX = 64, CURSOR_SETTLE_FRAMES = 3,
       STAT_MAX = 100000 };
typedef enum hud_mode { HUD_LINE, HUD_FULL, HUD_HIDDEN } hud_mode;
static const float MOUSE_SENSITIVITY = 0.0025f; /* radians per pixel */
static const float SPEED_STEP = 1.25f;          /* per scroll notch */
static const float DOLLY_STEP = 0.85f;          /* orbit: the distance to the pivot per scroll notch */
static const float DEFAULT_SPEED = 2.0f;        /* × the distance to the surface (adaptive scenes) */
static const float START_SPEED_FRACTION = 0.2f; /* others: the start view's distance to its look-at, per 5 s */
static const float MIN_SPEED_FACTOR = 1e-3f, MAX_SPEED_FACTOR = 1e3f; /* scroll: of the start speed */
static const float DEFAULT_EXPOSURE = 1.0f;
static const double IDLE_WAIT_S = 0.05;
static const float MIN_ADAPTIVE_DISTANCE = 1e-13f; /* metres: keeps a little speed at the surface (deep zooms too) */
static const float WALK_HEIGHT = 1.8f;             /* metres: eye height when walking on terrain */
static const float WALK_SPEED = 1.4f;              /* m/s: walking (Shift: ×4, running) */

static struct {
    const cli_options *opt;
    scene scene;
    bool have_scene;
    param_list params; /* what the panel shows: every tunable value of the scene */
    camera cam;
    panel_camera_mode mode;
    double pivot[3]; /* orbit: the point the camera turns about */
    float speed, start_speed; /* fly: m/s, or × distance in adaptive scenes */
    double mouse[2];
    bool mouse_valid, looking, orbiting;
    int settle_frames; /* after the cursor was captured: frames whose mouse motion is not a look */
    float scroll;
    char names[MAX_SCENES][SCENE_NAME_MAX];
    int scene_count, pending_scene; /* pending: −1 none */
    bool reload, screenshot, go_home, save_view, panel, add_key, clear_keys, toggle_play;
    bool undo, redo, save_preset, copy_preset, paste_preset, focus_field;
    int recall_view; /* Ctrl+1…9 pressed: 1…9; 0 none */
    hud_mode hud;
    render_view view;
    float exposure;
    knob_id knob;  /* the knob that =/- step */
    int knob_step; /* pending: +1 or -1 */
    overrides edits; /* the panel's and the knob keys' edits, after the base overrides */
    /* the overrides the scene was opened with: the command line's (first scene) or a recalled view's */
    char base[CLI_MAX_SETS][OVERRIDE_LEN];
    int base_count;
    float surface_distance; /* the distance estimate at the camera (fractals: sets the flying speed) */
    char message[ERR_MSG_MAX];
    double frame_ms[FRAME_HISTORY];
    int frame_index;
    double sample_ms;   /* the last full-size sample's time (or the moving frames' estimate of it) */
    double band_ms;     /* the current full-size sample's bands so far */
    double frame_sample_ms; /* this frame's sample */
    double overhead_ms; /* a frame's time besides its sample (display, HUD, panel, swap, probes): smoothed */
    res_controller res; /* the internal resolution while moving */
    bool scaled;        /* the last frame was rendered below full size */
    double band_rows;   /* rows of a still image's sample per display frame (0: not yet known) */
    panel_cost costs[COST_MAX]; /* what each edited parameter costs */
    int cost_count;
    int cost_pending;         /* the cost waiting for its samples and its converged image, −1: none */
    long unresolved;          /* the converged image's pixels out of steps (drawn as misses); −1: not counted */
    double full_ms[FULL_HISTORY]; /* this image's full-size sample times, for the costs' medians */
    int full_count;
    double reference_rmse;    /* the converged image against the grabbed reference; −1: none */
    char cursor_info[256];
    char preset_path[PATH_MAX_LEN];
    recorder flight;
    dem_geo *geo; /* the DEM's georeferencing (latitude and longitude under the cursor), or NULL */
    char geo_path[PATH_MAX_LEN];
    /* --frames: what each frame cost (the whole frame, and the panel's share), moving or still */
    double *stat_frame_ms, *stat_panel_ms, *stat_swap_ms;
    bool *stat_moving;
    int stat_count, stat_cap;
} app;

/* ---- input ------------------------------------------------------------------------------------- */

/* The next knob the window steps, after k (QUALITY_KNOBS' step column; only those the scene uses). */
static knob_id next_knob(knob_id k)
{
    for (int tries = 0; tries < KNOB_COUNT; tries++) {
        k = (knob_id)((k + 1) % KNOB_COUNT);
        if (knob_window_steps(k) && (!app.have_scene || scene_knob_applies(&app.scene, k)))
            break;
    }
    return k;
}

/* Keys with the Ctrl modifier: saved views, undo and presets. True when handled. */
static bool ctrl_key(int key, int mods)
{
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9)
        app.recall_view = key - GLFW_KEY_0;
    else if (key == GLFW_KEY_Z && (mods & GLFW_MOD_SHIFT))
        app.redo = true;
    else if (key == GLFW_KEY_Z)
        app.undo = true;
    else if (key == GLFW_KEY_Y)
        app.redo = true;
    else if (key == GLFW_KEY_S)
        app.save_preset = true;
    else if (key == GLFW_KEY_C)
        app.copy_preset = true;
    else if (key == GLFW_KEY_V)
        app.paste_preset = true;
    else
        return false;
    return true;
}

/* The window's own keys (letters by their position: GLFW names keys after the US layout's places). */
static void plain_key(GLFWwindow *w, int key, int mods)
{
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    case GLFW_KEY_F1:
    case GLFW_KEY_TAB: app.panel = !app.panel; break;
    case GLFW_KEY_ENTER:
    case GLFW_KEY_KP_ENTER: app.panel = app.focus_field = true; break;
    case GLFW_KEY_F2: app.hud = app.hud == HUD_FULL ? HUD_LINE : HUD_FULL; break;
    case GLFW_KEY_F3: app.hud = app.hud == HUD_HIDDEN ? HUD_LINE : HUD_HIDDEN; break;
    case GLFW_KEY_R: app.reload = true; break;
    case GLFW_KEY_P:
    case GLFW_KEY_F12: app.screenshot = true; break;
    case GLFW_KEY_H: app.view = app.view == VIEW_STEPS ? VIEW_COLOR : VIEW_STEPS; break;
    case GLFW_KEY_G:
        render_grab_reference(), app.reference_rmse = 0;
        snprintf(app.message, sizeof app.message, "grabbed this frame as the reference: V shows the difference");
        break;
    case GLFW_KEY_V: app.view = app.view == VIEW_DIFFERENCE ? VIEW_COLOR : VIEW_DIFFERENCE; break;
    case GLFW_KEY_O: app.mode = app.mode == CAMERA_ORBIT ? CAMERA_FLY : CAMERA_ORBIT; break;
    case GLFW_KEY_T: app.mode = app.mode == CAMERA_WALK ? CAMERA_FLY : CAMERA_WALK; break;
    case GLFW_KEY_HOME:
    case GLFW_KEY_BACKSPACE: app.go_home = true; break;
    case GLFW_KEY_B: app.save_view = true; break;
    case GLFW_KEY_N: *(mods & GLFW_MOD_SHIFT ? &app.clear_keys : &app.add_key) = true; break;
    case GLFW_KEY_L: app.toggle_play = true; break;
    case GLFW_KEY_K: app.knob = next_knob(app.knob); break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD: app.knob_step = +1; break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT: app.knob_step = -1; break;
    default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && key - GLFW_KEY_1 < app.scene_count)
            app.pending_scene = key - GLFW_KEY_1;
    }
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    if (action != GLFW_PRESS || panel_wants_keyboard()) /* typing into the panel */
        return;
    if (!(mods & GLFW_MOD_CONTROL) || !ctrl_key(key, mods))
        plain_key(w, key, mods);
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)w;
    (void)dx;
    if (!panel_wants_mouse())
        app.scroll += (float)dy;
}

/* The free cursor (the panel, orbiting) or the captured one (flying and walking: the mouse looks). */
static bool cursor_free(void) { return app.panel || app.mode == CAMERA_ORBIT; }

static camera_input read_input(GLFWwindow *w, bool *orbit_press)
{
    camera_input in = {0};
    bool keys = !panel_wants_keyboard();
    in.move[0] = keys ? (float)(glfwGetKey(w, GLFW_KEY_D) - glfwGetKey(w, GLFW_KEY_A)) : 0;
    in.move[1] = keys ? (float)(glfwGetKey(w, GLFW_KEY_SPACE) - glfwGetKey(w, GLFW_KEY_C)) : 0;
    in.move[2] = keys ? (float)(glfwGetKey(w, GLFW_KEY_W) - glfwGetKey(w, GLFW_KEY_S)) : 0;
    in.fast = keys && (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT));
    int cursor = cursor_free() ? GLFW_CURSOR_NORMAL : GLFW_CURSOR_DISABLED;
    if (glfwGetInputMode(w, GLFW_CURSOR) != cursor) {
        /* capturing warps the cursor to the window's centre, and GLFW's first motion events after it
         * can carry the jump from where X last saw the pointer: no look from the next few frames */
        glfwSetInputMode(w, GLFW_CURSOR, cursor);
        app.settle_frames = CURSOR_SETTLE_FRAMES;
    }
    if (app.settle_frames > 0) {
        app.settle_frames--;
        app.mouse_valid = false;
    }
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    bool over_panel = panel_wants_mouse();
    bool right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    bool left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    bool look = !cursor_free() || (right && (app.looking || !over_panel));
    bool orbit = app.mode == CAMERA_ORBIT && left && (app.orbiting || !over_panel);
    *orbit_press = orbit && !app.orbiting;
    if (app.mouse_valid && (look || orbit)) {
        in.look[0] = (float)(x - app.mouse[0]);
        in.look[1] = (float)(y - app.mouse[1]);
    }
    app.looking = look && cursor_free();
    app.orbiting = orbit;
    app.mouse[0] = x;
    app.mouse[1] = y;
    app.mouse_valid = true;
    return in;
}

/* ---- probes: the renderer's distance bound, and what is under the cursor --------------------------- */

/* The distance bound at n points (double, world): relative to the renderer's origin (a deep zoom's). */
static void probe_distances(void *ctx, const double *points, int n, float *out)
{
    (void)ctx;
    float p[PROBE_MAX * 3] = {0}, d[PROBE_MAX * 2];
    double origin[3];
    err_t e;
    assert(n <= PROBE_MAX);
    render_origin(origin);
    for (int i = 0; i < 3 * n; i++)
        p[i] = (float)(points[i] - origin[i % 3]);
    bool ok = render_probe(&app.scene, NULL, p, n, d, &e);
    for (int i = 0; i < n; i++)
        out[i] = ok ? d[2 * i] : -1.0f; /* unknown: the move is left alone */
}

/* The world point seen at window pixel (x, y) (from the top), by the depth of the image on show. */
static bool point_under(int x, int y, int w, int h, double out[3])
{
    int aw, ah;
    render_active_size(&aw, &ah);
    float aov[AOV_FLOATS];
    int ax = (int)((double)x * aw / w), ay = (int)((double)y * ah / h);
    if (!render_read_pixel(ax, ay, aov) || !isfinite(aov[AOV_SLOT_DEPTH]))
        return false;
    vec3 d;
    camera_ray(&app.cam, aw, ah, (float)ax, (float)(ah - 1 - ay), d);
    for (int i = 0; i < 3; i++)
        out[i] = app.cam.position[i] + (double)d[i] * (double)aov[AOV_SLOT_DEPTH];
    return true;
}

/* ---- the camera ---------------------------------------------------------------------------------- */

static void go_home(void)
{
    app.cam = camera_look_at_deg(app.scene.cam_position, app.scene.cam_look_at, app.scene.cam_fov_deg);
    app.speed = app.start_speed;
    memcpy(app.pivot, app.scene.cam_look_at, sizeof app.pivot);
    snprintf(app.message, sizeof app.message, "back at the start view");
}

/* Orbit: a drag turns the camera about the pivot (the point under the cursor where the drag began, or
 * the last one), the scroll wheel moves it toward or away from the pivot. */
static void orbit(const camera_input *in, bool press, int w, int h, double target[3])
{
    if (press && !point_under((int)app.mouse[0], (int)app.mouse[1], w, h, app.pivot) &&
        camera_distance(app.pivot, app.cam.position) <= 0)
        memcpy(app.pivot, app.scene.cam_look_at, sizeof app.pivot);
    camera_orbit(&app.cam, app.pivot, -in->look[0] * MOUSE_SENSITIVITY, -in->look[1] * MOUSE_SENSITIVITY);
    memcpy(target, app.cam.position, sizeof app.cam.position);
    if (app.scroll != 0) { /* the dolly goes through the slide rule like any move */
        double f = pow(DOLLY_STEP, app.scroll);
        for (int i = 0; i < 3; i++)
            target[i] = app.pivot[i] + (app.cam.position[i] - app.pivot[i]) * f;
        app.scroll = 0;
    }
}

/* Walking: along the ground at walking speed, the eye WALK_HEIGHT above it. */
static void walk(const camera_input *in, float dt, double target[3])
{
    camera_input flat = *in;
    flat.move[1] = 0;
    float pitch = app.cam.pitch;
    app.cam.pitch = 0; /* forward along the ground, wherever the eye looks */
    camera_update(&app.cam, &flat, dt, WALK_SPEED, MOUSE_SENSITIVITY);
    app.cam.pitch = fmaxf(fminf(pitch - in->look[1] * MOUSE_SENSITIVITY, CAMERA_MAX_PITCH), -CAMERA_MAX_PITCH);
    memcpy(target, app.cam.position, sizeof app.cam.position);
    float ground;
    if (render_ground_height((float)target[0], (float)target[2], &ground))
        target[1] = ground + WALK_HEIGHT;
}

/* One frame's move. Scroll sets the flying speed (within MIN/MAX_SPEED_FACTOR of the scene's start
 * speed), which follows the distance to the surface where the scene asks for it (fractals: close up
 * stays controllable). Every move goes through the slide rule, so the camera never enters or passes
 * through a solid and never sticks to one, and it stays within max_dist of the start view's look-at. */
static void move_camera(GLFWwindow *win, float dt, int w, int h)
{
    if (app.go_home) {
        go_home();
        app.go_home = false;
    }
    bool orbit_press;
    camera_input in = read_input(win, &orbit_press);
    float d;
    probe_distances(NULL, app.cam.position, 1, &d);
    app.surface_distance = fabsf(d);
    if (app.mode == CAMERA_WALK && !app.scene.terrain.heightmap[0])
        app.mode = CAMERA_FLY; /* walking needs a ground */
    double before[3], target[3];
    memcpy(before, app.cam.position, sizeof before);
    if (app.mode == CAMERA_ORBIT) {
        orbit(&in, orbit_press, w, h, target);
    } else if (app.mode == CAMERA_WALK) {
        walk(&in, dt, target);
    } else {
        if (app.scroll != 0) {
            app.speed = fminf(fmaxf(app.speed * powf(SPEED_STEP, app.scroll), MIN_SPEED_FACTOR * app.start_speed),
                              MAX_SPEED_FACTOR * app.start_speed);
            app.scroll = 0;
        }
        float speed = app.scene.adaptive_speed ? app.speed * fmaxf(app.surface_distance, MIN_ADAPTIVE_DISTANCE) : app.speed;
        camera_update(&app.cam, &in, dt, speed, MOUSE_SENSITIVITY);
        memcpy(target, app.cam.position, sizeof target);
    }
    memcpy(app.cam.position, before, sizeof before);
    if (memcmp(before, target, sizeof before))
        camera_slide(before, target, app.scene.quality.step_factor, camera_resolution(before, app.scene.fractal.deep_now),
                     probe_distances, NULL, NULL);
    memcpy(app.cam.position, target, sizeof target);
    camera_clamp_range(app.cam.position, app.scene.cam_look_at, app.scene.quality.max_dist);
}

/* ---- the scene and its edits -------------------------------------------------------------------- */

/* The overrides the scene loads with: the base ones, then the edits. */
static int current_sets(const char **sets)
{
    int n = 0;
    for (int i = 0; i < app.base_count; i++)
        sets[n++] = app.base[i];
    int m;
    overrides_list(&app.edits, sets + n, &m);
    return n + m;
}

static void reset_camera(bool first)
{
    const cli_options *opt = app.opt;
    float fov = first && opt->has_fov ? opt->fov_deg : app.scene.cam_fov_deg;
    const double *pos = first && opt->has_camera ? opt->camera : app.scene.cam_position;
    const double *at = first && opt->has_look_at ? opt->look_at : app.scene.cam_look_at;
    app.cam = first && opt->has_view ? opt->view : camera_look_at_deg(pos, at, fov);
    app.start_speed = app.scene.adaptive_speed
                          ? DEFAULT_SPEED
                          : START_SPEED_FRACTION * (float)camera_distance(app.scene.cam_position, app.scene.cam_look_at);
    app.speed = app.start_speed;
    memcpy(app.pivot, at, sizeof app.pivot);
    snprintf(app.preset_path, sizeof app.preset_path, "%s" SHOT_PRESET_EXT, app.scene.name);
    char msg[ERR_MSG_MAX];
    recorder_load(&app.flight, app.scene.name, msg, sizeof msg);
    if (msg[0])
        snprintf(app.message, sizeof app.message, "%s", msg);
}

/* Loads `name` with the base overrides and the edits; the camera stays where the user flew it unless
 * the file changed. On failure the last good scene stays. */
static bool load_scene(const char *name, bool first, err_t *err)
{
    const char *sets[CLI_MAX_SETS + OVERRIDES_MAX];
    int n = current_sets(sets);
    scene next;
    param_list params = {0};
    if (!scene_load_params(name, sets, n, &next, &params, err)) {
        params_free(&params);
        return false;
    }
    if (app.opt->spp)
        next.quality.spp = app.opt->spp;
    next.fractal.deep_now = next.fractal.deep_now || (app.have_scene && app.scene.fractal.deep_now && next.fractal.deep_ok &&
                                                      next.fractal.precision == PRECISION_AUTO);
    bool same_file = app.have_scene && !strcmp(app.scene.path, next.path);
    if (!render_set_scene(&next, NULL, err)) { /* the renderer copies what it needs */
        scene_free(&next);
        params_free(&params);
        if (app.have_scene) {
            err_t ignore;
            render_set_scene(&app.scene, NULL, &ignore); /* back to the last good scene */
        }
        return false;
    }
    if (app.have_scene)
        scene_free(&app.scene);
    params_free(&app.params);
    app.scene = next;
    app.params = params;
    app.have_scene = true;
    if (!same_file)
        reset_camera(first);
    if (strcmp(app.geo_path, app.scene.terrain.heightmap)) { /* a DEM's place on the Earth, for the cursor */
        dem_geo_close(app.geo);
        app.geo = app.scene.terrain.heightmap[0] ? dem_geo_open(app.scene.terrain.heightmap) : NULL;
        snprintf(app.geo_path, sizeof app.geo_path, "%s", app.scene.terrain.heightmap);
    }
    if (!knob_window_steps(app.knob) || !scene_knob_applies(&app.scene, app.knob))
        app.knob = next_knob(app.knob);
    return true;
}

/* Applies an edit ("key=value"), checked by the parser like --set; a rejected one is taken back. */
static bool edit(const char *kv)
{
    overrides keep = app.edits;
    err_t e;
    if (!overrides_set(&app.edits, kv)) {
        snprintf(app.message, sizeof app.message, "'%.200s' is not key=value (or too many edits)", kv);
        return false;
    }
    if (!load_scene(app.scene.path, false, &e)) {
        app.edits = keep;
        snprintf(app.message, sizeof app.message, "%s", e.msg);
        return false;
    }
    snprintf(app.message, sizeof app.message, "%.300s", kv);
    return true;
}

/* The median of this image's full-size sample times, but its first. */
static double median_full_ms(void)
{
    double v[FULL_HISTORY];
    int skip = app.full_count > 1; /* the first also compiled the program (llvmpipe: 200-400 ms more) */
    int n = app.full_count - skip;
    memcpy(v, app.full_ms + skip, sizeof v[0] * (size_t)n);
    for (int i = 1; i < n; i++) /* a handful: insertion sort */
        for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
            double t = v[j];
            v[j] = v[j - 1], v[j - 1] = t;
        }
    return n == 0 ? 0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* A cost entry for an edit of key: the sample time and the reference error before it; the after comes
 * with the next full-size sample (note_sample). */
static void note_cost(const char *kv)
{
    char key[PARAM_KEY_MAX];
    snprintf(key, sizeof key, "%.*s", (int)strcspn(kv, "="), kv);
    int i = 0;
    while (i < app.cost_count && strcmp(app.costs[i].key, key))
        i++;
    if (i < app.cost_count) { /* the newest edit is the last entry */
        memmove(app.costs + i, app.costs + i + 1, sizeof app.costs[0] * (size_t)(app.cost_count - i - 1));
        i = --app.cost_count;
    }
    if (i == app.cost_count) {
        if (app.cost_count == COST_MAX) { /* the oldest goes */
            memmove(app.costs, app.costs + 1, sizeof app.costs[0] * (COST_MAX - 1));
            i = --app.cost_count;
        }
        app.cost_count++;
        snprintf(app.costs[i].key, sizeof app.costs[i].key, "%s", key);
    }
    app.costs[i].ms_before = app.full_count ? median_full_ms() : app.sample_ms;
    app.costs[i].ms_after = 0;
    app.costs[i].rmse_before = app.reference_rmse;
    app.costs[i].rmse_after = -1;
    app.cost_pending = i;
}

/* Steps the selected knob (the same checks as --set). */
static void step_knob(int dir)
{
    const char *name = knob_get_def(app.knob)->name;
    double v = knob_step(app.knob, knob_value(&app.scene.quality, app.knob), dir);
    char kv[96];
    snprintf(kv, sizeof kv, "quality.%s=%g", name, v);
    overrides_checkpoint(&app.edits);
    note_cost(kv);
    edit(kv);
}

/* ---- shots, saved views and presets: the view as a shot description (view/shot.h) ------------------ */

static void describe(int w, int h, strbuf *out)
{
    const char *sets[CLI_MAX_SETS + OVERRIDES_MAX];
    int n = current_sets(sets);
    const char *formulas[SHOT_FORMULA_MAX];
    scene_formula_files(&app.scene, formulas);
    shot_describe_fractal(app.scene.path, sets, n, formulas, &app.cam, w, h, out);
}

/* Opens a shot description: its scene (carried or shipped), its overrides as the base (the edits go)
 * and its camera. */
static bool open_shot(const char *text, const char *source, err_t *err)
{
    shot_desc d;
    if (!shot_parse(text, source, &d, err))
        return false;
    if (d.scene_text)
        scene_provide_text(d.scene, d.scene_text);
    strbuf notes = {0};
    if (!shot_resolve_formulas(&d, &notes, err)) {
        sb_free(&notes);
        shot_free(&d);
        return false;
    }
    if (notes.data) /* its formulas: changed since, or carried (view/shot.h) */
        fputs(notes.data, stderr);
    sb_free(&notes);
    char keep_base[CLI_MAX_SETS][OVERRIDE_LEN];
    int keep_count = app.base_count;
    overrides keep_edits = app.edits;
    memcpy(keep_base, app.base, sizeof keep_base);
    for (int i = 0; i < d.set_count && i < CLI_MAX_SETS; i++)
        snprintf(app.base[i], OVERRIDE_LEN, "%s", d.sets[i]);
    app.base_count = d.set_count < CLI_MAX_SETS ? d.set_count : CLI_MAX_SETS;
    overrides_clear(&app.edits);
    bool ok = load_scene(d.scene, false, err);
    if (ok) {
        app.cam = d.cam;
    } else { /* what was in force stays */
        memcpy(app.base, keep_base, sizeof keep_base);
        app.base_count = keep_count;
        app.edits = keep_edits;
    }
    shot_free(&d);
    return ok;
}

/* B: the view into the first free slot 1…9; Ctrl+N: back to view N. True when the image restarts. */
static bool views(int w, int h)
{
    char file[PATH_MAX_LEN], *text;
    err_t e;
    bool restart = false;
    if (!app.save_view && !app.recall_view)
        return false;
    if (!views_file(app.scene.name, file, sizeof file, &e)) {
        snprintf(app.message, sizeof app.message, "%s", e.msg);
    } else if (app.save_view) {
        int slot = views_next_free(file);
        char name[2] = {(char)('0' + (slot ? slot : 9)), '\0'};
        strbuf d = {0};
        describe(w, h, &d);
        if (views_save(file, name, d.data, &e))
            snprintf(app.message, sizeof app.message, "saved view %s (Ctrl+%s recalls it; --view %s renders it)%s",
                     name, name, name, slot ? "" : ": all nine were used, 9 replaced");
        else
            snprintf(app.message, sizeof app.message, "%s", e.msg);
        sb_free(&d);
    } else {
        char name[2] = {(char)('0' + app.recall_view), '\0'};
        bool ok = views_load(file, name, &text, &e);
        if (ok) {
            ok = open_shot(text, file, &e);
            free(text);
        }
        if (ok)
            snprintf(app.message, sizeof app.message, "back at view %s", name), restart = true;
        else
            snprintf(app.message, sizeof app.message, "%s", e.msg);
    }
    app.save_view = false;
    app.recall_view = 0;
    return restart;
}

/* Save, copy, load or paste a preset (a shot's text on its own). True when the image restarts. */
static bool presets(GLFWwindow *win, const panel_actions *act, int w, int h)
{
    err_t e;
    bool save = app.save_preset || act->save_preset, copy = app.copy_preset || act->copy_preset;
    bool paste = app.paste_preset || act->paste_preset, restart = false;
    app.save_preset = app.copy_preset = app.paste_preset = false;
    if (act->preset_path[0])
        snprintf(app.preset_path, sizeof app.preset_path, "%s", act->preset_path);
    if (save || copy) {
        strbuf d = {0};
        describe(w, h, &d);
        if (copy) {
            glfwSetClipboardString(win, d.data);
            snprintf(app.message, sizeof app.message, "copied the preset (scene, edits, camera) to the clipboard");
        }
        if (save && util_write_text_atomic(app.preset_path, d.data, "the preset", &e))
            snprintf(app.message, sizeof app.message, "saved %.900s: fathom --scene %.900s opens it anywhere",
                     app.preset_path, app.preset_path);
        else if (save)
            snprintf(app.message, sizeof app.message, "%s", e.msg);
        sb_free(&d);
    }
    if (act->load_preset || paste) {
        char *text = NULL;
        const char *clip = paste ? glfwGetClipboardString(win) : NULL;
        bool ok = paste ? clip != NULL : util_read_file(app.preset_path, &text, NULL, &e);
        if (paste && !ok)
            err_set(&e, "the clipboard holds no text");
        ok = ok && open_shot(paste ? clip : text, paste ? "the clipboard" : app.preset_path, &e);
        free(text);
        snprintf(app.message, sizeof app.message, "%s", ok ? "opened the preset" : e.msg);
        restart = ok;
    }
    return restart;
}

/* P: the converged image, or the last complete one: a sample in progress is finished first, and a
 * moving (smaller) image is drawn once at full size. Never a half-refined mix. */
static void screenshot(int w, int h)
{
    int aw, ah;
    render_active_size(&aw, &ah);
    if (aw != w || ah != h) {
        render_set_active(w, h);
        render_begin(&app.cam);
        render_sample();
    } else if (render_band_rows() > 0) {
        render_sample_band(h);
    }
    char file[128];
    time_t now = time(NULL);
    strftime(file, sizeof file, "fathom-%Y%m%d-%H%M%S.png", localtime(&now));
    err_t err;
    strbuf description = {0}; /* the shot remembers how it was made */
    describe(w, h, &description);
    bool ok = offline_write(file, w, h, 0, description.data, &err);
    sb_free(&description);
    if (ok)
        snprintf(app.message, sizeof app.message, "saved %s (%d samples)", file, render_samples());
    else
        snprintf(app.message, sizeof app.message, "%s", err.msg);
    fprintf(stderr, "fathom: %s\n", app.message);
}

/* ---- the panel ---------------------------------------------------------------------------------- */

static double average_ms(void)
{
    double sum = 0;
    int n = 0;
    for (int i = 0; i < FRAME_HISTORY; i++)
        if (app.frame_ms[i] > 0)
            sum += app.frame_ms[i], n++;
    return n ? sum / n : 0;
}

/* The block of the scene file its program reads (the panel shows it first). */
static const char *program_block(const scene *s)
{
    if (program_is_fractal(s->program))
        return "fractal";
    return s->program == PROGRAM_CSG ? "objects" : "terrain";
}

/* The converged image's rays that found no answer: said, never hidden (they are drawn as misses). */
static const char *unresolved_text(void)
{
    static char text[160];
    snprintf(text, sizeof text, "%ld px ran out of steps (drawn as misses): H shows them magenta; raise quality.max_steps",
             app.unresolved);
    return text;
}

static void panel_model_of(int w, int h, panel_model *m)
{
    camera_basis b = camera_get_basis(&app.cam);
    double dist = camera_distance(app.cam.position, app.pivot);
    dist = dist > 0 ? dist : 1;
    *m = (panel_model){.params = &app.params, .scene_title = app.scene.title[0] ? app.scene.title : app.scene.name,
                       .program_block = program_block(&app.scene),
                       .fov_deg = glm_deg(app.cam.fov_y), .camera_mode = app.mode,
                       .can_walk = app.scene.terrain.heightmap[0] != 0, .ms_per_sample = app.sample_ms,
                       .samples = render_samples(), .spp = app.scene.quality.spp, .width = w, .height = h,
                       .double_precision = app.scene.fractal.deep_now, .reference_rmse = app.reference_rmse,
                       .costs = app.costs, .cost_count = app.cost_count, .exposure = app.exposure, .view = (int)app.view,
                       .heat_max = render_heat_max(), .can_undo = app.edits.undo_count > 0,
                       .can_redo = app.edits.redo_count > 0, .message = app.message,
                       .cursor_info = app.cursor_info[0] ? app.cursor_info : NULL, .preset_path = app.preset_path,
                       .focus_set_field = app.focus_field,
                       .unresolved = app.unresolved > 0 ? unresolved_text() : NULL};
    app.focus_field = false;
    double ms = average_ms();
    m->fps = ms > 0 ? 1000.0 / ms : 0;
    render_active_size(&m->internal_width, &m->internal_height);
    /* The look-at comes from a float direction: shown to the decimal that direction holds (-0.1, not
     * -0.0999999968; 0, not -8e-09), which is far below a double's digits only in a deep zoom. */
    double quantum = pow(10.0, floor(log10(dist * 1e-6)));
    for (int i = 0; i < 3; i++) {
        m->position[i] = app.cam.position[i];
        double offset = (double)b.forward[i] * dist;
        m->look_at[i] = app.cam.position[i] + offset;
        double rounded = round(m->look_at[i] / quantum) * quantum;
        if (fabs(rounded - m->look_at[i]) < 1e-6 * dist)
            m->look_at[i] = rounded + 0.0; /* and 0, not -0 */
    }
}

/* What the user did in the panel last frame. True when the image must restart. */
static bool panel_apply(const panel_actions *act)
{
    bool restart = false;
    if (act->edit_started && act->set[0])
        overrides_checkpoint(&app.edits);
    if (act->set[0]) {
        note_cost(act->set);
        restart |= edit(act->set);
    }
    err_t e;
    if ((act->undo || app.undo) && overrides_undo(&app.edits))
        restart |= load_scene(app.scene.path, false, &e) || (snprintf(app.message, sizeof app.message, "%s", e.msg), false);
    if ((act->redo || app.redo) && overrides_redo(&app.edits))
        restart |= load_scene(app.scene.path, false, &e) || (snprintf(app.message, sizeof app.message, "%s", e.msg), false);
    app.undo = app.redo = false;
    if (act->camera_typed) {
        if (camera_degenerate(act->position, act->look_at)) {
            snprintf(app.message, sizeof app.message, "the look-at point is the camera's position: no direction to look in");
        } else {
            app.cam = camera_look_at_deg(act->position, act->look_at, act->fov_deg);
            memcpy(app.pivot, act->look_at, sizeof app.pivot);
        }
    }
    if (act->camera_mode >= 0)
        app.mode = (panel_camera_mode)act->camera_mode;
    if (act->exposure_changed)
        app.exposure = act->exposure;
    if (act->view >= 0)
        app.view = (render_view)act->view;
    if (act->heat_changed)
        render_set_heat_max(act->heat_max);
    if (act->grab_reference)
        render_grab_reference(), app.reference_rmse = 0;
    return restart;
}

/* ---- the HUD: one line, all of it, or nothing -------------------------------------------------- */

static const char *const MODE_NAMES[CAMERA_MODE_COUNT] = {"flying", "orbiting", "walking"};

/* The full HUD's lines about the camera and the knobs the window steps (only those the scene uses). */
static void hud_details(int h, strbuf *t)
{
    const camera *c = &app.cam;
    if (app.mode == CAMERA_WALK)
        sb_printf(t, "walking %.1f m above the ground at %.1f m/s\n", (double)WALK_HEIGHT, (double)WALK_SPEED);
    else if (app.mode == CAMERA_ORBIT)
        sb_printf(t, "orbiting about (%.6g %.6g %.6g): drag turns, scroll moves in\n", app.pivot[0], app.pivot[1], app.pivot[2]);
    else if (app.scene.adaptive_speed)
        sb_printf(t, "speed %.2f x distance (%.3g m to the surface)\n", (double)app.speed, (double)app.surface_distance);
    else
        sb_printf(t, "speed %.3g m/s\n", (double)app.speed);
    sb_printf(t, "pos %.10g %.10g %.10g  fov %.1f\n", c->position[0], c->position[1], c->position[2],
              (double)glm_deg(c->fov_y));
    float d = app.surface_distance, pa = camera_pixel_angle(c, h);
    double floor = app.scene.fractal.deep_now ? camera_resolution(c->position, true)
                                              : (double)PRECISION_REL * (camera_norm(c->position) + (double)d);
    if (app.scene.adaptive_speed && (double)(app.scene.quality.hit_k * d * pa) < floor)
        sb_printf(t, "%s precision reached: detail below %.2g m cannot be resolved here\n",
                  app.scene.fractal.deep_now ? "double" : "float", floor);
    else if (app.scene.fractal.deep_now)
        sb_printf(t, "double precision (deep zoom)\n");
    for (int k = 0; k < KNOB_COUNT; k++)
        if (knob_window_steps((knob_id)k) && scene_knob_applies(&app.scene, (knob_id)k))
            sb_printf(t, "%s%s %g%s  ", k == (int)app.knob ? "[" : "", knob_get_def((knob_id)k)->name,
                      knob_value(&app.scene.quality, (knob_id)k), k == (int)app.knob ? "]" : "");
    sb_printf(t, "\nWASD move  mouse look  Space/C up/down  Shift fast  scroll speed  O orbit%s\n"
                 "F1 panel  Enter type an edit  F2 this help  F3 hide  1-%d scenes  K knob  =/- step  H steps  G grab  V difference\n"
                 "Home start  B save view  Ctrl+1-9 recall  Ctrl+Z undo  Ctrl+S preset  N keyframe (%d)  L play  "
                 "R reload  P shot  Esc quit\n",
              app.scene.terrain.heightmap[0] ? "  T walk" : "", app.scene_count, app.flight.key_count);
}

static void hud(int w, int h)
{
    if (app.hud == HUD_HIDDEN)
        return;
    double ms = average_ms();
    int iw, ih;
    render_active_size(&iw, &ih);
    strbuf t = {0};
    static const char *const views[] = {"", "  [steps]", "  [difference to the grabbed frame]"};
    sb_printf(&t, "%s  %s  %dx%d%s  %.0f ms/sample  %d/%d spp  %s%s  F1 panel  F2 help\n", app.scene.name,
              preset_name(app.scene.preset), iw, ih, views[app.view], app.sample_ms, render_samples(),
              app.scene.quality.spp, MODE_NAMES[app.mode], app.scene.fractal.deep_now ? "  double" : "");
    if (app.hud == HUD_FULL) {
        sb_printf(&t, "%.1f ms a frame (%.1f fps)\n", ms, ms > 0 ? 1000.0 / ms : 0.0);
        hud_details(h, &t);
    }
    if (app.unresolved > 0)
        sb_printf(&t, "%s\n", unresolved_text());
    if (app.cursor_info[0])
        sb_printf(&t, "%s\n", app.cursor_info);
    if (app.message[0] && !app.panel)
        sb_printf(&t, "%s\n", app.message);
    float scale = h >= 900 ? 2.0f : 1.5f;
    hud_draw(t.data, 0, 0, w, h, scale);
    sb_free(&t);
    if (app.view == VIEW_STEPS) { /* the legend's labels over the bar display.frag draws */
        char legend[160];
        snprintf(legend, sizeof legend, "primary-ray steps a pixel: 0 (blue) ... %.0f (red); magenta: unresolved (out of steps)",
                 (double)render_heat_max());
        hud_draw(legend, 16, -34, w, h, scale);
    }
}

/* ---- requests and drawing ------------------------------------------------------------------------ */

/* The shipped scenes, in --list-scenes order: number keys 1–9 pick them. */
static void list_scene_names(void)
{
    strbuf list = {0};
    scene_list(&list);
    for (char *line = list.data; line && *line && app.scene_count < MAX_SCENES;) {
        char *nl = strchr(line, '\n');
        snprintf(app.names[app.scene_count++], SCENE_NAME_MAX, "%.*s", (int)(nl ? nl - line : (long)strlen(line)), line);
        line = nl ? nl + 1 : line + strlen(line);
    }
    sb_free(&list);
}

static void flight_requests(void)
{
    double speed = app.scene.adaptive_speed ? (double)(app.speed * fmaxf(app.surface_distance, MIN_ADAPTIVE_DISTANCE))
                                            : (double)app.speed;
    if (app.add_key)
        recorder_add(&app.flight, app.scene.name, &app.cam, speed, app.message, sizeof app.message);
    if (app.clear_keys)
        recorder_clear(&app.flight, app.scene.name, app.message, sizeof app.message);
    if (app.toggle_play)
        recorder_toggle_play(&app.flight, app.message, sizeof app.message);
    app.add_key = app.clear_keys = app.toggle_play = false;
}

/* Scene switches, knob steps and reloads asked for by keys. True when the image must restart. */
static bool handle_requests(void)
{
    bool restart = false;
    err_t e;
    if (app.pending_scene >= 0) {
        app.base_count = 0; /* the command line's and a view's overrides belong to their own scene */
        overrides_clear(&app.edits);
        app.cost_count = 0;
        if (!load_scene(app.names[app.pending_scene], false, &e))
            snprintf(app.message, sizeof app.message, "%s", e.msg), fprintf(stderr, "fathom: %s\n", e.msg);
        else
            app.message[0] = '\0';
        app.pending_scene = -1;
        memset(app.frame_ms, 0, sizeof app.frame_ms); /* another scene's times say nothing of this one */
        app.res = res_init(app.res.target_ms > 0 ? 1000.0f / app.res.target_ms : DEFAULT_FPS, RES_MIN_SCALE);
        restart = true;
    }
    if (app.knob_step) {
        step_knob(app.knob_step);
        app.knob_step = 0;
        restart = true;
    }
    if (app.reload) {
        if (!render_reload(&e) || !load_scene(app.scene.path, false, &e)) {
            if (snprintf(app.message, sizeof app.message, "reload failed, kept the last good program:\n%s", e.msg) >=
                (int)sizeof app.message)
                app.message[sizeof app.message - 1] = '\0';
            fprintf(stderr, "fathom: %s\n", app.message);
        } else {
            snprintf(app.message, sizeof app.message, "shaders and scene reloaded");
        }
        app.reload = false;
        restart = true;
    }
    flight_requests();
    return restart;
}

/* After a sample: its time at full size (bands add up; a smaller moving frame is scaled up), and the
 * pending cost entry's "after". */
static void note_sample(double ms, int iw, int ih, int w, int h, bool complete)
{
    app.frame_ms[app.frame_index++ % FRAME_HISTORY] = ms;
    if (iw != w || ih != h) {
        app.sample_ms = ms * ((double)w * h) / ((double)iw * ih);
        app.band_ms = 0;
    } else {
        app.band_ms += ms;
        if (complete)
            app.sample_ms = app.band_ms, app.band_ms = 0;
    }
    if (!complete || iw != w || ih != h)
        return;
    if (render_samples() == 1) /* a new image: its samples' times start again */
        app.full_count = 0;
    if (app.full_count < FULL_HISTORY)
        app.full_ms[app.full_count++] = app.sample_ms;
    if (app.cost_pending >= 0) /* the median so far: one sample that also compiled or met a busy core is not the cost */
        app.costs[app.cost_pending].ms_after = median_full_ms();
}

/* Once the image has converged: its difference to the grabbed reference (the pending cost's "after"). */
static void note_converged(void)
{
    if (app.cost_pending >= 0 && app.reference_rmse < 0) { /* no reference: the time is all there is */
        app.cost_pending = -1;
        return;
    }
    if (app.reference_rmse < 0)
        return;
    double rmse = render_reference_rmse();
    if (rmse < 0)
        return;
    app.reference_rmse = rmse;
    if (app.cost_pending >= 0) {
        app.costs[app.cost_pending].rmse_after = rmse;
        app.cost_pending = -1;
    }
}

/* One frame's sample. Moving (or restarted): one sample at the internal resolution the controller
 * picks for the target frame rate, stretched to the window. Still: full resolution, samples
 * accumulating up to the preset's spp in bands of about one frame's time. True while there is work. */
static bool draw(int w, int h, bool restart, camera *shown, bool *moved)
{
    *moved = memcmp(shown, &app.cam, sizeof *shown) != 0;
    bool moving = *moved || restart;
    int aw, ah;
    render_active_size(&aw, &ah);
    if (!moving && render_samples() > 0 && (aw != w || ah != h))
        render_keep_preview(); /* the last moving image: shown until the still one's first sample covers it */
    render_resize(w, h);
    int iw = moving ? res_side(w, app.res.scale) : w, ih = moving ? res_side(h, app.res.scale) : h;
    render_active_size(&aw, &ah);
    if (moving || aw != iw || ah != ih || (render_samples() == 0 && render_band_rows() == 0)) {
        render_set_active(iw, ih);
        render_begin(&app.cam);
        *shown = app.cam;
    }
    bool refining = render_samples() < app.scene.quality.spp;
    if (refining || app.opt->frames) {
        double t0 = glfwGetTime();
        bool complete = true;
        if (moving || !refining) {
            render_sample();
        } else {
            /* a full-size sample in bands of about one frame's time, so the window reads input between
             * them instead of freezing */
            double per_row = (double)app.res.per_pixel_ms * (double)w;
            if (app.band_rows <= 0)
                app.band_rows = per_row > 0 ? app.res.target_ms / per_row : h / 8.0;
            app.band_rows = fmin(fmax(app.band_rows, 4.0), (double)h);
            complete = render_sample_band((int)app.band_rows);
        }
        glFinish();
        double ms = (glfwGetTime() - t0) * 1000.0;
        note_sample(ms, iw, ih, w, h, complete);
        app.frame_sample_ms = ms;
        if (moving) /* the whole frame keeps to the target: the display, HUD, panel and swap too */
            res_update(&app.res, ms + app.overhead_ms, (double)iw * ih, (double)w * h);
        else if (refining && ms > 0) /* the next band: as many rows as fit the target */
            app.band_rows *= fmin(fmax(app.res.target_ms / ms, 0.5), 2.0);
        if (render_samples() == 1)
            app.unresolved = -1;
        if (!moving && refining && render_samples() == app.scene.quality.spp)
            note_converged(), app.unresolved = render_unresolved_pixels(NULL);
    }
    app.scaled = iw != w || ih != h;
    render_display(0, w, h, app.exposure, app.view);
    return refining || app.scaled;
}

/* What the cursor points at, for the HUD and panel: the distance (and for a DEM the height). */
static void cursor_info(GLFWwindow *win, int w, int h)
{
    app.cursor_info[0] = '\0';
    if (!cursor_free())
        return;
    double p[3];
    if (!point_under((int)app.mouse[0], (int)app.mouse[1], w, h, p))
        return;
    (void)win;
    double dist = camera_distance(p, app.cam.position), lon, lat;
    int tx, ty;
    const heightfield *hf = res_heightfield_loaded(&tx, &ty);
    float ex = app.scene.terrain.exaggeration > 0 ? app.scene.terrain.exaggeration : 1.0f;
    if (hf && dem_geo_lonlat(app.geo, (p[0] - (double)hf->x0) / (double)hf->dx, (p[2] - (double)hf->z0) / (double)hf->dz,
                             &lon, &lat))
        snprintf(app.cursor_info, sizeof app.cursor_info, "under the cursor: %.5f° %c, %.5f° %c, %.0f m high, %.4g m away",
                 fabs(lat), lat >= 0 ? 'N' : 'S', fabs(lon), lon >= 0 ? 'E' : 'W', p[1] / (double)ex, dist);
    else if (hf)
        snprintf(app.cursor_info, sizeof app.cursor_info, "under the cursor: x %.6g, z %.6g, %.0f m high, %.4g m away",
                 p[0], p[2], p[1] / (double)ex, dist);
    else
        snprintf(app.cursor_info, sizeof app.cursor_info, "under the cursor: (%.6g, %.6g, %.6g), %.4g m away", p[0],
                 p[1], p[2], dist);
}

/* A deep zoom: the precision the view needs (render_fit_precision). True when the program changed. */
static bool fit_precision(int h)
{
    bool was = app.scene.fractal.deep_now;
    err_t e;
    if (!render_fit_precision(&app.scene, &app.cam, h, &e))
        snprintf(app.message, sizeof app.message, "%s", e.msg);
    if (was != app.scene.fractal.deep_now)
        snprintf(app.message, sizeof app.message, app.scene.fractal.deep_now
                                                     ? "deep zoom: the formula now runs in double precision"
                                                     : "back to float precision");
    return was != app.scene.fractal.deep_now;
}

static void loop(GLFWwindow *win)
{
    camera shown = {0};
    bool restart = true;
    double last = glfwGetTime();
    panel_actions act = {.camera_mode = -1, .view = -1};
    for (int frame = 0; !glfwWindowShouldClose(win) && (app.opt->frames == 0 || frame < app.opt->frames); frame++) {
        double now = glfwGetTime();
        float dt = (float)(now - last);
        last = now;
        glfwPollEvents();
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        if (w <= 0 || h <= 0) { /* minimised */
            glfwWaitEventsTimeout(IDLE_WAIT_S);
            continue;
        }
        if (!recorder_play(&app.flight, dt, &app.cam, app.message, sizeof app.message))
            move_camera(win, dt, w, h);
        bool asked = handle_requests(); /* every one runs, each applying what was asked: no short-circuit */
        asked = panel_apply(&act) || asked;
        asked = presets(win, &act, w, h) || asked;
        asked = views(w, h) || asked;
        asked = fit_precision(h) || asked;
        restart = restart || asked;
        bool moved, refining = draw(w, h, restart, &shown, &moved);
        restart = false;
        if (app.screenshot) {
            screenshot(w, h);
            app.screenshot = false;
        }
        cursor_info(win, w, h);
        hud(w, h);
        panel_model m;
        panel_model_of(w, h, &m);
        if (app.stat_count < app.stat_cap)
            glFinish(); /* what came before is not the panel's */
        double p0 = glfwGetTime();
        panel_frame(app.panel, &m, &act);
        bool stats = app.stat_count < app.stat_cap;
        double t = stats ? (glFinish(), glfwGetTime()) : 0;
        glfwSwapBuffers(win);
        double over = (glfwGetTime() - now) * 1000.0 - app.frame_sample_ms;
        app.overhead_ms = app.overhead_ms > 0 ? 0.8 * app.overhead_ms + 0.2 * over : over;
        app.frame_sample_ms = 0;
        if (stats) { /* --frames: what the frame, and the panel and the swap in it, cost */
            double t1 = glfwGetTime();
            app.stat_panel_ms[app.stat_count] = (t - p0) * 1000.0;
            app.stat_swap_ms[app.stat_count] = (t1 - t) * 1000.0;
            app.stat_frame_ms[app.stat_count] = (t1 - now) * 1000.0;
            app.stat_moving[app.stat_count++] = moved;
        }
        if (!refining && !moved && !app.opt->frames && !app.panel)
            glfwWaitEventsTimeout(IDLE_WAIT_S); /* converged: do not spin */
    }
}

static int cmp_ms(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of the n values v[i] where pick[i] == want (sorted in place into tmp); 0 when none. */
static double median_of(const double *v, const bool *pick, bool want, int n, double *tmp, int *count)
{
    int k = 0;
    for (int i = 0; i < n; i++)
        if (pick[i] == want)
            tmp[k++] = v[i];
    *count = k;
    qsort(tmp, (size_t)k, sizeof *tmp, cmp_ms);
    return k ? tmp[k / 2] : 0;
}

/* --frames N: one line on what the frames cost, moving and still, and the panel's share of them. */
static void frame_summary(int w, int h)
{
    if (!app.stat_count)
        return;
    double *tmp = util_alloc(sizeof *tmp * (size_t)app.stat_count, "the frame statistics");
    int moving, still;
    double mf = median_of(app.stat_frame_ms, app.stat_moving, true, app.stat_count, tmp, &moving);
    double mp = median_of(app.stat_panel_ms, app.stat_moving, true, app.stat_count, tmp, &moving);
    double sf = median_of(app.stat_frame_ms, app.stat_moving, false, app.stat_count, tmp, &still);
    double sp = median_of(app.stat_panel_ms, app.stat_moving, false, app.stat_count, tmp, &still);
    double ms = median_of(app.stat_swap_ms, app.stat_moving, true, app.stat_count, tmp, &moving);
    fprintf(stderr, "fathom: %d frames at %dx%d (%s): %d moving, median %.1f ms (%.1f fps), the panel %.2f ms of it, "
                    "the swap %.1f ms; %d still, median %.1f ms, the panel %.2f ms; %s backend, %s\n",
            app.stat_count, w, h, app.panel ? "panel open" : "panel closed", moving, mf, mf > 0 ? 1000.0 / mf : 0.0, mp,
            ms, still, sf, sp, render_backend_name(render_backend_used()), gpu_describe());
    free(tmp);
}

bool explore_run(const cli_options *opt, err_t *err)
{
    memset(&app, 0, sizeof app);
    app.opt = opt;
    app.pending_scene = -1;
    app.cost_pending = -1;
    app.reference_rmse = -1;
    app.unresolved = -1;
    app.exposure = DEFAULT_EXPOSURE;
    app.res = res_init((float)(opt->fps ? opt->fps : DEFAULT_FPS), RES_MIN_SCALE);
    app.knob = next_knob((knob_id)(KNOB_COUNT - 1));
    app.panel = opt->panel;
    if (opt->frames) {
        app.stat_cap = opt->frames < STAT_MAX ? opt->frames : STAT_MAX;
        app.stat_frame_ms = util_calloc((size_t)app.stat_cap, sizeof(double), "the frame statistics");
        app.stat_panel_ms = util_calloc((size_t)app.stat_cap, sizeof(double), "the frame statistics");
        app.stat_swap_ms = util_calloc((size_t)app.stat_cap, sizeof(double), "the frame statistics");
        app.stat_moving = util_calloc((size_t)app.stat_cap, sizeof(bool), "the frame statistics");
    }
    for (int i = 0; i < opt->set_count && i < CLI_MAX_SETS; i++)
        snprintf(app.base[i], OVERRIDE_LEN, "%s", opt->sets[i]);
    app.base_count = opt->set_count < CLI_MAX_SETS ? opt->set_count : CLI_MAX_SETS;
    list_scene_names();
    scene first; /* a bad scene is the error to report, even where no window can open */
    if (!scene_load(opt->scene, opt->sets, opt->set_count, &first, err))
        return false;
    scene_free(&first);
    if (!gpu_open(&(gpu_desc){.width = opt->width, .height = opt->height, .title = "fathom"}, err))
        return false;
    GLFWwindow *win = gpu_window();
    glfwSetKeyCallback(win, on_key); /* before the panel's: ImGui's callbacks chain to these */
    glfwSetScrollCallback(win, on_scroll);
    bool ok = render_init(err) && hud_init(err) && panel_init(win, err) && load_scene(opt->scene, true, err);
    render_set_adaptive(true); /* still images: samples after the first only on edges */
    if (ok) {
        fprintf(stderr, "fathom: %s, %s backend\n", gpu_describe(), render_backend_name(render_backend_used()));
        loop(win);
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        frame_summary(w, h);
    }
    free(app.stat_frame_ms);
    free(app.stat_panel_ms);
    free(app.stat_swap_ms);
    free(app.stat_moving);
    panel_shutdown();
    hud_shutdown();
    render_shutdown();
    recorder_free(&app.flight);
    dem_geo_close(app.geo);
    params_free(&app.params);
    if (app.have_scene)
        scene_free(&app.scene);
    gpu_close();
    return ok;
}
