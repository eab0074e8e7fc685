/* sky — the Earth's atmosphere as a participating medium, after Hillaire, "A Scalable and Production
 * Ready Sky and Atmosphere Rendering Technique" (EGSR 2020), whose parameters these are: Rayleigh
 * scattering (5.802, 13.558, 33.1)·10⁻⁶ /m with an 8 km scale height, Mie scattering 3.996·10⁻⁶ and
 * absorption 0.444·10⁻⁶ /m with a 1.2 km scale height (Cornette–Shanks phase, g 0.8), ozone absorbing
 * (0.650, 1.881, 0.085)·10⁻⁶ /m in a tent 30 km wide about 25 km; a sphere of 6,360 km under a 100 km
 * shell, a ground of albedo 0.3.
 *
 * Light: single scattering of the sun along a ray, plus Hillaire's multiple scattering: at each point
 * an isotropic Ψ_ms = L₂/(1 − f_ms) (his eq. 5–9), which depends on the altitude and the sun's zenith
 * only, so for one sun it is a table by altitude (SKY_MS_N rows) that the CPU fills here and the
 * shaders read (shaders/common/sky.glsl runs the same single-scattering march with fewer samples).
 *
 * Double precision, pure C: what the scene loader needs (the sun's light through the air, the sky's
 * mean for the ambient, the Ψ_ms table) and the tests' reference. Distances in metres, altitudes above
 * the sphere; directions unit vectors with +Y up (the local vertical: the planet's curvature enters
 * through the sphere's geometry, not the direction). Radiances are per unit of the sun's irradiance
 * at the top of the atmosphere (multiply by it). */
#ifndef FATHOM_SKY_H
#define FATHOM_SKY_H

#include <stdbool.h>

#define SKY_PLANET_RADIUS 6360000.0
#define SKY_TOP 100000.0 /* the atmosphere's thickness, metres */
enum { SKY_MS_N = 32 };  /* Ψ_ms rows: altitudes 0 … SKY_TOP, quadratic spacing (dense low) */

/* Extinction and scattering at an altitude, per metre: RGB (680, 550, 440 nm). */
void sky_extinction(double altitude, double ext[3]);

/* Transmittance from a point at `altitude` along `dir` over `dist` metres (dist < 0: to the top of the
 * atmosphere, 0 if the ray meets the ground), by `steps` midpoint steps. */
void sky_transmittance(double altitude, const double dir[3], double dist, int steps, double T[3]);

/* The altitude of row i of the Ψ_ms table, and Ψ_ms for the sun in direction `sun` (unit, toward it). */
double sky_ms_altitude(int i);
void sky_multiple_scattering(const double sun[3], double ms[SKY_MS_N][3]);

/* Radiance reaching a point at `altitude` from direction -dir (looking along dir) over `dist` metres
 * (dist < 0: the whole ray to the top or the ground), per unit of the sun's irradiance: in-scattered
 * single + multiple scattering, and the transmittance along that stretch. `ms` may be NULL (single
 * scattering only). steps: along the view ray (the sun's transmittance takes as many). */
void sky_radiance(double altitude, const double dir[3], double dist, const double sun[3],
                  const double (*ms)[3], int steps, double L[3], double T[3]);

/* The sky's mean radiance over the upper hemisphere seen from `altitude` (per unit of the sun's
 * irradiance), the sun's disc left out: the scene's ambient under a physical sky. */
void sky_mean(double altitude, const double sun[3], const double (*ms)[3], double L[3]);

#endif
