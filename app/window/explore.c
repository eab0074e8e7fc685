#include "window/explore.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "view/camera.h"
#include "gpu/gpu.h"
#include "window/hud.h"
#include "jobs/offline.h"
#include "view/path.h"
#include "gpu/render.h"
#include "view/resolution.h"
#include "scene/scene.h"
#include "view/shot.h"
#include "view/views.h"

enum { MAX_SCENES = 9, FRAME_HISTORY = 30, DEFAULT_FPS = 30, MAX_RECORDED_KEYS = 1000 };
static const float MOUSE_SENSITIVITY = 0.0025f; /* radians per pixel */
static const float SPEED_STEP = 1.25f;          /* per scroll notch */
static const float DEFAULT_SPEED = 2.0f;        /* × the distance to the surface (adaptive scenes) */
static const float START_SPEED_FRACTION = 0.2f; /* others: the start view's distance to its look-at, per 5 s */
static const float MIN_SPEED_FACTOR = 1e-3f, MAX_SPEED_FACTOR = 1e3f; /* scroll: of the start speed */
static const float EXPOSURE = 1.0f;
static const double IDLE_WAIT_S = 0.05;
static const float MIN_ADAPTIVE_DISTANCE = 1e-7f; /* metres: keeps a little speed at the surface */
static const float WALK_HEIGHT = 1.8f;            /* metres: eye height when walking on terrain */

static struct {
    scene scene;
    bool have_scene;
    camera cam;
    float speed;
    double mouse[2];
    bool mouse_valid;
    float scroll;
    char names[MAX_SCENES][SCENE_NAME_MAX];
    int scene_count;
    int pending_scene; /* -1 none */
    bool reload, screenshot, go_home, save_view;
    int recall_view; /* Ctrl+1…9 pressed: 1…9; 0 none */
    float start_speed; /* the scene's: m/s, or × distance in adaptive scenes */
    render_view view;
    bool walking; /* terrain: keep the eye WALK_HEIGHT above the ground */
    knob_id knob;                      /* the knob that =/- step (one the window steps) */
    int knob_step;                     /* pending: +1 or -1 */
    char knob_sets[KNOB_COUNT][64];    /* the stepped knobs, as --set overrides */
    /* a recalled view's overrides (its command line and stepped knobs when saved): they replace the
     * command line's for this scene until another scene is picked */
    char view_sets[CLI_MAX_SETS][256];
    int view_set_count;
    /* the overrides in force besides the stepped knobs: the command line's (first scene only) or a
     * recalled view's; what screenshots and saved views record */
    const char *base_sets[CLI_MAX_SETS];
    int base_set_count;
    float surface_distance; /* the distance estimate at the camera (fractals: sets the flying speed) */
    char message[ERR_MSG_MAX];
    double frame_ms[FRAME_HISTORY];
    int frame_index;
    res_controller res; /* the internal resolution while moving */
    bool scaled;        /* the last frame was rendered below full size */
    double band_rows;   /* rows of a still image's sample per display frame (0: not yet known) */
    /* the recorded flight (N adds a keyframe, Shift+N clears, L plays): docs/flights.md */
    path_camera keys[MAX_RECORDED_KEYS];
    int key_count;
    path flight; /* the keys as a path, once there are two */
    bool add_key, clear_keys, toggle_play, playing;
    double play_t;
} app;

/* The next knob the window steps, after k (QUALITY_KNOBS' step column says which). */
static knob_id next_knob(knob_id k)
{
    do
        k = (knob_id)((k + 1) % KNOB_COUNT);
    while (!knob_window_steps(k));
    return k;
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    if (action != GLFW_PRESS)
        return;
    if ((mods & GLFW_MOD_CONTROL) && key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
        app.recall_view = key - GLFW_KEY_0;
        return;
    }
    if (key == GLFW_KEY_ESCAPE)
        glfwSetWindowShouldClose(w, GLFW_TRUE);
    else if (key == GLFW_KEY_R)
        app.reload = true;
    else if (key == GLFW_KEY_P || key == GLFW_KEY_F12)
        app.screenshot = true;
    else if (key == GLFW_KEY_H)
        app.view = app.view == VIEW_STEPS ? VIEW_COLOR : VIEW_STEPS;
    else if (key == GLFW_KEY_G) {
        render_grab_reference();
        snprintf(app.message, sizeof app.message, "grabbed this frame as the reference: V shows the difference");
    } else if (key == GLFW_KEY_V)
        app.view = app.view == VIEW_DIFFERENCE ? VIEW_COLOR : VIEW_DIFFERENCE;
    else if (key == GLFW_KEY_T)
        app.walking = !app.walking;
    else if (key == GLFW_KEY_HOME || key == GLFW_KEY_BACKSPACE)
        app.go_home = true;
    else if (key == GLFW_KEY_B)
        app.save_view = true;
    else if (key == GLFW_KEY_N && (mods & GLFW_MOD_SHIFT))
        app.clear_keys = true;
    else if (key == GLFW_KEY_N)
        app.add_key = true;
    else if (key == GLFW_KEY_L)
        app.toggle_play = true;
    else if (key == GLFW_KEY_K)
        app.knob = next_knob(app.knob);
    else if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD)
        app.knob_step = +1;
    else if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT)
        app.knob_step = -1;
    else if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && key - GLFW_KEY_1 < app.scene_count)
        app.pending_scene = key - GLFW_KEY_1;
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)w;
    (void)dx;
    app.scroll += (float)dy;
}

/* The scene's recorded flight, if there is one (views_flight_file), as keys to add to. */
static void load_flight(void)
{
    char file[PATH_MAX_LEN];
    err_t e;
    path_free(&app.flight);
    app.key_count = 0;
    app.playing = false;
    if (!views_flight_file(app.scene.name, file, sizeof file, &e) || !util_file_exists(file))
        return;
    if (!path_load(file, &app.flight, &e)) {
        snprintf(app.message, sizeof app.message, "the recorded flight is unreadable (%.1500s); N starts a new one", e.msg);
        return;
    }
    for (int i = 0; i < app.flight.count && i < MAX_RECORDED_KEYS; i++)
        path_key_camera(&app.flight, i, &app.keys[app.key_count++]);
}

/* N, Shift+N, L: record, clear and play the flight. True when the camera was set by the flight. */
static bool flight_keys(float dt)
{
    char file[PATH_MAX_LEN];
    err_t e;
    if (app.add_key || app.clear_keys) {
        bool add = app.add_key;
        app.add_key = app.clear_keys = false;
        app.playing = false;
        if (!views_flight_file(app.scene.name, file, sizeof file, &e)) {
            snprintf(app.message, sizeof app.message, "%s", e.msg);
            return false;
        }
        if (!add) {
            app.key_count = 0;
            path_free(&app.flight);
            remove(file);
            snprintf(app.message, sizeof app.message, "flight cleared (%s removed)", file);
            return false;
        }
        if (app.key_count == MAX_RECORDED_KEYS) {
            snprintf(app.message, sizeof app.message, "the flight has %d keys already", MAX_RECORDED_KEYS);
            return false;
        }
        double pos[3] = {app.cam.position[0], app.cam.position[1], app.cam.position[2]};
        double speed = app.scene.adaptive_speed ? (double)(app.speed * fmaxf(app.surface_distance, MIN_ADAPTIVE_DISTANCE))
                                                : (double)app.speed;
        path_camera *k = &app.keys[app.key_count];
        k->time = path_next_key_time(app.keys, app.key_count, pos, speed);
        memcpy(k->position, pos, sizeof pos);
        k->yaw = app.cam.yaw;
        k->pitch = app.cam.pitch;
        k->fov_deg = glm_deg(app.cam.fov_y);
        app.key_count++;
        if (app.key_count < 2) {
            snprintf(app.message, sizeof app.message, "keyframe 1 at t = 0 s: fly on and press N again");
            return false;
        }
        strbuf text = {0};
        path_text_from_cameras(app.keys, app.key_count, &text);
        path_free(&app.flight);
        bool ok = path_parse(text.data, file, &app.flight, &e) && util_write_text_atomic(file, text.data, "the flight", &e);
        sb_free(&text);
        if (ok)
            snprintf(app.message, sizeof app.message, "keyframe %d at t = %.1f s, saved to %s (L plays; render it with "
                     "fathom render --path)", app.key_count, k->time, file);
        else
            snprintf(app.message, sizeof app.message, "%s", e.msg);
        return false;
    }
    if (app.toggle_play) {
        app.toggle_play = false;
        if (app.flight.count < 2) {
            snprintf(app.message, sizeof app.message, "no flight to play: N records keyframes");
        } else {
            app.playing = !app.playing;
            app.play_t = app.flight.keys[0].time;
            snprintf(app.message, sizeof app.message, app.playing ? "playing the flight (L stops)" : "stopped");
        }
    }
    if (!app.playing)
        return false;
    app.play_t += dt;
    path_sample smp;
    path_eval(&app.flight, app.play_t, &smp);
    for (int k = 0; k < 3; k++)
        app.cam.position[k] = (float)smp.position[k];
    app.cam.yaw = (float)smp.yaw;
    app.cam.pitch = (float)smp.pitch;
    app.cam.fov_y = glm_rad((float)smp.fov_deg);
    if (app.play_t >= app.flight.keys[app.flight.count - 1].time) {
        app.playing = false;
        snprintf(app.message, sizeof app.message, "flight played: %.1f s, %d keys", path_duration(&app.flight),
                 app.flight.count);
    }
    return true;
}

static bool load_scene(const char *name, const cli_options *opt, bool first, err_t *err)
{
    scene next;
    /* --set overrides belong to the scene named on the command line; stepped knobs to every scene */
    const char *sets[CLI_MAX_SETS + KNOB_COUNT];
    int n = 0;
    for (int i = 0; i < app.view_set_count; i++)
        sets[n++] = app.view_sets[i];
    for (int i = 0; first && !app.view_set_count && i < opt->set_count; i++)
        sets[n++] = opt->sets[i];
    int base = n;
    for (int k = 0; k < KNOB_COUNT; k++)
        if (app.knob_sets[k][0])
            sets[n++] = app.knob_sets[k];
    if (!scene_load(name, sets, n, &next, err))
        return false;
    if (opt->spp)
        next.quality.spp = opt->spp;
    bool same_file = app.have_scene && !strcmp(app.scene.path, next.path);
    if (!render_set_scene(&next, NULL, err)) { /* the renderer copies what it needs */
        scene_free(&next);
        if (app.have_scene) {
            err_t ignore;
            render_set_scene(&app.scene, NULL, &ignore); /* back to the last good scene */
        }
        return false;
    }
    if (app.have_scene)
        scene_free(&app.scene);
    app.scene = next;
    app.have_scene = true;
    memcpy(app.base_sets, sets, sizeof(char *) * (size_t)base);
    app.base_set_count = base;
    if (!same_file) { /* a reload of the same file keeps the camera where the user flew it */
        float fov = first && opt->has_fov ? opt->fov_deg : app.scene.cam_fov_deg;
        const double *pos = first && opt->has_camera ? opt->camera : app.scene.cam_position;
        const double *at = first && opt->has_look_at ? opt->look_at : app.scene.cam_look_at;
        app.cam = first && opt->has_view ? opt->view : camera_look_at_deg(pos, at, fov);
        app.start_speed = app.scene.adaptive_speed
                              ? DEFAULT_SPEED
                              : START_SPEED_FRACTION * (float)camera_distance(app.scene.cam_position, app.scene.cam_look_at);
        app.speed = app.start_speed;
        load_flight();
    }
    return true;
}

/* Steps the selected knob and reloads the scene with it (the same checks as --set). */
static void step_knob(const cli_options *opt, int dir)
{
    const char *name = knob_get_def(app.knob)->name;
    double v = knob_step(app.knob, knob_value(&app.scene.quality, app.knob), dir);
    snprintf(app.knob_sets[app.knob], sizeof app.knob_sets[0], "quality.%s=%g", name, v);
    err_t e;
    if (!load_scene(app.scene.path, opt, false, &e))
        snprintf(app.message, sizeof app.message, "%s", e.msg);
    else
        snprintf(app.message, sizeof app.message, "%s = %g", name, v);
}

/* The current view as a shot description: scene, overrides (the command line's, then the stepped knobs),
 * camera, size. */
static void describe(int w, int h, strbuf *out)
{
    const char *sets[CLI_MAX_SETS + KNOB_COUNT];
    int n = 0;
    for (int i = 0; i < app.base_set_count; i++)
        sets[n++] = app.base_sets[i];
    for (int k = 0; k < KNOB_COUNT; k++)
        if (app.knob_sets[k][0])
            sets[n++] = app.knob_sets[k];
    shot_describe(app.scene.path, sets, n, &app.cam, w, h, out);
}

/* B: the view into the first free slot 1…9; Ctrl+N: back to view N (its camera, fov and overrides).
 * B and Ctrl+1-9. True when a recalled view changed the scene's overrides (the image restarts). */
static bool views(const cli_options *opt, int w, int h)
{
    char file[PATH_MAX_LEN];
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
        char name[2] = {(char)('0' + app.recall_view), '\0'}, *text;
        shot_desc d;
        bool ok = views_load(file, name, &text, &e);
        if (ok) {
            ok = shot_parse(text, file, &d, &e);
            free(text);
        }
        if (ok) { /* the view's overrides replace the ones in force (its knobs were saved among them) */
            char keep_sets[KNOB_COUNT][64];
            memcpy(keep_sets, app.knob_sets, sizeof keep_sets);
            int keep_count = app.view_set_count;
            memset(app.knob_sets, 0, sizeof app.knob_sets);
            for (int i = 0; i < d.set_count; i++)
                snprintf(app.view_sets[i], sizeof app.view_sets[0], "%s", d.sets[i]);
            app.view_set_count = d.set_count > 0 ? d.set_count : 0;
            ok = load_scene(app.scene.path, opt, false, &e);
            if (!ok) { /* keep what was in force */
                memcpy(app.knob_sets, keep_sets, sizeof keep_sets);
                app.view_set_count = keep_count;
            }
        }
        if (ok) {
            app.cam = d.cam;
            snprintf(app.message, sizeof app.message, "back at view %s (%d override%s)", name, d.set_count,
                     d.set_count == 1 ? "" : "s");
            restart = true;
        } else {
            snprintf(app.message, sizeof app.message, "%s", e.msg);
        }
    }
    app.save_view = false;
    app.recall_view = 0;
    return restart;
}

static void screenshot(int w, int h)
{
    char file[128];
    time_t now = time(NULL);
    strftime(file, sizeof file, "fathom-%Y%m%d-%H%M%S.png", localtime(&now));
    err_t err;
    strbuf description = {0}; /* the shot remembers how it was made */
    describe(w, h, &description);
    bool ok = offline_write(file, w, h, 0, description.data, &err);
    sb_free(&description);
    if (ok)
        snprintf(app.message, sizeof app.message, "saved %s", file);
    else
        snprintf(app.message, sizeof app.message, "%s", err.msg);
    fprintf(stderr, "%s\n", app.message);
}

static camera_input read_input(GLFWwindow *w)
{
    camera_input in = {0};
    in.move[0] = (float)(glfwGetKey(w, GLFW_KEY_D) - glfwGetKey(w, GLFW_KEY_A));
    in.move[1] = (float)(glfwGetKey(w, GLFW_KEY_SPACE) - glfwGetKey(w, GLFW_KEY_C));
    in.move[2] = (float)(glfwGetKey(w, GLFW_KEY_W) - glfwGetKey(w, GLFW_KEY_S));
    in.fast = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT);
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    if (app.mouse_valid) {
        in.look[0] = (float)(x - app.mouse[0]);
        in.look[1] = (float)(y - app.mouse[1]);
    }
    app.mouse[0] = x;
    app.mouse[1] = y;
    app.mouse_valid = true;
    return in;
}

static void hud(int w, int h)
{
    double sum = 0;
    int n = 0;
    for (int i = 0; i < FRAME_HISTORY; i++)
        if (app.frame_ms[i] > 0)
            sum += app.frame_ms[i], n++;
    double ms = n ? sum / n : 0;
    char text[4096], speed[128], limit[256] = "";
    const camera *c = &app.cam;
    if (app.scene.adaptive_speed)
        snprintf(speed, sizeof speed, "speed %.2f x distance (%.3g m to the surface)", (double)app.speed,
                 (double)app.surface_distance);
    else
        snprintf(speed, sizeof speed, "speed %.2f m/s", (double)app.speed);
    /* where the hit threshold meets float resolution, closer detail would only be noise */
    float d = app.surface_distance, pa = camera_pixel_angle(c, h);
    float pnorm = (float)camera_norm(c->position);
    if (app.scene.adaptive_speed && app.scene.quality.hit_k * d * pa < PRECISION_REL * (pnorm + d))
        snprintf(limit, sizeof limit, "float precision reached: detail below %.2g m cannot be resolved here\n",
                 (double)(PRECISION_REL * (pnorm + d)));
    char internal[96];
    int iw, ih;
    render_active_size(&iw, &ih);
    double fps = 1000.0 / (double)app.res.target_ms;
    if (app.scaled)
        snprintf(internal, sizeof internal, "moving: %dx%d inside (target %.0f fps)", iw, ih, fps);
    else
        snprintf(internal, sizeof internal, "still: full size (moving: target %.0f fps)", fps);
    char knobs[512];
    int len = 0;
    for (int k = 0; k < KNOB_COUNT; k++)
        if (knob_window_steps((knob_id)k))
            len += snprintf(knobs + len, sizeof knobs - (size_t)len, "%s%s %g%s  ", k == (int)app.knob ? "[" : "",
                            knob_get_def((knob_id)k)->name, knob_value(&app.scene.quality, (knob_id)k),
                            k == (int)app.knob ? "]" : "");
    static const char *const views[] = {"", "  [steps]", "  [difference to grabbed frame]"};
    char adaptive[48] = "";
    if (render_samples() > 1 && !app.scaled)
        snprintf(adaptive, sizeof adaptive, " (after the 1st: %.0f %% of pixels, on edges)",
                 100.0 * render_adaptive_pixels() / ((double)w * h));
    if (app.walking && snprintf(limit + strlen(limit), sizeof limit - strlen(limit), "walking %.1f m above the ground\n",
                                (double)WALK_HEIGHT) < 0)
        limit[0] = '\0';
    snprintf(text, sizeof text,
             "%s  [%s]  %dx%d%s  %s\n"
             "%.1f ms/sample  %.1f fps  %d/%d spp%s\n"
             "%s\n"
             "pos %.4g %.4g %.4g  %s  fov %.0f\n%s"
             "WASD move  mouse look  Space/C up/down  Shift fast  scroll speed\n"
             "1-%d scenes  K knob  =/- step it  H steps  G grab  V difference  T walk  Home start  B save view  Ctrl+1-9 recall\n"
             "N keyframe (%d)  Shift+N clear  L play  R reload  P shot  Esc quit\n%s",
             app.scene.name, preset_name(app.scene.preset), w, h, views[app.view], internal, ms, ms > 0 ? 1000.0 / ms : 0.0,
             render_samples(), app.scene.quality.spp, adaptive, knobs, (double)c->position[0], (double)c->position[1],
             (double)c->position[2], speed, (double)glm_deg(c->fov_y), limit, app.scene_count, app.key_count,
             app.message);
    hud_draw(text, w, h, h >= 900 ? 2.0f : 1.5f);
}

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

/* The renderer's distance bound at n points (the slide rule's probe). */
static void probe_distances(void *ctx, const double *points, int n, float *out)
{
    (void)ctx;
    enum { MAX_POINTS = 64 };
    float p[MAX_POINTS * 3] = {0}, d[MAX_POINTS * 2];
    err_t e;
    assert(n <= MAX_POINTS);
    for (int i = 0; i < 3 * n; i++)
        p[i] = (float)points[i];
    bool ok = render_probe(&app.scene, NULL, p, n, d, &e);
    for (int i = 0; i < n; i++)
        out[i] = ok ? d[2 * i] : -1.0f; /* unknown: the move is left alone */
}

/* One frame's flight. Scroll sets the speed (within MIN/MAX_SPEED_FACTOR of the scene's start speed),
 * which follows the distance to the surface where the scene asks for it (fractals: close up stays
 * controllable). Every program's map() at the camera bounds the free space around it: the frame's step
 * is clamped inside it, so the camera never enters or passes through a solid however fast it flies,
 * and it stays within max_dist of the start view's look-at point. Home or Backspace: the start view. */
static void fly(GLFWwindow *win, float dt)
{
    if (app.scroll != 0) {
        app.speed = fminf(fmaxf(app.speed * powf(SPEED_STEP, app.scroll), MIN_SPEED_FACTOR * app.start_speed),
                          MAX_SPEED_FACTOR * app.start_speed);
        app.scroll = 0;
    }
    if (app.go_home) {
        app.cam = camera_look_at_deg(app.scene.cam_position, app.scene.cam_look_at, app.scene.cam_fov_deg);
        app.speed = app.start_speed;
        app.go_home = false;
        snprintf(app.message, sizeof app.message, "back at the start view");
    }
    camera_input in = read_input(win);
    float dist[2] = {0, 0};
    err_t e;
    float here[3] = {(float)app.cam.position[0], (float)app.cam.position[1], (float)app.cam.position[2]};
    render_probe(&app.scene, NULL, here, 1, dist, &e);
    app.surface_distance = fabsf(dist[0]);
    float speed = app.speed;
    if (app.scene.adaptive_speed)
        speed = app.speed * fmaxf(app.surface_distance, MIN_ADAPTIVE_DISTANCE);
    double before[3];
    memcpy(before, app.cam.position, sizeof before);
    camera_update(&app.cam, &in, dt, speed, MOUSE_SENSITIVITY);
    if (memcmp(before, app.cam.position, sizeof before))
        camera_slide(before, app.cam.position, app.scene.quality.step_factor, camera_resolution(before, false),
                     probe_distances, NULL, NULL);
    camera_clamp_range(app.cam.position, app.scene.cam_look_at, app.scene.quality.max_dist);
    float ground;
    if (app.walking && render_ground_height((float)app.cam.position[0], (float)app.cam.position[2], &ground))
        app.cam.position[1] = ground + WALK_HEIGHT;
}

/* Scene switches, knob steps and reloads asked for by keys. True when the image must restart. */
static bool handle_requests(const cli_options *opt)
{
    bool restart = false;
    if (app.pending_scene >= 0) {
        err_t e;
        app.view_set_count = 0; /* a recalled view's overrides belong to its own scene */
        if (!load_scene(app.names[app.pending_scene], opt, false, &e))
            snprintf(app.message, sizeof app.message, "%s", e.msg), fprintf(stderr, "%s\n", e.msg);
        else
            app.message[0] = '\0';
        app.pending_scene = -1;
        memset(app.frame_ms, 0, sizeof app.frame_ms); /* another scene's times say nothing of this one */
        app.res = res_init(app.res.target_ms > 0 ? 1000.0f / app.res.target_ms : DEFAULT_FPS, RES_MIN_SCALE);
        restart = true;
    }
    if (app.knob_step) {
        step_knob(opt, app.knob_step);
        app.knob_step = 0;
        restart = true;
    }
    if (app.reload) {
        err_t e;
        if (!render_reload(&e) || !load_scene(app.scene.path, opt, false, &e)) {
            if (snprintf(app.message, sizeof app.message, "reload failed, kept the last good program:\n%s", e.msg) >=
                (int)sizeof app.message)
                app.message[sizeof app.message - 1] = '\0';
            fprintf(stderr, "%s\n", app.message);
        } else {
            snprintf(app.message, sizeof app.message, "shaders and scene reloaded");
        }
        app.reload = false;
        restart = true;
    }
    return restart;
}

/* One frame. Moving (or restarted): one sample at the internal resolution the controller picks for the
 * target frame rate, stretched to the window. Still: full resolution, samples accumulating up to the
 * preset's spp. True while there is work left. */
static bool draw(const cli_options *opt, int w, int h, bool restart, camera *shown, bool *moved)
{
    *moved = memcmp(shown, &app.cam, sizeof *shown) != 0;
    bool moving = *moved || restart;
    int aw, ah;
    render_active_size(&aw, &ah);
    if (!moving && render_samples() > 0 && (aw != w || ah != h))
        render_keep_preview(); /* the last moving image: shown until the still one's first sample covers it */
    render_resize(w, h);
    int iw = w, ih = h;
    if (moving) {
        iw = res_side(w, app.res.scale);
        ih = res_side(h, app.res.scale);
    }
    render_active_size(&aw, &ah);
    if (moving || aw != iw || ah != ih || (render_samples() == 0 && render_band_rows() == 0)) {
        render_set_active(iw, ih);
        render_begin(&app.cam);
        *shown = app.cam;
    }
    bool refining = render_samples() < app.scene.quality.spp;
    if (refining || opt->frames) {
        double t0 = glfwGetTime();
        if (moving || !refining) {
            render_sample();
        } else {
            /* a full-size sample in bands of about one frame's time, so the window reads input between
             * them instead of freezing: the first band's rows from the moving frames' cost of a pixel,
             * then each band's from the last one's time */
            const res_controller *r = &app.res;
            double per_row = (double)r->per_pixel_ms * (double)w;
            if (app.band_rows <= 0)
                app.band_rows = per_row > 0 ? r->target_ms / per_row : h / 8.0;
            app.band_rows = fmin(fmax(app.band_rows, 4.0), (double)h);
            render_sample_band((int)app.band_rows);
        }
        glFinish();
        double ms = (glfwGetTime() - t0) * 1000.0;
        app.frame_ms[app.frame_index++ % FRAME_HISTORY] = ms;
        if (moving)
            res_update(&app.res, ms, (double)iw * ih, (double)w * h);
        else if (refining && ms > 0) /* the next band: as many rows as fit the target */
            app.band_rows *= fmin(fmax(app.res.target_ms / ms, 0.5), 2.0);
    }
    app.scaled = iw != w || ih != h;
    render_display(0, w, h, EXPOSURE, app.view);
    hud(w, h);
    if (app.screenshot) {
        screenshot(iw, ih);
        app.screenshot = false;
    }
    return refining || app.scaled;
}

static void loop(GLFWwindow *win, const cli_options *opt)
{
    camera shown = {0};
    bool restart = true;
    double last = glfwGetTime();
    for (int frame = 0; !glfwWindowShouldClose(win) && (opt->frames == 0 || frame < opt->frames); frame++) {
        double now = glfwGetTime();
        float dt = (float)(now - last);
        last = now;
        glfwPollEvents();
        if (!flight_keys(dt))
            fly(win, dt);
        restart |= handle_requests(opt);
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        if (w <= 0 || h <= 0) { /* minimised */
            glfwWaitEventsTimeout(IDLE_WAIT_S);
            continue;
        }
        restart |= views(opt, w, h);
        bool moved, refining = draw(opt, w, h, restart, &shown, &moved);
        restart = false;
        glfwSwapBuffers(win);
        if (!refining && !moved && !opt->frames)
            glfwWaitEventsTimeout(IDLE_WAIT_S); /* converged: do not spin */
    }
}

bool explore_run(const cli_options *opt, err_t *err)
{
    memset(&app, 0, sizeof app);
    app.pending_scene = -1;
    app.res = res_init((float)(opt->fps ? opt->fps : DEFAULT_FPS), RES_MIN_SCALE);
    app.knob = next_knob((knob_id)(KNOB_COUNT - 1));
    list_scene_names();
    scene first; /* a bad scene is the error to report, even where no window can open */
    if (!scene_load(opt->scene, opt->sets, opt->set_count, &first, err))
        return false;
    scene_free(&first);
    if (!gpu_open(&(gpu_desc){.width = opt->width, .height = opt->height, .title = "fathom"}, err))
        return false;
    GLFWwindow *win = gpu_window();
    bool ok = render_init(err) && hud_init(err) && load_scene(opt->scene, opt, true, err);
    render_set_adaptive(true); /* still images: samples after the first only on edges */
    if (!ok) {
        render_shutdown();
        gpu_close();
        return false;
    }
    glfwSetKeyCallback(win, on_key);
    glfwSetScrollCallback(win, on_scroll);
    glfwSetInputMode(win, GLFW_CURSOR, GLFW_CURSOR_DISABLED);
    fprintf(stderr, "fathom: %s\n", gpu_describe());
    loop(win, opt);
    hud_shutdown();
    render_shutdown();
    if (app.have_scene)
        scene_free(&app.scene);
    gpu_close();
    return true;
}
