#include "reference.h"

#include <math.h>
#include <string.h>

#define DEG2RAD (3.14159265358979323846 / 180.0)

double ref_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void normalize(double v[3])
{
    double l = sqrt(ref_dot(v, v));
    for (int i = 0; i < 3; i++)
        v[i] /= l;
}

static void mul(double A[3][3], double B[3][3], double C[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j];
}

void ref_rotation(const double deg[3], double R[3][3])
{
    double x = deg[0] * DEG2RAD, y = deg[1] * DEG2RAD, z = deg[2] * DEG2RAD;
    double Rx[3][3] = {{1, 0, 0}, {0, cos(x), -sin(x)}, {0, sin(x), cos(x)}};
    double Ry[3][3] = {{cos(y), 0, sin(y)}, {0, 1, 0}, {-sin(y), 0, cos(y)}};
    double Rz[3][3] = {{cos(z), -sin(z), 0}, {sin(z), cos(z), 0}, {0, 0, 1}};
    double T[3][3];
    mul(Ry, Rx, T);
    mul(Rz, T, R);
}

/* world → object: Rᵀ (p − c) */
static void to_object(double R[3][3], const double c[3], const double p[3], double out[3], bool point)
{
    double q[3];
    for (int i = 0; i < 3; i++)
        q[i] = point ? p[i] - c[i] : p[i];
    for (int i = 0; i < 3; i++)
        out[i] = R[0][i] * q[0] + R[1][i] * q[1] + R[2][i] * q[2];
}

static void to_world_dir(double R[3][3], const double v[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = R[i][0] * v[0] + R[i][1] * v[1] + R[i][2] * v[2];
}

dinterval ref_sphere(const dray *r, const double c[3], double radius)
{
    dinterval iv = {0};
    double oc[3] = {r->o[0] - c[0], r->o[1] - c[1], r->o[2] - c[2]};
    double b = ref_dot(oc, r->d), cc = ref_dot(oc, oc) - radius * radius;
    double disc = b * b - cc;
    if (disc < 0)
        return iv;
    double s = sqrt(disc);
    /* the stable pair of roots (no cancellation) */
    double q = b > 0 ? -b - s : -b + s;
    double ta = q, tb = cc / q;
    iv.t0 = fmin(ta, tb);
    iv.t1 = fmax(ta, tb);
    iv.hit = true;
    for (int i = 0; i < 3; i++) {
        iv.n0[i] = (r->o[i] + r->d[i] * iv.t0 - c[i]) / radius;
        iv.n1[i] = (r->o[i] + r->d[i] * iv.t1 - c[i]) / radius;
    }
    return iv;
}

dinterval ref_box(const dray *r, const double c[3], double R[3][3], const double half[3])
{
    dinterval iv = {.t0 = -INFINITY, .t1 = INFINITY};
    double o[3], d[3];
    to_object(R, c, r->o, o, true);
    to_object(R, c, r->d, d, false);
    int a0 = -1, a1 = -1;
    double s0 = 0, s1 = 0;
    for (int i = 0; i < 3; i++) {
        if (d[i] == 0) {
            if (fabs(o[i]) > half[i])
                return (dinterval){0};
            continue;
        }
        double ta = (-half[i] - o[i]) / d[i], tb = (half[i] - o[i]) / d[i];
        double sa = -1, sb = 1;
        if (ta > tb) {
            double t = ta;
            ta = tb, tb = t;
            sa = 1, sb = -1;
        }
        if (ta > iv.t0)
            iv.t0 = ta, a0 = i, s0 = sa;
        if (tb < iv.t1)
            iv.t1 = tb, a1 = i, s1 = sb;
    }
    if (iv.t0 > iv.t1 || a0 < 0 || a1 < 0)
        return (dinterval){0};
    iv.hit = true;
    double n0[3] = {0, 0, 0}, n1[3] = {0, 0, 0};
    n0[a0] = s0;
    n1[a1] = s1;
    to_world_dir(R, n0, iv.n0);
    to_world_dir(R, n1, iv.n1);
    return iv;
}

/* Distance from the box-local point to the nearest edge: the second-smallest gap to a face plane. */
double ref_box_crease(const dray *r, double t, const double c[3], double R[3][3], const double half[3])
{
    double p[3] = {r->o[0] + r->d[0] * t, r->o[1] + r->d[1] * t, r->o[2] + r->d[2] * t}, q[3];
    to_object(R, c, p, q, true);
    double g[3];
    for (int i = 0; i < 3; i++)
        g[i] = fabs(half[i] - fabs(q[i]));
    double lo = fmin(g[0], fmin(g[1], g[2])), hi = fmax(g[0], fmax(g[1], g[2]));
    return g[0] + g[1] + g[2] - lo - hi;
}

dhit ref_first(dinterval a)
{
    dhit h = {.crease = INFINITY};
    if (!a.hit || a.t1 < 0)
        return h;
    h.hit = true;
    h.t = a.t0;
    memcpy(h.n, a.n0, sizeof h.n);
    return h;
}

dhit ref_difference(dinterval a, dinterval b)
{
    dhit h = {.crease = INFINITY};
    if (!a.hit)
        return h;
    if (!b.hit || a.t0 < b.t0 || a.t0 > b.t1) /* a's entry is outside b */
        return ref_first(a);
    if (b.t1 < a.t1) { /* enters the solid where the ray leaves b, inside a */
        h.hit = true;
        h.t = b.t1;
        for (int i = 0; i < 3; i++)
            h.n[i] = -b.n1[i];
    }
    return h;
}

dhit ref_intersection(dinterval a, dinterval b)
{
    dhit h = {.crease = INFINITY};
    if (!a.hit || !b.hit)
        return h;
    double t0 = fmax(a.t0, b.t0), t1 = fmin(a.t1, b.t1);
    if (t0 > t1 || t1 < 0)
        return h;
    h.hit = true;
    h.t = t0;
    memcpy(h.n, a.t0 > b.t0 ? a.n0 : b.n0, sizeof h.n);
    return h;
}

/* (|p|² + R² − r²)² − 4 R² (x² + z²): negative inside the ring (axis Y). */
static double torus_f(const double p[3], double R, double r)
{
    double k = ref_dot(p, p) + R * R - r * r;
    return k * k - 4 * R * R * (p[0] * p[0] + p[2] * p[2]);
}

dhit ref_torus(const dray *ray, const double c[3], double R[3][3], double major, double minor, double tmax)
{
    const double STEP = 1e-3; /* finer than any feature the probes look at */
    dhit h = {.crease = INFINITY};
    double o[3], d[3];
    to_object(R, c, ray->o, o, true);
    to_object(R, c, ray->d, d, false);
    double prev_t = 0, p[3];
    for (int i = 0; i < 3; i++)
        p[i] = o[i];
    double prev = torus_f(p, major, minor);
    for (double t = STEP; t <= tmax; t += STEP) {
        for (int i = 0; i < 3; i++)
            p[i] = o[i] + d[i] * t;
        double f = torus_f(p, major, minor);
        if (prev > 0 && f <= 0) {
            double lo = prev_t, hi = t;
            for (int it = 0; it < 60; it++) {
                double mid = 0.5 * (lo + hi);
                for (int i = 0; i < 3; i++)
                    p[i] = o[i] + d[i] * mid;
                if (torus_f(p, major, minor) > 0)
                    lo = mid;
                else
                    hi = mid;
            }
            h.hit = true;
            h.t = 0.5 * (lo + hi);
            for (int i = 0; i < 3; i++)
                p[i] = o[i] + d[i] * h.t;
            double k = ref_dot(p, p) + major * major - minor * minor;
            double g[3] = {4 * k * p[0] - 8 * major * major * p[0], 4 * k * p[1], 4 * k * p[2] - 8 * major * major * p[2]};
            normalize(g);
            to_world_dir(R, g, h.n);
            return h;
        }
        prev = f;
        prev_t = t;
    }
    return h;
}

bool ref_refract(const double d[3], const double n[3], double eta, double out[3])
{
    double cosi = -ref_dot(d, n);
    double k = 1 - eta * eta * (1 - cosi * cosi);
    if (k < 0)
        return false;
    for (int i = 0; i < 3; i++)
        out[i] = eta * d[i] + (eta * cosi - sqrt(k)) * n[i];
    return true;
}


double ref_sd_sphere(const double p[3], const double c[3], double radius)
{
    double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
    return sqrt(ref_dot(d, d)) - radius;
}

double ref_sd_box(const double p[3], const double c[3], double R[3][3], const double half[3])
{
    double q[3], out = 0, in = -INFINITY;
    to_object(R, c, p, q, true);
    for (int i = 0; i < 3; i++) {
        double g = fabs(q[i]) - half[i];
        out += g > 0 ? g * g : 0;
        in = fmax(in, g);
    }
    return sqrt(out) + fmin(in, 0.0);
}

double ref_sd_torus(const double p[3], const double c[3], double R[3][3], double major, double minor)
{
    double q[3];
    to_object(R, c, p, q, true);
    double ring = sqrt(q[0] * q[0] + q[2] * q[2]) - major;
    return sqrt(ring * ring + q[1] * q[1]) - minor;
}
