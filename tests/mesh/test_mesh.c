/* Mesh extraction against closed forms (data/mesh/mesh.h): a sphere, an offset box (its faces flat and its
 * edges sharp), a torus and a block with a hole through it (genus 1), two linked-by-overlap tori (genus
 * 2), at several resolutions: closed, manifold, oriented, Euler characteristic 2 − 2g, area and volume
 * within the resolution's bound, every vertex on the surface; the sparse blocks give the dense mesh
 * exactly; a field whose bound lies still gives a closed mesh; keeping the largest shell. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "data/mesh/mesh.h"

typedef double (*sdf_fn)(const double p[3]);

static double sd_sphere(const double p[3])
{
    return sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0;
}

static const double BOX_C[3] = {0.0123, -0.0371, 0.0219}, BOX_H[3] = {0.71, 0.53, 0.62};

static double sd_box_at(const double p[3], const double c[3], const double half[3])
{
    double out = 0, in = -1e300;
    for (int k = 0; k < 3; k++) {
        double q = fabs(p[k] - c[k]) - half[k];
        out += q > 0 ? q * q : 0;
        in = fmax(in, q);
    }
    return sqrt(out) + fmin(in, 0.0);
}

static double sd_box(const double p[3])
{
    return sd_box_at(p, BOX_C, BOX_H);
}

static double sd_torus_at(const double p[3], double x0, double R, double r)
{
    double q = sqrt((p[0] - x0) * (p[0] - x0) + p[2] * p[2]) - R;
    return sqrt(q * q + p[1] * p[1]) - r;
}

static double sd_torus(const double p[3])
{
    return sd_torus_at(p, 0, 0.8, 0.3);
}

/* A block with a round hole through it along y: genus 1, sharp rims. */
static double sd_holed(const double p[3])
{
    static const double c[3] = {0, 0, 0}, h[3] = {0.9, 0.4, 0.9};
    return fmax(sd_box_at(p, c, h), 0.45 - sqrt(p[0] * p[0] + p[2] * p[2]));
}

static double sd_two_tori(const double p[3])
{
    return fmin(sd_torus_at(p, -0.55, 0.6, 0.22), sd_torus_at(p, 0.55, 0.6, 0.22));
}

typedef struct field {
    sdf_fn f;
    double lie; /* the bound multiplied by this (1: true) */
    long long calls;
} field;

static bool eval(void *user, const float *pts, size_t n, float *d, err_t *err)
{
    (void)err;
    field *f = user;
    for (size_t i = 0; i < n; i++) {
        double p[3] = {pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]};
        d[i] = (float)(f->f(p) * f->lie);
    }
    f->calls += (long long)n;
    return true;
}

static void extract(sdf_fn f, double ext, int res, float step, mesh *m, mesh_stats *st, double lie)
{
    field fl = {f, lie, 0};
    mesh_grid g = {.lo = {-ext, -ext, -ext}, .hi = {ext, ext, ext}, .res = res, .step = step, .field = eval, .user = &fl};
    err_t err;
    assert_true(mesh_extract(&g, m, st, &err));
    /* the estimate made before a long extraction (issue 58 item 20): the grid's samples, at most those evaluated;
     * the layers' memory, at most the peak */
    double samples, bytes;
    assert_true(mesh_extract_size(&g, &samples, &bytes));
    assert_true(samples == (double)(st->cells[0] + 1) * (st->cells[1] + 1) * (st->cells[2] + 1));
    assert_true((double)st->evaluated <= samples && bytes <= (double)st->peak_bytes);
}

/* The worst |sdf| over vertices, in voxels. */
static double worst_off(const mesh *m, sdf_fn f, double h)
{
    double w = 0;
    for (size_t v = 0; v < m->nv; v++) {
        double p[3] = {m->pos[3 * v], m->pos[3 * v + 1], m->pos[3 * v + 2]};
        w = fmax(w, fabs(f(p)));
    }
    return w / h;
}

static void closed(const char *what, sdf_fn f, double ext, int res, int genus, double area, double volume)
{
    mesh m = {0};
    mesh_stats st;
    extract(f, ext, res, 1.0f, &m, &st, 1.0);
    mesh_topology t;
    mesh_check(&m, &t);
    double h = st.voxel, off = worst_off(&m, f, h);
    fprintf(stderr, "  %-10s %4d³: %7zu triangles, euler %lld, area %.5f (%.5f), volume %.5f (%.5f), worst vertex "
                    "%.4f voxels, %lld of %lld blocks skipped, %lld clamped\n", what, res, m.nt, t.euler, t.area, area,
            t.volume, volume, off, st.skipped, st.blocks, st.clamped);
    assert_true(t.closed_manifold);
    assert_int_equal(t.open_edges, 0);
    assert_int_equal(t.nonmanifold_edges, 0);
    assert_int_equal(t.nonmanifold_vertices, 0);
    assert_int_equal(t.components, 1);
    assert_int_equal(t.euler, 2 - 2 * genus);
    /* vertices within a tenth of a voxel of the surface; a vertex within e of it moves the volume by
     * about area·e (measured: 0.019 area·h at worst, the torus at 24³) */
    assert_true(off < 0.1);
    assert_true(fabs(t.volume - volume) < area * h * 0.04);
    assert_true(fabs(t.area - area) < area * 0.02);
    mesh_free(&m);
}

static void closed_forms(void **state)
{
    (void)state;
    const double PI = 3.14159265358979323846;
    for (int res = 24; res <= 96; res *= 2) {
        closed("sphere", sd_sphere, 1.25, res, 0, 4 * PI, 4 * PI / 3);
        double a = 8 * (BOX_H[0] * BOX_H[1] + BOX_H[1] * BOX_H[2] + BOX_H[0] * BOX_H[2]);
        closed("box", sd_box, 0.9, res, 0, a, 8 * BOX_H[0] * BOX_H[1] * BOX_H[2]);
        closed("torus", sd_torus, 1.25, res, 1, 4 * PI * PI * 0.8 * 0.3, 2 * PI * PI * 0.8 * 0.09);
    }
    double holed_area = 2 * (1.8 * 1.8 - PI * 0.45 * 0.45) + 4 * 1.8 * 0.8 + 2 * PI * 0.45 * 0.8;
    closed("holed", sd_holed, 1.0, 80, 1, holed_area, (1.8 * 1.8 - PI * 0.45 * 0.45) * 0.8);
    mesh m = {0};
    mesh_stats st;
    mesh_topology t;
    extract(sd_two_tori, 1.4, 96, 1.0f, &m, &st, 1.0);
    mesh_check(&m, &t);
    assert_true(t.closed_manifold);
    assert_int_equal(t.euler, -2); /* genus 2 */
    mesh_free(&m);
}

/* The box's faces are flat and its edges sharp: the area whose normal is an axis's, within 0.5°. */
static void box_edges_sharp(void **state)
{
    (void)state;
    mesh m = {0};
    mesh_stats st;
    extract(sd_box, 0.9, 48, 1.0f, &m, &st, 1.0);
    double flat = 0, all = 0, worst_corner = 0;
    for (size_t f = 0; f < m.nt; f++) {
        const float *a = m.pos + 3 * m.tri[3 * f], *b = m.pos + 3 * m.tri[3 * f + 1], *c = m.pos + 3 * m.tri[3 * f + 2];
        double u[3], v[3], n[3];
        for (int k = 0; k < 3; k++) {
            u[k] = b[k] - a[k];
            v[k] = c[k] - a[k];
        }
        n[0] = u[1] * v[2] - u[2] * v[1];
        n[1] = u[2] * v[0] - u[0] * v[2];
        n[2] = u[0] * v[1] - u[1] * v[0];
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        all += len / 2;
        double best = fmax(fabs(n[0]), fmax(fabs(n[1]), fabs(n[2]))) / (len > 0 ? len : 1);
        flat += best > cos(0.5 * 3.14159265 / 180) ? len / 2 : 0;
    }
    for (int s = 0; s < 8; s++) { /* each corner of the box: the nearest vertex */
        double corner[3], best = 1e9;
        for (int k = 0; k < 3; k++)
            corner[k] = BOX_C[k] + (s >> k & 1 ? BOX_H[k] : -BOX_H[k]);
        for (size_t v = 0; v < m.nv; v++) {
            double d = 0;
            for (int k = 0; k < 3; k++)
                d += (m.pos[3 * v + (size_t)k] - corner[k]) * (m.pos[3 * v + (size_t)k] - corner[k]);
            best = fmin(best, sqrt(d));
        }
        worst_corner = fmax(worst_corner, best);
    }
    fprintf(stderr, "  box 48³: %.4f%% of the area on the faces' planes' normals; corners within %.2e (voxel %.3g)\n",
            100 * flat / all, worst_corner, st.voxel);
    assert_true(flat / all > 0.999);
    assert_true(worst_corner < 1e-3 * st.voxel);
    mesh_free(&m);
}

static bool same_mesh(const mesh *a, const mesh *b)
{
    return a->nv == b->nv && a->nt == b->nt && !memcmp(a->pos, b->pos, a->nv * 3 * sizeof(float)) &&
           !memcmp(a->tri, b->tri, a->nt * 3 * sizeof(uint32_t));
}

/* The blocks the bound skips hold nothing: the sparse mesh is the dense one; a sphere far smaller than
 * the box is mostly skipped. A bound that lies (10× too large) skips blocks it should not: the mesh
 * stays closed, and the crossings that met a skipped sample are counted. */
static void sparse_blocks(void **state)
{
    (void)state;
    mesh dense = {0}, sparse = {0};
    mesh_stats sd, ss;
    extract(sd_torus, 2.5, 160, 0.0f, &dense, &sd, 1.0);
    extract(sd_torus, 2.5, 160, 1.0f, &sparse, &ss, 1.0);
    fprintf(stderr, "  torus in a box 2× its size, 160³: %lld of %lld samples evaluated sparse, %lld dense\n",
            ss.evaluated, ss.samples, sd.evaluated);
    assert_true(same_mesh(&dense, &sparse));
    assert_true(ss.evaluated < sd.evaluated / 3);
    assert_int_equal(ss.unbounded, 0);
    mesh lied = {0};
    mesh_stats sl;
    mesh_topology t;
    extract(sd_torus, 2.5, 160, 1.0f, &lied, &sl, 10.0);
    mesh_check(&lied, &t);
    fprintf(stderr, "  a bound 10× too large: %lld blocks skipped (true: %lld), %zu triangles (true %zu), closed %d\n",
            sl.skipped, ss.skipped, lied.nt, sparse.nt, t.closed_manifold);
    assert_true(sl.skipped > ss.skipped);
    assert_true(sl.unbounded > 0); /* and the crossings that met a skipped sample say so */
    assert_true(t.closed_manifold);
    mesh_free(&dense);
    mesh_free(&sparse);
    mesh_free(&lied);
}

/* A surface crossing every block face: a plane slanted through the grid, cut by the box. */
static double sd_slant(const double p[3])
{
    return (0.31 * p[0] + 0.87 * p[1] + 0.38 * p[2] - 0.05) / sqrt(0.31 * 0.31 + 0.87 * 0.87 + 0.38 * 0.38);
}

static void block_seams(void **state)
{
    (void)state;
    mesh m = {0};
    mesh_stats st;
    mesh_topology t;
    extract(sd_slant, 1.0, 67, 1.0f, &m, &st, 1.0);
    mesh_check(&m, &t);
    assert_true(t.closed_manifold);
    assert_int_equal(t.euler, 2);
    mesh_free(&m);
}

static double sd_sphere_and_dust(const double p[3])
{
    double q[3] = {p[0] - 0.9, p[1] - 0.9, p[2] - 0.9}, r[3] = {p[0] + 0.85, p[1] + 0.85, p[2] - 0.85};
    return fmin(sd_sphere(p), fmin(sd_sphere(q) + 0.8, sd_sphere(r) + 0.88));
}

static void largest_shell(void **state)
{
    (void)state;
    mesh m = {0};
    mesh_stats st;
    mesh_topology t;
    extract(sd_sphere_and_dust, 1.3, 64, 1.0f, &m, &st, 1.0);
    mesh_check(&m, &t);
    assert_int_equal(t.components, 3);
    assert_int_equal(mesh_keep_largest(&m), 2);
    mesh_check(&m, &t);
    assert_int_equal(t.components, 1);
    assert_true(t.closed_manifold);
    assert_true(fabs(t.volume - 4 * 3.14159265 / 3) < 0.05);
    mesh_free(&m);
}

/* A gyroid and value noise, sampled coarsely: many cells whose faces' corners alternate in sign. Each such face one
 * patch holds twice on both sides is flipped (mesh_case): no edge of more than two faces, no pinched
 * vertex. (Without the flips: non-manifold edges here.) */
static double sd_gyroid(const double p[3])
{
    double x = 7 * p[0], y = 7 * p[1], z = 7 * p[2];
    return (sin(x) * cos(y) + sin(y) * cos(z) + sin(z) * cos(x)) / 7 + 0.02;
}

/* Value noise: random values on a lattice, trilinear between: signs nearly at random, cell by cell. */
static double lattice(int i, int j, int k)
{
    unsigned h = (unsigned)i * 73856093u ^ (unsigned)j * 19349663u ^ (unsigned)k * 83492791u;
    h = (h ^ (h >> 13)) * 1274126177u;
    return (double)((h ^ (h >> 16)) & 0xffff) / 65535.0 - 0.5;
}

static double sd_noise(const double p[3])
{
    double q[3], f[3];
    int c[3];
    for (int k = 0; k < 3; k++) {
        q[k] = p[k] / 0.11 + 50;
        c[k] = (int)floor(q[k]);
        f[k] = q[k] - c[k];
    }
    double v = 0;
    for (int n = 0; n < 8; n++) {
        double w = 1;
        for (int k = 0; k < 3; k++)
            w *= n >> k & 1 ? f[k] : 1 - f[k];
        v += w * lattice(c[0] + (n & 1), c[1] + (n >> 1 & 1), c[2] + (n >> 2 & 1));
    }
    return v * 0.05;
}

static void ambiguous_faces(void **state)
{
    (void)state;
    long long flipped_cases = 0;
    for (int cfg = 0; cfg < 256; cfg++)
        flipped_cases += mesh_case(cfg, 0)->twice != 0;
    for (int res = 12; res <= 41; res += 3) {
        mesh m = {0};
        mesh_stats st;
        mesh_topology t;
        extract(res % 2 ? sd_noise : sd_gyroid, 1.0, res, 0.0f, &m, &st, 1.0);
        mesh_check(&m, &t);
        fprintf(stderr, "  %s %d³: %zu triangles, open %lld, non-manifold edges %lld, vertices %lld, euler %lld\n", res % 2 ? "noise" : "gyroid", res,
                m.nt, t.open_edges, t.nonmanifold_edges, t.nonmanifold_vertices, t.euler);
        assert_true(t.closed_manifold);
        mesh_free(&m);
    }
    assert_true(flipped_cases > 0);
}

/* Two balls centred on diagonal corners of one cell face, each holding only its own corner: that face is
 * ambiguous (inside at two opposite corners). Faces are resolved with the insides apart (mesh_case), so
 * the grid gives two shells, as the field has; resolved the other way it bridged them into one. */
static const double BALL_H = 2.0 / 16; /* the grid's cell side: 16 cells across [-1, 1] */
static double sd_two_balls(const double p[3])
{
    const double a[3] = {0, 0, 0}, b[3] = {BALL_H, BALL_H, 0}, r = 0.6 * BALL_H;
    double da = 0, db = 0;
    for (int k = 0; k < 3; k++)
        da += (p[k] - a[k]) * (p[k] - a[k]), db += (p[k] - b[k]) * (p[k] - b[k]);
    return fmin(sqrt(da), sqrt(db)) - r;
}

static void ambiguous_face_keeps_balls_apart(void **state)
{
    (void)state;
    mesh m = {0};
    mesh_stats st;
    mesh_topology t;
    extract(sd_two_balls, 1.0, 16, 0.0f, &m, &st, 1.0);
    mesh_check(&m, &t);
    fprintf(stderr, "  two balls on a face's diagonal: %lld shells, euler %lld\n", t.components, t.euler);
    assert_true(t.closed_manifold);
    assert_int_equal(t.components, 2);
    assert_int_equal(t.euler, 4);
    mesh_free(&m);
}

/* A plate thinner than a voxel, between two sample planes: the grid misses it, and says so. A sphere
 * at the same resolution has no such edge. */
static double sd_plate(const double p[3])
{
    static const double c[3] = {0, 0.0151, 0}, h[3] = {0.6, 0.004, 0.6};
    return sd_box_at(p, c, h);
}

static void thin_features(void **state)
{
    (void)state;
    mesh m = {0};
    mesh_stats st;
    extract(sd_plate, 1.0, 64, 1.0f, &m, &st, 1.0);
    fprintf(stderr, "  a plate 0.27 voxels thick: %lld edges say a thin feature is lost, %zu triangles\n", st.thin, m.nt);
    assert_true(st.thin > 1000);
    extract(sd_sphere, 1.25, 64, 1.0f, &m, &st, 1.0);
    assert_int_equal(st.thin, 0);
    mesh_free(&m);
}

/* A tetrahedron (corners 0 … 3), wound outward, into m with its vertices offset by base. */
static void tetrahedron(mesh *m, float dx, uint32_t base, bool add_vertices)
{
    static const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    static const uint32_t f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (int i = 0; add_vertices && i < 4; i++)
        mesh_add_vertex(m, (const float[3]){p[i][0] + dx, p[i][1], p[i][2]}, (const float[3]){0, 0, 0});
    for (int i = 0; i < 4; i++)
        mesh_add_triangle(m, base + f[i][0], base + f[i][1], base + f[i][2]);
}

/* An edge of three faces (a book's spine) is non-manifold: the check counts it, and an edge of two does
 * not. */
static void three_faces_on_an_edge(void **state)
{
    (void)state;
    mesh m = {0};
    const float n[3] = {0, 0, 1}, p[5][3] = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}};
    for (int i = 0; i < 5; i++)
        mesh_add_vertex(&m, p[i], n);
    mesh_add_triangle(&m, 0, 1, 2);
    mesh_add_triangle(&m, 1, 0, 3);
    mesh_topology t;
    mesh_check(&m, &t);
    assert_int_equal(t.nonmanifold_edges, 0);
    mesh_add_triangle(&m, 0, 1, 4);
    mesh_check(&m, &t);
    assert_true(t.nonmanifold_edges >= 1);
    assert_false(t.closed_manifold);
    mesh_free(&m);
}

/* The repairs after a simplification: faces back to back dropped, sheets touching at a vertex parted,
 * a hole closed — each leaves a closed, manifold mesh. */
static void repairs(void **state)
{
    (void)state;
    mesh m = {0};
    mesh_topology t;
    tetrahedron(&m, 0, 0, true);
    mesh_add_vertex(&m, (const float[3]){0.5f, -1, 0}, (const float[3]){0, 0, 0});
    mesh_add_triangle(&m, 0, 1, 4); /* a fin on the edge (0, 1): two faces back to back */
    mesh_add_triangle(&m, 0, 4, 1);
    mesh_check(&m, &t);
    assert_false(t.closed_manifold);
    assert_int_equal(mesh_drop_fins(&m), 2);
    mesh_check(&m, &t);
    assert_true(t.closed_manifold);
    mesh_free(&m);
    tetrahedron(&m, 0, 0, true); /* two tetrahedra sharing corner 1 of the first (0 of the second) */
    tetrahedron(&m, 1, 4, true);
    for (size_t i = 12; i < 24; i++)
        m.tri[i] = m.tri[i] == 4 ? 1 : m.tri[i];
    mesh_check(&m, &t);
    assert_int_equal(t.nonmanifold_vertices, 1);
    assert_int_equal(mesh_split_pinches(&m), 1);
    mesh_check(&m, &t);
    assert_true(t.closed_manifold);
    assert_int_equal(t.components, 2);
    mesh_free(&m);
    tetrahedron(&m, 0, 0, true); /* a face missing: closed again by a fan */
    m.nt = 3;
    mesh_check(&m, &t);
    assert_int_equal(t.open_edges, 3);
    assert_int_equal(mesh_fill_holes(&m), 1);
    mesh_check(&m, &t);
    assert_true(t.closed_manifold);
    assert_true(fabs(t.volume - 1.0 / 6) < 1e-6);
    mesh_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(closed_forms), cmocka_unit_test(box_edges_sharp),
                                       cmocka_unit_test(sparse_blocks), cmocka_unit_test(block_seams),
                                       cmocka_unit_test(largest_shell), cmocka_unit_test(ambiguous_faces), cmocka_unit_test(ambiguous_face_keeps_balls_apart),
                                       cmocka_unit_test(thin_features), cmocka_unit_test(repairs),
                                       cmocka_unit_test(three_faces_on_an_edge)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
