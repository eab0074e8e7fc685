/* path — see path.h. */
#include "view/path.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/camera.h"

static const double DEG = 3.14159265358979323846 / 180.0;

/* ---- quaternions (x, y, z, w) ---- */

static void q_mul(const double a[4], const double b[4], double o[4])
{
    double r[4] = {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
                   a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
                   a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
                   a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
    memcpy(o, r, sizeof r);
}

static void q_normalize(double q[4])
{
    double l = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int k = 0; k < 4; k++)
        q[k] /= l;
}

static double q_dot(const double a[4], const double b[4])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

/* log of a unit quaternion: a pure quaternion (axis · half angle) */
static void q_log(const double q[4], double o[4])
{
    double v = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    double a = atan2(v, q[3]), k = v > 1e-15 ? a / v : 1.0;
    o[0] = q[0] * k;
    o[1] = q[1] * k;
    o[2] = q[2] * k;
    o[3] = 0;
}

static void q_exp(const double p[4], double o[4])
{
    double a = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), k = a > 1e-15 ? sin(a) / a : 1.0;
    o[0] = p[0] * k;
    o[1] = p[1] * k;
    o[2] = p[2] * k;
    o[3] = cos(a);
}

static void q_slerp(const double a[4], const double b[4], double u, double o[4])
{
    double d = q_dot(a, b);
    if (d > 0.9995) { /* nearly parallel: the normalized lerp is exact to rounding */
        for (int k = 0; k < 4; k++)
            o[k] = a[k] + u * (b[k] - a[k]);
        q_normalize(o);
        return;
    }
    d = fmax(-1.0, fmin(1.0, d));
    double th = acos(d), s = sin(th), wa = sin((1 - u) * th) / s, wb = sin(u * th) / s;
    for (int k = 0; k < 4; k++)
        o[k] = wa * a[k] + wb * b[k];
    q_normalize(o);
}

/* The camera's orientation: yaw about +Y, then pitch about the camera's right axis, then roll about
 * its view (camera.h). */
static void q_from_angles(double yaw, double pitch, double roll, double q[4])
{
    double qy[4] = {0, sin(yaw / 2), 0, cos(yaw / 2)}, qx[4] = {sin(pitch / 2), 0, 0, cos(pitch / 2)};
    double qz[4] = {0, 0, sin(roll / 2), cos(roll / 2)}, qyx[4];
    q_mul(qy, qx, qyx);
    q_mul(qyx, qz, q);
}

/* yaw, pitch and roll of a camera frame: its unit forward f and right r (camera_set_basis's rule:
 * straight up or down, roll 0 and yaw the whole turn) */
static void frame_angles(const double f[3], const double r[3], double *yaw, double *pitch, double *roll)
{
    double cp = sqrt(f[0] * f[0] + f[2] * f[2]);
    *pitch = atan2(f[1], cp);
    if (cp > 1e-9) {
        *yaw = atan2(-f[0], -f[2]);
        /* the level right r0 = (cos yaw, 0, −sin yaw) and up u0 = r0 × f; right = r0 cos roll + u0 sin roll */
        double r0[3] = {cos(*yaw), 0, -sin(*yaw)};
        double u0[3] = {r0[1] * f[2] - r0[2] * f[1], r0[2] * f[0] - r0[0] * f[2], r0[0] * f[1] - r0[1] * f[0]};
        *roll = atan2(r[0] * u0[0] + r[1] * u0[1] + r[2] * u0[2], r[0] * r0[0] + r[2] * r0[2]);
    } else {
        *yaw = atan2(-r[2], r[0]);
        *roll = 0;
    }
}

/* forward = q (0, 0, −1) q*, right = q (1, 0, 0) q* */
static void q_to_angles(const double q[4], double *yaw, double *pitch, double *roll)
{
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double f[3] = {-(2 * (x * z + w * y)), -(2 * (y * z - w * x)), -(1 - 2 * (x * x + y * y))};
    double r[3] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    frame_angles(f, r, yaw, pitch, roll);
}

/* ---- the position spline ---- */

static double dist(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Centripetal Catmull–Rom on segment i (keys i → i+1) at u ∈ [0, 1], Barry–Goldman pyramid. Ends and
 * repeated points get a mirrored phantom neighbour, so no knot interval is 0. */
static void segment_point(const path *p, int i, double u, double out[3])
{
    const double *P1 = p->keys[i].position, *P2 = p->keys[i + 1].position;
    double len12 = dist(P1, P2);
    if (len12 == 0) { /* the camera holds still here */
        memcpy(out, P1, sizeof(double) * 3);
        return;
    }
    double P0[3], P3[3];
    bool have0 = i > 0 && dist(p->keys[i - 1].position, P1) > 1e-9 * len12;
    bool have3 = i + 2 < p->count && dist(p->keys[i + 2].position, P2) > 1e-9 * len12;
    for (int k = 0; k < 3; k++) {
        P0[k] = have0 ? p->keys[i - 1].position[k] : 2 * P1[k] - P2[k];
        P3[k] = have3 ? p->keys[i + 2].position[k] : 2 * P2[k] - P1[k];
    }
    double t0 = 0, t1 = t0 + sqrt(dist(P0, P1)), t2 = t1 + sqrt(len12), t3 = t2 + sqrt(dist(P2, P3));
    double t = t1 + u * (t2 - t1);
    for (int k = 0; k < 3; k++) {
        double A1 = ((t1 - t) * P0[k] + (t - t0) * P1[k]) / (t1 - t0);
        double A2 = ((t2 - t) * P1[k] + (t - t1) * P2[k]) / (t2 - t1);
        double A3 = ((t3 - t) * P2[k] + (t - t2) * P3[k]) / (t3 - t2);
        double B1 = ((t2 - t) * A1 + (t - t0) * A2) / (t2 - t0);
        double B2 = ((t3 - t) * A2 + (t - t1) * A3) / (t3 - t1);
        out[k] = ((t2 - t) * B1 + (t - t1) * B2) / (t2 - t1);
    }
}

/* |dP/du| on segment i (central differences; one-sided at the ends of [0, 1]) */
static double speed_u(const path *p, int i, double u)
{
    const double h = 1e-6;
    double a = fmax(0.0, u - h), b = fmin(1.0, u + h), pa[3], pb[3];
    segment_point(p, i, a, pa);
    segment_point(p, i, b, pb);
    return dist(pa, pb) / (b - a);
}

/* Arc length of segment i from u0 to u1: 5-point Gauss–Legendre (Abramowitz & Stegun 25.4.30) */
static double arc_between(const path *p, int i, double u0, double u1)
{
    static const double X[5] = {0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
    static const double W[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891,
                                0.2369268850561891};
    double m = 0.5 * (u0 + u1), r = 0.5 * (u1 - u0), sum = 0;
    for (int k = 0; k < 5; k++)
        sum += W[k] * speed_u(p, i, m + r * X[k]);
    return sum * r;
}

/* Cumulative arc length along each segment at PATH_ARC_SAMPLES equal steps of u, and at each key. */
static void build_arc(path *p)
{
    int segs = p->count - 1, M = PATH_ARC_SAMPLES;
    p->arc = util_alloc(sizeof(double) * (size_t)segs * (size_t)(M + 1), "path arc lengths");
    p->key_length = util_alloc(sizeof(double) * (size_t)p->count, "path arc lengths");
    p->key_length[0] = 0;
    for (int i = 0; i < segs; i++) {
        double *a = p->arc + (size_t)i * (size_t)(M + 1);
        a[0] = 0;
        for (int k = 1; k <= M; k++)
            a[k] = a[k - 1] + arc_between(p, i, (double)(k - 1) / M, (double)k / M);
        p->key_length[i + 1] = p->key_length[i] + a[M];
    }
}

/* u on segment i where the arc length from its start is s: the table brackets it, Newton's method on
 * the integral finishes it (a linear inverse alone left the speed rippling by ±1 %). */
static double segment_u(const path *p, int i, double s)
{
    int M = PATH_ARC_SAMPLES;
    const double *a = p->arc + (size_t)i * (size_t)(M + 1);
    if (a[M] <= 0)
        return 0;
    int lo = 0, hi = M;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (a[mid] <= s)
            lo = mid;
        else
            hi = mid;
    }
    double u0 = (double)lo / M, u1 = (double)hi / M;
    double w = a[hi] > a[lo] ? (s - a[lo]) / (a[hi] - a[lo]) : 0;
    double u = u0 + fmax(0.0, fmin(1.0, w)) * (u1 - u0);
    for (int it = 0; it < 3; it++) {
        double v = speed_u(p, i, u);
        if (!(v > 0))
            break;
        u = fmax(u0, fmin(u1, u - (a[lo] + arc_between(p, i, u0, u) - s) / v));
    }
    return u;
}

/* ---- cubic Hermite in time ---- */

static double hermite(double y0, double y1, double m0, double m1, double h, double u)
{
    double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * y0 + (u3 - 2 * u2 + u) * h * m0 + (-2 * u3 + 3 * u2) * y1 + (u3 - u2) * h * m1;
}

/* Catmull–Rom tangent of a track at key i (one-sided at the ends). */
static double track_tangent(const path *p, int i, const double *v, size_t stride)
{
    int a = i > 0 ? i - 1 : i, b = i + 1 < p->count ? i + 1 : i;
    return (v[(size_t)b * stride] - v[(size_t)a * stride]) / (p->keys[b].time - p->keys[a].time);
}

/* Fritsch–Carlson tangents of the arc length against time: monotone, C1. */
static void arc_tangents(const path *p, double *m)
{
    int n = p->count;
    double *d = util_alloc(sizeof(double) * (size_t)n, "path tangents");
    for (int i = 0; i + 1 < n; i++)
        d[i] = (p->key_length[i + 1] - p->key_length[i]) / (p->keys[i + 1].time - p->keys[i].time);
    m[0] = d[0];
    m[n - 1] = d[n - 2];
    for (int i = 1; i + 1 < n; i++)
        m[i] = d[i - 1] * d[i] <= 0 ? 0 : 0.5 * (d[i - 1] + d[i]);
    for (int i = 0; i + 1 < n; i++) {
        if (d[i] == 0) {
            m[i] = m[i + 1] = 0;
            continue;
        }
        double a = m[i] / d[i], b = m[i + 1] / d[i], r = a * a + b * b;
        if (r > 9) {
            double t = 3 / sqrt(r);
            m[i] = t * a * d[i];
            m[i + 1] = t * b * d[i];
        }
    }
    free(d);
}

/* ---- evaluation ---- */

static int find_segment(const path *p, double t)
{
    int lo = 0, hi = p->count - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (p->keys[mid].time <= t)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* The orientation's velocity at key i, in log space per second (a 3-vector in the quaternion's pure part):
 * the mean of the two adjacent segments' mean rates, one-sided at the ends. Both segments meeting at a
 * key use the same one, so the turn rate is continuous there whatever the keys' spacing in time. */
static void key_turn_rate(const path *p, int i, double w[4])
{
    double a[4] = {0, 0, 0, 0}, b[4] = {0, 0, 0, 0};
    int n = 0;
    for (int side = 0; side < 2; side++) {
        int j = i - 1 + side; /* segment j: keys j → j+1 */
        if (j < 0 || j + 1 >= p->count)
            continue;
        const double *q0 = p->keys[j].quat, *q1 = p->keys[j + 1].quat;
        double inv[4] = {-q0[0], -q0[1], -q0[2], q0[3]}, d[4], l[4];
        q_mul(inv, q1, d);
        q_log(d, l);
        double h = p->keys[j + 1].time - p->keys[j].time;
        for (int k = 0; k < 3; k++)
            (side ? b : a)[k] = l[k] / h;
        n++;
    }
    for (int k = 0; k < 4; k++)
        w[k] = (a[k] + b[k]) / n;
}

/* Orientation on segment i at u: a cubic Bézier on the sphere of unit quaternions, evaluated by
 * repeated slerp (Shoemake 1985), whose inner control points carry the keys' turn rates. */
static void segment_orientation(const path *p, int i, double u, double out[4])
{
    double h = p->keys[i + 1].time - p->keys[i].time, wa[4], wb[4], ea[4], eb[4], b[4][4];
    key_turn_rate(p, i, wa);
    key_turn_rate(p, i + 1, wb);
    for (int k = 0; k < 4; k++) {
        ea[k] = wa[k] * h / 3;
        eb[k] = -wb[k] * h / 3;
    }
    double xa[4], xb[4];
    q_exp(ea, xa);
    q_exp(eb, xb);
    memcpy(b[0], p->keys[i].quat, sizeof b[0]);
    q_mul(p->keys[i].quat, xa, b[1]);
    q_mul(p->keys[i + 1].quat, xb, b[2]);
    memcpy(b[3], p->keys[i + 1].quat, sizeof b[3]);
    for (int level = 3; level > 0; level--)
        for (int k = 0; k < level; k++)
            q_slerp(b[k], b[k + 1], u, b[k]);
    memcpy(out, b[0], sizeof b[0]);
}

void path_eval(const path *p, double t, path_sample *out)
{
    const path_key *K = p->keys;
    t = fmax(K[0].time, fmin(K[p->count - 1].time, t));
    int i = find_segment(p, t);
    double h = K[i + 1].time - K[i].time, u = (t - K[i].time) / h;
    /* position: arc length from the monotone cubic, then the curve at that length */
    const double *m = p->speed;
    double s = hermite(p->key_length[i], p->key_length[i + 1], m[i], m[i + 1], h, u) - p->key_length[i];
    segment_point(p, i, segment_u(p, i, s), out->position);
    segment_orientation(p, i, u, out->quat);
    q_to_angles(out->quat, &out->yaw, &out->pitch, &out->roll);
    /* fov and parameter tracks */
    out->fov_deg = hermite(K[i].fov_deg, K[i + 1].fov_deg, track_tangent(p, i, &K[0].fov_deg, sizeof *K / sizeof(double)),
                           track_tangent(p, i + 1, &K[0].fov_deg, sizeof *K / sizeof(double)), h, u);
    for (int k = 0; k < p->param_count; k++)
        out->values[k] = hermite(K[i].values[k], K[i + 1].values[k],
                                 track_tangent(p, i, &K[0].values[k], sizeof *K / sizeof(double)),
                                 track_tangent(p, i + 1, &K[0].values[k], sizeof *K / sizeof(double)), h, u);
}

double path_duration(const path *p) { return p->keys[p->count - 1].time - p->keys[0].time; }

double path_length(const path *p) { return p->key_length[p->count - 1]; }

void path_free(path *p)
{
    free(p->keys);
    free(p->arc);
    free(p->key_length);
    free(p->speed);
    memset(p, 0, sizeof *p);
}

/* ---- the file ---- */

static bool num(const cJSON *o, const char *key, double lo, double hi, double *v, const char *name, int i, err_t *err)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble) || it->valuedouble < lo || it->valuedouble > hi)
        return err_set(err, "%s: keys.%d.%s: expected a number from %g to %g", name, i, key, lo, hi);
    *v = it->valuedouble;
    return true;
}

static bool vec3_of(const cJSON *o, const char *key, double v[3], const char *name, int i, err_t *err)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 3)
        return err_set(err, "%s: keys.%d.%s: expected [x, y, z] in metres", name, i, key);
    for (int k = 0; k < 3; k++) {
        const cJSON *c = cJSON_GetArrayItem(it, k);
        if (!cJSON_IsNumber(c) || !isfinite(c->valuedouble) || fabs(c->valuedouble) > CAMERA_MAX_COORD)
            return err_set(err, "%s: keys.%d.%s: expected [x, y, z], each a number within ±%g m", name, i, key,
                           CAMERA_MAX_COORD);
        v[k] = c->valuedouble;
    }
    return true;
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* The key's orientation: yaw and pitch, or look_at (with up: the image's top toward it), then roll. */
static bool key_orientation(const cJSON *k, path_key *K, int i, const char *name, err_t *err)
{
    double yaw = 0, pitch = 0, roll = 0; /* set on every path below; GCC -O3 cannot see it */
    bool has_angles = cJSON_GetObjectItemCaseSensitive(k, "yaw") || cJSON_GetObjectItemCaseSensitive(k, "pitch");
    bool has_up = cJSON_GetObjectItemCaseSensitive(k, "up") != NULL;
    if (cJSON_GetObjectItemCaseSensitive(k, "look_at")) {
        double at[3], up[3] = {0, 1, 0}, f[3], r[3];
        if (has_angles)
            return err_set(err, "%s: keys.%d: give yaw and pitch or look_at, not both", name, i);
        if (!vec3_of(k, "look_at", at, name, i, err) || (has_up && !vec3_of(k, "up", up, name, i, err)))
            return false;
        double l = dist(at, K->position);
        if (!(l > 1e-9 * (1 + fabs(K->position[0]) + fabs(K->position[1]) + fabs(K->position[2]))))
            return err_set(err, "%s: keys.%d.look_at: is the key's position: the camera needs a point to look at", name, i);
        for (int c = 0; c < 3; c++)
            f[c] = (at[c] - K->position[c]) / l;
        cross(f, up, r);
        double rl = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]), ul = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
        if (!(rl > 1e-6 * ul)) {
            if (has_up)
                return err_set(err, "%s: keys.%d.up: is zero or along the view: give the direction the image's top "
                                    "should face", name, i);
            double level[3] = {cos(atan2(-f[0], -f[2])), 0, -sin(atan2(-f[0], -f[2]))}; /* straight up or down */
            memcpy(r, level, sizeof r);
            rl = 1;
        }
        for (int c = 0; c < 3; c++)
            r[c] /= rl;
        frame_angles(f, r, &yaw, &pitch, &roll);
        if (!has_up) /* the level camera, as before: pitch stops short of ±90° */
            pitch = fmax(-CAMERA_MAX_PITCH, fmin(CAMERA_MAX_PITCH, pitch));
    } else {
        if (has_up)
            return err_set(err, "%s: keys.%d.up: goes with look_at (with yaw and pitch, give roll)", name, i);
        if (!num(k, "yaw", -1e4, 1e4, &yaw, name, i, err) || !num(k, "pitch", -90, 90, &pitch, name, i, err))
            return false;
        yaw *= DEG;
        pitch *= DEG;
    }
    double more = 0;
    if (cJSON_GetObjectItemCaseSensitive(k, "roll") && !num(k, "roll", -1e4, 1e4, &more, name, i, err))
        return false;
    q_from_angles(yaw, pitch, roll + more * DEG, K->quat);
    return true;
}

static bool parse_key(path *p, const cJSON *k, int i, const char *name, err_t *err)
{
    path_key *K = &p->keys[i];
    static const char *const allowed[] = {"time", "position", "yaw", "pitch", "roll", "look_at", "up", "fov", "set", NULL};
    if (!cJSON_IsObject(k))
        return err_set(err, "%s: keys.%d: expected an object with time, position and yaw/pitch or look_at", name, i);
    for (const cJSON *it = k->child; it; it = it->next) {
        bool ok = false;
        for (const char *const *a = allowed; *a && !ok; a++)
            ok = it->string && !strcmp(it->string, *a);
        if (!ok)
            return err_set(err, "%s: keys.%d: unknown key '%s' (allowed: time, position, yaw, pitch, roll, look_at, up, fov, set)",
                           name, i, it->string ? it->string : "");
    }
    if (!num(k, "time", -PATH_MAX_TIME, PATH_MAX_TIME, &K->time, name, i, err) || !vec3_of(k, "position", K->position, name, i, err))
        return false;
    if (i > 0 && !(K->time > K[-1].time))
        return err_set(err, "%s: keys.%d.time: %g is not after the previous key's %g; times must increase", name, i,
                       K->time, K[-1].time);
    if (!key_orientation(k, K, i, name, err))
        return false;
    if (i > 0 && q_dot(K->quat, K[-1].quat) < 0) /* the short way round */
        for (int c = 0; c < 4; c++)
            K->quat[c] = -K->quat[c];
    K->fov_deg = i > 0 ? K[-1].fov_deg : 50;
    if (cJSON_GetObjectItemCaseSensitive(k, "fov") && !num(k, "fov", 1, 179, &K->fov_deg, name, i, err))
        return false;
    const cJSON *set = cJSON_GetObjectItemCaseSensitive(k, "set");
    int n = 0;
    if (set && !cJSON_IsObject(set))
        return err_set(err, "%s: keys.%d.set: expected an object of scene keys and numbers, e.g. {\"fractal.power\": 8}",
                       name, i);
    for (const cJSON *it = set ? set->child : NULL; it; it = it->next, n++) {
        if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble))
            return err_set(err, "%s: keys.%d.set.%s: expected a number (tracks interpolate numbers)", name, i, it->string);
        if (n >= PATH_MAX_PARAMS || strlen(it->string) >= PATH_PARAM_NAME)
            return err_set(err, "%s: keys.%d.set: at most %d parameters, names shorter than %d", name, i,
                           PATH_MAX_PARAMS, PATH_PARAM_NAME);
        if (i == 0)
            snprintf(p->params[n], PATH_PARAM_NAME, "%s", it->string);
        else if (n >= p->param_count || strcmp(p->params[n], it->string))
            return err_set(err, "%s: keys.%d.set: lists '%s' where key 0 lists %s: every key sets the same "
                                "parameters, in the same order",
                           name, i, it->string, n < p->param_count ? p->params[n] : "nothing more");
        K->values[n] = it->valuedouble;
    }
    if (i == 0)
        p->param_count = n;
    else if (n != p->param_count)
        return err_set(err, "%s: keys.%d.set: %d parameters where key 0 has %d: every key sets the same ones", name, i,
                       n, p->param_count);
    return true;
}

bool path_parse(const char *text, const char *name, path *p, err_t *err)
{
    memset(p, 0, sizeof *p);
    cJSON *root = cJSON_Parse(text);
    if (!root)
        return err_set(err, "%s: malformed JSON (check commas, quotes and brackets)", name);
    const cJSON *keys = cJSON_GetObjectItemCaseSensitive(root, "keys");
    bool ok = true;
    int n = cJSON_IsArray(keys) ? cJSON_GetArraySize(keys) : 0;
    for (const cJSON *it = cJSON_IsObject(root) ? root->child : NULL; it && ok; it = it->next)
        if (!it->string || strcmp(it->string, "keys"))
            ok = err_set(err, "%s: unknown key '%s' (a path file holds \"keys\")", name, it->string ? it->string : "");
    if (ok && (n < 2 || n > PATH_MAX_KEYS))
        ok = err_set(err, "%s: keys: expected an array of 2 to %d keyframes, each {\"time\", \"position\", \"yaw\", "
                          "\"pitch\"} or with \"look_at\"",
                     name, PATH_MAX_KEYS);
    if (ok) {
        p->count = n;
        p->keys = util_calloc((size_t)n, sizeof *p->keys, "path keys");
        int i = 0;
        for (const cJSON *k = keys->child; k && ok; k = k->next, i++)
            ok = parse_key(p, k, i, name, err);
    }
    cJSON_Delete(root);
    if (!ok) {
        path_free(p);
        return false;
    }
    build_arc(p);
    p->speed = util_alloc(sizeof(double) * (size_t)p->count, "path speeds");
    arc_tangents(p, p->speed);
    return true;
}

bool path_load(const char *file, path *p, err_t *err)
{
    char *text;
    memset(p, 0, sizeof *p);
    if (!util_read_file(file, &text, NULL, err))
        return false;
    bool ok = path_parse(text, file, p, err);
    free(text);
    return ok;
}

void path_write(const path *p, strbuf *out)
{
    sb_append(out, "{\n  \"keys\": [\n");
    for (int i = 0; i < p->count; i++) {
        const path_key *K = &p->keys[i];
        double yaw, pitch, roll;
        q_to_angles(K->quat, &yaw, &pitch, &roll);
        sb_printf(out, "    {\"time\": %.17g, \"position\": [%.17g, %.17g, %.17g], \"yaw\": %.17g, \"pitch\": %.17g, "
                       "\"roll\": %.17g, \"fov\": %.17g",
                  K->time, K->position[0], K->position[1], K->position[2], yaw / DEG, pitch / DEG, roll / DEG, K->fov_deg);
        if (p->param_count) {
            sb_append(out, ", \"set\": {");
            for (int k = 0; k < p->param_count; k++)
                sb_printf(out, "%s\"%s\": %.17g", k ? ", " : "", p->params[k], K->values[k]);
            sb_append(out, "}");
        }
        sb_printf(out, "}%s\n", i + 1 < p->count ? "," : "");
    }
    sb_append(out, "  ]\n}\n");
}

/* ---- recording ---- */

double path_next_key_time(const path_camera *keys, int n, const double position[3], double speed)
{
    if (n == 0)
        return 0;
    double gap = speed > 0 ? dist(keys[n - 1].position, position) / speed : PATH_KEY_GAP_MIN;
    return keys[n - 1].time + fmax(PATH_KEY_GAP_MIN, fmin(PATH_KEY_GAP_MAX, gap));
}

void path_text_from_cameras(const path_camera *keys, int n, strbuf *out)
{
    sb_append(out, "{\n  \"keys\": [\n");
    for (int i = 0; i < n; i++)
        sb_printf(out, "    {\"time\": %.9g, \"position\": [%.9g, %.9g, %.9g], \"yaw\": %.9g, \"pitch\": %.9g, "
                       "\"roll\": %.9g, \"fov\": %.9g}%s\n",
                  keys[i].time, keys[i].position[0], keys[i].position[1], keys[i].position[2], keys[i].yaw / DEG,
                  keys[i].pitch / DEG, keys[i].roll / DEG, keys[i].fov_deg, i + 1 < n ? "," : "");
    sb_append(out, "  ]\n}\n");
}

void path_key_camera(const path *p, int i, path_camera *out)
{
    const path_key *K = &p->keys[i];
    out->time = K->time;
    memcpy(out->position, K->position, sizeof out->position);
    q_to_angles(K->quat, &out->yaw, &out->pitch, &out->roll);
    out->fov_deg = K->fov_deg;
}

/* ---- frames ---- */

static bool whole(const char *s, const char **end, long *v)
{
    if (*s < '0' || *s > '9')
        return false;
    char *e;
    errno = 0;
    *v = strtol(s, &e, 10);
    *end = e;
    return errno == 0 && *v <= 100000000;
}

bool path_parse_frames(const char *s, int *first, int *last, err_t *err)
{
    long a, b;
    const char *e;
    if (!whole(s, &e, &a))
        return err_set(err, "bad --frames '%s': expected a frame number or a range A-B (e.g. 0-299)", s);
    b = a;
    if (*e == '-' && !whole(e + 1, &e, &b))
        return err_set(err, "bad --frames '%s': expected a frame number or a range A-B (e.g. 0-299)", s);
    if (*e)
        return err_set(err, "bad --frames '%s': expected a frame number or a range A-B (e.g. 0-299)", s);
    if (b < a)
        return err_set(err, "bad --frames '%s': the range ends before it starts", s);
    *first = (int)a;
    *last = (int)b;
    return true;
}

bool path_frame_name(const char *pattern, int frame, char *out, size_t n, err_t *err)
{
    int conversions = 0;
    for (const char *c = pattern; *c; c++) {
        if (*c != '%')
            continue;
        if (c[1] == '%') {
            c++;
            continue;
        }
        const char *d = c + 1;
        while (*d >= '0' && *d <= '9')
            d++;
        if (*d != 'd' || d - c > 3)
            return err_set(err, "output pattern '%s': only %%d with an optional width (%%04d) may stand for the "
                                "frame number; write %%%% for a %% sign",
                           pattern);
        conversions++;
        c = d;
    }
    if (conversions != 1)
        return err_set(err, "output pattern '%s': needs exactly one %%d (e.g. frame_%%04d.png) for the frame number",
                       pattern);
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
    int w = snprintf(out, n, pattern, frame);
#pragma GCC diagnostic pop
    if (w < 0 || (size_t)w >= n)
        return err_set(err, "output pattern '%s': the file name is too long", pattern);
    return true;
}
