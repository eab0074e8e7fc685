/* mesh_qef — the patches of a cell's sign configuration and the quadric that places their vertices
 * (data/mesh/mesh.h). */
#include <math.h>
#include <string.h>

#include "data/mesh/mesh.h"

/* Corner c is (c & 1, c >> 1 & 1, c >> 2 & 1). Edges: along x, 0 … 3 at (y, z) = (e & 1, e >> 1);
 * along y, 4 … 7 at (x, z); along z, 8 … 11 at (x, y). */
static void edge_corners(int e, int *c0, int *c1)
{
    int a = e / 4, u = e & 1, v = e >> 1 & 1;
    static const int first[3] = {1, 0, 0}, second[3] = {2, 2, 1}; /* the two other axes, in order */
    *c0 = u << first[a] | v << second[a];
    *c1 = *c0 | 1 << a;
}

static int edge_between(int c0, int c1)
{
    int d = c0 ^ c1, a = d == 1 ? 0 : d == 2 ? 1 : 2, lo = c0 & c1;
    int x = lo & 1, y = lo >> 1 & 1, z = lo >> 2 & 1;
    return a == 0 ? y + 2 * z : a == 1 ? 4 + x + 2 * z : 8 + x + 2 * y;
}

static int find(int *parent, int e)
{
    while (parent[e] != e)
        e = parent[e] = parent[parent[e]];
    return e;
}

/* The face's crossing edges linked into the patch boundary: two crossings are one segment; four (the
 * corners alternate) are two segments, each cutting off an inside corner, or with flip each cutting
 * off an outside corner — decided by the face's corners and a flag both cells that share it compute
 * alike, so they draw the same segments. */
static void link_face(int cfg, int axis, int side, bool flip, int *parent)
{
    int b = (axis + 1) % 3, c = (axis + 2) % 3;
    int corner[4]; /* around the face */
    static const int ring[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; i++)
        corner[i] = side << axis | ring[i][0] << b | ring[i][1] << c;
    int cross[4], n = 0;
    for (int i = 0; i < 4; i++) { /* edge i joins corner i and i + 1 */
        int c0 = corner[i], c1 = corner[(i + 1) % 4];
        if ((cfg >> c0 & 1) != (cfg >> c1 & 1))
            cross[n++] = i;
    }
    if (n == 2) {
        int e0 = edge_between(corner[cross[0]], corner[(cross[0] + 1) % 4]);
        int e1 = edge_between(corner[cross[1]], corner[(cross[1] + 1) % 4]);
        parent[find(parent, e0)] = find(parent, e1);
    } else if (n == 4) {
        for (int i = 0; i < 4; i++)
            if ((cfg >> corner[i] & 1) != flip) { /* its two edges (i − 1 and i) make one segment */
                int e0 = edge_between(corner[(i + 3) % 4], corner[i]), e1 = edge_between(corner[i], corner[(i + 1) % 4]);
                parent[find(parent, e0)] = find(parent, e1);
            }
    }
}

/* Which faces of case k hold both their segments in one patch. */
static uint8_t twice_of(const mesh_cell_case *k)
{
    uint8_t twice = 0;
    for (int f = 0; f < 6; f++) {
        int a = f / 2, side = f & 1, p = -2, same = 1, n = 0;
        for (int e = 0; e < 12; e++) { /* the face's edges: not along a, at coordinate side on a */
            int c0, c1;
            edge_corners(e, &c0, &c1);
            if (e / 4 == a || (c0 >> a & 1) != side || k->patch_of[e] < 0)
                continue;
            n++;
            same &= p == -2 || p == k->patch_of[e];
            p = k->patch_of[e];
        }
        twice |= (uint8_t)((n == 4 && same) << f);
    }
    return twice;
}

static void make_case(int cfg, int flips, mesh_cell_case *k)
{
    int parent[12], label[12];
    for (int e = 0; e < 12; e++) {
        parent[e] = e;
        label[e] = -1;
    }
    for (int f = 0; f < 6; f++)
        link_face(cfg, f / 2, f & 1, flips >> f & 1, parent);
    k->patches = 0;
    for (int e = 0; e < 12; e++) {
        int c0, c1;
        edge_corners(e, &c0, &c1);
        k->patch_of[e] = -1;
        if ((cfg >> c0 & 1) == (cfg >> c1 & 1))
            continue;
        int r = find(parent, e);
        if (label[r] < 0)
            label[r] = k->patches++;
        k->patch_of[e] = (int8_t)label[r];
    }
    k->twice = twice_of(k);
}

const mesh_cell_case *mesh_case(int cfg, int flips)
{
    static mesh_cell_case table[256][64];
    static bool made[256][64];
    if (!made[cfg][flips]) {
        make_case(cfg, flips, &table[cfg][flips]);
        made[cfg][flips] = true;
    }
    return &table[cfg][flips];
}

/* Eigen-decomposition of a symmetric 3×3 matrix by Jacobi rotations: a = v · diag(w) · vᵀ. */
static void jacobi3(double a[3][3], double w[3], double v[3][3])
{
    memset(v, 0, sizeof(double[3][3]));
    for (int i = 0; i < 3; i++)
        v[i][i] = 1;
    for (int sweep = 0; sweep < 24; sweep++) {
        double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
        if (off < 1e-30)
            break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                if (fabs(a[p][q]) < 1e-30)
                    continue;
                double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
                double t = (theta >= 0 ? 1 : -1) / (fabs(theta) + sqrt(theta * theta + 1));
                double c = 1 / sqrt(t * t + 1), s = t * c;
                for (int k = 0; k < 3; k++) { /* a ← a·J, then Jᵀ·a */
                    double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) {
                    double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; k++) {
                    double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
    }
    for (int i = 0; i < 3; i++)
        w[i] = a[i][i];
}

void mesh_qef_solve(const float (*p)[3], const float (*nrm)[3], int n, const double lo[3], double h, float out[3],
                    bool *clamped)
{
    double mass[3] = {0, 0, 0}, ata[3][3] = {{0}}, atb[3] = {0, 0, 0};
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            mass[k] += (double)p[i][k] / n;
    for (int i = 0; i < n; i++) { /* planes through p relative to the mass point: n · (x − m) = n · (p − m) */
        double d = 0;
        for (int k = 0; k < 3; k++)
            d += nrm[i][k] * (p[i][k] - mass[k]);
        for (int r = 0; r < 3; r++) {
            atb[r] += nrm[i][r] * d;
            for (int c = 0; c < 3; c++)
                ata[r][c] += (double)nrm[i][r] * nrm[i][c];
        }
    }
    double w[3], v[3][3], x[3] = {0, 0, 0};
    jacobi3(ata, w, v);
    double wmax = fmax(fmax(fabs(w[0]), fabs(w[1])), fabs(w[2]));
    for (int e = 0; e < 3; e++) { /* x = V Σ⁺ Vᵀ atb, directions of small eigenvalues left at the mass point */
        if (fabs(w[e]) < 0.02 * wmax || w[e] <= 0)
            continue;
        double proj = (v[0][e] * atb[0] + v[1][e] * atb[1] + v[2][e] * atb[2]) / w[e];
        for (int k = 0; k < 3; k++)
            x[k] += v[k][e] * proj;
    }
    *clamped = false;
    for (int k = 0; k < 3; k++) {
        double c = mass[k] + x[k];
        if (c < lo[k] || c > lo[k] + h) {
            c = fmin(fmax(c, lo[k]), lo[k] + h);
            *clamped = true;
        }
        out[k] = (float)c;
    }
}
