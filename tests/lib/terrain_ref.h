/* terrain_ref — what the terrain tests (geo/test_terrain.c, test_terrain_grids.c, test_terrain_shading.c)
 * share: the exact reference, a ray against the solid column under a bilinear heightfield in double (a
 * cell walk with per-cell quadratics), every pixel of a set of views checked against it, and DEMs
 * generated for them. */
#ifndef FATHOM_TEST_TERRAIN_REF_H
#define FATHOM_TEST_TERRAIN_REF_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <epoxy/gl.h>

#include "check.h"
#include "gltest.h"
#include "data/media/image_io.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "data/geo/terrain.h"

/* The height of texel (i, j), and of the bilinear surface at cell coordinates (cx, cz). */
double texel(const heightfield *hf, int i, int j);
double height_cell(const heightfield *hf, double cx, double cz);
/* The first hit of ray r with the solid under the heightfield (its sides and floor included): false
 * when it misses. */
bool ref_terrain(const heightfield *hf, const dray *r, double *t_hit);
/* How long the ray stays under the surface after entering it at t (fine steps in double). */
double dip_length(const heightfield *hf, const dray *r, double t);

typedef struct view {
    const char *what;
    double eye[3], at[3], fov;
} view;
/* The five views of the Jacksboro DEM: grazing, inside the slab, below the surface, the footprint's edge
 * from outside, rays leaving the footprint. */
extern const view VIEWS[];
/* Every pixel of each view of scene_name (with `method` and the overrides) against ref_terrain: with
 * `exact`, every pixel agrees; else a disagreement must be a sliver shorter than the method's step. */
void check_views_in(const char *scene_name, const char *method, const char *const *sets, int nsets, bool exact,
                    const view *views, int nv);

/* A w × h float DEM of rolling hills (sum of sines, 0–300 m) with a sea clamped flat at 0, 30 m
 * texels, written as EXR with its scene file; returns the scene's path. */
void synthetic_dem(const char *dir, const char *name, int w, int h, bool holes, char *scene_path, size_t n);
/* Removes NAME.exr and NAME.json for each name, then the folder. */
void remove_dems(const char *dir, const char *const *names);
/* The scene file `name` with n overrides (a failure fails the test). */
void load_text_file(const char *name, const char *const *sets, int n, scene *s);

#endif
