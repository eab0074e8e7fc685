/* droplets — liquid droplets from a file (the droplets paper's use case: a CFD package's spray, tens
 * to hundreds of thousands of small spheres), and the uniform grid the shader walks to find them.
 * Pure C: files in, arrays out.
 *
 * File: CSV as ParaView writes it (columns "Points:0", "Points:1", "Points:2" and "radius" or
 * "diameter"; other columns are ignored), or plain "x,y,z,r" (a header row of those names, or four
 * numbers a row with no header). Parsed by libcsv. Metres; `scale` multiplies positions and radii.
 *
 * Grid (Amanatides & Woo, "A Fast Voxel Traversal Algorithm for Ray Tracing", Eurographics 1987):
 * about DROPLET_GRID_DENSITY cells per droplet over the droplets' bounds; every droplet is listed in
 * each cell its sphere overlaps. Built in O(N + references) by two counting passes (no sort).
 * The shader (shaders/common/droplets.glsl) reads three texture buffers:
 *   spheres   RGBA32F: centre, radius (droplet i at texel i)
 *   cells     R32UI:   cell c's droplets are index[cells[c] .. cells[c+1])  (cell c = x + nx (y + ny z))
 *   index     R32UI:   droplet numbers, cell after cell
 *
 * The alternative (scene key droplets.structure = "bvh", to compare): a bounding volume hierarchy by
 * median split (app/data/droplets/bvh.h), O(N log N) to build, walked front to back with a stack:
 *   nodes     RGBA32UI: 2 texels a node, (lo, first) and (hi, count), lo and hi as float bits
 *   index     R32UI:   droplet numbers in leaf order
 */
#ifndef FATHOM_DROPLETS_H
#define FATHOM_DROPLETS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "util.h"

/* At most this many droplets a file (16.7 M: 268 MB of spheres; GL's texture buffers hold 128 M texels
 * on llvmpipe and NVIDIA). */
#define DROPLETS_MAX (1 << 24)
/* Coordinates and radii beyond this many metres are refused: the shader's float grid walk would lose
 * the droplets' size against their position. */
#define DROPLETS_COORD_MAX 1e6
/* Radii below this (metres: a nanometre) are refused: a mistake in units, and floats cannot hold them
 * next to metre-sized positions. */
#define DROPLETS_RADIUS_MIN 1e-9
/* Cells per droplet the grid aims at, and its limits (cells, and cell listings in all). */
#define DROPLET_GRID_DENSITY 2.0
#define DROPLET_GRID_MAX_SIDE 1024
#define DROPLET_GRID_MAX_CELLS (1 << 24)
#define DROPLET_REFS_MAX (1u << 27)

typedef struct droplets {
    float *spheres; /* x, y, z, r per droplet */
    int count;
    float r_min, r_max;
    /* the grid */
    float lo[3], hi[3], cell[3];
    int dims[3];
    uint32_t *cells; /* dims[0]·dims[1]·dims[2] + 1 offsets into index */
    uint32_t *index;
    size_t refs; /* entries in index */
    /* the BVH instead (droplets_build_bvh): nodes packed as the shader reads them; cells NULL */
    uint32_t *nodes;
    int node_count;
} droplets;

/* Reads a droplet file (scale multiplies positions and radii). Errors name file, line and column. */
bool droplets_read(const char *path, float scale, droplets *d, err_t *err);

/* Reads droplets from CSV text in memory (path is used in messages). */
bool droplets_read_text(const char *text, size_t len, const char *path, float scale, droplets *d, err_t *err);

/* Builds the grid over d->spheres. Fails only when the droplets' sizes are so uneven that the cell
 * listings would pass DROPLET_REFS_MAX even at the coarsest grid. */
bool droplets_build_grid(droplets *d, err_t *err);

size_t droplets_cell_count(const droplets *d);
/* The signed distance from p to the nearest droplet's surface (negative inside one), by the grid: exact
 * wherever the nearest droplet meets one of the 27 cells around p's (within a cell of p, from inside the
 * grid's box), else a lower bound (the distance to those cells' outer walls, or to the grid's box from
 * outside it): a bound a mesher may step by. */
double droplets_distance(const droplets *d, const float p[3]);

/* Builds the BVH over d->spheres instead of the grid (lo/hi: the root's box). */
void droplets_build_bvh(droplets *d);

/* Bytes the spheres, cells and index take (on the GPU as well). */
size_t droplets_bytes(const droplets *d);

void droplets_free(droplets *d);

/* Sub-pixel droplets are not traced but attenuate the ray by their mean over the disc they cover
 * (the level of detail of shaders/common/droplets.glsl). For index of refraction ior, the disc's area
 * is split into DROPLET_LOD_NODES Gauss–Legendre nodes in w = (impact parameter / radius)²; node k
 * carries weight[k] · (1 − F(θ_k))² (in and out: a ray leaves a sphere at the angle it entered, so
 * F is the same at both surfaces), and the chord inside is 2 r cos_t[k] (Snell's refracted angle);
 * reflect is the disc's mean Fresnel reflectance (the light the droplet sends back). */
enum { DROPLET_LOD_NODES = 8 };
typedef struct droplet_lod_table {
    float weight[DROPLET_LOD_NODES], cos_t[DROPLET_LOD_NODES];
    float reflect;
} droplet_lod_table;
void droplets_lod_table(float ior, droplet_lod_table *t);

/* Exact Fresnel reflectance of a dielectric interface for unpolarized light, double precision:
 * cos_i the incidence cosine, eta = n_incident / n_transmitted; 1 beyond the critical angle. */
double droplets_fresnel(double cos_i, double eta);

#endif
