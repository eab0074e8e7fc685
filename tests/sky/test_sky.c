/* The atmosphere (data/sky/sky.h) against closed forms: Beer–Lambert along a short horizontal path
 * (constant air: T = exp(−σ(h) L)) and straight up (the exponential profiles and the ozone tent
 * integrate exactly); the march's convergence at the shader's sample counts; and what a sky must do:
 * blue overhead, red toward a low sun, darker with altitude, multiple scattering adding light, the
 * Earth's shadow at night. */
#define _XOPEN_SOURCE 700 /* M_PI is XSI */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "data/sky/sky.h"

static void horizontal_beer_lambert(void **state)
{
    (void)state;
    const double hs[] = {0, 1000, 5000, 25000};
    for (size_t i = 0; i < sizeof hs / sizeof hs[0]; i++) {
        double dir[3] = {1, 0, 0}, T[3], e[3];
        sky_transmittance(hs[i], dir, 1000, 64, T);
        sky_extinction(hs[i], e);
        for (int k = 0; k < 3; k++) {
            /* over 1 km the path rises L²/2R = 0.08 m: the closed form for the air at the start */
            double want = exp(-e[k] * 1000);
            assert_true(fabs(T[k] / want - 1) < 2e-6);
        }
    }
}

static void vertical_closed_form(void **state)
{
    (void)state;
    double up[3] = {0, 1, 0}, T[3];
    sky_transmittance(0, up, -1, 4096, T);
    /* ∫ σ e^(−h/H) dh over 0 … 100 km, and the ozone tent (10 … 40 km) of area 15 km */
    static const double RAY[3] = {5.802e-6, 13.558e-6, 33.1e-6}, OZ[3] = {0.650e-6, 1.881e-6, 0.085e-6};
    for (int k = 0; k < 3; k++) {
        double od = RAY[k] * 8000 * (1 - exp(-100000.0 / 8000)) + 4.40e-6 * 1200 * (1 - exp(-100000.0 / 1200)) +
                    OZ[k] * 15000;
        print_message("zenith transmittance, channel %d: %.6f (closed form %.6f)\n", k, T[k], exp(-od));
        assert_true(fabs(T[k] - exp(-od)) < 1e-5);
    }
}

/* The shader marches 16 steps with 8 toward the sun: within 3 % of 512 here, over the sky. */
static void converges_at_the_shaders_counts(void **state)
{
    (void)state;
    double sun[3] = {0, sin(20 * M_PI / 180), cos(20 * M_PI / 180)}, ms[SKY_MS_N][3];
    sky_multiple_scattering(sun, ms);
    double worst = 0;
    for (int e = 2; e <= 90; e += 8)
        for (int a = 0; a < 360; a += 45) {
            double el = e * M_PI / 180, az = a * M_PI / 180;
            double dir[3] = {cos(el) * sin(az), sin(el), cos(el) * cos(az)}, lo[3], hi[3], T[3];
            sky_radiance(500, dir, -1, sun, (const double(*)[3])ms, 16, lo, T);
            sky_radiance(500, dir, -1, sun, (const double(*)[3])ms, 512, hi, T);
            for (int k = 0; k < 3; k++)
                worst = fmax(worst, fabs(lo[k] / hi[k] - 1));
        }
    print_message("16 steps against 512: worst %.2f %%\n", 100 * worst);
    assert_true(worst < 0.03);
}

static void what_a_sky_does(void **state)
{
    (void)state;
    double low[3] = {0, sin(3 * M_PI / 180), cos(3 * M_PI / 180)}, high[3] = {0, sin(60 * M_PI / 180), cos(60 * M_PI / 180)};
    double ms[SKY_MS_N][3], zen[3] = {0, 1, 0}, L[3], Lsingle[3], T[3], L10[3];
    sky_multiple_scattering(high, ms);
    sky_radiance(0, zen, -1, high, (const double(*)[3])ms, 64, L, T);
    assert_true(L[2] > L[1] && L[1] > L[0]); /* blue overhead */
    sky_radiance(0, zen, -1, high, NULL, 64, Lsingle, T);
    for (int k = 0; k < 3; k++)
        assert_true(L[k] > Lsingle[k] * 1.05); /* multiple scattering adds light */
    sky_radiance(10000, zen, -1, high, (const double(*)[3])ms, 64, L10, T);
    assert_true(L10[2] < 0.5 * L[2]); /* thinner air above 10 km: a darker sky */
    double Ts[3];
    sky_transmittance(0, low, -1, 256, Ts);
    assert_true(Ts[0] > 2 * Ts[2]); /* a low sun's light reddened */
    double toward[3] = {0, sin(4 * M_PI / 180), cos(4 * M_PI / 180)};
    sky_multiple_scattering(low, ms);
    sky_radiance(0, toward, -1, low, (const double(*)[3])ms, 64, L, T);
    assert_true(L[0] > L[2] * 0.8); /* the horizon under a setting sun glows red-orange */
    double night[3] = {0, -0.3, sqrt(1 - 0.09)};
    sky_transmittance(0, night, -1, 64, Ts);
    assert_true(Ts[0] == 0 && Ts[1] == 0 && Ts[2] == 0); /* the Earth's shadow */
    double mean[3];
    sky_multiple_scattering(high, ms);
    sky_mean(0, high, (const double(*)[3])ms, mean);
    print_message("the sky's cosine-weighted mean under a sun 60 deg up: %.4f %.4f %.4f per unit irradiance\n", mean[0],
                  mean[1], mean[2]);
    assert_true(mean[2] > 0.01 && mean[2] < 0.1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(horizontal_beer_lambert), cmocka_unit_test(vertical_closed_form),
        cmocka_unit_test(converges_at_the_shaders_counts), cmocka_unit_test(what_a_sky_does),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
