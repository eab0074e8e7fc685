/* water — the lakes a DEM implies: its depressions filled to their spill heights (docs/guide/gis.md).
 *
 * Priority-flood (Barnes, Lehman & Mulla 2014, "Priority-Flood: An optimal depression-filling and
 * watershed-labeling algorithm", Computers & Geosciences 62, Algorithm 2): water leaves the grid at its
 * edge and at nodata; from there the lowest cell not yet reached is taken next (a priority queue), and a
 * neighbour lower than it is raised to its height and flooded at once (a plain queue: the pit). Every
 * cell ends at its spill height: the lowest, over all paths to the edge or nodata, of the highest cell on
 * the path (8 neighbours). O(n log n), exact for any grid: no tolerance, no iteration.
 *
 * Lakes are the 8-connected pieces of raised cells (their water level is one: two raised neighbours
 * always share it); a lake shallower than min_depth or smaller than min_area is left dry. */
#ifndef FATHOM_WATER_H
#define FATHOM_WATER_H

#include <stdbool.h>
#include <stddef.h>

#include "util.h"

typedef struct water_fill_desc {
    const float *ground; /* w × h heights, row 0 north; NaN = nodata (water drains into it) */
    int w, h;
    double dx, dz;       /* metres per texel (area thresholds) */
    double min_depth;    /* metres: a lake whose deepest cell is shallower stays dry (0: keep every lake) */
    double min_area;     /* square metres: a lake covering less stays dry (0: keep every lake) */
} water_fill_desc;

typedef struct water_fill_stats {
    size_t lakes, dropped;  /* lakes kept, and left dry by the thresholds */
    size_t wet;             /* cells under water */
    double volume;          /* cubic metres of water (depth × texel area, summed) */
    double deepest;         /* metres */
} water_fill_stats;

/* surface (w × h): the water's level where a kept lake covers the cell, NaN elsewhere (dry, and nodata).
 * False with a message only when memory runs out. */
bool water_fill(const water_fill_desc *d, float *surface, water_fill_stats *st, err_t *err);

/* A terrain's water to draw (shaders/terrain/terrain.glsl TERRAIN_WATER_GRID): each texel's water level in
 * out (w × h), or WATER_DRY; ground is the grid as drawn (heights times the exaggeration ex, nodata as
 * TERRAIN_HOLE, −1e30; dx, dz metres a texel: rivers' widths). file NULL: the lakes the ground implies (water_fill, every lake); a vector file
 * (water_is_vector): its polygons with their levels on dem's grid (geo_water_polygons); else band 1 of that
 * raster, water-surface heights in metres on the DEM's own grid (the same size: a flood model's output, or
 * fathom water's). Levels times ex, nodata dry. *top: the highest level (−1e30 when all is dry). */
#define WATER_DRY (-1e30f)
bool water_grid(const float *ground, int w, int h, double dx, double dz, const char *dem, const char *file, float ex,
                float *out, float *top, err_t *err);
/* Rivers (data/geo/geo.h geo_river: courses in texel coordinates, width and depth in metres) into out (w × h,
 * water levels or WATER_DRY; a texel already wet keeps the higher level): each course followed downhill,
 * from its higher end, in steps of at most half a texel, its surface `depth` above the ground there (times
 * ex) but never above its level upstream, so it only ever runs down; each texel within half the width of the
 * course (dx, dz: metres a texel) takes the level of the nearest step. ground as water_grid's. */
struct geo_river;
void water_rivers(const float *ground, int w, int h, double dx, double dz, float ex, const struct geo_river *r, int n,
                  float *out);
/* Whether terrain.water's file is vector data (by its name: .geojson, .json, .gpkg, .shp, .kml, .gml, .fgb). */
bool water_is_vector(const char *file);

#endif
