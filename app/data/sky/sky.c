/* sky — Hillaire's (2020) atmosphere in double precision (sky.h). */
#define _XOPEN_SOURCE 700 /* M_PI is XSI */
#include "data/sky/sky.h"

#include <math.h>
#include <string.h>

static const double RAYLEIGH[3] = {5.802e-6, 13.558e-6, 33.1e-6}, RAYLEIGH_H = 8000;
static const double MIE_SCATTER = 3.996e-6, MIE_EXTINCT = 4.40e-6, MIE_H = 1200, MIE_G = 0.8;
static const double OZONE[3] = {0.650e-6, 1.881e-6, 0.085e-6}, OZONE_CENTRE = 25000, OZONE_HALF = 15000;
static const double GROUND_ALBEDO = 0.3;
static const double R = SKY_PLANET_RADIUS, TOP = SKY_PLANET_RADIUS + SKY_TOP;

static void scattering(double h, double rayleigh[3], double *mie)
{
    double r = exp(-h / RAYLEIGH_H);
    for (int k = 0; k < 3; k++)
        rayleigh[k] = RAYLEIGH[k] * r;
    *mie = MIE_SCATTER * exp(-h / MIE_H);
}

void sky_extinction(double h, double ext[3])
{
    double r = exp(-h / RAYLEIGH_H), m = exp(-h / MIE_H), o = fmax(0, 1 - fabs(h - OZONE_CENTRE) / OZONE_HALF);
    for (int k = 0; k < 3; k++)
        ext[k] = RAYLEIGH[k] * r + MIE_EXTINCT * m + OZONE[k] * o;
}

/* A ray from altitude h with zenith cosine mu: the altitude after t metres (the sphere's geometry). */
static double altitude_at(double h, double mu, double t)
{
    double r = R + h;
    return sqrt(r * r + 2 * t * r * mu + t * t) - R;
}

/* Where the ray leaves the atmosphere, or meets the ground (*ground true); -1 if it never enters. */
static double ray_end(double h, double mu, bool *ground)
{
    double r = R + h, b = r * mu;
    double disc_ground = b * b - (r * r - R * R);
    *ground = b < 0 && disc_ground >= 0;
    if (*ground)
        return -b - sqrt(disc_ground);
    double disc_top = b * b - (r * r - TOP * TOP);
    return disc_top >= 0 ? -b + sqrt(disc_top) : -1;
}

/* Optical depth along mu from h over dist, quadratic midpoint steps (dense near the start, where a
 * ray from the ground meets the densest air). */
static void optical_depth(double h, double mu, double dist, int steps, double od[3])
{
    od[0] = od[1] = od[2] = 0;
    for (int i = 0; i < steps; i++) {
        double a = (double)i / steps, b = (double)(i + 1) / steps;
        double t = dist * (0.5 * (a + b)) * (0.5 * (a + b)), dt = dist * (b * b - a * a);
        double e[3];
        sky_extinction(altitude_at(h, mu, t), e);
        for (int k = 0; k < 3; k++)
            od[k] += e[k] * dt;
    }
}

/* Transmittance toward the sun from altitude h, the sun at zenith cosine mu: 0 in the Earth's shadow. */
static void sun_transmittance(double h, double mu, int steps, double T[3])
{
    bool ground;
    double end = ray_end(h, mu, &ground);
    if (ground) {
        T[0] = T[1] = T[2] = 0;
        return;
    }
    double od[3];
    optical_depth(h, mu, fmax(end, 0), steps, od);
    for (int k = 0; k < 3; k++)
        T[k] = exp(-od[k]);
}

void sky_transmittance(double altitude, const double dir[3], double dist, int steps, double T[3])
{
    bool ground;
    double end = ray_end(altitude, dir[1], &ground);
    if (dist < 0 && ground) {
        T[0] = T[1] = T[2] = 0;
        return;
    }
    double od[3];
    optical_depth(altitude, dir[1], dist < 0 ? fmax(end, 0) : dist, steps, od);
    for (int k = 0; k < 3; k++)
        T[k] = exp(-od[k]);
}

double sky_ms_altitude(int i)
{
    double u = (double)i / (SKY_MS_N - 1);
    return SKY_TOP * u * u;
}

/* The sun's zenith cosine at a point t along a ray from altitude h (zenith cosine mu), the sun's
 * direction given in the ray's start frame (+Y up): the local vertical turns with the sphere. */
static double sun_mu_at(double h, const double dir[3], double t, const double sun[3])
{
    double p[3] = {t * dir[0], R + h + t * dir[1], t * dir[2]};
    double n = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return (p[0] * sun[0] + p[1] * sun[1] + p[2] * sun[2]) / n;
}

/* Hillaire's eq. 5–10 at altitude h: 64 directions, 20 steps each (his LUT pass's counts). */
static void multiple_at(double h, const double sun[3], double ms[3])
{
    enum { DIRS = 64, STEPS = 20 };
    double l2[3] = {0, 0, 0}, fms[3] = {0, 0, 0};
    const double iso = 1 / (4 * M_PI);
    for (int d = 0; d < DIRS; d++) { /* a Fibonacci sphere */
        double y = 1 - (d + 0.5) * 2.0 / DIRS, rr = sqrt(fmax(0, 1 - y * y)), phi = d * M_PI * (3 - sqrt(5.0));
        double dir[3] = {rr * cos(phi), y, rr * sin(phi)};
        bool ground;
        double end = ray_end(h, y, &ground), T[3] = {1, 1, 1};
        if (end <= 0)
            continue;
        for (int i = 0; i < STEPS; i++) {
            double t = end * (i + 0.5) / STEPS, dt = end / STEPS, ha = altitude_at(h, y, t);
            double ray[3], mie, e[3], Ts[3];
            scattering(ha, ray, &mie);
            sky_extinction(ha, e);
            sun_transmittance(ha, sun_mu_at(h, dir, t, sun), 10, Ts);
            for (int k = 0; k < 3; k++) {
                double seg = exp(-e[k] * dt), s = ray[k] + mie;
                /* the stretch's share, integrated exactly for constant coefficients */
                double w = e[k] > 0 ? T[k] * (1 - seg) / e[k] : T[k] * dt;
                l2[k] += w * s * Ts[k] * iso;
                fms[k] += w * s;
                T[k] *= seg;
            }
        }
        if (ground) { /* the lit ground, Lambertian */
            double Ts[3], mu_g = sun_mu_at(h, dir, end, sun);
            sun_transmittance(0, mu_g, 10, Ts);
            for (int k = 0; k < 3; k++)
                l2[k] += T[k] * GROUND_ALBEDO / M_PI * fmax(mu_g, 0) * Ts[k];
        }
    }
    for (int k = 0; k < 3; k++) {
        double L2 = l2[k] / DIRS * 4 * M_PI * iso, f = fms[k] / DIRS * 4 * M_PI * iso;
        ms[k] = L2 / (1 - f);
    }
}

void sky_multiple_scattering(const double sun[3], double ms[SKY_MS_N][3])
{
    for (int i = 0; i < SKY_MS_N; i++) {
        /* the table is by altitude for this sun: its direction is taken in each row's own frame */
        multiple_at(sky_ms_altitude(i), sun, ms[i]);
    }
}

/* Ψ_ms at altitude h, linear between the rows (quadratic spacing: u = √(h / top)). */
static void ms_lookup(const double (*ms)[3], double h, double out[3])
{
    double u = sqrt(fmin(fmax(h, 0), SKY_TOP) / SKY_TOP) * (SKY_MS_N - 1);
    int i = (int)fmin(floor(u), SKY_MS_N - 2);
    double f = u - i;
    for (int k = 0; k < 3; k++)
        out[k] = ms[i][k] * (1 - f) + ms[i + 1][k] * f;
}

void sky_radiance(double altitude, const double dir[3], double dist, const double sun[3], const double (*ms)[3],
                  int steps, double L[3], double T[3])
{
    bool ground;
    double end = ray_end(altitude, dir[1], &ground);
    double len = dist < 0 ? fmax(end, 0) : dist;
    double mu = dir[0] * sun[0] + dir[1] * sun[1] + dir[2] * sun[2];
    double pr = 3 / (16 * M_PI) * (1 + mu * mu), g = MIE_G;
    double pm = 3 / (8 * M_PI) * (1 - g * g) * (1 + mu * mu) / ((2 + g * g) * pow(1 + g * g - 2 * g * mu, 1.5));
    for (int k = 0; k < 3; k++)
        L[k] = 0, T[k] = 1;
    for (int i = 0; i < steps; i++) {
        double a = (double)i / steps, b = (double)(i + 1) / steps;
        double t = len * (0.5 * (a + b)) * (0.5 * (a + b)), dt = len * (b * b - a * a);
        double h = altitude_at(altitude, dir[1], t), ray[3], mie, e[3], Ts[3], m[3] = {0, 0, 0};
        scattering(h, ray, &mie);
        sky_extinction(h, e);
        sun_transmittance(h, sun_mu_at(altitude, dir, t, sun), steps, Ts);
        if (ms)
            ms_lookup(ms, h, m);
        for (int k = 0; k < 3; k++) {
            double seg = exp(-e[k] * dt), w = e[k] > 0 ? T[k] * (1 - seg) / e[k] : T[k] * dt;
            L[k] += w * ((ray[k] * pr + mie * pm) * Ts[k] + (ray[k] + mie) * m[k]);
            T[k] *= seg;
        }
    }
    if (dist < 0 && ground) { /* the planet's ground beyond everything else: lit, Lambertian */
        double Ts[3], mu_g = sun_mu_at(altitude, dir, len, sun);
        sun_transmittance(0, mu_g, steps, Ts);
        for (int k = 0; k < 3; k++)
            L[k] += T[k] * GROUND_ALBEDO / M_PI * fmax(mu_g, 0) * Ts[k];
    }
}

void sky_mean(double altitude, const double sun[3], const double (*ms)[3], double L[3])
{
    enum { DIRS = 128 };
    L[0] = L[1] = L[2] = 0;
    double wsum = 0;
    for (int d = 0; d < DIRS; d++) { /* the upper half of a Fibonacci sphere, cosine-weighted */
        double y = 1 - (d + 0.5) / DIRS, rr = sqrt(fmax(0, 1 - y * y)), phi = d * M_PI * (3 - sqrt(5.0));
        double dir[3] = {rr * cos(phi), y, rr * sin(phi)}, l[3], T[3];
        sky_radiance(altitude, dir, -1, sun, ms, 24, l, T);
        for (int k = 0; k < 3; k++)
            L[k] += l[k] * y;
        wsum += y;
    }
    for (int k = 0; k < 3; k++)
        L[k] /= wsum;
}
