/* res_droplets — the droplets on the GPU (a render_resource kind). */
#ifndef FATHOM_RES_DROPLETS_H
#define FATHOM_RES_DROPLETS_H

#include "data/droplets/droplets.h"
#include "gpu/render_resource.h"

/* The loaded droplets (NULL without), and the seconds reading the file and building the grid took. */
const droplets *res_droplets_loaded(double *read_s, double *grid_s);

#endif
