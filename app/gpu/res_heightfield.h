/* res_heightfield — the terrain's heights and pyramid on the GPU (a render_resource kind). */
#ifndef FATHOM_RES_HEIGHTFIELD_H
#define FATHOM_RES_HEIGHTFIELD_H

#include "data/geo/terrain.h"
#include "gpu/render_resource.h"

/* The loaded grid's description (NULL without one) and its texture tiles (1 x 1 when it fits one). */
const heightfield *res_heightfield_loaded(int *tiles_x, int *tiles_y);

#endif
