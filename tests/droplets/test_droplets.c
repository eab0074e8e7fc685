/* Droplet files and the droplets' grid (app/data/droplets/droplets.c), without GL:
 *  - ParaView's CSV (quoted headers, extra columns, diameter), plain x,y,z,r, no header;
 *  - bad files get one error naming file, line and column: empty, missing columns, not a number,
 *    NaN, negative or zero radius, short rows, coordinates out of range; 10⁷ rows load within memory;
 *  - the grid lists a droplet in exactly the cells its sphere meets (brute force in double), for
 *    random clouds, a flat sheet, a thin line, one droplet and a few huge droplets among small ones;
 *  - the level of detail's mean transmittance and reflectance equal rays traced through a sphere in
 *    double (vector Snell and Fresnel from the amplitude coefficients: nothing shared with the table). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "check.h"
#include "data/droplets/droplets.h"

static double frand(unsigned *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (*seed >> 8) / 16777216.0;
}

static void load(const char *text, float scale, droplets *d)
{
    err_t e;
    if (!droplets_read_text(text, strlen(text), "t.csv", scale, d, &e))
        fail_msg("%s", e.msg);
}

static void paraview_csv(void **st)
{
    (void)st;
    droplets d;
    /* as ParaView's "Save Data" writes a point cloud: quoted names, other arrays beside */
    load("\"velocity:0\",\"velocity:1\",\"velocity:2\",\"diameter\",\"Points:0\",\"Points:1\",\"Points:2\"\r\n"
         "1,2,3,0.002,0.5,1.5,-2\r\n"
         "0,0,0,1e-3,  -1 , 0 , 3e-1\r\n",
         1, &d);
    assert_int_equal(d.count, 2);
    const float want[8] = {0.5f, 1.5f, -2, 0.001f, -1, 0, 0.3f, 0.0005f};
    for (int i = 0; i < 8; i++)
        assert_near(d.spheres[i], want[i], 1e-7);
    assert_near(d.r_min, 0.0005, 1e-9);
    assert_near(d.r_max, 0.001, 1e-9);
    droplets_free(&d);
    load("x,y,z,radius\n1,2,3,0.5\n\n4,5,6,0.25\n", 2, &d); /* a blank line; scale 2 */
    assert_int_equal(d.count, 2);
    assert_near(d.spheres[4], 8, 0);
    assert_near(d.spheres[7], 0.5, 0);
    droplets_free(&d);
    load("\xEF\xBB\xBF" "1,2,3,0.5\n4,5,6,0.25", 1, &d); /* no header (and a byte-order mark), no final newline */
    assert_int_equal(d.count, 2);
    assert_near(d.spheres[0], 1, 0);
    assert_near(d.spheres[7], 0.25, 0);
    droplets_free(&d);
}

static void bad_files(void **st)
{
    (void)st;
    static const struct {
        const char *text, *want;
    } cases[] = {
        {"", "holds no droplets"},
        {"x,y,z,r\n", "holds no droplets"},
        {"a,b,c\n1,2,3\n", ":1: no x column in the first row's 3 fields"},
        {"Points:0,Points:1,Points:2\n1,2,3\n", ":1: no radius or diameter column"},
        {"x,y,z,r\n1,2,3,0.1\n1,2,abc,0.1\n", ":3: column 3 (z): 'abc' is not a number"},
        {"x,y,z,r\n1,2,3,nan\n", ":2: column 4 (r): nan is not a finite number"},
        {"x,y,z,r\n1,2,3,inf\n", ":2: column 4 (r): inf is not a finite number"},
        {"x,y,z,r\n1,2,3,-0.5\n", ":2: column 4 (r): -0.5: a droplet's size must be positive"},
        {"x,y,z,diameter\n1,2,3,0\n", ":2: column 4 (diameter): 0: a droplet's size must be positive"},
        {"x,y,z,r\n1,2,3,0.1\n1,2\n", ":3: the row has no column 3 (z)"},
        {"x,y,z,r\n1e300,2,3,0.1\n", ":2: column 1 (x): 1e300 is beyond"},
        {"x,y,z,r\n0,0,0,4.3e-93\n", ":2: column 4 (r): 4.3e-93: a droplet smaller than 2e-09 m across"},
        {"x,y,z,r\n\"1,2,3,0.1\n", ":2: column 1 (x): '1,2,3,0.1"}, /* an open quote swallows the rest of the file */
        {"x,y,z,r\n1,2,3,\n", ":2: column 4 (r): '' is not a number"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        droplets d;
        err_t e = {{0}};
        bool ok = droplets_read_text(cases[i].text, strlen(cases[i].text), "t.csv", 1, &d, &e);
        if (ok || !strstr(e.msg, cases[i].want) || strncmp(e.msg, "droplets file 't.csv'", 21) != 0)
            fail_msg("case %zu: %s; got '%s', expected '%s'", i, ok ? "accepted" : "refused", e.msg, cases[i].want);
        assert_null(d.spheres);
    }
    /* a file that is not droplets (someone's private file named in a shared scene): its first line is
     * not repeated in the message */
    {
        static const char secret[] = "user,password,token\nalice,hunter2,42\n";
        droplets d;
        err_t e = {{0}};
        assert_false(droplets_read_text(secret, strlen(secret), "t.csv", 1, &d, &e));
        assert_null(strstr(e.msg, "password"));
        assert_null(strstr(e.msg, "user"));
    }
    /* a NUL inside a number is no number ("1\0junk" read as 1 before) */
    {
        static const char nul[] = "x,y,z,r\n1,2,3\0junk,0.1\n";
        droplets d;
        err_t e = {{0}};
        assert_false(droplets_read_text(nul, sizeof nul - 1, "t.csv", 1, &d, &e));
        assert_non_null(strstr(e.msg, ":2: field 3 holds a NUL byte"));
    }
    droplets d;
    err_t e;
    assert_false(droplets_read("/nonexistent/spray.csv", 1, &d, &e));
    assert_non_null(strstr(e.msg, "No such file"));
}

/* 10⁷ rows from a file: read and gridded, in bounded memory. */
static void ten_million_rows(void **st)
{
    (void)st;
    enum { N = 10000000 };
    char path[] = "/tmp/fathom-droplets-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs("x,y,z,r\n", f);
    unsigned seed = 5;
    for (int i = 0; i < N; i++) /* a 10 m cube of 1–5 mm droplets */
        fprintf(f, "%.4f,%.4f,%.4f,%.4f\n", 10 * frand(&seed), 10 * frand(&seed), 10 * frand(&seed),
                0.001 + 0.004 * frand(&seed));
    fclose(f);
    droplets d;
    err_t e;
    bool ok = droplets_read(path, 1, &d, &e) && droplets_build_grid(&d, &e);
    unlink(path);
    if (!ok)
        fail_msg("%s", e.msg);
    assert_int_equal(d.count, N);
    size_t cells = droplets_cell_count(&d);
    /* about DROPLET_GRID_DENSITY cells a droplet up to the grid's limit, and few listings beyond one a droplet */
    assert_true(cells > DROPLET_GRID_MAX_CELLS / 2 && cells <= DROPLET_GRID_MAX_CELLS);
    assert_true(d.refs < (size_t)2 * N);
    assert_true(droplets_bytes(&d) < (size_t)1 << 30);
    assert_int_equal(d.cells[cells], d.refs);
    droplets_free(&d);
}

static bool meets(const droplets *d, const float *s, int x, int y, int z)
{
    int c[3] = {x, y, z};
    double dist2 = 0;
    for (int k = 0; k < 3; k++) {
        double a = d->lo[k] + (double)d->cell[k] * c[k], b = d->lo[k] + (double)d->cell[k] * (c[k] + 1);
        double e = s[k] < a ? a - s[k] : s[k] > b ? s[k] - b : 0;
        dist2 += e * e;
    }
    return dist2 <= (double)s[3] * s[3];
}

/* Every droplet is listed in exactly the cells its sphere meets (and nowhere else). */
static void check_grid(droplets *d)
{
    err_t e;
    if (!droplets_build_grid(d, &e))
        fail_msg("%s", e.msg);
    size_t cells = droplets_cell_count(d);
    assert_int_equal(d->cells[cells], d->refs);
    int *listed = calloc((size_t)d->count, sizeof(int));
    for (size_t c = 0; c < cells; c++) {
        assert_true(d->cells[c] <= d->cells[c + 1]);
        int x = (int)(c % (size_t)d->dims[0]), y = (int)(c / (size_t)d->dims[0] % (size_t)d->dims[1]),
            z = (int)(c / ((size_t)d->dims[0] * (size_t)d->dims[1]));
        for (uint32_t k = d->cells[c]; k < d->cells[c + 1]; k++) {
            uint32_t i = d->index[k];
            assert_true(i < (uint32_t)d->count);
            if (!meets(d, d->spheres + 4 * (size_t)i, x, y, z))
                fail_msg("droplet %u listed in cell (%d %d %d) it does not meet", i, x, y, z);
            listed[i]++;
        }
    }
    /* and is listed in every cell it meets: count them by brute force over all cells (small grids) or
     * over the box around it */
    for (int i = 0; i < d->count; i++) {
        const float *s = d->spheres + 4 * (size_t)i;
        int want = 0;
        for (int z = 0; z < d->dims[2]; z++) {
            double a = d->lo[2] + (double)d->cell[2] * z;
            if (a > s[2] + s[3] || a + d->cell[2] < s[2] - s[3])
                continue;
            for (int y = 0; y < d->dims[1]; y++) {
                double b = d->lo[1] + (double)d->cell[1] * y;
                if (b > s[1] + s[3] || b + d->cell[1] < s[1] - s[3])
                    continue;
                for (int x = 0; x < d->dims[0]; x++)
                    want += meets(d, s, x, y, z);
            }
        }
        if (want != listed[i] || want == 0)
            fail_msg("droplet %d meets %d cells, listed in %d", i, want, listed[i]);
        /* every droplet lies within the grid */
        for (int k = 0; k < 3; k++)
            assert_true(s[k] - s[3] >= d->lo[k] && s[k] + s[3] <= d->lo[k] + (double)d->cell[k] * d->dims[k]);
    }
    free(listed);
}

/* droplets_distance (the mesher's droplets) against every droplet: the same sign, never more than the
 * true distance (a bound to step by), and equal to it within a cell of the nearest surface from inside
 * the grid's box. */
static void check_distance(const droplets *d, unsigned seed)
{
    double cell = fmin(d->cell[0], fmin(d->cell[1], d->cell[2])), worst = 0;
    int exact = 0;
    for (int q = 0; q < 1000; q++) {
        float p[3];
        for (int k = 0; k < 3; k++) { /* the grid's box and a cell-wide margin around it */
            double lo = d->lo[k] - cell, hi = d->lo[k] + (double)d->cell[k] * d->dims[k] + cell;
            p[k] = (float)(lo + (hi - lo) * frand(&seed));
        }
        if (q % 2) { /* half of them near a droplet's surface */
            const float *s = d->spheres + 4 * (size_t)(q % d->count);
            for (int k = 0; k < 3; k++)
                p[k] = s[k] + (float)((k == 0 ? 1 : 0.3) * s[3] * (0.5 + frand(&seed)));
        }
        double brute = INFINITY;
        for (int i = 0; i < d->count; i++) {
            const float *s = d->spheres + 4 * (size_t)i;
            double dx = (double)p[0] - s[0], dy = (double)p[1] - s[1], dz = (double)p[2] - s[2];
            brute = fmin(brute, sqrt(dx * dx + dy * dy + dz * dz) - s[3]);
        }
        double got = droplets_distance(d, p);
        assert_true((got < 0) == (brute < 0));
        assert_true(got <= brute + 1e-6);
        bool inside = true; /* in the grid's box: its block reaches a cell beyond p's every way */
        for (int k = 0; k < 3; k++)
            inside = inside && p[k] >= d->lo[k] && p[k] <= d->lo[k] + (double)d->cell[k] * d->dims[k];
        if (inside && brute < cell) {
            worst = fmax(worst, fabs(got - brute));
            exact++;
        }
    }
    fprintf(stderr, "  distance: %d points within a cell of a surface, worst difference %.3g\n", exact, worst);
    assert_true(exact > 200);
    assert_true(worst < 1e-6);
}

static void grid_lists_every_meeting_cell(void **st)
{
    (void)st;
    enum { N = 20000 };
    for (int kind = 0; kind < 5; kind++) {
        droplets d = {0};
        int n = kind == 3 ? 1 : N;
        d.spheres = calloc((size_t)n * 4, sizeof(float));
        d.count = n;
        unsigned seed = 77u + (unsigned)kind;
        for (int i = 0; i < n; i++) {
            float *s = d.spheres + 4 * (size_t)i;
            s[0] = (float)(4 * frand(&seed) - 2);
            double y = 2 * frand(&seed), z = 3 * frand(&seed) - 1;
            s[1] = kind == 1 ? 0.5f : kind == 2 ? 1.0f : (float)y; /* 1: a flat sheet, 2: a thin line */
            s[2] = kind == 2 ? 0.0f : (float)z;
            s[3] = (float)(0.002 + 0.03 * frand(&seed));
            if (kind == 4 && i % 5000 == 0) /* a few huge droplets among small ones */
                s[3] = 1.5f;
        }
        d.r_min = INFINITY;
        for (int i = 0; i < n; i++) {
            d.r_min = fminf(d.r_min, d.spheres[4 * (size_t)i + 3]);
            d.r_max = fmaxf(d.r_max, d.spheres[4 * (size_t)i + 3]);
        }
        check_grid(&d);
        check_distance(&d, 91u + (unsigned)kind);
        if (kind == 0) /* about DROPLET_GRID_DENSITY cells a droplet */
            assert_true(droplets_cell_count(&d) >= N && (double)droplets_cell_count(&d) <= 3 * DROPLET_GRID_DENSITY * N);
        droplets_free(&d);
    }
}

/* Fresnel for unpolarized light from the amplitude transmission coefficients (Born & Wolf §1.5.2):
 * transmitted power T = (n_t cos θ_t / n_i cos θ_i)(t_s² + t_p²)/2; R = 1 − T. */
static double fresnel_by_transmission(double cos_i, double n_i, double n_t)
{
    double sin_t = n_i / n_t * sqrt(fmax(0, 1 - cos_i * cos_i));
    if (sin_t >= 1)
        return 1;
    double cos_t = sqrt(1 - sin_t * sin_t);
    double ts = 2 * n_i * cos_i / (n_i * cos_i + n_t * cos_t), tp = 2 * n_i * cos_i / (n_t * cos_i + n_i * cos_t);
    return 1 - (n_t * cos_t) / (n_i * cos_i) * 0.5 * (ts * ts + tp * tp);
}

static void refract3(double d[3], const double n[3], double eta)
{
    double c = -(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]), k = 1 - eta * eta * (1 - c * c);
    assert_true(k >= 0);
    for (int a = 0; a < 3; a++)
        d[a] = eta * d[a] + (eta * c - sqrt(k)) * n[a];
}

/* Rays through a unit sphere over its disc, in double: the mean of (entry transmission) · e^(−σ l) ·
 * (exit transmission), and the mean entry reflectance. */
static void traced_means(double ior, double sigma_r, double *T, double *R)
{
    enum { M = 200000 };
    double sumT = 0, sumR = 0;
    for (int i = 0; i < M; i++) {
        double b = sqrt((i + 0.5) / M); /* equal areas of the disc */
        double p[3] = {b, 0, -sqrt(1 - b * b)}, n[3] = {p[0], p[1], p[2]}, d[3] = {0, 0, 1};
        double Fin = fresnel_by_transmission(-(d[0] * n[0] + d[2] * n[2]), 1, ior);
        refract3(d, n, 1 / ior);
        double l = -2 * (p[0] * d[0] + p[1] * d[1] + p[2] * d[2]); /* chord from p along d */
        double q[3] = {p[0] + l * d[0], p[1] + l * d[1], p[2] + l * d[2]};
        double Fout = fresnel_by_transmission(q[0] * d[0] + q[1] * d[1] + q[2] * d[2], ior, 1);
        sumT += (1 - Fin) * exp(-sigma_r * l) * (1 - Fout);
        sumR += Fin;
    }
    *T = sumT / M;
    *R = sumR / M;
}

static void lod_means_equal_traced_rays(void **st)
{
    (void)st;
    const double iors[] = {1.33, 1.5, 2.4}, sigmas[] = {0, 0.3, 3, 30};
    for (size_t a = 0; a < 3; a++) {
        droplet_lod_table t;
        droplets_lod_table((float)iors[a], &t);
        for (size_t b = 0; b < 4; b++) {
            double T, R, mine = 0;
            traced_means(iors[a], sigmas[b], &T, &R);
            for (int k = 0; k < DROPLET_LOD_NODES; k++)
                mine += t.weight[k] * exp(-sigmas[b] * 2 * t.cos_t[k]);
            if (fabs(mine - T) > 2e-3 || fabs(t.reflect - R) > 2e-3)
                fail_msg("ior %g, sigma r %g: table T %.5f R %.5f, traced T %.5f R %.5f", iors[a], sigmas[b], mine,
                         (double)t.reflect, T, R);
        }
    }
    /* the double-precision Fresnel the table uses against the transmission form */
    for (int i = 1; i <= 100; i++) {
        double c = i / 100.0;
        assert_near(droplets_fresnel(c, 1 / 1.33), fresnel_by_transmission(c, 1, 1.33), 1e-12);
        assert_near(droplets_fresnel(c, 1.33), fresnel_by_transmission(c, 1.33, 1), 1e-12);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(paraview_csv),
        cmocka_unit_test(bad_files),
        cmocka_unit_test(grid_lists_every_meeting_cell),
        cmocka_unit_test(lod_means_equal_traced_rays),
        cmocka_unit_test(ten_million_rows),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
