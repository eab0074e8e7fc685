/* flycam — the window's camera control: fly (WASD and the mouse), orbit about a pivot (drag and
 * scroll) or walk on a DEM, every move by real time (view/camera.h: camera_travel) and through the
 * slide rule, so the camera never enters or passes through a solid. It reads GLFW's keys and mouse
 * and the renderer's distance bound; the state below is all it keeps. GL and GLFW. */
#ifndef FATHOM_FLYCAM_H
#define FATHOM_FLYCAM_H

#include <stdbool.h>

#include "scene/scene.h"
#include "util.h"
#include "view/camera.h"
#include "window/panel.h"

struct GLFWwindow;

typedef struct flycam {
    camera cam;
    panel_camera_mode mode;
    double pivot[3];          /* orbit: the point the camera turns about */
    float speed, start_speed; /* fly: m/s, or × distance in adaptive scenes */
    float surface_distance;   /* the distance bound at the camera (fractals: sets the flying speed) */
    float scroll;             /* notches not yet applied */
    double mouse[2];
    bool mouse_valid, looking, orbiting;
    bool level; /* the horizon is kept (yaw about the vertical, pitch limited); Q/E roll into free flight */
    int settle_frames; /* after the cursor was captured: frames whose mouse motion is not a look */
} flycam;

/* The camera at `cam` (a new scene, or the command line's view), the pivot at look_at, and the speed
 * the scene starts with. */
void flycam_start(flycam *f, const scene *s, const camera *cam, const double look_at[3]);
/* Back to the scene's start view and speed. */
void flycam_home(flycam *f, const scene *s);
/* The cursor is free (the panel is open, or orbiting) or captured (the mouse looks). */
bool flycam_cursor_free(const flycam *f, bool panel_open);
/* U: back to a level horizon (roll 0), or free flight. */
void flycam_toggle_level(flycam *f);
/* One frame's move of dt seconds (the recorded flight is not playing). */
void flycam_move(flycam *f, struct GLFWwindow *win, const scene *s, bool panel_open, float dt, int w, int h);
/* The world point seen at window pixel (x, y) of a w × h window (from the top), by the image on show. */
bool flycam_point_under(const flycam *f, int x, int y, int w, int h, double out[3]);
/* The renderer's distance bound at n points (xyz each, world): ctx is the scene (camera_probe_fn). */
void flycam_probe(void *ctx, const double *points, int n, float *out);
/* The HUD's line on how the camera moves. */
void flycam_describe(const flycam *f, const scene *s, strbuf *out);
/* "flying", "orbiting" or "walking". */
const char *flycam_mode_name(const flycam *f);
/* The speed a recorded key is timed by (m/s). */
double flycam_speed(const flycam *f, const scene *s);

#endif
