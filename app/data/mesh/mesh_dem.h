/* mesh_dem — a heightfield (data/geo/terrain.h) as a closed solid for printing: the surface through every
 * step-th texel centre (and the last row and column), two triangles a cell, walls down from the border
 * to a flat base at a given height, the base fanned from its centre. Vertices sit on the texels'
 * heights exactly (as the renderer's bilinear surface passes through them); nodata texels take the
 * lowest height, counted. No GL. */
#ifndef FATHOM_MESH_DEM_H
#define FATHOM_MESH_DEM_H

#include "data/mesh/mesh.h"
#include "data/geo/terrain.h"

typedef struct mesh_dem_stats {
    size_t top_vertices; /* the first top_vertices of the mesh are the surface's */
    size_t holes;        /* of them, nodata texels set to the lowest height */
} mesh_dem_stats;

bool mesh_dem_solid(const heightfield *hf, int step, double base, mesh *out, mesh_dem_stats *st, err_t *err);

#endif
