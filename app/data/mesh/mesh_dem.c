/* mesh_dem — a heightfield as a printable solid: its surface, four walls and a base (data/mesh/mesh_dem.h). */
#include "data/mesh/mesh_dem.h"

#include <math.h>
#include <stdlib.h>

/* The grid's columns (or rows) kept: every step-th, and the last. */
static int kept(int n, int step, int k)
{
    int m = (n - 1 + step - 1) / step; /* cells */
    return k >= m ? n - 1 : k * step;
}

bool mesh_dem_solid(const heightfield *hf, int step, double base, mesh *out, mesh_dem_stats *st, err_t *err)
{
    mesh_free(out);
    *st = (mesh_dem_stats){0};
    if (step < 1)
        return err_set(err, "mesh: the DEM's step must be at least 1 texel (got %d)", step);
    if (hf->width < 2 || hf->height < 2)
        return err_set(err, "mesh: a DEM of %dx%d texels has no surface (at least 2x2)", hf->width, hf->height);
    if (!(base < hf->hmin))
        return err_set(err, "mesh: the base (%g) must lie below the DEM's lowest point (%g)", base, (double)hf->hmin);
    int nx = (hf->width - 1 + step - 1) / step + 1, nz = (hf->height - 1 + step - 1) / step + 1;
    if ((double)nx * nz > 4.0e8)
        return err_set(err, "mesh: %dx%d vertices is too many: lower --resolution", nx, nz);
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nx; i++) {
            int ti = kept(hf->width, step, i), tj = kept(hf->height, step, j);
            float h = hf->h[(size_t)tj * (size_t)hf->width + (size_t)ti];
            if (TERRAIN_IS_HOLE(h)) { /* nodata: at the lowest height, counted */
                h = hf->hmin;
                st->holes++;
            }
            float p[3] = {hf->x0 + ((float)ti + 0.5f) * hf->dx, h, hf->z0 + ((float)tj + 0.5f) * hf->dz}, n[3] = {0, 1, 0};
            mesh_add_vertex(out, p, n);
        }
    for (int j = 0; j + 1 < nz; j++)
        for (int i = 0; i + 1 < nx; i++) { /* counter-clockwise seen from above (+y): x east, z south */
            uint32_t a = (uint32_t)(j * nx + i), b = a + 1, c = a + (uint32_t)nx, d = c + 1;
            mesh_add_triangle(out, a, c, d);
            mesh_add_triangle(out, a, d, b);
        }
    st->top_vertices = (size_t)nx * (size_t)nz;
    /* the border, as the top's triangles run along it: each edge a → b gets a wall down to the base and
     * a triangle of the base fanned from its centre */
    float centre[3] = {hf->x0 + 0.5f * (float)hf->width * hf->dx, (float)base, hf->z0 + 0.5f * (float)hf->height * hf->dz};
    uint32_t c0 = mesh_add_vertex(out, centre, (const float[3]){0, -1, 0});
    uint32_t *below = util_alloc(st->top_vertices * sizeof *below, "mesh base");
    for (size_t v = 0; v < st->top_vertices; v++) {
        int i = (int)(v % (size_t)nx), j = (int)(v / (size_t)nx);
        below[v] = UINT32_MAX;
        if (i == 0 || j == 0 || i == nx - 1 || j == nz - 1) {
            float p[3] = {out->pos[3 * v], (float)base, out->pos[3 * v + 2]}, n[3] = {0, -1, 0};
            below[v] = mesh_add_vertex(out, p, n);
        }
    }
    int total = 2 * (nx - 1) + 2 * (nz - 1);
    for (int e = 0; e < total; e++) {
        uint32_t a, b;
        if (e < nx - 1) { /* north row, westward */
            a = (uint32_t)(e + 1), b = (uint32_t)e;
        } else if (e < nx - 1 + nz - 1) { /* west column, southward */
            int j = e - (nx - 1);
            a = (uint32_t)(j * nx), b = (uint32_t)((j + 1) * nx);
        } else if (e < 2 * (nx - 1) + nz - 1) { /* south row, eastward */
            int i = e - (nx - 1) - (nz - 1);
            a = (uint32_t)((nz - 1) * nx + i), b = a + 1;
        } else { /* east column, northward */
            int j = e - 2 * (nx - 1) - (nz - 1);
            a = (uint32_t)((j + 1) * nx + nx - 1), b = (uint32_t)(j * nx + nx - 1);
        }
        mesh_add_triangle(out, b, a, below[a]);
        mesh_add_triangle(out, b, below[a], below[b]);
        mesh_add_triangle(out, below[b], below[a], c0);
    }
    free(below);
    return true;
}
