/* camera — free-fly camera maths. Pure functions over a small struct (cglm), no GL, no input state.
 *
 * Conventions: right-handed, Y up. The orientation is yaw about +Y, then pitch about the camera's
 * level right axis, then roll about its view direction (R = Ry(yaw) Rx(pitch) Rz(roll) turning the
 * frame right = +X, up = +Y, forward = −Z). yaw = 0 looks down −Z; yaw grows turning left
 * (counter-clockwise seen from above); pitch > 0 looks up (the mouse stops it short of ±90°, a file
 * may give ±90° exactly); roll > 0 turns the camera's right toward its up (counter-clockwise as the
 * camera sees it: the world in the image turns clockwise). roll = 0 keeps the horizon level.
 *
 * Primary rays (shaders/common/camera.glsl does the same per sample): pixel (x, y) counts from the
 * bottom-left (GL's window origin), its centre at +0.5; with stereo each eye is half the image (left
 * eye: the left half, or the top half) and (x, y), width and height are the eye's. sx = 2 (x + 0.5) /
 * width − 1, sy = 2 (y + 0.5) / height − 1, aspect = width / height, t = tan(fov/2):
 *   perspective      dir = normalize(forward + sx t aspect right + sy t up), from the eye;
 *   orthographic     dir = forward, from eye + (sx aspect right + sy up) · focus t: the plane at the
 *                    focal distance is framed as the perspective camera frames it;
 *   equirectangular  longitude λ = π sx (0 straight ahead, > 0 to the right), latitude φ = π sy / 2:
 *                    dir = cos φ (sin λ right + cos λ forward) + sin φ up (360° × 180°, fov unused);
 *   fisheye          equidistant, 180° across the height: r = |(sx aspect, sy)|, θ = r π/2 off the axis;
 *                    pixels with r > 1 see nothing (fulldome / domemaster).
 * A thin lens (aperture > 0): each sample's ray leaves a point of the lens disc (radius `aperture`,
 * in the right/up plane through the eye) toward the point the pinhole ray meets at the focal
 * distance (measured along forward; along the ray for equirectangular and fisheye), so the plane at
 * the focal distance is sharp and a point at distance d spreads to a disc of radius
 * aperture · |d − focus| / d on the focal plane (the circle of confusion).
 * Stereo: the eyes sit at ∓eye_separation/2 along right and aim so that the focal plane has no
 * disparity (off-axis, as a lens offset); for equirectangular, omnidirectional stereo: each ray's eye
 * lies on the circle of radius eye_separation/2, at right angles to the ray's horizontal direction, and
 * a pixel's two rays are parallel: they converge at infinity, whatever the focus.
 * fov is the vertical field of view in radians.
 */
#ifndef FATHOM_CAMERA_H
#define FATHOM_CAMERA_H

#include <cglm/cglm.h>
#include <stdbool.h>

typedef enum camera_projection {
    PROJECTION_PERSPECTIVE,
    PROJECTION_ORTHOGRAPHIC,
    PROJECTION_EQUIRECTANGULAR,
    PROJECTION_FISHEYE,
    PROJECTION_COUNT
} camera_projection;
typedef enum camera_stereo { STEREO_NONE, STEREO_SIDE_BY_SIDE, STEREO_TOP_BOTTOM, STEREO_COUNT } camera_stereo;
/* The names files and the command line use, in enum order. */
extern const char *const CAMERA_PROJECTIONS[PROJECTION_COUNT + 1];
extern const char *const CAMERA_STEREOS[STEREO_COUNT + 1];

/* How the camera images the world (see top); zero is today's pinhole perspective. */
typedef struct camera_lens {
    camera_projection projection;
    float aperture;       /* thin lens radius (world units); 0: a pinhole, all sharp */
    float focus;          /* focal distance (world units); 0: not set (callers set the look-at distance) */
    camera_stereo stereo;
    float eye_separation; /* world units, between the eyes */
} camera_lens;

typedef struct camera {
    double position[3]; /* double: a deep zoom resolves detail far below a float's step at |p| ~ 1 */
    float yaw, pitch, roll; /* radians */
    float fov_y;      /* radians */
    camera_lens lens;
} camera;

typedef struct camera_basis {
    vec3 forward, right, up;
} camera_basis;

/* What the user asks for this frame; the caller maps keys and mouse to it. */
typedef struct camera_input {
    float move[3];     /* right, up, forward: each -1..1 */
    float look[2];     /* mouse delta in pixels: x right, y down */
    float roll;        /* Q/E: -1..1, > 0 rolls the camera's right toward its up at CAMERA_ROLL_RATE */
    bool fast;         /* Shift */
    bool free;         /* free flight: turns about the camera's own axes and up is its up; else the
                          horizon stays as it is (yaw about the world's vertical, pitch limited) */
} camera_input;
#define CAMERA_ROLL_RATE 1.5f /* radians per second */

#define CAMERA_MAX_PITCH 1.5533430f /* 89 degrees */
/* Camera and look-at coordinates lie within ±CAMERA_MAX_COORD metres: beyond, a float cannot tell a
 * camera from its look-at point a few metres away. */
#define CAMERA_MAX_COORD 1e7

/* True when target is (within float rounding of) eye: no direction to look in. Scene files and the
 * command line refuse it. */
bool camera_degenerate(const double eye[3], const double target[3]);
/* A camera at `eye` looking at `target` (target == eye keeps yaw = pitch = 0). */
camera camera_look_at(const double eye[3], const double target[3], float fov_y);
/* The same with the field of view in degrees (scene files and the command line speak degrees). */
camera camera_look_at_deg(const double eye[3], const double target[3], float fov_y_deg);
/* The same with the image's up toward `up` (a world direction, not along the view; NULL or +Y: level):
 * roll follows from it, and pitch may be ±90° exactly (a Z-up camera looking along −Y). */
camera camera_look_at_up(const double eye[3], const double target[3], const double up[3], float fov_y);
camera_basis camera_get_basis(const camera *c);
/* yaw, pitch and roll from a forward and up direction (unit, at right angles): camera_get_basis's
 * inverse. Straight up or down, yaw takes the whole turn about the view and roll is 0. */
void camera_set_basis(camera *c, vec3 forward, vec3 up);
/* Turns the camera about its own axes: dyaw about its up, dpitch about its right, droll about its
 * view (a free flight: no horizon kept, no pitch limit). Signs as camera_update's. */
void camera_turn(camera *c, float dyaw, float dpitch, float droll);

/* Moves and turns by one frame of input: speed in m/s, sensitivity in radians per pixel. Up/down moves
 * along the world's vertical, or in free flight along the camera's up. */
void camera_update(camera *c, const camera_input *in, float dt, float speed, float sensitivity);

/* Safe flight that slides. The renderer's distance bound (times its step factor) around a point is
 * free of surfaces. The camera is a ball CAMERA_SKIN of its step wide: closer than that to a surface
 * (the gradient of the distance at `from` gives its normal) it first lifts straight out to that
 * clearance; then the part of the move into the surface is cut so that it keeps that clearance, and
 * the rest slides along the surface. Each leg is kept as far as a chain of free balls, centred on
 * samples along it, covers it from its start, and ends on a sample at least `resolution` clear: the
 * camera never crosses or enters a solid, never sticks to a surface (the skin shrinks with the step,
 * so a slower camera comes closer), and moving away from a surface is never held back. Inside a
 * solid (a bound <= 0 at `from`) the move is left alone, so a camera can get out.
 * probe(ctx, points, n, out) fills out[i] with the distance bound at points[i] (xyz each);
 * resolution: the smallest step the renderer resolves there (camera_resolution). corner (may be
 * NULL) gets the end of the first leg: the camera's path is from → corner → to. Returns the fraction
 * of the move's length kept along the second leg. */
typedef void (*camera_probe_fn)(void *ctx, const double *points, int n, float *out);
enum { CAMERA_SLIDE_UNIFORM = 16, CAMERA_SLIDE_NEAR = 8,
       CAMERA_SLIDE_SAMPLES = CAMERA_SLIDE_UNIFORM + CAMERA_SLIDE_NEAR, CAMERA_LIFT_SAMPLES = 12 };
#define CAMERA_SKIN (2.0 / CAMERA_SLIDE_UNIFORM) /* of the step: free balls of neighbours still overlap */
#define CAMERA_SAFE_FRACTION 0.9 /* of the start's free ball: always a safe move */
float camera_slide(const double from[3], double to[3], float step_factor, double resolution, camera_probe_fn probe,
                   void *ctx, double corner[3]);

/* One frame's flight of dt seconds by real time: steps of at most CAMERA_STEP_S each, every step through
 * the slide rule, so a slow frame (2 fps) moves the camera as far as the same time at 30 fps would. The
 * look turns once. speed: m/s, or with per_distance that many times the distance bound at the camera
 * (at least min_distance: some speed at the surface). A frame longer than CAMERA_MAX_STEPS steps
 * moves that far only (a stalled machine does not jump the camera). Returns the steps taken. */
#define CAMERA_STEP_S (1.0f / 30.0f)
enum { CAMERA_MAX_STEPS = 60 };
typedef struct camera_travel_rule {
    float speed, sensitivity;
    bool per_distance;
    float min_distance;
    float step_factor; /* the renderer's: its distance bound times this is free */
    bool deep;         /* the renderer works in double here (camera_resolution) */
} camera_travel_rule;
int camera_travel(camera *c, const camera_input *in, float dt, const camera_travel_rule *r, camera_probe_fn probe,
                  void *ctx);
/* The steps a frame of dt seconds moves in, and each one's length (*step_dt): camera_travel's, for a
 * caller that moves its own way (walking). */
int camera_steps(float dt, float *step_dt);

/* The position's resolution where the renderer works in float (deep = false) or in double (a deep
 * zoom): a few units in the last place of |p|, with room. */
double camera_resolution(const double p[3], bool deep);

/* Turntable about a pivot: the camera turns by dyaw about the vertical through the pivot and by dpitch
 * about its own horizontal axis through the pivot, its view turning with it, so the pivot stays
 * where it is on the screen (the point under the cursor a drag started on). Pitch stops short of
 * ±CAMERA_MAX_PITCH. */
void camera_orbit(camera *c, const double pivot[3], float dyaw, float dpitch);

/* Keeps pos within max_distance of centre (along the line from centre): no flight to infinity. */
void camera_clamp_range(double pos[3], const double centre[3], double max_distance);

/* |a − b| and |a| in double (positions are double). */
double camera_distance(const double a[3], const double b[3]);
double camera_norm(const double a[3]);

/* The unit primary-ray direction through pixel (x, y) of a width × height image (see top): the centre
 * of the lens (or of the eye), no lens sample. */
void camera_ray(const camera *c, int width, int height, float x, float y, vec3 dir);
/* The same with the ray's origin; false where the pixel sees nothing (outside a fisheye's circle). */
bool camera_ray_from(const camera *c, int width, int height, float x, float y, double origin[3], vec3 dir);

/* One eye's image: the whole image, or half of it with stereo. */
void camera_eye_size(const camera *c, int width, int height, int *eye_width, int *eye_height);

/* Angle one pixel spans at the image centre: 2 tan(fov/2) / eye height (perspective and orthographic),
 * π / eye height (equirectangular and fisheye). Hit thresholds scale with the footprint
 * angle · (t + camera_footprint_t0): a pixel's width at distance t along its ray. */
float camera_pixel_angle(const camera *c, int height);
/* 0, or for orthographic the focal distance: its pixels are focus · angle wide from the start. */
float camera_footprint_t0(const camera *c);
/* The focal distance camera_ray_from and the shader use: lens.focus, or 1 where it is not set. */
float camera_focus(const camera *c);

/* The camera for compositors, as OpenEXR's worldToCamera and worldToNDC attributes hold it: Imath's
 * row-vector matrices (p' = [x y z 1] · M, M[row][column] at m[4 row + column]). Camera space is
 * OpenEXR's: left-handed, x right, y up, z along the view, the eye at the origin. NDC: x from 0 (left
 * edge) to 1 (right), y from 0 (top) to 1 (bottom), after the divide by w (the depth along the view,
 * perspective; 1, orthographic); z/w = 1/depth (perspective), depth (orthographic). Equirectangular and
 * fisheye have no such matrix: false, and only world_to_camera is filled. width and height: the whole image.
 * With stereo, eye's (−1 left, +1 right; 0 is taken as left): its camera sits eye_separation/2 along x, and its
 * NDC is the whole image's, so a point seen by the left eye lands in the left (side by side) or top
 * (top-bottom) half where that eye drew it. Without stereo, eye is ignored. */
bool camera_matrices(const camera *c, int width, int height, int eye, float world_to_camera[16], float world_to_ndc[16]);

#endif
