/* path — see path.h. */
#include "view/path.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/camera.h"
#include "view/path_internal.h"

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

double path_q_dot(const double a[4], const double b[4])
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
    double d = path_q_dot(a, b);
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
void path_q_from_angles(double yaw, double pitch, double roll, double q[4])
{
    double qy[4] = {0, sin(yaw / 2), 0, cos(yaw / 2)}, qx[4] = {sin(pitch / 2), 0, 0, cos(pitch / 2)};
    double qz[4] = {0, 0, sin(roll / 2), cos(roll / 2)}, qyx[4];
    q_mul(qy, qx, qyx);
    q_mul(qyx, qz, q);
}

/* yaw, pitch and roll of a camera frame: its unit forward f and right r (camera_set_basis's rule:
 * straight up or down, roll 0 and yaw the whole turn) */
void path_frame_angles(const double f[3], const double r[3], double *yaw, double *pitch, double *roll)
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
void path_q_to_angles(const double q[4], double *yaw, double *pitch, double *roll)
{
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double f[3] = {-(2 * (x * z + w * y)), -(2 * (y * z - w * x)), -(1 - 2 * (x * x + y * y))};
    double r[3] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
    path_frame_angles(f, r, yaw, pitch, roll);
}

/* ---- the position spline ---- */

double path_dist(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Centripetal Catmull–Rom on segment i (keys i → i+1) at u ∈ [0, 1], Barry–Goldman pyramid. Ends and
 * repeated points get a mirrored phantom neighbour, so no knot interval is 0. */
static void segment_point(const path *p, int i, double u, double out[3])
{
    const double *P1 = p->keys[i].position, *P2 = p->keys[i + 1].position;
    double len12 = path_dist(P1, P2);
    if (len12 == 0) { /* the camera holds still here */
        memcpy(out, P1, sizeof(double) * 3);
        return;
    }
    double P0[3], P3[3];
    bool have0 = i > 0 && path_dist(p->keys[i - 1].position, P1) > 1e-9 * len12;
    bool have3 = i + 2 < p->count && path_dist(p->keys[i + 2].position, P2) > 1e-9 * len12;
    for (int k = 0; k < 3; k++) {
        P0[k] = have0 ? p->keys[i - 1].position[k] : 2 * P1[k] - P2[k];
        P3[k] = have3 ? p->keys[i + 2].position[k] : 2 * P2[k] - P1[k];
    }
    double t0 = 0, t1 = t0 + sqrt(path_dist(P0, P1)), t2 = t1 + sqrt(len12), t3 = t2 + sqrt(path_dist(P2, P3));
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
    return path_dist(pa, pb) / (b - a);
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

const char *const PATH_EASES[PATH_EASE_COUNT + 1] = {"none", "in", "out", "in-out", NULL};

double path_ease_u(int ease, double u)
{
    switch (ease) {
    case PATH_EASE_IN: return u * u;
    case PATH_EASE_OUT: return 1 - (1 - u) * (1 - u);
    case PATH_EASE_IN_OUT: return u * u * (3 - 2 * u);
    default: return u;
    }
}

/* A zoom segment's point at time fraction u (path.h): the distance to the zoom point geometric in u,
 * the point moving in proportion to how much of that distance is gone, the direction by slerp. */
static void zoom_point(const path *p, int i, double u, double out[3])
{
    const path_key *a = &p->keys[i], *b = &p->keys[i + 1];
    double s0 = path_dist(a->position, a->zoom_to), s1 = path_dist(b->position, b->zoom_to);
    double s = u <= 0 ? s0 : u >= 1 ? s1 : exp((1 - u) * log(s0) + u * log(s1));
    double w = s0 != s1 ? (s0 - s) / (s0 - s1) : u, d0[3], d1[3], c = 0;
    for (int k = 0; k < 3; k++) {
        d0[k] = (a->position[k] - a->zoom_to[k]) / s0;
        d1[k] = (b->position[k] - b->zoom_to[k]) / s1;
        c += d0[k] * d1[k];
    }
    double angle = acos(fmax(-1.0, fmin(1.0, c))), k0 = 1 - u, k1 = u, len = 0, d[3];
    if (angle > 1e-9) { /* slerp; nearly parallel: the straight blend, normalized below */
        k0 = sin((1 - u) * angle) / sin(angle);
        k1 = sin(u * angle) / sin(angle);
    }
    for (int k = 0; k < 3; k++) {
        d[k] = k0 * d0[k] + k1 * d1[k];
        len += d[k] * d[k];
    }
    len = sqrt(len);
    for (int k = 0; k < 3; k++)
        out[k] = a->zoom_to[k] + w * (b->zoom_to[k] - a->zoom_to[k]) + d[k] / len * s;
}

void path_eval(const path *p, double t, path_sample *out)
{
    const path_key *K = p->keys;
    t = fmax(K[0].time, fmin(K[p->count - 1].time, t));
    int i = find_segment(p, t);
    double h = K[i + 1].time - K[i].time, u = path_ease_u(K[i].ease, (t - K[i].time) / h);
    if (K[i].zoom && K[i + 1].zoom) {
        zoom_point(p, i, u, out->position);
    } else { /* arc length from the monotone cubic, then the curve at that length */
        const double *m = p->speed;
        double s = hermite(p->key_length[i], p->key_length[i + 1], m[i], m[i + 1], h, u) - p->key_length[i];
        segment_point(p, i, segment_u(p, i, s), out->position);
    }
    segment_orientation(p, i, u, out->quat);
    path_q_to_angles(out->quat, &out->yaw, &out->pitch, &out->roll);
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

void path_prepare(path *p)
{
    build_arc(p);
    p->speed = util_alloc(sizeof(double) * (size_t)p->count, "path speeds");
    arc_tangents(p, p->speed);
}
