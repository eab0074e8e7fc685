/* Shared harness of the GL tests: a headless context, scenes from text, rendering with readback,
 * primary rays in double precision. */
#ifndef FATHOM_TEST_GLTEST_H
#define FATHOM_TEST_GLTEST_H

#include "view/aov.h"
#include "view/camera.h"
#include "reference.h"
#include "scene/scene.h"

enum { W = 97, H = 61, AOV = AOV_FLOATS };
#define DEG2RAD (GLM_PI / 180.0)

int gl_setup(void **st);
int gl_teardown(void **st);
void load_text(const char *json, const char *const *sets, int nsets, scene *s);
/* A fractal scene of `program` with the "fractal" block and "quality" block given as JSON, lit by a sun. */
void load_fractal(const char *program, const char *fractal, const char *quality_json, scene *s);
/* The scene's map() at n points (3 floats each; 2 floats each into out: distance, material), the
 * program compiled with `extra` #defines (NULL: none); a failure fails the test. */
void gl_probe(const scene *s, const char *extra, const float *pts, int n, float *out);
/* Renders `spp` samples of s; fills aov (w*h*8, top row first) and rgba (w*h*4) when not NULL. */
void draw(const scene *s, const camera *cam, int w, int h, int spp, const char *extra, float *aov, float *rgba);
camera cam_at(double ex, double ey, double ez, double tx, double ty, double tz, double fov_deg);
/* The primary ray of pixel (x, row) with row 0 at the top, in double (camera.h's convention). */
dray pixel_ray(const camera *c, int x, int row, int w, int h);
/* Fails unless every colour and AOV value is finite (depth: finite, or +inf with a zero normal). */
void check_finite(const char *what, const float *aov, const float *rgba, int n);

#endif
