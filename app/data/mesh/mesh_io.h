/* mesh_io — meshes to and from files, and simplified, through assimp and meshoptimizer (Debian's
 * libassimp and libmeshoptimizer) in the module fathom_mesh.so, loaded on first use (data/lazy/lazy.h), so a
 * run that writes no mesh never maps them. No hand-written writers.
 *
 * Formats by the file's extension: .ply (binary, with normals: without colours, which assimp 5.2 writes
 * wrong there), .stl (binary),
 * .obj (no material file), .glb (glTF 2 binary, with normals and colours), .3mf (3D printing, in
 * millimetres by the format's definition), .stp (STEP, a faceted solid for CAD). A file is written
 * whole or not at all (util_atomic: a temporary file beside it, renamed over it). */
#ifndef FATHOM_MESH_IO_H
#define FATHOM_MESH_IO_H

#include <stdbool.h>
#include <stddef.h>

#include "data/mesh/mesh.h"
#include "util.h"

/* assimp's exporter for path's extension; false with err (the formats listed) for any other. */
bool mesh_io_format(const char *path, const char **exporter, err_t *err);
/* Writes m to path (its extension picks the format). */
bool mesh_io_write(const mesh *m, const char *path, err_t *err);
/* Reads a mesh file, identical vertices joined (an STL's by position alone, as a slicer joins them;
 * positions only: what the checks need). */
bool mesh_io_read(const char *path, mesh *m, err_t *err);
/* Simplifies m toward target triangles (meshoptimizer: edge collapses by quadric error, Garland &
 * Heckbert 1997) while no collapse moves the surface by more than tolerance (world units); *error: the
 * largest deviation meshoptimizer reports. Normals and colours follow their vertices. */
bool mesh_io_simplify(mesh *m, size_t target, double tolerance, double *error, err_t *err);

/* The module's entry points (mesh_file.cpp), by name through lazy_symbol. */
typedef struct mesh_io_view {
    const float *pos, *nrm, *col;
    const uint32_t *tri;
    size_t nv, nt;
} mesh_io_view;
typedef bool (*mesh_io_encode_fn)(const mesh_io_view *v, const char *exporter, void **data, size_t *size, char *err,
                                  size_t n);
typedef bool (*mesh_io_export_fn)(const mesh_io_view *v, const char *exporter, const char *path, char *err, size_t n);
typedef bool (*mesh_io_decode_fn)(const char *path, float **pos, size_t *nv, uint32_t **tri, size_t *nt, char *err,
                                  size_t n);
typedef size_t (*mesh_io_simplify_fn)(const mesh_io_view *v, uint32_t *out, size_t target_triangles, float tolerance,
                                      float *error);

#endif
