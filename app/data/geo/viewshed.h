/* viewshed — which texels of a heightfield an observer sees, exactly, in double precision.
 *
 * The surface is the renderer's (data/geo/terrain.h, shaders/terrain/terrain.glsl): heights at texel
 * centres, bilinear in each cell between four of them; a cell with a nodata corner has no surface
 * (a line of sight passes over it). A texel is visible when the straight line from the observer's eye
 * (observer_height above the ground under it) to the point target_height above the texel's centre
 * stays on or above the surface all the way. Earth curvature and refraction: every point d metres
 * from the observer lies lower by (1 − k) d² / 2R (R = 6,371 km, k the refraction coefficient, 0.13 the
 * surveyors' default; Yoeli 1985, the same rule as gdal_viewshed's -cc 0.87).
 *
 * Along a line of sight the clearance (sight line minus dropped surface) is, inside each cell, a
 * quadratic in the line's parameter (the bilinear patch and the d² drop are both quadratics there), so
 * each cell is decided exactly by that quadratic's minimum. Cells are reached by descending a pyramid
 * of cell maxima (the max-mip traversal): a node whose highest point lies below the line's lowest
 * clearance bound over it is skipped whole; so no line tunnels through a ridge. */
#ifndef FATHOM_VIEWSHED_H
#define FATHOM_VIEWSHED_H

#include <stdbool.h>
#include <stddef.h>

#include "util.h"

#define VIEWSHED_EARTH_RADIUS 6371000.0 /* m: the IUGG mean radius (as data/geo/dem.h's spacing) */
#define VIEWSHED_REFRACTION 0.13        /* k: the surveyors' refraction coefficient, the defaults' (and the renderer's) */
#define VIEWSHED_TIE 1e-6               /* m: a sight line this close to the surface still sees (grazing) */

enum { VIEWSHED_HIDDEN = 0, VIEWSHED_VISIBLE = 1, VIEWSHED_NODATA = 255 };

typedef struct viewshed_desc {
    const float *heights; /* w × h, row 0 north, metres; NaN = nodata */
    int w, h;
    double dx, dz;                  /* metres per texel: column and row spacing */
    double col, row;                /* the observer, in texels (texel centres at whole numbers) */
    double observer_height;         /* metres above the ground under the observer */
    double target_height;           /* metres above each texel's ground */
    double refraction;              /* k: 0 = no refraction; the drop is (1 − k) d² / 2R */
    bool curvature;                 /* false: a flat Earth (no drop at all) */
    double radius;                  /* metres: texels farther are VIEWSHED_NODATA (0: no limit) */
    int threads;                    /* 0: one a CPU */
} viewshed_desc;

typedef struct viewshed_stats {
    size_t visible, hidden, nodata; /* texels of each answer */
    double nodes_per_texel;         /* pyramid nodes visited, a texel on average */
    double seconds;                 /* wall clock of the computation */
    int threads;                    /* it ran on */
} viewshed_stats;

/* Fills out (w × h bytes) with VIEWSHED_VISIBLE, _HIDDEN or _NODATA (a nodata texel, or beyond the
 * radius). Fails with a message when the observer is outside the grid or over a hole. */
bool viewshed_compute(const viewshed_desc *d, unsigned char *out, viewshed_stats *stats, err_t *err);

#endif
