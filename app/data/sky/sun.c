/* sun — NOAA's solar position, refraction and the direct beam's colour (sun.h). */
/* M_PI is XSI */
#define _XOPEN_SOURCE 700
#include "data/sky/sun.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "util.h"

static double rad(double d) { return d * M_PI / 180; }
static double deg(double r) { return r * 180 / M_PI; }
static double wrap360(double d) { return d - 360 * floor(d / 360); }

sun_position sun_at(double unix_seconds, double latitude, double longitude)
{
    double jd = unix_seconds / 86400.0 + 2440587.5; /* the Unix epoch is JD 2440587.5 */
    double T = (jd - 2451545.0) / 36525.0;          /* Julian centuries from J2000.0 */
    double L0 = wrap360(280.46646 + T * (36000.76983 + T * 0.0003032));
    double M = 357.52911 + T * (35999.05029 - 0.0001537 * T);
    double e = 0.016708634 - T * (0.000042037 + 0.0000001267 * T);
    double C = sin(rad(M)) * (1.914602 - T * (0.004817 + 0.000014 * T)) + sin(rad(2 * M)) * (0.019993 - 0.000101 * T) +
               sin(rad(3 * M)) * 0.000289;
    double omega = 125.04 - 1934.136 * T;
    double lambda = L0 + C - 0.00569 - 0.00478 * sin(rad(omega)); /* apparent longitude */
    double eps0 = 23 + (26 + (21.448 - T * (46.815 + T * (0.00059 - T * 0.001813))) / 60) / 60;
    double eps = eps0 + 0.00256 * cos(rad(omega));
    double decl = deg(asin(sin(rad(eps)) * sin(rad(lambda))));
    double y = tan(rad(eps / 2)) * tan(rad(eps / 2));
    double eot = 4 * deg(y * sin(2 * rad(L0)) - 2 * e * sin(rad(M)) + 4 * e * y * sin(rad(M)) * cos(2 * rad(L0)) -
                         0.5 * y * y * sin(4 * rad(L0)) - 1.25 * e * e * sin(2 * rad(M))); /* minutes */
    double day_minutes = fmod(unix_seconds, 86400.0) / 60.0;
    if (day_minutes < 0)
        day_minutes += 1440;
    double tst = fmod(day_minutes + eot + 4 * longitude, 1440.0); /* true solar time, minutes */
    if (tst < 0)
        tst += 1440;
    double ha = tst / 4 - 180; /* hour angle, degrees: 0 at solar noon */
    double phi = rad(latitude), d = rad(decl);
    double cz = fmax(-1.0, fmin(1.0, sin(phi) * sin(d) + cos(phi) * cos(d) * cos(rad(ha))));
    double zenith = acos(cz);
    sun_position p = {.declination = decl, .equation_of_time = eot};
    p.true_elevation = 90 - deg(zenith);
    p.elevation = p.true_elevation + sun_refraction(p.true_elevation);
    /* azimuth from north, clockwise: atan2 of the east and north components of the sun's direction */
    double east = -sin(rad(ha)) * cos(d);
    double north = cos(phi) * sin(d) - sin(phi) * cos(d) * cos(rad(ha));
    p.azimuth = wrap360(deg(atan2(east, north)));
    return p;
}

double sun_refraction(double e)
{
    if (e > 85)
        return 0;
    double t = tan(rad(e)), arcsec;
    if (e > 5)
        arcsec = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / pow(t, 5);
    else if (e > -0.575)
        arcsec = 1735 + e * (-518.2 + e * (103.4 + e * (-12.79 + e * 0.711)));
    else
        arcsec = -20.772 / t;
    return arcsec / 3600;
}

/* Kasten & Young (1989): the relative optical air mass at apparent elevation e degrees. */
static double air_mass(double e)
{
    e = fmax(e, 0);
    return 1 / (sin(rad(e)) + 0.50572 * pow(e + 6.07995, -1.6364));
}

void sun_color(double elevation, float rgb[3])
{
    static const double um[3] = {0.68, 0.55, 0.44}; /* wavelengths, micrometres */
    double m = air_mass(elevation), disc = fmin(1, fmax(0, (elevation + 0.27) / 0.54));
    for (int k = 0; k < 3; k++) {
        double l2 = um[k] * um[k], l4 = l2 * l2;
        /* Hansen & Travis (1974) eq. 2.29: dry air at 1013.25 hPa; Ångström β λ^−α for the aerosol */
        double tau = 0.008569 / l4 * (1 + 0.0113 / l2 + 0.00013 / l4) + 0.05 * pow(um[k], -1.3);
        rgb[k] = (float)(disc * exp(-tau * (m - air_mass(90))));
    }
}

bool sun_time(const char *date, double hour, double utc_offset, double *unix_seconds)
{
    int y, mo, d, used = 0;
    if (!date || sscanf(date, "%4d-%2d-%2d%n", &y, &mo, &d, &used) != 3 || used != 10 || date[used] || mo < 1 ||
        mo > 12 || d < 1 || !(hour >= 0 && hour <= 24) || !(fabs(utc_offset) <= 14))
        return false;
    static const int mdays[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
    if (d > mdays[mo - 1] || (mo == 2 && d == 29 && !leap))
        return false;
    *unix_seconds = (double)util_days_from_civil(y, mo, d) * 86400 + (hour - utc_offset) * 3600;
    return true;
}
