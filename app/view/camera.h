/* camera — free-fly camera maths. Pure functions over a small struct (cglm), no GL, no input state.
 *
 * Conventions: right-handed, Y up. yaw = 0 looks down -Z; yaw grows turning left (counter-clockwise
 * seen from above); pitch > 0 looks up, clamped short of ±90° so the basis never degenerates.
 * Primary rays: pixel (x, y) counts from the bottom-left (GL's window origin), its centre at +0.5;
 *   dir = normalize(forward + sx * tan(fov/2) * aspect * right + sy * tan(fov/2) * up),
 *   sx = 2 (x + 0.5) / width - 1,  sy = 2 (y + 0.5) / height - 1,  aspect = width / height.
 * fov is the vertical field of view in radians.
 */
#ifndef FATHOM_CAMERA_H
#define FATHOM_CAMERA_H

#include <cglm/cglm.h>
#include <stdbool.h>

typedef struct camera {
    vec3 position;
    float yaw, pitch; /* radians */
    float fov_y;      /* radians */
} camera;

typedef struct camera_basis {
    vec3 forward, right, up;
} camera_basis;

/* What the user asks for this frame; the caller maps keys and mouse to it. */
typedef struct camera_input {
    float move[3];     /* right, up, forward: each -1..1 */
    float look[2];     /* mouse delta in pixels: x right, y down */
    bool fast;         /* Shift */
} camera_input;

#define CAMERA_MAX_PITCH 1.5533430f /* 89 degrees */
/* Camera and look-at coordinates lie within ±CAMERA_MAX_COORD metres: beyond, a float cannot tell a
 * camera from its look-at point a few metres away. */
#define CAMERA_MAX_COORD 1e7

/* True when target is (within float rounding of) eye: no direction to look in. Scene files and the
 * command line refuse it. */
bool camera_degenerate(const vec3 eye, const vec3 target);
/* A camera at `eye` looking at `target` (target == eye keeps yaw = pitch = 0). */
camera camera_look_at(const vec3 eye, const vec3 target, float fov_y);
/* The same with the field of view in degrees (scene files and the command line speak degrees). */
camera camera_look_at_deg(const vec3 eye, const vec3 target, float fov_y_deg);
camera_basis camera_get_basis(const camera *c);

/* Moves and turns by one frame of input: speed in m/s, sensitivity in radians per pixel. */
void camera_update(camera *c, const camera_input *in, float dt, float speed, float sensitivity);

/* Safe flight. free_from and free_to bound the free space around `from` and around the proposed `to`
 * (a distance bound times its step factor: no surface lies closer). If the two free balls cover the
 * segment (|to − from| < free_from + free_to, less float resolution) the move cannot cross a surface
 * and is kept; else it is shortened to CAMERA_SAFE_FRACTION of free_from. Either way the camera stays
 * float resolution away from any surface, and can always move away from one. free_from <= 0 (inside a
 * solid, or unknown) leaves the move alone, so a camera inside can get out. Returns the fraction kept. */
#define CAMERA_SAFE_FRACTION 0.9f
float camera_clamp_step(const vec3 from, vec3 to, float free_from, float free_to);

/* Keeps pos within max_distance of centre (along the line from centre): no flight to infinity. */
void camera_clamp_range(vec3 pos, const vec3 centre, float max_distance);

/* The unit primary-ray direction through pixel (x, y) of a width × height image (see top). */
void camera_ray(const camera *c, int width, int height, float x, float y, vec3 dir);

/* Angle one pixel spans at the image centre: 2 tan(fov/2) / height. Hit thresholds scale with it. */
float camera_pixel_angle(const camera *c, int height);

#endif
