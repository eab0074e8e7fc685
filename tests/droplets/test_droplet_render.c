/* Droplets on the GPU (shaders/common/droplets.glsl and the path in common/sdf_main.glsl) against
 * references in double precision that share nothing with the shaders:
 *  - the grid walk (and the BVH measured against it): 10,000 random droplets (overlapping ones among them), rays from outside the
 *    cloud, from inside it, from inside droplets, and rays grazing droplets just inside and just
 *    outside their radius, against a brute-force loop over every droplet;
 *  - one droplet: the direction a ray leaves in against Snell's law in vector form, the Beer–Lambert
 *    factor against e^(−σ l) over the exact chord, and the shader's Fresnel reflectance against 1 − the
 *    transmittance from the amplitude coefficients (R + T = 1 at each interface);
 *  - a rendered droplet: the pixel through its centre equals the closed form
 *    C (F0 + (1 − F0)² e^(−2σr)) in a uniform environment C;
 *  - overlapping droplets and droplets half sunk into the ground render without NaN or holes: every
 *    pixel's depth is the nearest of ground and spheres, traced in double. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "check.h"
#include "data/droplets/droplets.h"
#include "gltest.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"

static double frand(unsigned *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (*seed >> 8) / 16777216.0;
}

static char csv_path[64];
static const char *structure = "grid"; /* droplets.structure of the scenes made next */
/* a csg scene needs an object: one far out of the way */
#define FAR_OBJECT "\"objects\": [{\"shape\": \"sphere\", \"radius\": 0.1, \"position\": [0, 1, 50], \"material\": \"a\"}], "

/* Writes n droplets (x, y, z, r) to a temporary CSV and loads a csg scene holding them. */
static void droplet_scene(const double *spheres, int n, const char *extra_json, scene *s)
{
    snprintf(csv_path, sizeof csv_path, "/tmp/fathom-drops-XXXXXX");
    int fd = mkstemp(csv_path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs("x,y,z,r\n", f);
    for (int i = 0; i < n; i++) /* %.9g: the float the GPU gets is the float the reference rounds to */
        fprintf(f, "%.9g,%.9g,%.9g,%.9g\n", spheres[4 * i], spheres[4 * i + 1], spheres[4 * i + 2], spheres[4 * i + 3]);
    fclose(f);
    char json[4096];
    snprintf(json, sizeof json,
             "{\"program\": \"csg\", \"materials\": {\"a\": {}}, %s \"droplets\": {\"file\": \"%s\", \"absorption\": "
             "[0.5, 2, 300], \"structure\": \"%s\"}}",
             extra_json, csv_path, structure);
    load_text(json, NULL, 0, s);
}

/* Spheres as the GPU holds them: float centres and radii. */
static void to_float(double *spheres, int n)
{
    for (int i = 0; i < 4 * n; i++)
        spheres[i] = (float)spheres[i];
}

/* Entry of a ray (origin outside the sphere) into a sphere: t, or −1 on a miss; also the closest
 * approach of the line to the centre, in units of the radius. */
static double entry(const double o[3], const double d[3], const double *s, double *closest)
{
    double f[3] = {o[0] - s[0], o[1] - s[1], o[2] - s[2]};
    double b = f[0] * d[0] + f[1] * d[1] + f[2] * d[2], c = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - s[3] * s[3];
    double l2 = c + s[3] * s[3] - b * b;
    *closest = sqrt(fmax(l2, 0)) / s[3];
    if (c <= 0)
        return -1; /* the origin is inside: no entry */
    double disc = s[3] * s[3] - l2;
    if (disc < 0)
        return -1;
    double t = -b - sqrt(disc);
    return t > 0 ? t : -1;
}

static void walk_matches_brute_force_in(const char *which)
{
    structure = which;
    fprintf(stderr, "  %s:\n", which);
    enum { N = 10000, R = 8192 };
    static double sph[4 * N];
    unsigned seed = 2024;
    for (int i = 0; i < N; i++) { /* a 2 m cloud, 5–50 mm droplets; some touch or overlap */
        sph[4 * i] = 2 * frand(&seed) - 1;
        sph[4 * i + 1] = 2 * frand(&seed);
        sph[4 * i + 2] = 2 * frand(&seed) - 1;
        sph[4 * i + 3] = 0.005 + 0.045 * frand(&seed) * frand(&seed);
    }
    to_float(sph, N);
    scene s;
    droplet_scene(sph, N, FAR_OBJECT "\"quality\": {\"droplet_lod\": 0},", &s);
    static float rays[6 * R], out[4 * R];
    int kind_of[R];
    for (int r = 0; r < R; r++) {
        int kind = r % 4;
        kind_of[r] = kind;
        double o[3], d[3];
        if (kind == 0 || kind == 1) { /* 0: from outside the cloud toward a point in it; 1: from inside it */
            double target[3] = {2 * frand(&seed) - 1, 2 * frand(&seed), 2 * frand(&seed) - 1};
            for (int a = 0; a < 3; a++)
                o[a] = kind == 0 ? 6 * frand(&seed) - 3 : 2 * frand(&seed) - 1 + (a == 1);
            if (kind == 0)
                o[2] = -4;
            for (int a = 0; a < 3; a++)
                d[a] = kind == 0 ? target[a] - o[a] : 2 * frand(&seed) - 1;
        } else {
            const double *t = sph + 4 * (int)(frand(&seed) * N);
            double u[3] = {2 * frand(&seed) - 1, 2 * frand(&seed) - 1, 2 * frand(&seed) - 1};
            if (kind == 2) { /* from inside a droplet, any way */
                for (int a = 0; a < 3; a++) {
                    o[a] = t[a] + 0.5 * t[3] * u[a];
                    d[a] = 2 * frand(&seed) - 1;
                }
            } else { /* grazing: a line passing the centre at (1 ± 1e-4) radii, from 0.5 m away */
                double w[3] = {2 * frand(&seed) - 1, 2 * frand(&seed) - 1, 2 * frand(&seed) - 1};
                double wl = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
                for (int a = 0; a < 3; a++)
                    w[a] /= wl;
                double ud = u[0] * w[0] + u[1] * w[1] + u[2] * w[2], ul; /* u ⟂ w, unit */
                for (int a = 0; a < 3; a++)
                    u[a] -= ud * w[a];
                ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
                double k = (r / 4) % 2 ? 1 + 1e-4 : 1 - 1e-4;
                for (int a = 0; a < 3; a++) {
                    o[a] = t[a] + k * t[3] * u[a] / ul - 0.5 * w[a];
                    d[a] = w[a];
                }
            }
        }
        double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int a = 0; a < 3; a++) {
            rays[6 * r + a] = (float)o[a];
            rays[6 * r + 3 + a] = (float)(d[a] / dl);
        }
    }
    err_t e;
    if (!render_set_scene(&s, NULL, &e) || !render_probe_rays(&s, "dropletprobe.frag", NULL, rays, R, out, &e))
        fail_msg("%s", e.msg);
    int hits = 0, grazing_ok = 0, inside = 0, wrong = 0, near_tangent = 0;
    double worst = 0;
    for (int r = 0; r < R; r++) {
        double o[3], d[3];
        for (int a = 0; a < 3; a++) {
            o[a] = rays[6 * r + a];
            d[a] = rays[6 * r + 3 + a];
        }
        double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int a = 0; a < 3; a++)
            d[a] /= dl;
        double best = INFINITY, closest_best = 0;
        int want = -1, at = -1;
        for (int i = 0; i < N; i++) {
            double cl, t = entry(o, d, sph + 4 * i, &cl);
            if (t > 0 && t < best) {
                best = t;
                want = i;
                closest_best = cl;
            }
            double f[3] = {o[0] - sph[4 * i], o[1] - sph[4 * i + 1], o[2] - sph[4 * i + 2]};
            if (at < 0 && f[0] * f[0] + f[1] * f[1] + f[2] * f[2] < sph[4 * i + 3] * sph[4 * i + 3])
                at = i;
        }
        int got = (int)out[4 * r + 1];
        int got_at = (int)out[4 * r + 3];
        inside += at >= 0;
        /* the droplet holding the origin: any droplet that holds it (overlaps may hold it twice) */
        if ((got_at < 0) != (at < 0))
            fail_msg("ray %d: the origin is in droplet %d, the shader says %d", r, at, got_at);
        if (got == want) {
            hits += want >= 0;
            if (want >= 0) {
                double err = fabs(out[4 * r] - best) / (1 + best);
                worst = fmax(worst, err);
                if (err > 2e-6)
                    fail_msg("ray %d: droplet %d at t %.9g, the shader says %.9g", r, want, best, (double)out[4 * r]);
            }
            grazing_ok += kind_of[r] == 3;
            continue;
        }
        /* a different answer is allowed only where the reference's droplet (or the shader's) is met
         * within float resolution of tangent: closest approach within 1e-5 radii of the radius */
        double cl_got = 2;
        if (got >= 0)
            entry(o, d, sph + 4 * got, &cl_got);
        if ((want >= 0 && fabs(closest_best - 1) < 1e-5) || (got >= 0 && fabs(cl_got - 1) < 1e-5)) {
            near_tangent++;
            continue;
        }
        wrong++;
        fprintf(stderr, "ray %d (kind %d): reference droplet %d at %.9g, shader %d at %.9g\n", r, kind_of[r], want, best,
                got, (double)out[4 * r]);
    }
    fprintf(stderr, "  %d rays, %d hits, %d from inside droplets, %d grazing agree, %d within float of tangent, "
                    "worst t error %.2g\n",
            R, hits, inside, grazing_ok, near_tangent, worst);
    assert_int_equal(wrong, 0);
    assert_true(hits > R / 3 && inside > R / 8);
    assert_true(near_tangent < R / 100);
    unlink(csv_path);
    scene_free(&s);
    structure = "grid";
}

/* Both structures: the uniform grid fathom uses, and the BVH it was measured against. */
static void walk_matches_brute_force(void **st)
{
    (void)st;
    walk_matches_brute_force_in("grid");
    walk_matches_brute_force_in("bvh");
}

static void refract_d(double d[3], const double n[3], double eta)
{
    double c = -(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]), k = 1 - eta * eta * (1 - c * c);
    for (int a = 0; a < 3; a++)
        d[a] = eta * d[a] + (eta * c - sqrt(k)) * n[a];
}

static void single_droplet_follows_snell(void **st)
{
    (void)st;
    enum { R = 512 };
    double sph[4] = {0.3, 1.2, -0.4, 0.05};
    to_float(sph, 1);
    scene s;
    droplet_scene(sph, 1, FAR_OBJECT "\"quality\": {\"droplet_lod\": 0},", &s);
    static float rays[6 * R], out[4 * R];
    double ior = s.droplets.ior, sigma = s.droplets.absorption[0];
    for (int r = 0; r < R; r++) { /* impact parameters 0 … 0.999 radii, from the −z side, rotated about z */
        double b = 0.999 * r / (R - 1), phi = 2.0 * r;
        rays[6 * r] = (float)(sph[0] + b * sph[3] * cos(phi));
        rays[6 * r + 1] = (float)(sph[1] + b * sph[3] * sin(phi));
        rays[6 * r + 2] = (float)(sph[2] - 1);
        rays[6 * r + 5] = 1;
    }
    err_t e;
    if (!render_set_scene(&s, NULL, &e) ||
        !render_probe_rays(&s, "dropletprobe.frag", "#define DROPLET_PROBE_PASS 1\n", rays, R, out, &e))
        fail_msg("%s", e.msg);
    double worst_dir = 0, worst_beer = 0;
    for (int r = 0; r < R; r++) {
        double o[3] = {rays[6 * r], rays[6 * r + 1], rays[6 * r + 2]}, d[3] = {0, 0, 1}, cl;
        double t = entry(o, d, sph, &cl);
        assert_true(t > 0);
        double p[3], n[3];
        for (int a = 0; a < 3; a++) {
            p[a] = o[a] + t * d[a];
            n[a] = (p[a] - sph[a]) / sph[3];
        }
        refract_d(d, n, 1 / ior);
        double l = -2 * ((p[0] - sph[0]) * d[0] + (p[1] - sph[1]) * d[1] + (p[2] - sph[2]) * d[2]);
        for (int a = 0; a < 3; a++) {
            p[a] += l * d[a];
            n[a] = -(p[a] - sph[a]) / sph[3]; /* facing the ray inside */
        }
        refract_d(d, n, ior);
        double err = 0;
        for (int a = 0; a < 3; a++)
            err = fmax(err, fabs(out[4 * r + a] - d[a]));
        worst_dir = fmax(worst_dir, err);
        worst_beer = fmax(worst_beer, fabs(out[4 * r + 3] - exp(-sigma * l)));
        if (err > 2e-4 || fabs(out[4 * r + 3] - exp(-sigma * l)) > 1e-5)
            fail_msg("impact %.4f: leaves along (%.6f %.6f %.6f), Snell says (%.6f %.6f %.6f); Beer %.7f vs %.7f",
                     0.999 * r / (R - 1), (double)out[4 * r], (double)out[4 * r + 1], (double)out[4 * r + 2], d[0], d[1],
                     d[2], (double)out[4 * r + 3], exp(-sigma * l));
    }
    fprintf(stderr, "  exit directions within %.2g of Snell's, Beer–Lambert within %.2g\n", worst_dir, worst_beer);
    /* Fresnel: the shader's reflectance R and the transmittance from the amplitude coefficients T (Born
     * & Wolf §1.5.2) add to 1 at every angle, both ways across the surface (past the critical angle R = 1) */
    enum { F = 402 };
    static float pts[3 * F], fr[2 * F];
    for (int i = 0; i < F; i++) {
        pts[3 * i] = (float)((i % (F / 2) + 0.5) / (F / 2));
        pts[3 * i + 1] = (float)(i < F / 2 ? 1 / ior : ior);
    }
    if (!render_probe_with(&s, "dropletprobe.frag", "#define DROPLET_PROBE_FRESNEL 1\n", pts, F, fr, &e))
        fail_msg("%s", e.msg);
    double worst_sum = 0;
    for (int i = 0; i < F; i++) {
        double ci = pts[3 * i], ni = i < F / 2 ? 1 : ior, nt = i < F / 2 ? ior : 1;
        double sin_t = ni / nt * sqrt(1 - ci * ci), T = 0;
        if (sin_t < 1) {
            double ct = sqrt(1 - sin_t * sin_t);
            double ts = 2 * ni * ci / (ni * ci + nt * ct), tp = 2 * ni * ci / (nt * ci + ni * ct);
            T = nt * ct / (ni * ci) * 0.5 * (ts * ts + tp * tp);
        }
        worst_sum = fmax(worst_sum, fabs(fr[2 * i] + T - 1));
    }
    fprintf(stderr, "  R + T = 1 within %.2g over %d angles\n", worst_sum, F);
    assert_true(worst_sum < 1e-5);
    unlink(csv_path);
    scene_free(&s);
}

/* One droplet sph and nothing else in view of a camera at z = −2 looking at it (the scene's one sphere
 * is far behind that camera), no lights, a uniform environment (0.8, 0.6, 0.4); lod: quality.droplet_lod. */
static void lone_droplet(const double sph[4], double lod, scene *s)
{
    char text[512];
    snprintf(text, sizeof text,
             "\"objects\": [{\"shape\": \"sphere\", \"radius\": 0.1, \"position\": [0, 1, -50], \"material\": \"a\"}], "
             "\"environment\": {\"color\": [0.8, 0.6, 0.4], \"intensity\": 1}, \"lights\": [], "
             "\"quality\": {\"droplet_lod\": %g, \"spp\": 1},",
             lod);
    droplet_scene(sph, 1, text, s);
}

static void centre_pixel_is_the_closed_form(void **st)
{
    (void)st;
    double sph[4] = {0, 1, 0, 0.25};
    scene s;
    lone_droplet(sph, 0, &s);
    enum { S = 33 };
    camera cam = cam_at(0, 1, -2, 0, 1, 0, 20);
    static float aov[S * S * AOV], rgba[S * S * 4];
    draw(&s, &cam, S, S, 1, NULL, aov, rgba);
    check_finite("single droplet", aov, rgba, S * S);
    const float *px = rgba + 4 * (S / 2 * S + S / 2);
    double n = s.droplets.ior, F0 = (n - 1) * (n - 1) / ((n + 1) * (n + 1)), C[3] = {0.8, 0.6, 0.4};
    for (int c = 0; c < 3; c++) {
        double want = C[c] * (F0 + (1 - F0) * (1 - F0) * exp(-s.droplets.absorption[c] * 2 * sph[3]));
        fprintf(stderr, "  channel %d: %.6f, closed form %.6f\n", c, (double)px[c], want);
        assert_near(px[c], want, 2e-5 * (1 + want));
    }
    /* its depth is the droplet's front */
    assert_near(aov[(S / 2 * S + S / 2) * AOV + AOV_SLOT_DEPTH], 2 - sph[3], 1e-5);
    unlink(csv_path);
    scene_free(&s);
}

/* The same pixel when the droplet is below the level of detail (radius 1 mm at 2 m, a pixel 1.1 mm
 * there, droplet_lod 2): the ray is not bent but goes on dimmed by the mean transmittance over the
 * droplet's disc, Σ w_k e^(−σ 2r cos θt_k), and gathers its mean reflectance R (both from the table
 * test_droplets checks against traced rays), so in a uniform environment C it is C · (T + R). With the
 * reflection dropped it is C · T: off by R ≈ 0.066 (water), 60x the tolerance. */
static void centre_pixel_below_the_level_of_detail(void **st)
{
    (void)st;
    double sph[4] = {0, 1, 0, 0.001};
    scene s;
    lone_droplet(sph, 2, &s);
    enum { S = 33 };
    camera cam = cam_at(0, 1, -2, 0, 1, 0, 1);
    assert_true(sph[3] < 2 * camera_pixel_angle(&cam, S) * 2); /* below the level of detail: not traced */
    static float aov[S * S * AOV], rgba[S * S * 4];
    draw(&s, &cam, S, S, 1, NULL, aov, rgba);
    check_finite("a sub-pixel droplet", aov, rgba, S * S);
    const float *px = rgba + 4 * (S / 2 * S + S / 2);
    droplet_lod_table t;
    droplets_lod_table(s.droplets.ior, &t);
    const double C[3] = {0.8, 0.6, 0.4};
    for (int c = 0; c < 3; c++) {
        double T = 0;
        for (int k = 0; k < DROPLET_LOD_NODES; k++)
            T += t.weight[k] * exp(-s.droplets.absorption[c] * 2 * sph[3] * t.cos_t[k]);
        double want = C[c] * (T + t.reflect);
        fprintf(stderr, "  channel %d: %.6f, mean transmittance %.5f + reflectance %.5f: %.6f\n", c, (double)px[c], T,
                (double)t.reflect, want);
        assert_near(px[c], want, 1e-3);
    }
    /* a pixel beside it sees the environment untouched, and the droplet is no surface */
    assert_near(rgba[4 * (S / 2 * S + S / 2 - 3)], C[0], 1e-5);
    assert_true(isinf(aov[(S / 2 * S + S / 2) * AOV + AOV_SLOT_DEPTH]));
    unlink(csv_path);
    scene_free(&s);
}

static void no_holes_in(const char *kind)
{
    structure = kind;
    enum { N = 300, WW = 160, HH = 90 };
    static double sph[4 * N];
    unsigned seed = 31;
    for (int i = 0; i < N; i++) { /* clusters of overlapping droplets; a third of them sunk into the ground */
        double cx = 1.6 * frand(&seed) - 0.8, cz = 1.6 * frand(&seed) - 0.8;
        sph[4 * i] = cx;
        sph[4 * i + 1] = i % 3 == 0 ? 0.01 * frand(&seed) : 0.05 + 0.6 * frand(&seed);
        sph[4 * i + 2] = cz;
        sph[4 * i + 3] = 0.02 + 0.08 * frand(&seed);
        if (i % 10) { /* the rest of a cluster: beside its first droplet, overlapping it */
            const double *f = sph + 4 * (i - i % 10);
            for (int a = 0; a < 3; a++)
                sph[4 * i + a] = f[a] + (frand(&seed) - 0.5) * f[3];
        }
    }
    to_float(sph, N);
    scene s;
    droplet_scene(sph, N,
                  "\"objects\": [{\"shape\": \"box\", \"size\": [60, 0.5, 60], \"position\": [0, -0.25, 0], \"material\": \"a\"}], "
                  "\"environment\": {\"color\": [0.7, 0.8, 1], \"intensity\": 1}, "
                  "\"quality\": {\"droplet_lod\": 0, \"spp\": 1, \"droplet_events\": 64},",
                  &s);
    static float aov[WW * HH * AOV], rgba[WW * HH * 4];
    camera cams[2] = {cam_at(0.3, 0.9, -2.2, 0, 0.2, 0, 50), cam_at(-1.3, 0.5, -1.0, 0, 0.15, 0, 60)};
    for (int v = 0; v < 2; v++) {
        draw(&s, &cams[v], WW, HH, 1, NULL, aov, rgba);
        check_finite("overlapping and cut droplets", aov, rgba, WW * HH);
        int wrong = 0, drop_px = 0, dark = 0;
        for (int row = 0; row < HH; row++)
            for (int x = 0; x < WW; x++) {
                dray r = pixel_ray(&cams[v], x, row, WW, HH);
                double best = INFINITY, cl;
                if (r.d[1] < 0) /* the ground's top face, y = 0 */
                    best = -r.o[1] / r.d[1];
                if (best > 6) /* far, grazing ground: the marcher's own tolerance (tests/gpu/test_silhouette.c) */
                    continue;
                bool drop = false, tangent = false;
                for (int i = 0; i < N; i++) {
                    double t = entry(r.o, r.d, sph + 4 * i, &cl);
                    if (t > 0 && t < best) {
                        best = t;
                        drop = true;
                    }
                    tangent |= fabs(cl - 1) < 1e-3 && t > 0;
                }
                if (tangent) /* within 1e-3 radii of a droplet's rim: float decides */
                    continue;
                const float *a = aov + (row * WW + x) * AOV;
                double got = a[AOV_SLOT_DEPTH];
                drop_px += drop;
                if (!(fabs(got - best) <= 1e-3 * best || (isinf(got) && isinf(best)))) {
                    if (wrong++ < 8)
                        fprintf(stderr, "    pixel (%d, %d): depth %.6g, reference %.6g (%s)\n", x, row, got, best,
                                drop ? "droplet" : "ground");
                }
                /* a hole would show black: the path lost in the liquid or the ground */
                const float *c = rgba + 4 * (row * WW + x);
                dark += drop && c[0] + c[1] + c[2] < 1e-3;
            }
        fprintf(stderr, "  view %d: %d droplet pixels, %d depths off the reference, %d black droplet pixels\n", v,
                drop_px, wrong, dark);
        assert_true(drop_px > WW * HH / 20);
        assert_true(wrong <= WW * HH / 1000); /* only where a pixel's ray is within 1e-3 radii of tangent */
        assert_int_equal(dark, 0);
    }
    unlink(csv_path);
    scene_free(&s);
    structure = "grid";
}

static void overlapping_and_cut_droplets_leave_no_holes(void **st)
{
    (void)st;
    no_holes_in("grid");
    no_holes_in("bvh");
}

/* Sub-pixel droplets are not traced but dim the ray by their mean transmittance: a cloud of them in one
 * sample per pixel gives the same mean image as the same cloud traced exactly with many jittered
 * samples (the reference shares nothing with the level of detail but the droplets). */
static void sub_pixel_in(const char *which)
{
    structure = which;
    enum { N = 10000, S = 48 };
    static double sph[4 * N];
    unsigned seed = 99;
    /* a 1.2 m square, 0.3 m deep, 3 m away; at 48 px over 30°, a pixel is 5.8 mm there: radii 2–4 mm,
     * below the level of detail's 2 pixels (they cover about a fifth of the view; blue is absorbed
     * strongly inside) */
    for (int i = 0; i < N; i++) {
        sph[4 * i] = 1.2 * frand(&seed) - 0.6;
        sph[4 * i + 1] = 1 + 1.2 * frand(&seed) - 0.6;
        sph[4 * i + 2] = 0.3 * frand(&seed);
        sph[4 * i + 3] = 0.002 + 0.002 * frand(&seed);
    }
    to_float(sph, N);
    static float lod[S * S * 4], traced[S * S * 4], aov[S * S * AOV];
    camera cam = cam_at(0, 1, -3, 0, 1, 0, 30);
    double mean[2] = {0, 0}, clear = 0;
    for (int pass = 0; pass < 2; pass++) {
        scene s;
        char extra[512];
        snprintf(extra, sizeof extra,
                 "\"objects\": [{\"shape\": \"sphere\", \"radius\": 0.1, \"position\": [0, 1, 50], \"material\": "
                 "\"a\"}], \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1}, \"lights\": [], "
                 "\"quality\": {\"droplet_lod\": %s, \"spp\": %d},",
                 pass ? "0" : "2", pass ? 256 : 1);
        droplet_scene(sph, N, extra, &s);
        float *img = pass ? traced : lod;
        draw(&s, &cam, S, S, pass ? 256 : 1, NULL, aov, img);
        check_finite("sub-pixel droplets", aov, img, S * S);
        for (int i = 0; i < S * S; i++)
            mean[pass] += img[4 * i + 2] / (S * S);
        unlink(csv_path);
        scene_free(&s);
    }
    clear = 1; /* the environment: what the image would be without droplets */
    fprintf(stderr, "  %s: mean blue: level of detail %.5f, traced %.5f (no droplets %.1f)\n", which, mean[0], mean[1], clear);
    assert_true(clear - mean[1] > 0.01); /* the droplets dim the image measurably */
    assert_near(mean[0], mean[1], 0.1 * (clear - mean[1]));
    structure = "grid";
}

static void sub_pixel_droplets_dim_like_traced_ones(void **st)
{
    (void)st;
    sub_pixel_in("grid");
    sub_pixel_in("bvh");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(walk_matches_brute_force),
        cmocka_unit_test(single_droplet_follows_snell),
        cmocka_unit_test(centre_pixel_is_the_closed_form),
        cmocka_unit_test(centre_pixel_below_the_level_of_detail),
        cmocka_unit_test(overlapping_and_cut_droplets_leave_no_holes),
        cmocka_unit_test(sub_pixel_droplets_dim_like_traced_ones),
    };
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
