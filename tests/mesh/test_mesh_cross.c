/* Faces that cross each other (issue 58 item 19: 57 of 70 meshes intersected themselves, where marching
 * cubes on the same fields had none). The detector (mesh_crossing_faces: a grid of boxes, orientation
 * signs) against a brute force over every pair by another method (Möller and Trumbore's barycentric
 * segment test, 1997); and an extraction whose quadric points make faces cross comes out untangled. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "data/mesh/mesh.h"

/* Whether segment p→q meets the interior of triangle (a, b, c) strictly inside both (Möller & Trumbore,
 * "Fast, minimum storage ray-triangle intersection", 1997). */
static bool segment_hits(const float *p, const float *q, const float *a, const float *b, const float *c)
{
    double d[3], e1[3], e2[3], s[3], h[3], k[3];
    for (int i = 0; i < 3; i++)
        d[i] = (double)q[i] - p[i], e1[i] = (double)b[i] - a[i], e2[i] = (double)c[i] - a[i], s[i] = (double)p[i] - a[i];
    h[0] = d[1] * e2[2] - d[2] * e2[1], h[1] = d[2] * e2[0] - d[0] * e2[2], h[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (det == 0)
        return false; /* parallel to the plane */
    double u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / det;
    k[0] = s[1] * e1[2] - s[2] * e1[1], k[1] = s[2] * e1[0] - s[0] * e1[2], k[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = (d[0] * k[0] + d[1] * k[1] + d[2] * k[2]) / det;
    double t = (e2[0] * k[0] + e2[1] * k[1] + e2[2] * k[2]) / det;
    return u > 0 && v > 0 && u + v < 1 && t > 0 && t < 1;
}

static const float *V(const mesh *m, size_t f, int i) { return m->pos + 3 * (size_t)m->tri[3 * f + (size_t)((i + 3) % 3)]; }

/* Every pair of faces: one sharing an edge is a neighbour; one sharing a corner crosses only by the edges
 * away from it; others by any edge. */
static long long brute_force(const mesh *m)
{
    long long pairs = 0;
    for (size_t f = 0; f < m->nt; f++)
        for (size_t g = f + 1; g < m->nt; g++) {
            int shared = 0, sf = 0, sg = 0;
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    if (m->tri[3 * f + (size_t)i] == m->tri[3 * g + (size_t)j])
                        shared++, sf = i, sg = j;
            bool hit = false;
            if (shared == 1)
                hit = segment_hits(V(m, f, sf + 1), V(m, f, sf + 2), V(m, g, 0), V(m, g, 1), V(m, g, 2)) ||
                      segment_hits(V(m, g, sg + 1), V(m, g, sg + 2), V(m, f, 0), V(m, f, 1), V(m, f, 2));
            for (int i = 0; shared == 0 && i < 3 && !hit; i++)
                hit = segment_hits(V(m, f, i), V(m, f, i + 1), V(m, g, 0), V(m, g, 1), V(m, g, 2)) ||
                      segment_hits(V(m, g, i), V(m, g, i + 1), V(m, f, 0), V(m, f, 1), V(m, f, 2));
            pairs += hit;
        }
    return pairs;
}

static uint32_t rng = 2463534242u;
static float uniform(void)
{
    rng ^= rng << 13, rng ^= rng >> 17, rng ^= rng << 5;
    return (float)(rng >> 8) / 16777216.0f;
}

/* A soup of 600 small triangles over a pool of 700 points, so many share a corner or an
 * edge: the grid's count equals the brute force's, and the marks cover both faces of each pair. */
static void detector_against_brute_force(void **state)
{
    (void)state;
    mesh m = {0};
    float w[3] = {0.5f, 0.5f, 0.5f}, n[3] = {0, 0, 1};
    for (int i = 0; i < 700; i++) { /* a random walk: points near in the pool are near in space (unclamped: */
        for (int k = 0; k < 3; k++) /* points on a common plane would make contacts, which neither counts) */
            w[k] += 0.15f * (uniform() - 0.5f);
        mesh_add_vertex(&m, w, n);
    }
    for (int f = 0; f < 600; f++) { /* corners near each other: a point and two of the next dozen */
        uint32_t a = (uint32_t)(uniform() * 680), b = a + 1 + (uint32_t)(uniform() * 12), c = a + 1 + (uint32_t)(uniform() * 12);
        if (b == c)
            c = b + 1;
        mesh_add_triangle(&m, a, b, c);
    }
    uint8_t *crossed = calloc(m.nt, 1);
    long long grid = mesh_crossing_faces(&m, crossed), brute = brute_force(&m), marked = 0;
    for (size_t f = 0; f < m.nt; f++)
        marked += crossed[f];
    fprintf(stderr, "  soup of %zu faces: %lld crossing pairs by the grid, %lld by every pair; %lld faces marked\n", m.nt,
            grid, brute, marked);
    assert_true(brute > 50 && brute < 5000);
    assert_int_equal(grid, brute);
    assert_true(marked > 0 && marked <= 2 * grid && marked < (long long)m.nt);
    free(crossed);
    mesh_free(&m);
}

/* A square plate 0.4 voxels thick, tilted 0.6 rad about two axes: both its sheets pass through single
 * cells, and the quadric pulls their vertices to each other's side (10 pairs of faces crossed at 40
 * cells). After the extraction no pair crosses, by the brute force, and the mesh is still closed. */
static double angle = 0.6, half_thick = 0.4 / 40;
static double sd_tilted_plate(const double p[3])
{
    double c = cos(angle), s = sin(angle);
    double y = c * p[1] - s * p[0], x = s * p[1] + c * p[0];
    double z = c * p[2] - s * y;
    y = s * p[2] + c * y;
    double q[3] = {fabs(x) - 0.6, fabs(y) - half_thick, fabs(z) - 0.6}, o = 0;
    for (int k = 0; k < 3; k++)
        o += fmax(q[k], 0) * fmax(q[k], 0);
    return sqrt(o) + fmin(fmax(q[0], fmax(q[1], q[2])), 0.0);
}

static bool eval(void *user, const float *pts, size_t n, float *d, err_t *err)
{
    (void)user, (void)err;
    for (size_t i = 0; i < n; i++)
        d[i] = (float)sd_tilted_plate((const double[3]){pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]});
    return true;
}

static void thin_plate_untangled(void **state)
{
    (void)state;
    mesh m = {0};
    mesh_stats st;
    err_t e;
    mesh_grid g = {.lo = {-1, -1, -1}, .hi = {1, 1, 1}, .res = 40, .step = 1, .field = eval};
    assert_true(mesh_extract(&g, &m, &st, &e));
    mesh_topology t;
    mesh_check(&m, &t);
    long long brute = brute_force(&m);
    double off = 0; /* the corners' distance to the plate, in voxels */
    for (size_t v = 0; v < m.nv; v++)
        off = fmax(off, fabs(sd_tilted_plate((const double[3]){m.pos[3 * v], m.pos[3 * v + 1], m.pos[3 * v + 2]})) / st.voxel);
    fprintf(stderr, "  tilted plate at 40 cells: %zu faces; %lld pairs crossed as placed, %lld corners moved, %lld left "
            "(every pair: %lld); corners within %.3f voxels of the plate\n", m.nt, st.crossing, st.untangled,
            st.crossing_left, brute, off);
    assert_true(st.crossing > 0); /* there was something to untangle */
    assert_true(st.untangled > 0);
    assert_int_equal(st.crossing_left, 0);
    assert_int_equal(brute, 0);
    assert_true(t.closed_manifold);
    assert_true(off < 0.15); /* at mass points the corners stay on the plate (0.13; smoothing alone: 0.19) */
    mesh_free(&m);
}

/* Contact is not crossing: a corner of one triangle exactly on another's face, or an edge meeting it at
 * one point, counts nothing; pushed a little further through, it crosses. */
static void contact_is_not_crossing(void **state)
{
    (void)state;
    mesh m = {0};
    const float n[3] = {0, 0, 1}, p[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.25f, 0.25f, 0}, {0.25f, 0.25f, 1}, {1, 1, 1}};
    for (int i = 0; i < 6; i++)
        mesh_add_vertex(&m, p[i], n);
    mesh_add_triangle(&m, 0, 1, 2);
    mesh_add_triangle(&m, 3, 4, 5);
    assert_int_equal(mesh_crossing_faces(&m, NULL), 0);
    assert_int_equal(brute_force(&m), 0);
    m.pos[3 * 3 + 2] = -0.125f; /* the corner through the face */
    assert_int_equal(mesh_crossing_faces(&m, NULL), 1);
    assert_int_equal(brute_force(&m), 1);
    mesh_free(&m);
}

/* Without mass points (after a weld or a simplification): a sphere's vertex pushed through to the far
 * side, its fan now crossing the faces there, is brought back by its neighbours' mean until nothing
 * crosses. */
static bool sphere_eval(void *user, const float *pts, size_t n, float *d, err_t *err)
{
    (void)user, (void)err;
    for (size_t i = 0; i < n; i++)
        d[i] = sqrtf(pts[3 * i] * pts[3 * i] + pts[3 * i + 1] * pts[3 * i + 1] + pts[3 * i + 2] * pts[3 * i + 2]) - 0.7f;
    return true;
}

static void fold_smoothed(void **state)
{
    (void)state;
    mesh m = {0};
    mesh_stats st;
    err_t e;
    mesh_grid g = {.lo = {-1, -1, -1}, .hi = {1, 1, 1}, .res = 12, .step = 1, .field = sphere_eval};
    assert_true(mesh_extract(&g, &m, &st, &e));
    assert_int_equal(st.crossing, 0);
    for (int k = 0; k < 3; k++) /* vertex 0 through the middle, 8 times as far on the other side */
        m.pos[k] *= -8.0f;
    long long pushed = brute_force(&m), before, left, moved = mesh_untangle(&m, NULL, &before, &left);
    long long after = brute_force(&m);
    fprintf(stderr, "  sphere with a vertex pushed through: %lld pairs cross (grid %lld); %lld corners moved, %lld left "
            "(every pair: %lld)\n", pushed, before, moved, left, after);
    assert_true(pushed > 10);
    assert_int_equal(before, pushed);
    assert_int_equal(left, 0);
    assert_int_equal(after, 0);
    double r = sqrt((double)m.pos[0] * m.pos[0] + (double)m.pos[1] * m.pos[1] + (double)m.pos[2] * m.pos[2]);
    fprintf(stderr, "  the pushed vertex back at radius %.3f (the sphere's 0.7)\n", r);
    assert_true(fabs(r - 0.7) < 0.2); /* brought back to the surface, not left halfway across */
    mesh_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(detector_against_brute_force),
                                       cmocka_unit_test(thin_plate_untangled), cmocka_unit_test(fold_smoothed),
                                       cmocka_unit_test(contact_is_not_crossing)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
