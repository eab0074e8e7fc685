/* mesh — a distance field's surface as a closed triangle mesh, and what a mesh is checked for.
 *
 * Extraction (mesh.c) is dual contouring over a grid of samples, in layers: only two sample layers,
 * their crossings and two layers of cells are held at a time, so the working memory grows with the
 * square of the resolution, not its cube; the mesh itself is the output and is held whole.
 *  - Sparse: the grid is cut into blocks of MESH_BLOCK³ cells; a block whose centre's distance bound
 *    (times the field's step factor) exceeds the block's half diagonal holds no surface, and its
 *    samples are not evaluated (they take a positive value). A sample shared with a visited block is
 *    always evaluated, so every sample has one sign: the mesh is closed even where a bound lies.
 *  - Clipped: the field is max(field − iso, box), the box the caller's, so a scene with an endless
 *    floor closes at the box's faces (flat, with sharp edges).
 *  - Vertices: one per surface patch of a cell (a cell whose corners' signs make several patches gets
 *    one vertex each: the marching-cubes polygon of each, faces decided by their corners alone so two
 *    cells agree), placed by the quadric of the patch's crossings and normals (Garland–Heckbert's
 *    quadric error, solved as in Ju et al. 2002, "Dual Contouring of Hermite Data", with small
 *    eigenvalues truncated, Lindstrom 2000) and kept in its cell: sharp edges and corners stay sharp.
 *    Where faces so placed cross each other (a patch pulled to a sharp feature through a neighbour's,
 *    two sheets of a solid thinner than a cell), their corners go back to their patches' mass points
 *    (the centroid of the crossings, as marching cubes would place them): mesh_untangle.
 *  - Crossings: on each edge whose samples differ in sign, found by linear interpolation and one step
 *    of regula falsi; normals by central differences of the field there.
 *  - Thin features: an edge whose ends share a sign but lie within a voxel of the surface together has
 *    its midpoint evaluated; where that has the other sign, a feature thinner than a voxel is missed
 *    (counted: the caller reports it).
 *  - Faces: one quad per crossing edge, joining the four cells around it, split along its shorter
 *    diagonal, wound so normals point out (negative is inside).
 * The field is a callback, so the same code meshes a closed form in the tests and the scene's own
 * map() on the GPU (jobs/mesh/mesh_job.c). No GL.
 *
 * Checks (mesh_check.c): each directed edge once and its reverse once (closed, manifold, oriented),
 * one fan around each vertex, components, Euler characteristic, area and enclosed volume. */
#ifndef FATHOM_MESH_H
#define FATHOM_MESH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "util.h"

enum { MESH_BLOCK = 8, MESH_MAX_RES = 8192 };

typedef struct mesh {
    float *pos, *nrm, *col; /* 3 floats a vertex each (col: linear RGB, NULL until coloured) */
    uint32_t *tri;          /* 3 vertex indices a triangle, counter-clockwise seen from outside */
    size_t nv, nt, cap_v, cap_t;
} mesh;

/* Distances at n points (xyz each) into dist; false with err to stop the extraction. */
typedef bool (*mesh_field_fn)(void *user, const float *points, size_t n, float *dist, err_t *err);

typedef struct mesh_grid {
    double lo[3], hi[3]; /* the box meshed (the surface is clipped by it) */
    int res;             /* cells along the box's longest side */
    float iso;           /* the level meshed: field − iso = 0 */
    float step;          /* the field is a bound after this factor (distance ≥ field · step); 0: never skip */
    mesh_field_fn field;
    void *user;
    void (*progress)(void *user, double done); /* optional: 0 … 1 as layers finish */
} mesh_grid;

typedef struct mesh_stats {
    int cells[3];               /* the grid's cells along x, y, z (with one cell of margin each side) */
    double voxel;               /* a cell's side */
    long long samples;          /* grid samples in all */
    long long evaluated;        /* of them, evaluated (the rest in blocks the bound skipped) */
    long long blocks, skipped;  /* blocks, and those the bound skipped */
    long long crossings;        /* edges the surface crosses */
    long long unbounded;        /* crossings with a skipped sample: the field's bound was wrong there */
    long long clamped;          /* vertices whose quadric's point fell outside the cell (kept inside) */
    long long thin;             /* edges whose ends agree in sign and whose midpoint does not: a feature
                                   thinner than a voxel the grid misses there */
    size_t peak_bytes;          /* the most the extraction's own arrays held (the mesh aside) */
    long long crossing;         /* pairs of faces that crossed each other as first placed */
    long long untangled;        /* vertices moved to their patch's mass point to part them */
    long long crossing_left;    /* pairs still crossing after that (-1: not checked, out of memory) */
} mesh_stats;

/* Extracts g's surface into out (emptied first). False with err on a field error, or a grid over
 * MESH_MAX_RES. */
bool mesh_extract(const mesh_grid *g, mesh *out, mesh_stats *st, err_t *err);
/* What an extraction of g takes before it starts: *samples, the grid's (the bound skips empty blocks, so at most
 * this many are evaluated), and *bytes, its layers' working memory (the mesh it makes comes on top). */
bool mesh_extract_size(const mesh_grid *g, double *samples, double *bytes);
void mesh_free(mesh *m);
/* The signed distance from p to the box [lo, hi] (negative inside): the clip. */
double mesh_box_distance(const double lo[3], const double hi[3], const float p[3]);
/* Appends a vertex (returns its index) and a triangle. */
uint32_t mesh_add_vertex(mesh *m, const float p[3], const float n[3]);
void mesh_add_triangle(mesh *m, uint32_t a, uint32_t b, uint32_t c);

typedef struct mesh_topology {
    long long vertices, edges, faces;
    long long components;
    long long open_edges;        /* directed edges without their reverse: holes */
    long long nonmanifold_edges; /* directed edges used twice, or edges of more than two faces */
    long long nonmanifold_vertices; /* vertices whose faces form more than one fan */
    long long unused_vertices;
    long long degenerate;        /* faces with a repeated vertex */
    long long euler;             /* V − E + F over the used vertices */
    double area, volume;         /* volume by the divergence theorem: positive when wound outward */
    bool closed_manifold;        /* no open, non-manifold or degenerate faces */
} mesh_topology;

/* One vertex a position: vertices at exactly the same place merged (the first one's normal and colour kept),
 * as a file without indices (STL) or a reader that merges positions sees them; the number merged. Faces it
 * collapses are mesh_drop_fins'. */
long long mesh_weld(mesh *m);
/* Drops the vertices no triangle uses (after a simplification or a repair), keeping their normals and colours. */
void mesh_compact(mesh *m);
/* Checks m (no change to it). */
void mesh_check(const mesh *m, mesh_topology *t);
/* Drops faces that repeat another's corners (a simplification's collapsed slivers: two faces back to
 * back) and faces with a repeated corner; the number dropped. */
long long mesh_drop_fins(mesh *m);
/* A vertex whose faces form several fans (joined across edges of exactly two faces, one each way) gets
 * a copy for each fan past the first, moved a thousandth of the way into its fan (so no two vertices share a
 * position): sheets that touch at a vertex or along an edge part there. The number of vertices added. */
long long mesh_split_pinches(mesh *m);
/* Closes each loop of open edges with a fan of triangles; the number of holes filled. */
long long mesh_fill_holes(mesh *m);
/* Keeps only the largest component (by faces); the number of components dropped. */
long long mesh_keep_largest(mesh *m);
/* Pairs of m's faces that cross each other (mesh_intersect.c: an edge of one through the other's
 * interior; neighbours only by their far edges), -1 out of memory; crossed (m->nt bytes, or NULL) marks
 * the faces of those pairs. */
long long mesh_crossing_faces(const mesh *m, uint8_t *crossed);
/* Parts crossing faces: the corners of each crossing face moved to their patch's mass point (mass: 3
 * floats a vertex, the centroid of the crossings its quadric was placed by; NULL: none), then, while
 * faces still cross, halfway to their neighbours' mean, in up to 12 rounds; the number of vertices
 * moved, *before the pairs that crossed, *left those still crossing (-1: out of memory). */
long long mesh_untangle(mesh *m, const float *mass, long long *before, long long *left);

/* Internal to mesh.c and mesh_qef.c: the patches of a cell's sign configuration, and the quadric. */
typedef struct mesh_cell_case {
    int8_t patches;      /* surface patches in the cell (0 … 4) */
    int8_t patch_of[12]; /* each edge's patch, −1 where no crossing */
    uint8_t twice;       /* faces (bit 2·axis + side) whose two segments belong to one patch */
} mesh_cell_case;
/* The case of corner bits cfg (bit c set: corner c inside) with the faces in flips (bit 2·axis + side)
 * resolved the other way. A face whose two segments one patch holds in both its cells (twice, with no
 * flips) is flipped: its dual would join the same two vertices twice (a non-manifold edge); flipped,
 * each cell's patch splits in two (Schaefer et al. 2007, "Manifold Dual Contouring", reach the same
 * end by clustering). */
const mesh_cell_case *mesh_case(int cfg, int flips);
/* Which diagonal splits quad v (counter-clockwise): 0 for v0–v2, 1 for v1–v3 (mesh_check.c). */
int mesh_split_of(const mesh *m, const uint32_t v[4]);
/* The point minimising the quadric of n planes (point p[i], unit normal nrm[i]), truncated toward the
 * mass point; inside the cell [lo, lo + h] (clamped: *clamped set). */
void mesh_qef_solve(const float (*p)[3], const float (*nrm)[3], int n, const double lo[3], double h, float out[3],
                    bool *clamped);

#endif
