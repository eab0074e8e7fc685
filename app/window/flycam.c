/* flycam — the window's camera control (flycam.h). */
#include "window/flycam.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <math.h>
#include <string.h>

#include "view/aov.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "window/panel.h"

enum { PROBE_MAX = 64, CURSOR_SETTLE_FRAMES = 3 };
static const float MOUSE_SENSITIVITY = 0.0025f; /* radians per pixel */
static const float SPEED_STEP = 1.25f;          /* per scroll notch */
static const float DOLLY_STEP = 0.85f;          /* orbit: the distance to the pivot per scroll notch */
static const float DEFAULT_SPEED = 2.0f;        /* × the distance to the surface (adaptive scenes) */
static const float START_SPEED_FRACTION = 0.2f; /* others: the start view's distance to its look-at, per 5 s */
static const float MIN_SPEED_FACTOR = 1e-3f, MAX_SPEED_FACTOR = 1e3f; /* scroll: of the start speed */
static const float MIN_ADAPTIVE_DISTANCE = 1e-13f; /* metres: keeps a little speed at the surface (deep zooms too) */
static const float WALK_HEIGHT = 1.8f;             /* metres: eye height when walking on terrain */
static const float WALK_SPEED = 1.4f;              /* m/s: walking (Shift: ×4, running) */

void flycam_start(flycam *f, const scene *s, const camera *cam, const double look_at[3])
{
    f->cam = *cam;
    f->level = cam->roll == 0;
    f->start_speed = s->adaptive_speed ? DEFAULT_SPEED
                                       : START_SPEED_FRACTION * (float)camera_distance(s->cam_position, s->cam_look_at);
    f->speed = f->start_speed;
    memcpy(f->pivot, look_at, sizeof f->pivot);
}

void flycam_home(flycam *f, const scene *s)
{
    camera cam = scene_camera(s, s->cam_position, s->cam_look_at, s->cam_fov_deg);
    flycam_start(f, s, &cam, s->cam_look_at);
}

void flycam_toggle_level(flycam *f)
{
    f->level = !f->level;
    if (f->level) { /* upright: the roll goes, the view's direction stays (within the pitch limit) */
        f->cam.roll = 0;
        f->cam.pitch = fmaxf(fminf(f->cam.pitch, CAMERA_MAX_PITCH), -CAMERA_MAX_PITCH);
    }
}

bool flycam_cursor_free(const flycam *f, bool panel_open) { return panel_open || f->mode == CAMERA_ORBIT; }

double flycam_speed(const flycam *f, const scene *s)
{
    return s->adaptive_speed ? (double)(f->speed * fmaxf(f->surface_distance, MIN_ADAPTIVE_DISTANCE)) : (double)f->speed;
}

static camera_input read_input(flycam *f, GLFWwindow *w, bool panel_open, bool *orbit_press)
{
    camera_input in = {0};
    bool keys = !panel_wants_keyboard();
    in.move[0] = keys ? (float)(glfwGetKey(w, GLFW_KEY_D) - glfwGetKey(w, GLFW_KEY_A)) : 0;
    in.move[1] = keys ? (float)(glfwGetKey(w, GLFW_KEY_SPACE) - glfwGetKey(w, GLFW_KEY_C)) : 0;
    in.move[2] = keys ? (float)(glfwGetKey(w, GLFW_KEY_W) - glfwGetKey(w, GLFW_KEY_S)) : 0;
    in.fast = keys && (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT));
    in.roll = keys && f->mode == CAMERA_FLY ? (float)(glfwGetKey(w, GLFW_KEY_Q) - glfwGetKey(w, GLFW_KEY_E)) : 0;
    f->level = f->level && in.roll == 0; /* rolling is free flight */
    in.free = !f->level && f->mode == CAMERA_FLY;
    bool free = flycam_cursor_free(f, panel_open);
    int cursor = free ? GLFW_CURSOR_NORMAL : GLFW_CURSOR_DISABLED;
    if (glfwGetInputMode(w, GLFW_CURSOR) != cursor) {
        /* capturing warps the cursor to the window's centre, and GLFW's first motion events after it
         * can carry the jump from where X last saw the pointer: no look from the next few frames */
        glfwSetInputMode(w, GLFW_CURSOR, cursor);
        f->settle_frames = CURSOR_SETTLE_FRAMES;
    }
    if (f->settle_frames > 0) {
        f->settle_frames--;
        f->mouse_valid = false;
    }
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    bool over_panel = panel_wants_mouse();
    bool right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    bool left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    bool look = !free || (right && (f->looking || !over_panel));
    bool orbit = f->mode == CAMERA_ORBIT && left && (f->orbiting || !over_panel);
    *orbit_press = orbit && !f->orbiting;
    if (f->mouse_valid && (look || orbit)) {
        in.look[0] = (float)(x - f->mouse[0]);
        in.look[1] = (float)(y - f->mouse[1]);
    }
    f->looking = look && free;
    f->orbiting = orbit;
    f->mouse[0] = x;
    f->mouse[1] = y;
    f->mouse_valid = true;
    return in;
}

/* Relative to the renderer's origin (a deep zoom's), in chunks of PROBE_MAX points. */
void flycam_probe(void *ctx, const double *points, int n, float *out)
{
    float p[PROBE_MAX * 3] = {0}, d[PROBE_MAX * 2];
    double origin[3];
    err_t e;
    if (n > PROBE_MAX) {
        flycam_probe(ctx, points, PROBE_MAX, out);
        flycam_probe(ctx, points + 3 * PROBE_MAX, n - PROBE_MAX, out + PROBE_MAX);
        return;
    }
    render_origin(origin);
    for (int i = 0; i < 3 * n; i++)
        p[i] = (float)(points[i] - origin[i % 3]);
    bool ok = render_probe((const scene *)ctx, NULL, p, n, d, &e);
    for (int i = 0; i < n; i++)
        out[i] = ok ? d[2 * i] : -1.0f; /* unknown: the move is left alone */
}

bool flycam_point_under(const flycam *f, int x, int y, int w, int h, double out[3])
{
    int aw, ah;
    render_active_size(&aw, &ah);
    float aov[AOV_FLOATS];
    int ax = (int)((double)x * aw / w), ay = (int)((double)y * ah / h);
    if (!render_read_pixel(ax, ay, aov) || !isfinite(aov[AOV_SLOT_DEPTH]))
        return false;
    vec3 d;
    double o[3]; /* orthographic rays and stereo eyes start off the camera's position */
    if (!camera_ray_from(&f->cam, aw, ah, (float)ax, (float)(ah - 1 - ay), o, d))
        return false;
    for (int i = 0; i < 3; i++)
        out[i] = o[i] + (double)d[i] * (double)aov[AOV_SLOT_DEPTH];
    return true;
}

/* Moves the camera from where it is to target through the slide rule. */
static void slide_to(flycam *f, const scene *s, const double before[3], double target[3])
{
    if (memcmp(before, target, sizeof(double) * 3))
        camera_slide(before, target, s->quality.step_factor, camera_resolution(before, s->fractal.deep_now),
                     flycam_probe, (void *)s, NULL);
    memcpy(f->cam.position, target, sizeof f->cam.position);
}

/* Orbit: a drag turns the camera about the pivot (the point under the cursor where the drag began, or
 * the last one), the scroll wheel moves it toward or away from the pivot; the move goes through the
 * slide rule like any other. */
static void orbit(flycam *f, const scene *s, const camera_input *in, bool press, int w, int h)
{
    if (press && !flycam_point_under(f, (int)f->mouse[0], (int)f->mouse[1], w, h, f->pivot) &&
        camera_distance(f->pivot, f->cam.position) <= 0)
        memcpy(f->pivot, s->cam_look_at, sizeof f->pivot);
    double before[3], target[3];
    memcpy(before, f->cam.position, sizeof before);
    camera_orbit(&f->cam, f->pivot, -in->look[0] * MOUSE_SENSITIVITY, -in->look[1] * MOUSE_SENSITIVITY);
    memcpy(target, f->cam.position, sizeof target);
    if (f->scroll != 0) {
        double k = pow(DOLLY_STEP, f->scroll);
        for (int i = 0; i < 3; i++)
            target[i] = f->pivot[i] + (f->cam.position[i] - f->pivot[i]) * k;
        f->scroll = 0;
    }
    slide_to(f, s, before, target);
}

/* Walking: along the ground at walking speed, the eye WALK_HEIGHT above it, by real time in steps of
 * at most CAMERA_STEP_S (as camera_travel flies). */
static void walk(flycam *f, const scene *s, const camera_input *in, float dt)
{
    camera_input flat = *in;
    flat.move[1] = 0;
    float pitch = fmaxf(fminf(f->cam.pitch - in->look[1] * MOUSE_SENSITIVITY, CAMERA_MAX_PITCH), -CAMERA_MAX_PITCH);
    f->cam.pitch = 0; /* forward along the ground, wherever the eye looks */
    float step_dt;
    int steps = camera_steps(dt, &step_dt);
    for (int k = 0; k < steps; k++) {
        double before[3], target[3];
        memcpy(before, f->cam.position, sizeof before);
        camera_update(&f->cam, &flat, step_dt, WALK_SPEED, MOUSE_SENSITIVITY);
        flat.look[0] = flat.look[1] = 0; /* the look turns once a frame */
        memcpy(target, f->cam.position, sizeof target);
        float ground;
        if (render_ground_height((float)target[0], (float)target[2], &ground))
            target[1] = ground + WALK_HEIGHT;
        slide_to(f, s, before, target);
    }
    f->cam.pitch = pitch;
}

void flycam_move(flycam *f, GLFWwindow *win, const scene *s, bool panel_open, float dt, int w, int h)
{
    bool orbit_press;
    camera_input in = read_input(f, win, panel_open, &orbit_press);
    float d;
    flycam_probe((void *)s, f->cam.position, 1, &d);
    f->surface_distance = fabsf(d);
    if (f->mode == CAMERA_WALK && !s->terrain.heightmap[0])
        f->mode = CAMERA_FLY; /* walking needs a ground */
    if (f->mode == CAMERA_ORBIT) {
        orbit(f, s, &in, orbit_press, w, h);
    } else if (f->mode == CAMERA_WALK) {
        walk(f, s, &in, dt);
    } else {
        if (f->scroll != 0) {
            f->speed = fminf(fmaxf(f->speed * powf(SPEED_STEP, f->scroll), MIN_SPEED_FACTOR * f->start_speed),
                             MAX_SPEED_FACTOR * f->start_speed);
            f->scroll = 0;
        }
        camera_travel_rule r = {.speed = f->speed, .sensitivity = MOUSE_SENSITIVITY, .per_distance = s->adaptive_speed,
                                .min_distance = MIN_ADAPTIVE_DISTANCE, .step_factor = s->quality.step_factor,
                                .deep = s->fractal.deep_now};
        camera_travel(&f->cam, &in, dt, &r, flycam_probe, (void *)s);
    }
    camera_clamp_range(f->cam.position, s->cam_look_at, s->quality.max_dist);
}

static const char *const MODE_NAMES[CAMERA_MODE_COUNT] = {"flying", "orbiting", "walking"};

void flycam_describe(const flycam *f, const scene *s, strbuf *t)
{
    if (f->mode == CAMERA_WALK)
        sb_printf(t, "walking %.1f m above the ground at %.1f m/s\n", (double)WALK_HEIGHT, (double)WALK_SPEED);
    else if (f->mode == CAMERA_ORBIT)
        sb_printf(t, "orbiting about (%.6g %.6g %.6g): drag turns, scroll moves in\n", f->pivot[0], f->pivot[1], f->pivot[2]);
    else if (s->adaptive_speed)
        sb_printf(t, "speed %.2f x distance (%.3g m to the surface)\n", (double)f->speed, (double)f->surface_distance);
    else
        sb_printf(t, "speed %.3g m/s\n", (double)f->speed);
}

const char *flycam_mode_name(const flycam *f) { return MODE_NAMES[f->mode]; }
