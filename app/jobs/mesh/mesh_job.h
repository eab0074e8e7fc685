/* mesh_job — `fathom mesh`: a scene's surface as a mesh file (data/mesh/mesh.h, data/mesh/mesh_io.h).
 *
 * A distance-field scene (fractal formulas, fragments, csg, the torus, the noise terrain) is meshed by
 * the scene's own map() probed on the GPU (render_probe.h): the mesh is the surface the renderer
 * marches. Fractals are meshed at the level half a voxel (a voxel is their footprint, as a pixel is
 * the renderer's; a fragment's Detail sets it instead), everything else at 0. A terrain scene with a
 * DEM becomes a printable solid (data/mesh/mesh_dem.h). Then, as asked: the largest shell only, a triangle
 * budget (meshoptimizer, within a tolerance), a print size in millimetres, vertex colours from the
 * materials, and a report: time, memory, triangles, the topology check, and the vertices' distance to
 * the field (in voxels) before and after simplification. */
#ifndef FATHOM_MESH_JOB_H
#define FATHOM_MESH_JOB_H

#include <stdbool.h>
#include <stddef.h>

#include "util.h"

enum { MESH_JOB_DEFAULT_RES = 256 }; /* cells along the box's longest side when none is given */

typedef struct mesh_desc {
    const char *scene;
    const char *const *sets;
    int set_count;
    const char *output;
    int resolution;       /* cells (a DEM: vertices) along the longest side; 0: the default */
    bool has_box;
    double box[6];        /* x0, y0, z0, x1, y1, z1 */
    size_t triangles;     /* simplify toward this many; 0: keep all */
    double tolerance;     /* simplification's largest deviation, in voxels (a DEM: texels) */
    bool one_shell;       /* keep the largest connected piece */
    double print_mm;      /* scale so the longest side is this many millimetres; 0: scene units */
    double base;          /* a DEM solid's base, metres below its lowest point; 0: the default */
    bool quiet;
} mesh_desc;

/* Loads d->scene, opens the GL (a field scene) and meshes it. */
bool mesh_job_run(const mesh_desc *d, err_t *err);
/* Meshes s, already loaded and set in the renderer (a field scene: the window's M key). */
struct scene;
bool mesh_job_scene(const mesh_desc *d, const struct scene *s, err_t *err);

#endif
