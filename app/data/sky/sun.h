/* sun — where the sun stands in the sky at a time and place, and what the air leaves of its light.
 *
 * Position: NOAA's solar calculator (Global Monitoring Laboratory, "NOAA Solar Calculator" and its
 * spreadsheet, after Meeus, "Astronomical Algorithms", 1991): the sun's apparent longitude from its
 * mean longitude and anomaly, the obliquity with nutation, the equation of time, then the hour angle
 * at the longitude. NOAA states its positions good to about 0.01° for years 1800–2100 (past ±72° of
 * latitude sunrise and sunset times lose accuracy, not the angles); tests/sky/test_sun.c checks it
 * against the NREL SPA's published example (Reda & Andreas 2004) and an independent algorithm (the
 * Astronomical Almanac's, Michalsky 1988) over a year at three latitudes.
 *
 * Refraction: NOAA's piecewise formula (Bennett's near the horizon) for a standard atmosphere.
 * Colour: the direct beam through Rayleigh (Hansen & Travis 1974's optical depth of dry air at sea
 * level) and aerosol extinction (Ångström's law, β 0.05, α 1.3: a clear continental sky) along the
 * Kasten & Young (1989) relative air mass: the sun reddens and dims toward the horizon. This is the
 * sun's own light only; the sky's scattered light stays the scene's environment. */
#ifndef FATHOM_SUN_H
#define FATHOM_SUN_H

#include <stdbool.h>

typedef struct sun_position {
    double azimuth;   /* degrees clockwise from true north (90 = east) */
    double elevation; /* degrees above the horizon, refraction included (apparent) */
    double true_elevation; /* the same without refraction (geometric) */
    double declination, equation_of_time; /* degrees; minutes (what the tests compare) */
} sun_position;

/* The sun at `unix_seconds` (UTC) seen from latitude and longitude (degrees, east positive). */
sun_position sun_at(double unix_seconds, double latitude, double longitude);

/* Atmospheric refraction in degrees for the sun at geometric elevation e (degrees): NOAA's formula. */
double sun_refraction(double elevation);

/* The direct beam's transmittance at wavelengths 680, 550 and 440 nm (red, green, blue) for the sun at
 * apparent elevation `elevation` degrees, divided by its value with the sun overhead: white at noon
 * in the tropics, orange and dimmer at sunset, 0 once the disc is below the horizon (the disc's
 * visible share between −0.27° and +0.27°). */
void sun_color(double elevation, float rgb[3]);

/* Seconds since the epoch from a date "YYYY-MM-DD", a local hour (0–24, fractions for minutes) and
 * the time zone's offset from UTC in hours (e.g. 5.75 for Nepal); false for a malformed or impossible
 * date. */
bool sun_time(const char *date, double hour, double utc_offset, double *unix_seconds);

#endif
