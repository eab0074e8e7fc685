/* path — camera paths for flights: keyframes from a file, smooth in position, orientation, field of
 * view and any numeric scene parameter, evaluated at any time. Pure C, double precision.
 *
 * File (JSON, human-editable; angles in degrees, times in seconds, metres):
 *   { "keys": [
 *       { "time": 0,   "position": [0, 1, 5], "yaw": 0, "pitch": -10, "fov": 50 },
 *       { "time": 2.5, "position": [3, 1, 2], "look_at": [0, 0, 0],
 *         "set": { "fractal.power": 9 } } ] }
 * Each key gives yaw/pitch (camera.h's convention) or look_at (and "up": the direction the image's
 * top faces, default +Y), and may add "roll" (degrees, camera.h's sign); fov defaults to the previous key's
 * (the first: 50). "set" holds numeric scene keys (as --set takes them); every key must list the same
 * ones. Times strictly increase; at least two keys.
 *
 * Smoothness:
 *   position     centripetal Catmull–Rom (α = 1/2: no cusps or self-intersections within a segment;
 *                Yuksel, Schaefer & Keyser, "Parameterization and applications of Catmull–Rom
 *                curves", CAD 2011), evaluated by the Barry–Goldman pyramid;
 *   speed        the camera moves along the curve by arc length, and arc length follows time by a
 *                monotone cubic through (key time, arc length at the key) (Fritsch & Carlson, "Monotone
 *                piecewise cubic interpolation", SIAM J. Numer. Anal. 1980): it passes every key at
 *                its time, never runs backwards, and its speed is continuous (C1);
 *   orientation  unit quaternions, each key's sign chosen next to the previous one's (no flip across
 *                180°); per segment a cubic Bézier on the quaternion sphere evaluated by repeated slerp
 *                (Shoemake, "Animating rotation with quaternion curves", SIGGRAPH 1985), its inner
 *                control points set from each key's turn rate (the mean of the adjacent segments'),
 *                so the turn rate is continuous in time however unevenly the keys are spaced;
 *   fov, "set"   cubic Hermite in time with Catmull–Rom tangents (C1, through the keys);
 *   zooms        a segment whose two keys both give "zoom_to" (the point a deep zoom closes in on) keeps
 *                its scale: the distance s to that point changes geometrically in time (s0 (s1/s0)^u:
 *                the same fraction every frame, a constant apparent speed), the point itself moves from
 *                one key's to the next in proportion to s0 − s (so it drifts across the view by a
 *                bounded amount however deep), and the direction from it turns by slerp. A plain
 *                segment through a 1e-12 zoom would spend nearly every frame at the wrong scale;
 *   easing       "ease": "in", "out" or "in-out" on a key eases the segment that starts there (its
 *                time fraction u becomes u², 1 − (1 − u)² or 3u² − 2u³, for every track): the camera
 *                starts or stops there at rest ("none", the default: as above).
 */
#ifndef FATHOM_PATH_H
#define FATHOM_PATH_H

#include <stdbool.h>

#include "util.h"

enum { PATH_MAX_KEYS = 10000, PATH_MAX_PARAMS = 16, PATH_PARAM_NAME = 64, PATH_ARC_SAMPLES = 64 };
/* Key times lie within ±PATH_MAX_TIME seconds: a day either way, so a path's frames (at most 1000 a
 * second) and the probes along them stay far inside an int. */
#define PATH_MAX_TIME 86400.0

typedef struct path_key {
    double time;
    double position[3];
    double quat[4]; /* x, y, z, w: unit, sign-aligned with the previous key */
    double fov_deg;
    double values[PATH_MAX_PARAMS];
    bool zoom;          /* zoom_to was given */
    double zoom_to[3];  /* the point a zoom segment closes in on (see top) */
    int ease;           /* path_ease: how the segment from this key starts and ends */
} path_key;
typedef enum path_ease { PATH_EASE_NONE, PATH_EASE_IN, PATH_EASE_OUT, PATH_EASE_IN_OUT, PATH_EASE_COUNT } path_ease;
extern const char *const PATH_EASES[PATH_EASE_COUNT + 1];
/* The eased time fraction (see top). */
double path_ease_u(int ease, double u);

typedef struct path {
    int count;
    path_key *keys;
    int param_count;
    char params[PATH_MAX_PARAMS][PATH_PARAM_NAME]; /* scene keys of the "set" tracks */
    /* arc length: cumulative at each key, and per segment a table of PATH_ARC_SAMPLES + 1 lengths
     * at equal steps of the segment's spline parameter */
    double *key_length;
    double *arc;
    double *speed; /* d(arc length)/dt at each key: the monotone cubic's tangents */
} path;

typedef struct path_sample {
    double position[3];
    double quat[4];
    double yaw, pitch, roll; /* radians, from the quaternion's frame (camera.h's angles) */
    double fov_deg;
    double values[PATH_MAX_PARAMS];
} path_sample;

/* Reads a path file / path text (name is used in messages). Errors name the key and what to do. */
bool path_load(const char *file, path *p, err_t *err);
bool path_parse(const char *text, const char *name, path *p, err_t *err);
void path_free(path *p);

/* The camera and parameters at time t (clamped to the first and last key's times). */
void path_eval(const path *p, double t, path_sample *out);

double path_duration(const path *p);
/* Arc length of the whole path (metres). */
double path_length(const path *p);

/* The path as a file path_parse reads back to the same keys (yaw, pitch and roll written from the quaternions). */
void path_write(const path *p, strbuf *out);

/* Recording (the window's N key): keys as cameras, turned into a path file's text. */
typedef struct path_camera {
    double time, position[3], yaw, pitch, roll, fov_deg; /* angles in radians */
} path_camera;
#define PATH_KEY_GAP_MIN 0.5  /* seconds between recorded keys, at least … */
#define PATH_KEY_GAP_MAX 10.0 /* … and at most */
/* The time of a key added at `position` after keys[0 … n−1]: 0 for the first; else the last key's time
 * plus the distance from it at `speed` m/s, within [PATH_KEY_GAP_MIN, PATH_KEY_GAP_MAX]. */
double path_next_key_time(const path_camera *keys, int n, const double position[3], double speed);
void path_text_from_cameras(const path_camera *keys, int n, strbuf *out);
/* Key i of a loaded path as a camera. */
void path_key_camera(const path *p, int i, path_camera *out);

/* "A-B" (inclusive) or "N": frame numbers ≥ 0. */
bool path_parse_frames(const char *s, int *first, int *last, err_t *err);

/* The frame's file name from a pattern with one printf integer conversion (%d, %04d, …; %% for a
 * literal %). Returns false, with the reason, for a pattern without exactly one such conversion. */
bool path_frame_name(const char *pattern, int frame, char *out, size_t n, err_t *err);

#endif
