/* The sun's position (data/sky/sun.h) against the NREL SPA's published example and, over a year at three
 * latitudes, against an algorithm that shares none of NOAA's series: the Astronomical Almanac's
 * low-precision formulas as Michalsky (1988) gives them (good to 0.01° in 1950-2050), written here
 * from the paper. Then the beam's colour and the date parser's refusals. */
#define _XOPEN_SOURCE 700 /* M_PI is XSI */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "data/sky/sun.h"
#include "util.h"

static double rad(double d) { return d * M_PI / 180; }
static double deg(double r) { return r * 180 / M_PI; }

/* Michalsky 1988, "The Astronomical Almanac's algorithm for approximate solar position (1950-2050)":
 * geometric elevation and azimuth (clockwise from north). */
static void almanac(double unix_seconds, double lat, double lon, double *el, double *az)
{
    double n = unix_seconds / 86400.0 + 2440587.5 - 2451545.0;
    double L = fmod(280.460 + 0.9856474 * n, 360), g = rad(fmod(357.528 + 0.9856003 * n, 360));
    double lambda = rad(L + 1.915 * sin(g) + 0.020 * sin(2 * g)), eps = rad(23.439 - 0.0000004 * n);
    double ra = atan2(cos(eps) * sin(lambda), cos(lambda)), dec = asin(sin(eps) * sin(lambda));
    double hours = fmod(unix_seconds, 86400.0) / 3600;
    double gmst = fmod(6.697375 + 0.0657098242 * n + hours, 24);
    double ha = rad(fmod((gmst + lon / 15) * 15, 360)) - ra;
    double phi = rad(lat);
    *el = deg(asin(sin(dec) * sin(phi) + cos(dec) * cos(phi) * cos(ha)));
    double a = deg(atan2(-cos(dec) * sin(ha), sin(dec) * cos(phi) - cos(dec) * sin(phi) * cos(ha)));
    *az = a < 0 ? a + 360 : a;
}

/* Reda & Andreas (2004), NREL/TP-560-34302, Table A5.1: 2003-10-17 12:30:30 at UTC−7, 39.742476° N,
 * 105.1786° W: zenith 50.11162° (topocentric, refracted at 820 hPa and 11 °C), azimuth 194.34024°,
 * geocentric declination −9.31434°. NOAA's formulas leave out the 0.002° parallax and assume a
 * standard atmosphere (0.004° more refraction here): within 0.02°. */
static void spa_example(void **state)
{
    (void)state;
    double t;
    assert_true(sun_time("2003-10-17", 12 + 30 / 60.0 + 30 / 3600.0, -7, &t));
    sun_position p = sun_at(t, 39.742476, -105.1786);
    print_message("SPA example: zenith %.5f (50.11162), azimuth %.5f (194.34024), declination %.5f (-9.31434)\n",
                  90 - p.elevation, p.azimuth, p.declination);
    assert_true(fabs(90 - p.elevation - 50.11162) < 0.02);
    assert_true(fabs(p.azimuth - 194.34024) < 0.02);
    assert_true(fabs(p.declination - -9.31434) < 0.01);
}

/* Every 37 hours through 2026 at the equator (Quito), 47° N (Zürich) and 64° N (Reykjavik): the two
 * agree within 0.05° in elevation and, with the sun above 2° and below 85°, 0.1° in azimuth. */
static void almanac_over_a_year(void **state)
{
    (void)state;
    static const double places[3][2] = {{-0.18, -78.47}, {47.37, 8.54}, {64.15, -21.94}};
    double t0;
    assert_true(sun_time("2026-01-01", 0, 0, &t0));
    double worst_el = 0, worst_az = 0;
    int compared = 0;
    for (int p = 0; p < 3; p++)
        for (double t = t0; t < t0 + 365 * 86400.0; t += 37 * 3600.0) {
            sun_position s = sun_at(t, places[p][0], places[p][1]);
            double el, az;
            almanac(t, places[p][0], places[p][1], &el, &az);
            worst_el = fmax(worst_el, fabs(s.true_elevation - el));
            if (el > 2 && el < 85) {
                double d = fabs(s.azimuth - az);
                worst_az = fmax(worst_az, fmin(d, 360 - d));
                compared++;
            }
        }
    print_message("NOAA against the Almanac over 2026: worst elevation %.4f deg, azimuth %.4f deg (%d above 2 deg)\n",
                  worst_el, worst_az, compared);
    assert_true(worst_el < 0.05);
    assert_true(worst_az < 0.1);
    assert_true(compared > 300);
}

/* The equation of time's known extremes: about −14.2 minutes in mid-February and +16.4 at the start of
 * November; the declination ±23.44° at the solstices. */
static void equation_of_time_and_solstices(void **state)
{
    (void)state;
    double t;
    assert_true(sun_time("2026-02-11", 12, 0, &t));
    assert_true(fabs(sun_at(t, 0, 0).equation_of_time - -14.2) < 0.2);
    assert_true(sun_time("2026-11-03", 12, 0, &t));
    assert_true(fabs(sun_at(t, 0, 0).equation_of_time - 16.4) < 0.2);
    assert_true(sun_time("2026-06-21", 12, 0, &t));
    assert_true(fabs(sun_at(t, 0, 0).declination - 23.44) < 0.01);
    assert_true(sun_time("2026-12-21", 12, 0, &t));
    assert_true(fabs(sun_at(t, 0, 0).declination - -23.44) < 0.01);
}

static void colour_and_refusals(void **state)
{
    (void)state;
    float noon[3], low[3], night[3];
    sun_color(90, noon);
    sun_color(3, low);
    sun_color(-1, night);
    for (int k = 0; k < 3; k++)
        assert_true(fabsf(noon[k] - 1) < 1e-6f && night[k] == 0);
    assert_true(low[0] > low[1] && low[1] > low[2] && low[2] < 0.3f); /* reddened and dimmed */
    assert_true(fabs(sun_refraction(0) - 0.4819) < 0.01); /* 1735 arcsec: the textbook half degree */
    /* against Bennett's formula (1982), R = cot(h + 7.31 / (h + 4.4)) arcminutes at the apparent elevation h, over
     * each of NOAA's pieces, and the pieces meeting at −0.575° (issue 58 item 17: a coefficient off by 10 survived) */
    static const double at[] = {2, 6, 10, 45};
    for (size_t i = 0; i < sizeof at / sizeof *at; i++) {
        double r = sun_refraction(at[i]), h = at[i] + r;
        double bennett = 1 / tan((h + 7.31 / (h + 4.4)) * 3.14159265358979323846 / 180) / 60;
        print_message("refraction at %g°: NOAA %.4f°, Bennett %.4f°\n", at[i], r, bennett);
        assert_true(fabs(r / bennett - 1) < 0.03);
    }
    assert_true(fabs(sun_refraction(-0.5749) - sun_refraction(-0.5751)) < 0.01 * sun_refraction(-0.5751));
    double t;
    assert_false(sun_time("2026-02-29", 12, 0, &t));
    assert_false(sun_time("2026-13-01", 12, 0, &t));
    assert_false(sun_time("2026-1-1", 12, 0, &t));
    assert_false(sun_time("2026-01-01", 24.5, 0, &t));
    assert_false(sun_time("2026-01-01", 12, 15, &t));
    assert_true(sun_time("2024-02-29", 24, 0, &t));
    assert_true(t == (double)util_days_from_civil(2024, 3, 1) * 86400);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(spa_example), cmocka_unit_test(almanac_over_a_year),
        cmocka_unit_test(equation_of_time_and_solstices), cmocka_unit_test(colour_and_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
