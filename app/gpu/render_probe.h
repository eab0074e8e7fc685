/* render_probe — the scene's shader evaluated at points, not pixels: its distance estimate (the
 * window's flying speed and slide rule, tests), other probe shaders (fog, droplets, loop counts), the
 * ground under a walker, and the precision a deep zoom's view needs. Uses the renderer (render.h):
 * the origin its points are relative to, and the scene it re-sets. GL. */
#ifndef FATHOM_RENDER_PROBE_H
#define FATHOM_RENDER_PROBE_H

#include <stdbool.h>
#include <stdint.h>

#include "scene/scene.h"
#include "util.h"
#include "view/camera.h"

/* Evaluates the scene's map() on the GPU at n points (xyz each) into out (distance, material each):
 * the shader's own distance estimate, for tests and the window's flying speed. */
bool render_probe(const scene *s, const char *extra_defines, const float *points, int n, float *out, err_t *err);
/* The same with another probe shader: fogprobe.frag gives the fog's optical depth for (y, dir y, length). */
bool render_probe_with(const scene *s, const char *frag, const char *extra_defines, const float *points, int n,
                       float *out, err_t *err);
/* The loop iterations map() runs at each of n points (into loops), measured against the driver's loop
 * limiter (llvmpipe's; shaders/common/budget.glsl); false with err where the driver has none to
 * measure against. */
bool render_probe_loops(const scene *s, const float *points, int n, int *loops, err_t *err);
/* A probe shader over n rays (origin xyz, direction xyz each, in uPoints and uDirs) into out (4 floats
 * each): dropletprobe.frag gives the droplets' grid walk for tests. */
bool render_probe_rays(const scene *s, const char *frag, const char *extra_defines, const float *rays, int n,
                       float *out, err_t *err);
/* Adaptive sampling's stopping rule (shaders/errormask.frag) on given sums: sum and squares are w × h
 * RGBA floats each, bottom row first (target 0: Σ radiance and the sample count; target 3: Σ radiance²
 * and the samples that passed a surface by); mask gets 1 where the pixel takes another sample. Tests. */
bool render_probe_error_mask(const float *sum, const float *squares, int w, int h, float tolerance, uint8_t *mask,
                             err_t *err);
/* Terrain scenes: the ground height under world (x, z); false for other scenes. */
bool render_ground_height(float x, float z, float *height);

/* Deep zoom. A fractal whose formula compiles in double (formula.h @deep) switches to double where a
 * float cannot resolve the view (scene_needs_double). The shader then works in coordinates relative
 * to an origin, the eye, held here in double (render_begin sets it); probes take their points
 * relative to it too (0 everywhere else). render_fit_precision probes the distance at the camera and
 * sets s->fractal.deep_now as the view needs, re-setting the scene when it changes (false: the GL
 * lacks doubles, or a GL error). */
bool render_fit_precision(scene *s, const camera *c, int height, err_t *err);

#endif
