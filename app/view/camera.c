#include "view/camera.h"

#include <float.h>

#include <math.h>
#include <string.h>

static float clampf(float v, float lo, float hi) { return v < lo ? lo : v > hi ? hi : v; }

const char *const CAMERA_PROJECTIONS[PROJECTION_COUNT + 1] = {"perspective", "orthographic", "equirectangular",
                                                               "fisheye", NULL};
const char *const CAMERA_STEREOS[STEREO_COUNT + 1] = {"none", "side-by-side", "top-bottom", NULL};

double camera_distance(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return camera_norm(d);
}

double camera_norm(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

camera camera_look_at(const double eye[3], const double target[3], float fov_y)
{
    camera c = {.fov_y = fov_y};
    double d[3];
    for (int i = 0; i < 3; i++) {
        c.position[i] = eye[i];
        d[i] = target[i] - eye[i];
    }
    double len = camera_norm(d);
    if (len > 0) {
        c.yaw = (float)atan2(-d[0], -d[2]);
        c.pitch = clampf((float)asin(fmin(fmax(d[1] / len, -1.0), 1.0)), -CAMERA_MAX_PITCH, CAMERA_MAX_PITCH);
    }
    return c;
}

bool camera_degenerate(const double eye[3], const double target[3])
{
    /* double positions: a deep zoom looks at a point 1e-13 away; nearer than a few ulps is no direction */
    return !(camera_distance(eye, target) > 8 * DBL_EPSILON * (1.0 + camera_norm(eye)));
}

camera camera_look_at_deg(const double eye[3], const double target[3], float fov_y_deg)
{
    return camera_look_at(eye, target, glm_rad(fov_y_deg));
}

camera camera_look_at_up(const double eye[3], const double target[3], const double up[3], float fov_y)
{
    camera c = camera_look_at(eye, target, fov_y);
    double d[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}, len = camera_norm(d);
    if (!up || !(len > 0) || (up[0] == 0 && up[2] == 0 && up[1] > 0))
        return c;
    vec3 f = {(float)(d[0] / len), (float)(d[1] / len), (float)(d[2] / len)}, u = {(float)up[0], (float)up[1], (float)up[2]}, r;
    glm_vec3_cross(f, u, r);
    if (!(glm_vec3_norm(r) > 1e-6f * glm_vec3_norm(u))) /* up along the view: the level camera */
        return c;
    glm_vec3_normalize(r);
    glm_vec3_cross(r, f, u);
    camera_set_basis(&c, f, u);
    return c;
}

camera_basis camera_get_basis(const camera *c)
{
    camera_basis b;
    float cp = cosf(c->pitch), sp = sinf(c->pitch), cy = cosf(c->yaw), sy = sinf(c->yaw);
    b.forward[0] = -sy * cp;
    b.forward[1] = sp;
    b.forward[2] = -cy * cp;
    /* the level right (horizontal: forward × world up) and up, then turned by the roll */
    vec3 r0 = {cy, 0, -sy}, u0;
    glm_vec3_cross(r0, b.forward, u0);
    float cr = cosf(c->roll), sr = sinf(c->roll);
    for (int i = 0; i < 3; i++) {
        b.right[i] = cr * r0[i] + sr * u0[i];
        b.up[i] = cr * u0[i] - sr * r0[i];
    }
    return b;
}

void camera_set_basis(camera *c, vec3 forward, vec3 up)
{
    float cp = sqrtf(forward[0] * forward[0] + forward[2] * forward[2]);
    c->pitch = atan2f(forward[1], cp);
    if (cp > 1e-6f) {
        c->yaw = atan2f(-forward[0], -forward[2]);
        camera level = {.yaw = c->yaw, .pitch = c->pitch};
        camera_basis b = camera_get_basis(&level);
        vec3 right;
        glm_vec3_cross(forward, up, right);
        c->roll = atan2f(glm_vec3_dot(right, b.up), glm_vec3_dot(right, b.right));
    } else { /* straight up or down: the level right is the camera's right, roll 0 */
        vec3 right;
        glm_vec3_cross(forward, up, right);
        c->yaw = atan2f(-right[2], right[0]);
        c->roll = 0;
    }
}

/* v turned by angle a about the unit axis k (Rodrigues), in float. */
static void turn(vec3 v, vec3 k, float a)
{
    glm_vec3_rotate(v, a, k);
}

void camera_turn(camera *c, float dyaw, float dpitch, float droll)
{
    camera_basis b = camera_get_basis(c);
    /* yaw about the camera's up, then pitch about its (turned) right, then roll about its view */
    turn(b.forward, b.up, dyaw);
    turn(b.right, b.up, dyaw);
    turn(b.forward, b.right, dpitch);
    turn(b.up, b.right, dpitch);
    turn(b.up, b.forward, -droll); /* about −forward: right turns toward up */
    turn(b.right, b.forward, -droll);
    /* orthonormal again (turns add up): right = forward × up, up = right × forward */
    glm_vec3_normalize(b.forward);
    glm_vec3_cross(b.forward, b.up, b.right);
    glm_vec3_normalize(b.right);
    glm_vec3_cross(b.right, b.forward, b.up);
    camera_set_basis(c, b.forward, b.up);
}

void camera_update(camera *c, const camera_input *in, float dt, float speed, float sensitivity)
{
    static const float FAST_FACTOR = 4.0f;
    if (in->free) {
        camera_turn(c, -in->look[0] * sensitivity, -in->look[1] * sensitivity, in->roll * CAMERA_ROLL_RATE * dt);
    } else {
        c->yaw -= in->look[0] * sensitivity;
        c->pitch = clampf(c->pitch - in->look[1] * sensitivity, -CAMERA_MAX_PITCH, CAMERA_MAX_PITCH);
        c->roll = remainderf(c->roll + in->roll * CAMERA_ROLL_RATE * dt, 2.0f * GLM_PIf);
    }
    c->yaw = remainderf(c->yaw, 2.0f * GLM_PIf);
    camera_basis b = camera_get_basis(c);
    double step = (double)speed * (double)dt * (in->fast ? FAST_FACTOR : 1.0);
    vec3 up = {0, 1, 0};
    if (in->free)
        glm_vec3_copy(b.up, up);
    for (int i = 0; i < 3; i++)
        c->position[i] += step * ((double)(in->move[0] * b.right[i]) + (double)(in->move[2] * b.forward[i]) +
                                  (double)(in->move[1] * up[i]));
}

double camera_resolution(const double p[3], bool deep)
{
    /* 4 ulps of the largest coordinate's magnitude, and of 1 near the origin */
    double ulp = deep ? DBL_EPSILON : (double)FLT_EPSILON;
    return 8.0 * ulp * (1.0 + camera_norm(p));
}

/* The tetrahedron of central differences: the gradient is the sum of k[i] · f(p + h k[i]). */
static const double TETRAHEDRON[4][3] = {{1, -1, -1}, {-1, -1, 1}, {-1, 1, -1}, {1, 1, 1}};

/* The distance's gradient at `from` from the tetrahedron's four probes, unit or 0. */
static void slide_normal(const float d[4], double n[3])
{
    const double(*k)[3] = TETRAHEDRON;
    for (int i = 0; i < 3; i++)
        n[i] = k[0][i] * d[0] + k[1][i] * d[1] + k[2][i] * d[2] + k[3][i] * d[3];
    double len = camera_norm(n);
    for (int i = 0; i < 3; i++)
        n[i] = len > 0 ? n[i] / len : 0.0;
}

/* Where the samples lie along a leg, as fractions in increasing order. The slide (CAMERA_SLIDE_SAMPLES):
 * CAMERA_SLIDE_NEAR of them geometrically close to the start (a move away from a surface the camera
 * is near: each free ball there is small), then CAMERA_SLIDE_UNIFORM evenly to the end (a move
 * along a surface, CAMERA_SKIN away from it). The lift (CAMERA_LIFT_SAMPLES, straight out from a
 * surface): geometrically, each free ball about twice the last. */
static double slide_fraction(int i)
{
    if (i < CAMERA_SLIDE_NEAR)
        return ldexp(1.0 / CAMERA_SLIDE_UNIFORM, i - CAMERA_SLIDE_NEAR);
    return (double)(i - CAMERA_SLIDE_NEAR + 1) / CAMERA_SLIDE_UNIFORM;
}

static double lift_fraction(int i) { return ldexp(1.0, i - (CAMERA_LIFT_SAMPLES - 1)); }

/* How far along a leg of length `len` a chain of free balls reaches from its start (free radius
 * `reach`): the fraction of the last sample it covers that lies `resolution` clear of any surface.
 * *last gets that sample's free radius. */
static double covered(const float *d, int n, double (*fraction)(int), double len, double reach, float step_factor,
                      double resolution, double *last)
{
    double keep = 0.0;
    for (int j = 0; j < n; j++) {
        double t = len * fraction(j), r = (double)d[j] * (double)step_factor - resolution;
        if (!(r > 0) || t - r > reach)
            break;
        reach = fmax(reach, t + r);
        keep = fraction(j);
        *last = r;
    }
    return keep;
}

float camera_slide(const double from[3], double to[3], float step_factor, double resolution, camera_probe_fn probe,
                   void *ctx, double corner[3])
{
    double corner_here[3];
    corner = corner ? corner : corner_here;
    for (int i = 0; i < 3; i++)
        corner[i] = from[i];
    double m[3] = {to[0] - from[0], to[1] - from[1], to[2] - from[2]};
    double len = camera_norm(m);
    if (!(len > 0))
        return 1.0f;
    /* the distance at `from` and its gradient */
    const double(*k)[3] = TETRAHEDRON;
    enum { N = CAMERA_LIFT_SAMPLES + CAMERA_SLIDE_SAMPLES };
    double h = fmax(4.0 * resolution, 1e-3 * len), pts[N * 3];
    float d[N];
    for (int j = 0; j < 5; j++)
        for (int i = 0; i < 3; i++)
            pts[3 * j + i] = from[i] + (j ? h * k[j - 1][i] : 0.0);
    probe(ctx, pts, 5, d);
    double free0 = (double)d[0] * (double)step_factor;
    if (!(free0 > 0)) /* inside a solid, or unknown: let the camera out */
        return 1.0f;
    /* the camera keeps CAMERA_SKIN of its step from surfaces: closer, it first lifts straight out to
     * there (leg 1); then it moves, the part of the move into the surface cut so that it stays there,
     * the rest sliding along (leg 2) */
    double n[3], skin = fmax(CAMERA_SKIN * len, 4.0 * resolution);
    slide_normal(d + 1, n);
    double lift = camera_norm(n) > 0 ? fmax(skin - free0, 0.0) : 0.0, start[3];
    for (int i = 0; i < 3; i++)
        start[i] = from[i] + lift * n[i];
    double into = -(m[0] * n[0] + m[1] * n[1] + m[2] * n[2]), allowed = fmax(free0 + lift - skin, 0.0);
    if (into > allowed)
        for (int i = 0; i < 3; i++)
            m[i] += (into - allowed) * n[i];
    /* both legs' free balls in one probe */
    for (int j = 0; j < CAMERA_LIFT_SAMPLES; j++)
        for (int i = 0; i < 3; i++)
            pts[3 * j + i] = from[i] + lift * n[i] * lift_fraction(j);
    for (int j = 0; j < CAMERA_SLIDE_SAMPLES; j++)
        for (int i = 0; i < 3; i++)
            pts[3 * (CAMERA_LIFT_SAMPLES + j) + i] = start[i] + m[i] * slide_fraction(j);
    probe(ctx, pts, N, d);
    double last = free0 - resolution, keep1 = 1.0, keep2 = 0.0, slid = camera_norm(m);
    if (lift > 0)
        keep1 = covered(d, CAMERA_LIFT_SAMPLES, lift_fraction, lift, free0 - resolution, step_factor, resolution, &last);
    if (keep1 == 1.0)
        keep2 = covered(d + CAMERA_LIFT_SAMPLES, CAMERA_SLIDE_SAMPLES, slide_fraction, slid, last, step_factor,
                        resolution, &last);
    if (keep1 < 1.0 && keep1 * lift < CAMERA_SAFE_FRACTION * free0) { /* no way out: what the start's own free ball allows */
        keep1 = 0.0;
        keep2 = slid > 0 ? fmin(fmax(CAMERA_SAFE_FRACTION * free0 - resolution, 0.0) / slid, 1.0) : 0.0;
    }
    for (int i = 0; i < 3; i++) {
        corner[i] = from[i] + lift * n[i] * keep1;
        to[i] = corner[i] + m[i] * keep2;
    }
    return (float)(keep2 * slid / len);
}

int camera_steps(float dt, float *step_dt)
{
    int steps = (int)ceilf(dt / CAMERA_STEP_S - 1e-3f);
    steps = steps < 1 ? 1 : steps > CAMERA_MAX_STEPS ? CAMERA_MAX_STEPS : steps;
    *step_dt = fminf(dt, CAMERA_STEP_S * (float)steps) / (float)steps;
    return steps;
}

int camera_travel(camera *c, const camera_input *in, float dt, const camera_travel_rule *r, camera_probe_fn probe,
                  void *ctx)
{
    float step_dt;
    int steps = camera_steps(dt, &step_dt);
    camera_input step = *in;
    for (int k = 0; k < steps; k++) {
        double before[3];
        memcpy(before, c->position, sizeof before);
        float speed = r->speed;
        if (r->per_distance) {
            float d;
            probe(ctx, c->position, 1, &d);
            speed *= fmaxf(fabsf(d), r->min_distance);
        }
        camera_update(c, &step, step_dt, speed, r->sensitivity);
        step.look[0] = step.look[1] = 0; /* the look turns once a frame */
        double target[3];
        memcpy(target, c->position, sizeof target);
        memcpy(c->position, before, sizeof before);
        if (memcmp(before, target, sizeof before))
            camera_slide(before, target, r->step_factor, camera_resolution(before, r->deep), probe, ctx, NULL);
        memcpy(c->position, target, sizeof target);
    }
    return steps;
}

/* v rotated by angle a about the unit axis k (Rodrigues). */
static void rotate(double v[3], const double k[3], double a)
{
    double c = cos(a), s = sin(a), kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    double x[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
    for (int i = 0; i < 3; i++)
        v[i] = v[i] * c + x[i] * s + k[i] * kv * (1 - c);
}

void camera_orbit(camera *c, const double pivot[3], float dyaw, float dpitch)
{
    float pitch = clampf(c->pitch + dpitch, -CAMERA_MAX_PITCH, CAMERA_MAX_PITCH);
    dpitch = pitch - c->pitch;
    /* about the level right axis: the roll stays as it is */
    double off[3], up[3] = {0, 1, 0}, right[3] = {cos(c->yaw), 0, -sin(c->yaw)};
    for (int i = 0; i < 3; i++)
        off[i] = c->position[i] - pivot[i];
    /* a pitch up turns the view up about the camera's right axis: the camera goes down around the pivot */
    rotate(off, right, dpitch);
    rotate(off, up, dyaw);
    for (int i = 0; i < 3; i++)
        c->position[i] = pivot[i] + off[i];
    c->yaw = remainderf(c->yaw + dyaw, 2.0f * GLM_PIf);
    c->pitch = pitch;
}

void camera_clamp_range(double pos[3], const double centre[3], double max_distance)
{
    double d = camera_distance(pos, centre);
    if (d > max_distance)
        for (int i = 0; i < 3; i++)
            pos[i] = centre[i] + (pos[i] - centre[i]) * (max_distance / d);
}

void camera_eye_size(const camera *c, int width, int height, int *eye_width, int *eye_height)
{
    *eye_width = c->lens.stereo == STEREO_SIDE_BY_SIDE ? width / 2 : width;
    *eye_height = c->lens.stereo == STEREO_TOP_BOTTOM ? height / 2 : height;
}

float camera_focus(const camera *c) { return c->lens.focus > 0 ? c->lens.focus : 1.0f; }

bool camera_ray_from(const camera *c, int width, int height, float x, float y, double origin[3], vec3 dir)
{
    camera_basis b = camera_get_basis(c);
    int w, h;
    camera_eye_size(c, width, height, &w, &h);
    float eye = 0; /* -1 left, +1 right, 0 none */
    if (c->lens.stereo == STEREO_SIDE_BY_SIDE) {
        eye = x >= (float)w ? 1.0f : -1.0f;
        x -= x >= (float)w ? (float)w : 0.0f;
    } else if (c->lens.stereo == STEREO_TOP_BOTTOM) { /* left eye on top: GL rows count up */
        eye = y >= (float)h ? -1.0f : 1.0f;
        y -= y >= (float)h ? (float)h : 0.0f;
    }
    float aspect = (float)w / (float)h, t = tanf(0.5f * c->fov_y), focus = camera_focus(c);
    float sx = 2.0f * (x + 0.5f) / (float)w - 1.0f, sy = 2.0f * (y + 0.5f) / (float)h - 1.0f;
    vec3 d, offset = {0, 0, 0}; /* d: the direction from the eye; offset: the ray's start from it */
    bool sees = true;
    switch (c->lens.projection) {
    case PROJECTION_ORTHOGRAPHIC:
        glm_vec3_copy(b.forward, d);
        for (int i = 0; i < 3; i++)
            offset[i] = (sx * aspect * b.right[i] + sy * b.up[i]) * focus * t;
        break;
    case PROJECTION_EQUIRECTANGULAR: {
        float lon = GLM_PIf * sx, lat = 0.5f * GLM_PIf * sy;
        for (int i = 0; i < 3; i++)
            d[i] = cosf(lat) * (sinf(lon) * b.right[i] + cosf(lon) * b.forward[i]) + sinf(lat) * b.up[i];
        /* omnidirectional stereo: the eye on a circle, at right angles to the ray's horizontal direction */
        for (int i = 0; i < 3; i++)
            offset[i] = eye * 0.5f * c->lens.eye_separation * (cosf(lon) * b.right[i] - sinf(lon) * b.forward[i]);
        eye = 0;
        break;
    }
    case PROJECTION_FISHEYE: {
        float px = sx * aspect, r = sqrtf(px * px + sy * sy), th = 0.5f * GLM_PIf * r;
        sees = r <= 1.0f;
        float k = r > 0 ? sinf(th) / r : 0.5f * GLM_PIf;
        for (int i = 0; i < 3; i++)
            d[i] = cosf(th) * b.forward[i] + k * (px * b.right[i] + sy * b.up[i]);
        break;
    }
    default:
        for (int i = 0; i < 3; i++)
            d[i] = b.forward[i] + sx * t * aspect * b.right[i] + sy * t * b.up[i];
    }
    glm_vec3_normalize(d);
    if (eye != 0) { /* an eye beside the centre, aiming so that the focal plane has no disparity */
        float along = c->lens.projection == PROJECTION_PERSPECTIVE ? focus / glm_vec3_dot(d, b.forward) : focus;
        for (int i = 0; i < 3; i++) {
            float e = eye * 0.5f * c->lens.eye_separation * b.right[i];
            d[i] = d[i] * along + offset[i] - (offset[i] + e);
            offset[i] += e;
        }
        glm_vec3_normalize(d);
    }
    glm_vec3_copy(d, dir);
    for (int i = 0; i < 3; i++)
        origin[i] = c->position[i] + (double)offset[i];
    return sees;
}

void camera_ray(const camera *c, int width, int height, float x, float y, vec3 dir)
{
    double origin[3];
    camera_ray_from(c, width, height, x, y, origin, dir);
}

float camera_pixel_angle(const camera *c, int height)
{
    int w, h;
    camera_eye_size(c, height, height, &w, &h);
    if (c->lens.projection == PROJECTION_EQUIRECTANGULAR || c->lens.projection == PROJECTION_FISHEYE)
        return GLM_PIf / (float)h;
    return 2.0f * tanf(0.5f * c->fov_y) / (float)h;
}

float camera_footprint_t0(const camera *c)
{
    return c->lens.projection == PROJECTION_ORTHOGRAPHIC ? camera_focus(c) : 0.0f;
}

bool camera_matrices(const camera *c, int width, int height, int eye, float world_to_camera[16], float world_to_ndc[16])
{
    camera_basis b = camera_get_basis(c);
    const float *axes[3] = {b.right, b.up, b.forward};
    bool stereo = c->lens.stereo != STEREO_NONE;
    eye = stereo ? (eye > 0 ? 1 : -1) : 0;
    float e = (float)eye * 0.5f * c->lens.eye_separation; /* the eye's place along right */
    float *m = world_to_camera;
    for (int j = 0; j < 3; j++) { /* column j: the camera axis; the last row: −eye · axis */
        double t = 0;
        for (int i = 0; i < 3; i++) {
            m[4 * i + j] = axes[j][i];
            t += c->position[i] * (double)axes[j][i];
        }
        m[12 + j] = (float)-t - (j == 0 ? e : 0.0f);
        m[4 * j + 3] = 0;
    }
    m[15] = 1;
    int w, h;
    camera_eye_size(c, width, height, &w, &h);
    float ty = tanf(0.5f * c->fov_y), tx = ty * (float)w / (float)h, focus = camera_focus(c);
    bool ortho = c->lens.projection == PROJECTION_ORTHOGRAPHIC;
    if (!ortho && c->lens.projection != PROJECTION_PERSPECTIVE)
        return false;
    /* camera (x, y, z, 1) → (X, Y, Z, W): perspective X/W = ½ + ½ x / (z tx), Y/W = ½ − ½ y / (z ty),
     * W = z, Z = 1; orthographic the same with focus for z in the scale and W = 1, Z = z. An eye aims so
     * that the focal plane has no disparity (camera_ray_from): its x shifts by e·z/focus (orthographic) or
     * its x/z by e/focus (perspective) */
    float s = ortho ? focus : 1.0f, p[16] = {0};
    p[0] = 0.5f / (tx * s);
    p[5] = -0.5f / (ty * s);
    if (ortho) {
        p[10] = 1, p[12] = 0.5f, p[13] = 0.5f, p[15] = 1;
        p[8] = e / (2 * tx * focus * focus);
    } else {
        p[8] = 0.5f + e / (2 * tx * focus), p[9] = 0.5f, p[11] = 1, p[14] = 1;
    }
    for (int r = 0; r < 4; r++) /* world_to_ndc = world_to_camera · p */
        for (int k = 0; k < 4; k++) {
            float v = 0;
            for (int j = 0; j < 4; j++)
                v += m[4 * r + j] * p[4 * j + k];
            world_to_ndc[4 * r + k] = v;
        }
    /* the eye's half of the whole image: side by side the left eye left, top-bottom the left eye on top; a
     * coordinate u of the eye is (u + half) / 2 of the image, u·W being column 0 (x) or 1 (y) */
    int col = c->lens.stereo == STEREO_SIDE_BY_SIDE ? 0 : 1;
    float half = eye > 0 ? 1.0f : 0.0f;
    for (int r = 0; stereo && r < 4; r++)
        world_to_ndc[4 * r + col] = 0.5f * (world_to_ndc[4 * r + col] + half * world_to_ndc[4 * r + 3]);
    return true;
}
