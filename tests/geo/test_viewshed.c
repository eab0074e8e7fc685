/* The viewshed (data/geo/viewshed.h) against a brute-force reference that shares only the surface's
 * definition: every cell in the line's bounding box is clipped by its own slab test, and the clearance
 * there is evaluated directly (bilinear height at the point, the drop (1 − k) d² / 2R from the
 * metres travelled) at three points in long double, whose parabola gives the exact minimum (the
 * clearance is a quadratic inside a cell). No pyramid, no coefficients, no traversal order. Then the
 * closed form: over a flat Earth-sized plain the horizon lies at √(2 R h / (1 − k)). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "data/geo/viewshed.h"

typedef long double ld;

static size_t at(int w, int i, int j) { return (size_t)j * (size_t)w + (size_t)i; }
static float hv(const viewshed_desc *d, int i, int j) { return d->heights[at(d->w, i, j)]; }

static ld ref_ground(const viewshed_desc *d, int i, int j, ld c, ld r)
{
    ld u = c - i, v = r - j;
    ld h00 = hv(d, i, j), h10 = hv(d, i + 1, j), h01 = hv(d, i, j + 1), h11 = hv(d, i + 1, j + 1);
    return h00 * (1 - u) * (1 - v) + h10 * u * (1 - v) + h01 * (1 - u) * v + h11 * u * v;
}

/* The smallest clearance (sight line minus the dropped surface) over the line to texel (ti, tj). */
static ld ref_clearance(const viewshed_desc *d, int ti, int tj)
{
    ld c = d->curvature ? (1 - (ld)d->refraction) / (2 * (ld)VIEWSHED_EARTH_RADIUS) : 0;
    ld oc = d->col, orow = d->row;
    int oi = (int)fminl(floorl(oc), d->w - 2), oj = (int)fminl(floorl(orow), d->h - 2);
    ld yo = ref_ground(d, oi, oj, oc, orow) + d->observer_height;
    ld D = sqrtl(powl((ti - oc) * d->dx, 2) + powl((tj - orow) * d->dz, 2));
    ld yt = (ld)hv(d, ti, tj) + d->target_height;
    ld worst = INFINITY;
    int i0 = (int)floorl(fminl(oc, ti)), i1 = (int)ceill(fmaxl(oc, ti)), j0 = (int)floorl(fminl(orow, tj)),
        j1 = (int)ceill(fmaxl(orow, tj));
    for (int j = j0 > 0 ? j0 - 1 : 0; j <= j1 && j < d->h - 1; j++)
        for (int i = i0 > 0 ? i0 - 1 : 0; i <= i1 && i < d->w - 1; i++) {
            if (isnan(hv(d, i, j)) || isnan(hv(d, i + 1, j)) || isnan(hv(d, i, j + 1)) || isnan(hv(d, i + 1, j + 1)))
                continue;
            /* the line's parameters inside the cell's square, axis by axis */
            ld lo = 0, hi = 1;
            ld org[2] = {oc, orow}, dir[2] = {ti - oc, tj - orow}, a[2] = {i, j};
            for (int k = 0; k < 2; k++) {
                if (fabsl(dir[k]) < 1e-300L) {
                    if (org[k] < a[k] || org[k] > a[k] + 1)
                        lo = 2;
                    continue;
                }
                ld s0 = (a[k] - org[k]) / dir[k], s1 = (a[k] + 1 - org[k]) / dir[k];
                lo = fmaxl(lo, fminl(s0, s1));
                hi = fminl(hi, fmaxl(s0, s1));
            }
            if (lo > hi)
                continue;
            ld s[3] = {lo, 0.5L * (lo + hi), hi}, f[3];
            for (int k = 0; k < 3; k++) {
                ld line = yo + s[k] * (yt - c * D * D - yo);
                ld surf = ref_ground(d, i, j, oc + s[k] * dir[0], orow + s[k] * dir[1]) - c * s[k] * s[k] * D * D;
                f[k] = line - surf;
            }
            ld m = fminl(f[0], f[2]);
            ld w = hi - lo;
            if (w > 0) { /* the parabola through the three: f = f1 + g t + q t², t from the middle */
                ld half = w / 2, q = (f[0] + f[2] - 2 * f[1]) / (2 * half * half), g = (f[2] - f[0]) / (2 * half);
                if (q > 0 && fabsl(-g / (2 * q)) < half)
                    m = fminl(m, f[1] - g * g / (4 * q));
            }
            worst = fminl(worst, m);
        }
    return worst;
}

/* Hills of several wavelengths, with a few nodata texels. */
static float *rugged(int w, int h, unsigned seed, int holes)
{
    float *v = malloc(sizeof(float) * at(w, 0, h));
    srand(seed);
    double ph[6];
    for (int k = 0; k < 6; k++)
        ph[k] = rand() / (double)RAND_MAX * 6.283;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            v[at(w, i, j)] = (float)(600 + 400 * sin(0.21 * i + ph[0]) * cos(0.17 * j + ph[1]) +
                                           180 * sin(0.63 * i + 0.4 * j + ph[2]) + 90 * cos(1.3 * j - 0.7 * i + ph[3]) +
                                           40 * (rand() / (double)RAND_MAX));
    for (int k = 0; k < holes; k++)
        v[at(w, rand() % w, rand() % h)] = NAN;
    return v;
}

/* Every texel against the reference; returns the differences off ties (|clearance| < tie). */
static int compare(const viewshed_desc *d, int *ties, size_t *visible)
{
    unsigned char *out = malloc(at(d->w, 0, d->h));
    err_t e;
    viewshed_stats st;
    if (!viewshed_compute(d, out, &st, &e))
        fail_msg("%s", e.msg);
    int diff = 0;
    *ties = 0;
    for (int j = 0; j < d->h; j++)
        for (int i = 0; i < d->w; i++) {
            unsigned char got = out[at(d->w, i, j)];
            if (isnan(hv(d, i, j))) {
                diff += got != VIEWSHED_NODATA;
                continue;
            }
            ld m = ref_clearance(d, i, j);
            if (fabsl(m + VIEWSHED_TIE) < 2e-7L) { /* within rounding of the rule's threshold */
                (*ties)++;
                continue;
            }
            unsigned char want = m < -VIEWSHED_TIE ? VIEWSHED_HIDDEN : VIEWSHED_VISIBLE;
            if (got != want && diff++ < 5)
                print_message("texel %d,%d: viewshed %d, reference %d (clearance %.6Lf m)\n", i, j, got, want, m);
        }
    *visible = st.visible;
    free(out);
    return diff;
}

/* A rugged DEM over 30 km with holes, from several observers, with and without curvature and
 * refraction: 0 differences off ties, and the answers are neither all visible nor all hidden. */
static void matches_brute_force(void **state)
{
    (void)state;
    enum { W = 61, H = 47 };
    float *v = rugged(W, H, 7, 12);
    const double obs[][2] = {{30.4, 20.7}, {3, 44}, {58.9, 1.2}, {17, 17}};
    const double k[] = {0.13, 0.0, 1.0};
    int total_ties = 0;
    for (size_t a = 0; a < sizeof obs / sizeof obs[0]; a++)
        for (size_t q = 0; q < 4; q++) {
            viewshed_desc d = {.heights = v, .w = W, .h = H, .dx = 520, .dz = 610, .col = obs[a][0], .row = obs[a][1],
                               .observer_height = q == 3 ? 300 : 1.7, .target_height = q == 1 ? 10 : 0,
                               .refraction = k[q % 3], .curvature = q != 2, .threads = (int)q % 2 + 1};
            if (isnan(v[at(W, (int)d.col, (int)d.row)]))
                continue;
            int ties;
            size_t vis;
            int diff = compare(&d, &ties, &vis);
            total_ties += ties;
            assert_int_equal(diff, 0);
            assert_true(vis > 10 && vis < (size_t)W * H - 10);
        }
    assert_true(total_ties < 40);
    free(v);
}

/* Curvature that matters: a 120 km DEM where the drop (up to ~1 km) decides, compared with the same
 * lines on a flat Earth. */
static void curvature_matters(void **state)
{
    (void)state;
    enum { W = 81, H = 81 };
    float *v = rugged(W, H, 11, 0);
    viewshed_desc d = {.heights = v, .w = W, .h = H, .dx = 1500, .dz = 1500, .col = 40, .row = 40,
                       .observer_height = 1200, .refraction = 0.13, .curvature = true};
    int ties;
    size_t curved, flat;
    assert_int_equal(compare(&d, &ties, &curved), 0);
    d.curvature = false;
    assert_int_equal(compare(&d, &ties, &flat), 0);
    print_message("visible: %zu curved, %zu flat\n", curved, flat);
    assert_true(curved + 50 < flat); /* the Earth's bulge hides far texels */
    free(v);
}

/* A plain at sea level 200 km long: from h metres up, the horizon lies at √(2 R h / (1 − k)). */
static void horizon_closed_form(void **state)
{
    (void)state;
    enum { W = 2001, H = 3 };
    float *v = calloc((size_t)W * H, sizeof(float));
    unsigned char *out = malloc((size_t)W * H);
    const double hs[] = {100, 25}, ks[] = {0.13, 0};
    for (int c = 0; c < 2; c++) {
        viewshed_desc d = {.heights = v, .w = W, .h = H, .dx = 100, .dz = 100, .col = 0, .row = 1,
                           .observer_height = hs[c], .refraction = ks[c], .curvature = true};
        err_t e;
        assert_true(viewshed_compute(&d, out, NULL, &e));
        double horizon = sqrt(2 * VIEWSHED_EARTH_RADIUS * hs[c] / (1 - ks[c]));
        int last = -1, first_hidden = W;
        for (int i = 0; i < W; i++) {
            if (out[W + i] == VIEWSHED_VISIBLE)
                last = i;
            else if (first_hidden == W)
                first_hidden = i;
        }
        print_message("h %.0f m, k %.2f: horizon %.1f m, last visible texel at %d m\n", hs[c], ks[c], horizon, last * 100);
        assert_true(last + 1 == first_hidden);      /* one horizon: visible, then hidden */
        assert_true(fabs(last * 100.0 - horizon) <= 100); /* within the texel the horizon falls in */
    }
    free(v);
    free(out);
}

static void radius_threads_and_refusals(void **state)
{
    (void)state;
    enum { W = 40, H = 30 };
    float *v = rugged(W, H, 3, 0);
    unsigned char *a = malloc(W * H), *b = malloc(W * H);
    viewshed_desc d = {.heights = v, .w = W, .h = H, .dx = 30, .dz = 30, .col = 20, .row = 15, .observer_height = 2,
                       .refraction = 0.13, .curvature = true, .radius = 300, .threads = 1};
    err_t e;
    viewshed_stats st;
    assert_true(viewshed_compute(&d, a, &st, &e));
    d.threads = 3;
    assert_true(viewshed_compute(&d, b, NULL, &e));
    assert_memory_equal(a, b, W * H);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            assert_int_equal(a[j * W + i] == VIEWSHED_NODATA, hypot((i - 20) * 30.0, (j - 15) * 30.0) > 300);
    assert_true(st.nodata > 0 && st.visible > 0);
    d.col = 40;
    assert_false(viewshed_compute(&d, a, NULL, &e));
    assert_non_null(strstr(e.msg, "outside the DEM"));
    d.col = 20;
    v[15 * W + 20] = NAN;
    assert_false(viewshed_compute(&d, a, NULL, &e));
    assert_non_null(strstr(e.msg, "nodata hole"));
    free(v);
    free(a);
    free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(matches_brute_force), cmocka_unit_test(curvature_matters),
        cmocka_unit_test(horizon_closed_form), cmocka_unit_test(radius_threads_and_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
