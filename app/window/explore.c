/* explore — the interactive window (explore.h). One frame: read the keys, move the camera
 * (window/flycam.h), apply what the keys and the panel asked (edits through window/session.h, views and
 * presets through window/shots.h), draw a sample (moving: at the resolution the frame-rate controller
 * picks; still: full size, refining, each edit's cost noted by window/costs.h), then the HUD and the
 * panel; window/framestats.h keeps what the frames cost. */
#include "window/explore.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/gpu.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "gpu/res_heightfield.h"
#include "scene/formula/frag.h"
#include "scene/program.h"
#include "view/resolution.h"
#include "window/explore_app.h"
#include "window/hud.h"
#include "window/panel.h"
#include "window/shots.h"

static const float DEFAULT_EXPOSURE = 1.0f;
static const double IDLE_WAIT_S = 0.05;

static explore_app app;

/* ---- the scene, its edits and the camera ---------------------------------------------------------- */

/* A new scene file: the camera at its start view (the command line's, the first time), its preset
 * path and its recorded flight. */
static void reset_camera(bool first)
{
    const cli_options *opt = app.opt;
    const scene *s = &app.s.scene;
    float fov = first && opt->has_fov ? opt->fov_deg : s->cam_fov_deg;
    const double *pos = first && opt->has_camera ? opt->camera : s->cam_position;
    const double *at = first && opt->has_look_at ? opt->look_at : s->cam_look_at;
    camera cam = first && opt->has_view ? opt->view : scene_camera(s, pos, at, fov);
    cam.lens = first && opt->has_view ? scene_lens(s) : cam.lens;
    flycam_start(&app.fly, s, &cam, at);
    snprintf(app.preset_path, sizeof app.preset_path, "%s" SHOT_PRESET_EXT, s->name);
    char msg[ERR_MSG_MAX];
    recorder_load(&app.flight, s->name, msg, sizeof msg);
    if (msg[0])
        snprintf(app.message, sizeof app.message, "%s", msg);
}

/* After the scene loaded: the camera starts again with a new file, and the knob is one it uses. */
static void loaded(bool new_file, bool first)
{
    if (new_file)
        reset_camera(first);
    if (!knob_window_steps(app.knob) || !scene_knob_applies(&app.s.scene, app.knob))
        app.knob = explore_next_knob(&app, app.knob);
}

static bool reload_scene(err_t *err)
{
    bool new_file;
    if (!session_load(&app.s, app.s.scene.path, &new_file, err))
        return false;
    loaded(new_file, false);
    return true;
}

/* An edit of camera.up or camera.roll turns the live camera too: its view's direction kept, its image's
 * top as the scene now says (the start view follows with the scene). */
static void apply_up_and_roll(const char *kv)
{
    if (strncmp(kv, "camera.up=", 10) && strncmp(kv, "camera.roll=", 12))
        return;
    const scene *s = &app.s.scene;
    camera *c = &app.fly.cam;
    camera_basis b = camera_get_basis(c);
    double at[3];
    for (int i = 0; i < 3; i++)
        at[i] = c->position[i] + (double)b.forward[i];
    camera turned = camera_look_at_up(c->position, at, s->cam_up, c->fov_y);
    turned.roll = remainderf(turned.roll + glm_rad(s->cam_roll_deg), 2.0f * GLM_PIf);
    turned.lens = c->lens;
    *c = turned;
    app.fly.level = c->roll == 0;
}

/* An edit (the panel's or a knob key's): its cost noted, the scene reloaded. True when it took. */
static bool edit(const char *kv)
{
    err_t e;
    costs_note_edit(&app.cost, kv);
    if (!session_edit(&app.s, kv, &e)) {
        snprintf(app.message, sizeof app.message, "%s", e.msg);
        return false;
    }
    loaded(false, false);
    apply_up_and_roll(kv);
    snprintf(app.message, sizeof app.message, "%.300s", kv);
    return true;
}

/* Steps the selected knob (the same checks as --set). */
static void step_knob(int dir)
{
    const char *name = knob_get_def(app.knob)->name;
    double v = knob_step(app.knob, knob_value(&app.s.scene.quality, app.knob), dir);
    char kv[96];
    snprintf(kv, sizeof kv, "quality.%s=%g", name, v);
    overrides_checkpoint(&app.s.edits);
    edit(kv);
}

/* A view or preset opened: its camera. True when the image restarts. */
static bool opened(shots_opened r)
{
    if (!r.opened)
        return false;
    loaded(r.new_file, false);
    app.fly.cam = r.cam;
    return true;
}

/* B, Ctrl+1…9 and the presets (keys and panel). True when the image restarts. */
static bool views_and_presets(GLFWwindow *win, const panel_actions *act, int w, int h)
{
    bool restart = opened(shots_views(&app.s, &app.fly.cam, app.ask.save_view, app.ask.recall_view, w, h, app.message,
                                      sizeof app.message));
    app.ask.save_view = false;
    app.ask.recall_view = 0;
    restart |= opened(shots_fragment_preset(&app.s, app.ask.fragment_preset, &app.fragment_preset, app.message,
                                            sizeof app.message));
    app.ask.fragment_preset = 0;
    if (act->preset_path[0])
        snprintf(app.preset_path, sizeof app.preset_path, "%s", act->preset_path);
    shots_preset_ask ask = {.save = app.ask.save_preset || act->save_preset, .copy = app.ask.copy_preset || act->copy_preset,
                            .load = act->load_preset, .paste = app.ask.paste_preset || act->paste_preset};
    app.ask.save_preset = app.ask.copy_preset = app.ask.paste_preset = false;
    return opened(shots_presets(win, &app.s, &app.fly.cam, ask, app.preset_path, w, h, app.message, sizeof app.message)) ||
           restart;
}

/* ---- the panel ---------------------------------------------------------------------------------- */

/* The panel's title: the scene file's, and when overrides (the command line's, a view's, the panel's)
 * change the scene, that they do (a title such as "power 8" says what the file draws). */
static const char *panel_title(const scene *s)
{
    static char title[sizeof s->title + 64];
    const char *base = s->title[0] ? s->title : s->name;
    int changes = app.s.base_count + app.s.edits.now.count;
    if (changes == 0)
        return base;
    snprintf(title, sizeof title, "%s (the file's title; %d override%s in force)", base, changes, changes == 1 ? "" : "s");
    return title;
}

static void panel_model_of(int w, int h, panel_model *m)
{
    const scene *s = &app.s.scene;
    const camera *cam = &app.fly.cam;
    camera_basis b = camera_get_basis(cam);
    double dist = camera_distance(cam->position, app.fly.pivot);
    dist = dist > 0 ? dist : 1;
    *m = (panel_model){.params = &app.s.params, .scene_title = panel_title(s),
                       .program_block = program_get(s->program)->block,
                       .fov_deg = glm_deg(cam->fov_y), .camera_mode = app.fly.mode,
                       .can_walk = s->terrain.heightmap[0] != 0, .ms_per_sample = app.cost.sample_ms,
                       .samples = render_samples(), .spp = s->quality.spp, .width = w, .height = h,
                       .double_precision = s->fractal.deep_now, .reference_rmse = app.cost.reference_rmse,
                       .costs = app.cost.entries, .cost_count = app.cost.count, .exposure = app.exposure,
                       .view = (int)app.view, .heat_max = render_heat_max(), .can_undo = app.s.edits.undo_count > 0,
                       .can_redo = app.s.edits.redo_count > 0, .message = app.message,
                       .cursor_info = app.cursor_info[0] ? app.cursor_info : NULL, .preset_path = app.preset_path,
                       .focus_set_field = app.focus_field,
                       .unresolved = app.unresolved > 0 ? explore_unresolved_text(&app) : NULL};
    app.focus_field = false;
    double ms = framestats_average_ms(&app.stats);
    m->fps = ms > 0 ? 1000.0 / ms : 0;
    render_active_size(&m->internal_width, &m->internal_height);
    /* The look-at comes from a float direction: shown to the decimal that direction holds (-0.1, not
     * -0.0999999968; 0, not -8e-09), which is far below a double's digits only in a deep zoom. */
    double quantum = pow(10.0, floor(log10(dist * 1e-6)));
    for (int i = 0; i < 3; i++) {
        m->position[i] = cam->position[i];
        double offset = (double)b.forward[i] * dist;
        m->look_at[i] = cam->position[i] + offset;
        double rounded = round(m->look_at[i] / quantum) * quantum;
        if (fabs(rounded - m->look_at[i]) < 1e-6 * dist)
            m->look_at[i] = rounded + 0.0; /* and 0, not -0 */
    }
}

/* Undo or redo: the scene again with the edits as they were. True when it reloaded. */
static bool undo_redo(bool undo)
{
    err_t e;
    if (!(undo ? overrides_undo(&app.s.edits) : overrides_redo(&app.s.edits)))
        return false;
    if (reload_scene(&e))
        return true;
    snprintf(app.message, sizeof app.message, "%s", e.msg);
    return false;
}

/* What the user did in the panel last frame. True when the image must restart. */
static bool panel_apply(const panel_actions *act)
{
    bool restart = false;
    if (act->edit_started && act->set[0])
        overrides_checkpoint(&app.s.edits);
    if (act->set[0])
        restart |= edit(act->set);
    if (act->undo || app.ask.undo)
        restart |= undo_redo(true);
    if (act->redo || app.ask.redo)
        restart |= undo_redo(false);
    app.ask.undo = app.ask.redo = false;
    if (act->camera_typed) {
        if (camera_degenerate(act->position, act->look_at)) {
            snprintf(app.message, sizeof app.message, "the look-at point is the camera's position: no direction to look in");
        } else {
            app.fly.cam = scene_camera(&app.s.scene, act->position, act->look_at, act->fov_deg);
            memcpy(app.fly.pivot, act->look_at, sizeof app.fly.pivot);
        }
    }
    if (act->camera_mode >= 0)
        app.fly.mode = (panel_camera_mode)act->camera_mode;
    if (act->exposure_changed)
        app.exposure = act->exposure;
    if (act->view >= 0)
        app.view = (render_view)act->view;
    if (act->heat_changed)
        render_set_heat_max(act->heat_max);
    if (act->grab_reference)
        render_grab_reference(), costs_grabbed(&app.cost);
    return restart;
}

/* ---- requests and drawing ------------------------------------------------------------------------ */

/* The shipped scenes, in --list-scenes order: number keys 1–9 pick them. */
static void list_scene_names(void)
{
    strbuf list = {0};
    scene_list(&list, false);
    for (char *line = list.data; line && *line && app.scene_count < MAX_SCENES;) {
        char *nl = strchr(line, '\n');
        snprintf(app.names[app.scene_count++], SCENE_NAME_MAX, "%.*s", (int)(nl ? nl - line : (long)strlen(line)), line);
        line = nl ? nl + 1 : line + strlen(line);
    }
    sb_free(&list);
}

static void flight_requests(void)
{
    const scene *s = &app.s.scene;
    if (app.ask.add_key) { /* the terminal hears it too: where the flight went, or why the key was not added */
        recorder_add(&app.flight, s->name, &app.fly.cam, flycam_speed(&app.fly, s), flycam_probe, (void *)s, app.message,
                     sizeof app.message);
        fprintf(stderr, "fathom: %s\n", app.message);
    }
    if (app.ask.clear_keys)
        recorder_clear(&app.flight, s->name, app.message, sizeof app.message);
    if (app.ask.toggle_play)
        recorder_toggle_play(&app.flight, app.message, sizeof app.message);
    app.ask.add_key = app.ask.clear_keys = app.ask.toggle_play = false;
}

/* A number key's scene: the command line's and a view's overrides belong to their own scene. */
static void switch_scene(int i)
{
    err_t e;
    bool new_file;
    costs_clear(&app.cost);
    if (!session_switch(&app.s, app.names[i], &new_file, &e)) {
        snprintf(app.message, sizeof app.message, "%s", e.msg), fprintf(stderr, "fathom: %s\n", e.msg);
    } else {
        loaded(new_file, false);
        app.message[0] = '\0';
    }
    framestats_forget(&app.stats); /* another scene's times say nothing of this one */
    app.res = res_init(app.res.target_ms > 0 ? 1000.0f / app.res.target_ms : DEFAULT_FPS, RES_MIN_SCALE);
}

/* Scene switches, knob steps, reloads and the flight's keys asked for by keys. True when the image
 * must restart. */
static bool handle_requests(void)
{
    bool restart = false;
    err_t e;
    if (app.ask.go_home) {
        flycam_home(&app.fly, &app.s.scene);
        snprintf(app.message, sizeof app.message, "back at the start view");
        app.ask.go_home = false;
    }
    if (app.ask.pending_scene >= 0) {
        switch_scene(app.ask.pending_scene);
        app.ask.pending_scene = -1;
        restart = true;
    }
    if (app.ask.knob_step) {
        step_knob(app.ask.knob_step);
        app.ask.knob_step = 0;
        restart = true;
    }
    if (app.ask.reload) {
        if (!render_reload(&e) || !reload_scene(&e)) {
            if (snprintf(app.message, sizeof app.message, "reload failed, kept the last good program:\n%s", e.msg) >=
                (int)sizeof app.message)
                app.message[sizeof app.message - 1] = '\0';
            fprintf(stderr, "fathom: %s\n", app.message);
        } else {
            snprintf(app.message, sizeof app.message, "shaders and scene reloaded");
        }
        app.ask.reload = false;
        restart = true;
    }
    flight_requests();
    return restart;
}

/* F: the lens focused on the point under the cursor (the window's centre while the mouse looks): the
 * focal plane through it, as an override (undo takes it back, a preset keeps it). True when it took. */
static bool focus_lens(int w, int h)
{
    if (!app.ask.focus)
        return false;
    app.ask.focus = false;
    if (!(app.fly.cam.lens.aperture > 0)) { /* a pinhole is sharp everywhere (and orthographic's focus frames it) */
        snprintf(app.message, sizeof app.message, "no lens to focus: give camera.aperture a radius first (the panel's "
                                                  "camera section, or --set camera.aperture=0.05)");
        return false;
    }
    bool captured = !flycam_cursor_free(&app.fly, app.panel);
    int x = captured ? w / 2 : (int)app.fly.mouse[0], y = captured ? h / 2 : (int)app.fly.mouse[1];
    double p[3];
    if (!flycam_point_under(&app.fly, x, y, w, h, p)) {
        snprintf(app.message, sizeof app.message, "nothing under the cursor to focus on");
        return false;
    }
    camera_basis b = camera_get_basis(&app.fly.cam);
    double d = 0;
    for (int i = 0; i < 3; i++)
        d += (p[i] - app.fly.cam.position[i]) * (double)b.forward[i];
    if (app.fly.cam.lens.projection == PROJECTION_EQUIRECTANGULAR || app.fly.cam.lens.projection == PROJECTION_FISHEYE)
        d = camera_distance(p, app.fly.cam.position); /* their focus is along the ray */
    char kv[64];
    snprintf(kv, sizeof kv, "camera.focus=%.9g", fmax(d, 1e-30));
    overrides_checkpoint(&app.s.edits);
    return edit(kv);
}

/* A streamed terrain (gpu/res_heightfield.h): the tiles the last sample asked for go to the loader thread,
 * and the ones it has read are uploaded, a few a frame so the window keeps its pace; the image restarts
 * with them (what it drew in their place was a plateau). */
static void stream_tiles(void)
{
    enum { UPLOADS_PER_FRAME = 8 };
    err_t e;
    res_heightfield_settled r = res_heightfield_settle_async(UPLOADS_PER_FRAME, &e);
    if (r == TERRAIN_FAILED)
        fprintf(stderr, "fathom: %s\n", e.msg);
    if (r == TERRAIN_LOADED)
        render_begin(&app.fly.cam);
}

/* One frame's sample. Moving (or restarted): one sample at the internal resolution the controller
 * picks for the target frame rate, stretched to the window. Still: full resolution, samples
 * accumulating up to the preset's spp in bands of about one frame's time. True while there is work. */
static bool draw(int w, int h, bool restart, camera *shown, bool *moved)
{
    app.fly.cam.lens = scene_lens(&app.s.scene); /* the panel's and F's edits: projection, lens, stereo */
    *moved = memcmp(shown, &app.fly.cam, sizeof *shown) != 0;
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
        render_begin(&app.fly.cam);
        *shown = app.fly.cam;
    }
    int spp = app.s.scene.quality.spp;
    bool refining = render_samples() < spp;
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
        framestats_note_sample(&app.stats, ms);
        costs_note_sample(&app.cost, ms, iw, ih, w, h, complete, render_samples() == 1);
        app.frame_sample_ms = ms;
        if (moving) /* the whole frame keeps to the target: the display, HUD, panel and swap too */
            res_update(&app.res, ms + app.stats.overhead_ms, (double)iw * ih, (double)w * h);
        else if (refining && ms > 0) /* the next band: as many rows as fit the target */
            app.band_rows *= fmin(fmax(app.res.target_ms / ms, 0.5), 2.0);
        if (complete && res_heightfield_streamed())
            stream_tiles();
        if (render_samples() == 1)
            app.unresolved = -1;
        if (!moving && refining && render_samples() == spp) {
            costs_note_converged(&app.cost, app.cost.reference_rmse >= 0 ? render_reference_rmse() : -1);
            app.unresolved = render_unresolved_pixels(NULL);
        }
    }
    app.scaled = iw != w || ih != h;
    render_display(0, w, h, app.exposure, app.view);
    return refining || app.scaled;
}

/* What the cursor points at, for the HUD and panel: the distance (and for a DEM the height). */
static void cursor_info(int w, int h)
{
    app.cursor_info[0] = '\0';
    double p[3];
    if (!flycam_cursor_free(&app.fly, app.panel) ||
        !flycam_point_under(&app.fly, (int)app.fly.mouse[0], (int)app.fly.mouse[1], w, h, p))
        return;
    double dist = camera_distance(p, app.fly.cam.position), lon, lat;
    int tx, ty;
    const heightfield *hf = res_heightfield_loaded(&tx, &ty);
    float ex = app.s.scene.terrain.exaggeration > 0 ? app.s.scene.terrain.exaggeration : 1.0f;
    if (hf && dem_geo_lonlat(app.s.geo, (p[0] - (double)hf->x0) / (double)hf->dx, (p[2] - (double)hf->z0) / (double)hf->dz,
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
    scene *s = &app.s.scene;
    bool was = s->fractal.deep_now;
    err_t e;
    if (!render_fit_precision(s, &app.fly.cam, h, &e))
        snprintf(app.message, sizeof app.message, "%s", e.msg);
    if (was != s->fractal.deep_now)
        snprintf(app.message, sizeof app.message, s->fractal.deep_now ? "deep zoom: the formula now runs in double precision"
                                                                       : "back to float precision");
    return was != s->fractal.deep_now;
}

/* The panel and the swap; with --frames, what they and the frame cost. */
static void finish_frame(GLFWwindow *win, int w, int h, panel_actions *act, double start, bool moved)
{
    panel_model m;
    panel_model_of(w, h, &m);
    bool stats = framestats_recording(&app.stats);
    if (stats)
        glFinish(); /* what came before is not the panel's */
    double p0 = glfwGetTime();
    panel_frame(app.panel, &m, act);
    double t = stats ? (glFinish(), glfwGetTime()) : 0;
    glfwSwapBuffers(win);
    double t1 = glfwGetTime();
    framestats_note_overhead(&app.stats, (t1 - start) * 1000.0, app.frame_sample_ms);
    app.frame_sample_ms = 0;
    if (stats)
        framestats_note_frame(&app.stats, (t1 - start) * 1000.0, (t - p0) * 1000.0, (t1 - t) * 1000.0, moved);
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
        if (!recorder_play(&app.flight, dt, &app.fly.cam, app.message, sizeof app.message)) {
            flycam_move(&app.fly, win, &app.s.scene, app.panel, dt, w, h);
            recorder_follow(&app.flight, &app.fly.cam);
        }
        bool asked = handle_requests(); /* every one runs, each applying what was asked: no short-circuit */
        asked = panel_apply(&act) || asked;
        asked = views_and_presets(win, &act, w, h) || asked;
        asked = fit_precision(h) || asked;
        asked = focus_lens(w, h) || asked;
        restart = restart || asked;
        bool moved, refining = draw(w, h, restart, &shown, &moved);
        restart = false;
        if (app.ask.mesh) {
            shots_mesh(&app.s, app.message, sizeof app.message);
            app.ask.mesh = false;
        }
        if (app.ask.screenshot) {
            shots_screenshot(&app.s, &app.fly.cam, w, h, app.message, sizeof app.message);
            app.ask.screenshot = false;
        }
        cursor_info(w, h);
        explore_hud(&app, w, h);
        finish_frame(win, w, h, &act, now, moved);
        if (!refining && !moved && !app.opt->frames && !app.panel)
            glfwWaitEventsTimeout(IDLE_WAIT_S); /* converged: do not spin */
    }
}

bool explore_run(const cli_options *opt, err_t *err)
{
    memset(&app, 0, sizeof app);
    app.opt = opt;
    session_init(&app.s, opt);
    costs_init(&app.cost);
    framestats_init(&app.stats, opt->frames);
    app.ask.pending_scene = -1;
    app.fragment_preset = -1; /* the preset showing (a fragment's: below) */
    app.unresolved = -1;
    app.exposure = DEFAULT_EXPOSURE;
    app.res = res_init((float)(opt->fps ? opt->fps : DEFAULT_FPS), RES_MIN_SCALE);
    app.knob = explore_next_knob(&app, (knob_id)(KNOB_COUNT - 1));
    app.panel = opt->panel;
    list_scene_names();
    scene first; /* a bad scene is the error to report, even where no window can open */
    if (!scene_load(opt->scene, opt->sets, opt->set_count, &first, err)) {
        framestats_free(&app.stats);
        return false;
    }
    if (program_is_fractal(first.program) && first.fractal.formula.fragment) /* where its presets start (J) */
        app.fragment_preset = frag_preset_index(first.fractal.formula.file, opt->view_name);
    scene_free(&first);
    if (!gpu_open(&(gpu_desc){.width = opt->width, .height = opt->height, .title = "fathom"}, err)) {
        framestats_free(&app.stats);
        return false;
    }
    GLFWwindow *win = gpu_window();
    explore_keys_install(win, &app); /* before the panel's: ImGui's callbacks chain to these */
    bool new_file = false;
    bool ok = render_init(err) && hud_init(err) && panel_init(win, err) && session_load(&app.s, opt->scene, &new_file, err);
    render_set_adaptive(true); /* still images: samples after the first only on edges */
    if (ok) {
        loaded(new_file, true);
        fprintf(stderr, "fathom: %s, %s backend\n", gpu_describe(), render_backend_name(render_backend_used()));
        loop(win);
        int w, h;
        glfwGetFramebufferSize(win, &w, &h);
        char what[256];
        snprintf(what, sizeof what, "%s backend, %s", render_backend_name(render_backend_used()), gpu_describe());
        framestats_summary(&app.stats, w, h, app.panel, what);
        if (res_heightfield_streamed()) {
            res_heightfield_stats st = res_heightfield_get_stats();
            fprintf(stderr, "fathom: terrain streamed: %ld tiles read from disk, %d of %d resident (%d slots), %d "
                            "pending at the last frame\n", st.loaded, st.resident, st.tiles, st.slots, st.pending);
        }
    }
    framestats_free(&app.stats);
    panel_shutdown();
    hud_shutdown();
    render_shutdown();
    recorder_free(&app.flight);
    session_free(&app.s);
    gpu_close();
    return ok;
}
