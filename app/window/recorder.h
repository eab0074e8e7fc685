/* recorder — the window's recorded flight: N adds the camera as a keyframe (timed by the flying
 * speed), Shift+N clears, L plays; the keys are saved as a camera path (view/path.h) beside the
 * scene's saved views, so `fathom render --path` renders the flight. Between keys it keeps the
 * camera's trail, and where the spline through the keys would cut through a surface the camera slid
 * around, keys from the trail route it around (view/route.h): what N records renders. Its state is
 * the caller's. */
#ifndef FATHOM_RECORDER_H
#define FATHOM_RECORDER_H

#include <stdbool.h>

#include "view/camera.h"
#include "view/path.h"
#include "util.h"

enum { RECORDER_MAX_KEYS = 1000, RECORDER_TRAIL_MAX = 4096 };

typedef struct recorder {
    path_camera keys[RECORDER_MAX_KEYS];
    int key_count;
    path flight; /* the keys as a path, once there are two */
    bool playing;
    double play_t;
    path_camera trail[RECORDER_TRAIL_MAX]; /* the camera since the last key (thinned when full) */
    int trail_count;
} recorder;

/* The scene's recorded flight, if it has one, as keys to add to (message: what went wrong, or ""). */
void recorder_load(recorder *r, const char *scene_name, char *message, size_t n);
/* Adds the camera as the next key (speed: m/s, to time it), routed around what the spline would cut
 * through (probe: the distance bound, as camera_slide's), and saves the flight. */
void recorder_add(recorder *r, const char *scene_name, const camera *c, double speed, camera_probe_fn probe,
                  void *ctx, char *message, size_t n);
/* Each frame the camera moves (not while playing): the trail to the next key. */
void recorder_follow(recorder *r, const camera *c);
/* Clears the flight and removes its file. */
void recorder_clear(recorder *r, const char *scene_name, char *message, size_t n);
void recorder_toggle_play(recorder *r, char *message, size_t n);
/* While playing: moves the camera dt seconds on along the flight. True when it did. */
bool recorder_play(recorder *r, double dt, camera *c, char *message, size_t n);
void recorder_free(recorder *r);

#endif
