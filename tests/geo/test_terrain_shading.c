/* Terrain beyond the first hit: a changed DEM file read again, the ground height probe, ridge outlines
 * without dark dashes, the height fog against quadrature in double, and the noise terrain against a
 * double-precision march of the same field. */
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
#include <epoxy/gl.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include "check.h"
#include "gltest.h"
#include "data/media/image_io.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "data/geo/terrain.h"
#include "terrain_ref.h"

/* The heightfield stays on the GPU while scenes read the same file (a flight's frames), and a file
 * rewritten on disk (R reload) is read again: the key holds its size and modification time. */
static void changed_file_is_read_again(void **st)
{
    (void)st;
    enum { N = 16 };
    float heights[N * N];
    char dir[] = "/tmp/fathom-reread-XXXXXX", path[128], json[512];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/dem.exr", dir);
    snprintf(json, sizeof json, "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"quality\": {\"spp\": 1}, "
             "\"terrain\": {\"heightmap\": \"%s\", \"spacing\": [1, 1]}}", path);
    camera cam = cam_at(0, 50, 0.01, 0, 0, 0, 30); /* straight down on the middle */
    static float aov[W * H * AOV];
    double depth[3];
    err_t e;
    for (int k = 0; k < 3; k++) {
        if (k != 1) { /* k = 1 draws again without touching the file */
            for (int i = 0; i < N * N; i++)
                heights[i] = k ? 20.0f : 5.0f;
            assert_true(image_write_f32(path, N, N, 1, (const char *const[]){"Y"}, heights, &e));
        }
        scene s;
        load_text(json, NULL, 0, &s);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        depth[k] = aov[(H / 2 * W + W / 2) * AOV + AOV_SLOT_DEPTH];
        scene_free(&s);
    }
    fprintf(stderr, "depth to the middle: %.3f, again %.3f, after the file changed %.3f\n", depth[0], depth[1], depth[2]);
    assert_near(depth[0], 45, 0.05);
    assert_near(depth[1], 45, 0.05);
    assert_near(depth[2], 30, 0.05);
    unlink(path);
    rmdir(dir);
}

/* The heights live only on the GPU once uploaded; the walking camera's ground is a probe of the
 * shader's surface. It must equal the bilinear surface in double (the CPU reference) everywhere on the
 * footprint, and report no ground over a nodata hole. */
static void ground_height_probe(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-ground-XXXXXX", scene_path[300];
    assert_non_null(mkdtemp(dir));
    synthetic_dem(dir, "holes", 256, 192, true, scene_path, sizeof scene_path);
    scene s;
    err_t e;
    if (!scene_load(scene_path, NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    heightfield hf;
    heightfield_desc d = {.path = s.terrain.heightmap, .spacing = {s.terrain.spacing[0], s.terrain.spacing[1]},
                          .exaggeration = 1};
    if (!heightfield_load(&d, &hf, &e))
        fail_msg("%s", e.msg);
    camera cam = cam_at(0, 3000, 1, 0, 0, 0, 40);
    draw(&s, &cam, 8, 8, 1, NULL, NULL, NULL); /* puts the scene on the GPU */
    int checked = 0, holes = 0;
    double worst = 0;
    for (int k = 0; k < 400; k++) {
        double x = hf.x0 + hf.dx * (0.5 + (hf.width - 1) * ((k * 0.6180339887) - floor(k * 0.6180339887)));
        double z = hf.z0 + hf.dz * (0.5 + (hf.height - 1) * ((k * 0.7548776662) - floor(k * 0.7548776662)));
        double cx = (x - hf.x0) / hf.dx - 0.5, cz = (z - hf.z0) / hf.dz - 0.5;
        int i = (int)fmin(floor(cx), hf.width - 2), j = (int)fmin(floor(cz), hf.height - 2);
        bool hole = TERRAIN_IS_HOLE(fmin(fmin(texel(&hf, i, j), texel(&hf, i + 1, j)),
                                         fmin(texel(&hf, i, j + 1), texel(&hf, i + 1, j + 1))));
        float g;
        bool got = render_ground_height((float)x, (float)z, &g);
        if (hole) {
            assert_false(got);
            holes++;
            continue;
        }
        assert_true(got);
        worst = fmax(worst, fabs(g - height_cell(&hf, cx, cz)));
        checked++;
    }
    fprintf(stderr, "ground probe: %d points within %.2g m of the bilinear surface in double, %d over holes\n", checked,
            worst, holes);
    assert_true(worst < 1e-3 * (hf.hmax - hf.hmin) && holes > 0 && checked > 300);
    heightfield_free(&hf);
    scene_free(&s);
    remove_dems(dir, (const char *const[]){"holes", NULL});
}

/* ---- height fog against quadrature in double -------------------------------------------------------- */

static double tau_quadrature(double sigma0, double b, double y0, double oy, double dy, double s)
{
    enum { N = 200000 }; /* composite Simpson; the integrand is smooth */
    double h = s / N, sum = 0;
    for (int i = 0; i <= N; i++) {
        double w = (i == 0 || i == N) ? 1 : (i % 2 ? 4 : 2);
        sum += w * sigma0 * exp(-b * (oy + dy * i * h - y0));
    }
    return sum * h / 3;
}

static void fog_against_quadrature(void **st)
{
    (void)st;
    const double sigma0 = 2e-4, y0 = 400;
    const double falloffs[] = {0.0015, 0.05}; /* gentle, and very steep */
    const double oys[] = {0, 400, 3000};
    const double dys[] = {0, 1e-7, -1e-7, 1e-3, -1e-3, 0.3, -0.3, 1, -1};
    const double lengths[] = {10, 1e4, 1e6};
    enum { MAXN = 256 };
    static float pts[MAXN * 3], out[MAXN * 2], naive[MAXN * 2];
    double want[MAXN];
    for (size_t f = 0; f < 2; f++) {
        char json[512];
        snprintf(json, sizeof json,
                 "{\"program\": \"csg\", \"fog\": {\"density\": %g, \"falloff\": %g, \"height\": %g},"
                 " \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": \"sphere\", \"material\": \"m\"}]}",
                 sigma0, falloffs[f], y0);
        scene s;
        load_text(json, NULL, 0, &s);
        int n = 0;
        for (size_t a = 0; a < 3; a++)
            for (size_t b = 0; b < sizeof dys / sizeof dys[0]; b++)
                for (size_t c = 0; c < 3; c++) {
                    pts[n * 3] = (float)oys[a], pts[n * 3 + 1] = (float)dys[b], pts[n * 3 + 2] = (float)lengths[c];
                    want[n++] = tau_quadrature(sigma0, falloffs[f], y0, oys[a], (float)dys[b], lengths[c]);
                }
        err_t e;
        assert_true(render_probe_with(&s, "fogprobe.frag", NULL, pts, n, out, &e));
        assert_true(render_probe_with(&s, "fogprobe.frag", "#define FOG_NAIVE 1\n", pts, n, naive, &e));
        int naive_wrong = 0;
        double worst = 0;
        for (int i = 0; i < n; i++) {
            double T = exp(-(double)out[2 * i]), Tref = exp(-want[i]);
            /* transmittance and in-scatter (1 − T) both within float precision */
            if (!isfinite(out[2 * i]) || fabs(T - Tref) > 2e-5 + 1e-4 * Tref)
                fail_msg("fog b=%g, y=%g, dir.y=%g, s=%g: tau %g, quadrature %g", falloffs[f], (double)pts[i * 3],
                         (double)pts[i * 3 + 1], (double)pts[i * 3 + 2], (double)out[2 * i], want[i]);
            if (want[i] < 30 && fabs(out[2 * i] - want[i]) > 1e-4 * want[i] + 1e-7)
                fail_msg("fog b=%g, y=%g, dir.y=%g, s=%g: tau %.7g, quadrature %.7g", falloffs[f], (double)pts[i * 3],
                         (double)pts[i * 3 + 1], (double)pts[i * 3 + 2], (double)out[2 * i], want[i]);
            worst = fmax(worst, fabs(T - Tref));
            double Tn = exp(-(double)naive[2 * i]);
            naive_wrong += !isfinite(naive[2 * i]) || fabs(Tn - Tref) > 2e-5 + 1e-4 * Tref;
        }
        fprintf(stderr, "fog falloff %g: %d rays match quadrature (worst transmittance error %.2g); the lab's "
                "closed form as written gets %d wrong\n", falloffs[f], n, worst, naive_wrong);
        assert_true(naive_wrong > 0); /* level rays give it 0/0 */
        scene_free(&s);
    }
}

/* ---- ridges: no black dashes ------------------------------------------------------------------------
 * The shading normal comes from ±1-texel differences; on a ridge seen from its back slope it can face
 * away from the viewer by 9–13°. Flipped to face the viewer (what the shared main does for a camera
 * inside a solid) it pointed into the ground: no sun, no sky, a black dash along the ridge. Lit
 * terrain has no pixel that dark: count pixels that hit the ground and are darker than 10 % of the
 * median hit pixel, and those of them in runs of two or more with lit ground above and below (dashes),
 * at the shipped terrains' own views, 1280x720 (13 and 90 dashes before the normal was bent instead of
 * flipped, 0 after). The Himalaya 640 km from the origin also from two cameras moved by 0.3 m and 4 m:
 * there ambient-occlusion probes nearer than the position's float step read rounding as occlusion,
 * dark speckles that moved with every rounding (0–64 dark pixels, 0–6 in dashes as the camera moved;
 * 4 dashes on an NVIDIA H100 at the shipped view, 0 here); with the probes kept off the floor, 0. */
static void ridges_have_no_black_dashes(void **st)
{
    (void)st;
    enum { RW = 1280, RH = 720 };
    static float aov[RW * RH * AOV], rgba[RW * RH * 4];
    static const struct {
        const char *scene;
        double move[3];
    } SHOTS[] = {{"jacksboro", {0, 0, 0}}, {"himalaya", {0, 0, 0}}, {"himalaya", {0, 0, 0.3}}, {"himalaya", {3, 0, -3}}};
    int total = 0;
    for (size_t k = 0; k < 2 * sizeof SHOTS / sizeof SHOTS[0]; k++) { /* smooth normals, then the patches' own */
        size_t v = k % (sizeof SHOTS / sizeof SHOTS[0]);
        bool patch = k >= sizeof SHOTS / sizeof SHOTS[0];
        scene s;
        const char *sets[] = {"quality.spp=1", patch ? "terrain.normals=patch" : "terrain.normals=smooth"};
        load_text_file(SHOTS[v].scene, sets, 2, &s);
        double eye[3], at[3];
        for (int i = 0; i < 3; i++)
            eye[i] = s.cam_position[i] + SHOTS[v].move[i], at[i] = s.cam_look_at[i];
        camera cam = camera_look_at_deg(eye, at, s.cam_fov_deg);
        draw(&s, &cam, RW, RH, 1, NULL, aov, rgba);
        static float lum[RW * RH];
        static double vals[RW * RH];
        int n = 0;
        for (int i = 0; i < RW * RH; i++) {
            lum[i] = 0.2126f * rgba[4 * i] + 0.7152f * rgba[4 * i + 1] + 0.0722f * rgba[4 * i + 2];
            if (!isinf(aov[i * AOV + AOV_SLOT_DEPTH]))
                vals[n++] = lum[i];
        }
        double median = util_median(vals, n);
        int dark = 0, dashes = 0;
        for (int y = 2; y < RH - 2; y++)
            for (int x = 0; x < RW; x++) {
                int i = y * RW + x;
                if (isinf(aov[i * AOV + AOV_SLOT_DEPTH]) || lum[i] >= 0.1 * median)
                    continue;
                dark++;
                bool run = (x > 0 && lum[i - 1] < 0.1 * median) || (x + 1 < RW && lum[i + 1] < 0.1 * median);
                dashes += run && lum[i - 2 * RW] >= 0.25 * median && lum[i + 2 * RW] >= 0.25 * median;
            }
        fprintf(stderr, "  %s moved by (%g, %g, %g) m, %s normals: %d ground pixels, %d darker than 10 %% of the median, "
                "%d of them in thin dashes\n", SHOTS[v].scene, SHOTS[v].move[0], SHOTS[v].move[1], SHOTS[v].move[2],
                patch ? "patch" : "smooth", n, dark, dashes);
        assert_true(n > RW * RH / 10);
        total += dark;
        scene_free(&s);
    }
    assert_int_equal(total, 0);
}

/* ---- the noise terrain against a double-precision reference of the same filtered surface ----------------
 * shaders/terrain/noise.glsl's surface written again in double: f(p) = y − base − A Σ wᵢ aᵢ nᵢ(p fᵢ + 17.31 i),
 * value noise on Teschner's spatial hash of the lattice and one multiply-xorshift round, with the quintic fade, each octave's weight wᵢ fading
 * from 1 at 4 pixel footprints a wavelength to 0 at 2 (the footprint at p: its distance to the eye times
 * the pixel's angle). The reference marches it with one global Lipschitz bound, safe everywhere:
 * |∇f| ≤ 1 + A Σ aᵢ fᵢ (S √3 + 8 α), S = 30/16 the quintic's steepest slope, 8 α fᵢ the steepest a
 * weight changes with the distance (α the pixel angle), so its first root is the true first crossing
 * (to 1e-6 m), found in as many steps as it takes. Against it the shader's local bounds, filtered
 * octaves and tail, at the shipped view and a low one across the valleys, at draft, interactive and final
 * (draft does not refine: it drew 2,049 pixels of false ground above the horizon before it marched on to
 * the crossing, and 135 depths short by up to a tail step before that crossing was refined). */
static double ref_hash3(int x, int y, int z)
{
    /* Teschner et al.'s spatial hash of the lattice point, then one multiply-xorshift round */
    uint32_t h = ((uint32_t)x * 73856093u ^ (uint32_t)y * 19349663u ^ (uint32_t)z * 83492791u) * 0x27d4eb2du;
    return (h ^ (h >> 15)) * (1.0 / 4294967295.0);
}

static double ref_value_noise(const double q[3])
{
    int i[3];
    double u[3];
    for (int k = 0; k < 3; k++) {
        double fl = floor(q[k]), f = q[k] - fl;
        i[k] = (int)fl;
        u[k] = f * f * f * (f * (f * 6 - 15) + 10);
    }
    double v = 0;
    for (int c = 0; c < 8; c++) { /* trilinear in the faded coordinates */
        int bx = c & 1, by = (c >> 1) & 1, bz = (c >> 2) & 1;
        v += ref_hash3(i[0] + bx, i[1] + by, i[2] + bz) * (bx ? u[0] : 1 - u[0]) * (by ? u[1] : 1 - u[1]) *
             (bz ? u[2] : 1 - u[2]);
    }
    return v;
}

typedef struct {
    double base, amplitude, frequency, pixel_angle, eye[3], lipschitz;
    int octaves;
} noise_ref;

static double noise_ref_f(const noise_ref *n, const double p[3])
{
    double e[3] = {p[0] - n->eye[0], p[1] - n->eye[1], p[2] - n->eye[2]};
    double footprint = fmax(n->pixel_angle * sqrt(ref_dot(e, e)), 1e-30), sum = 0, amp = 0.5, freq = n->frequency;
    for (int o = 0; o < n->octaves; o++, amp *= 0.5, freq *= 2) {
        double w = fmin(fmax((1 / (footprint * freq) - 2) / 2, 0), 1);
        if (w <= 0)
            break;
        double q[3] = {p[0] * freq + 17.31 * o, p[1] * freq + 17.31 * o, p[2] * freq + 17.31 * o};
        sum += amp * w * ref_value_noise(q);
    }
    return p[1] - n->base - n->amplitude * sum;
}

/* The first crossing along the ray within tmax (+inf: none); NAN when the march could not decide. */
static double noise_ref_hit(const noise_ref *n, const dray *r, double tmax)
{
    double t = 0;
    for (int i = 0; i < 2000000; i++) {
        double p[3] = {r->o[0] + r->d[0] * t, r->o[1] + r->d[1] * t, r->o[2] + r->d[2] * t};
        if (p[1] > n->base + n->amplitude && r->d[1] >= 0)
            return INFINITY; /* above every octave's reach, and rising */
        double f = noise_ref_f(n, p);
        if (f < 1e-6)
            return t;
        t += f / n->lipschitz;
        if (t > tmax)
            return INFINITY;
    }
    return NAN;
}

static void noise_against_double_reference(void **st)
{
    (void)st;
    static float aov[W * H * AOV];
    static double ref[W * H];
    for (int p = PRESET_DRAFT; p <= PRESET_FINAL; p++) {
        char preset[64];
        snprintf(preset, sizeof preset, "quality.preset=%s", preset_name((quality_preset)p));
        scene s;
        load_text_file("noise", (const char *const[]){preset, "quality.spp=1"}, 2, &s);
        double eye[3], at[3];
        for (int i = 0; i < 3; i++)
            eye[i] = s.cam_position[i], at[i] = s.cam_look_at[i];
        camera cams[2] = {camera_look_at_deg(eye, at, s.cam_fov_deg)};
        eye[1] = at[1] = 0.5 * s.terrain.amplitude; /* halfway up the hills, level: the far valleys */
        cams[1] = camera_look_at_deg(eye, at, s.cam_fov_deg);
        for (int c = 0; c < 2; c++) {
            noise_ref n = {s.terrain.base, s.terrain.amplitude, s.terrain.frequency, camera_pixel_angle(&cams[c], H),
                           {cams[c].position[0], cams[c].position[1], cams[c].position[2]}, 1, s.terrain.octaves};
            for (int o = 0; o < n.octaves; o++) {
                double freq = n.frequency * ldexp(1, o);
                n.lipschitz += n.amplitude * ldexp(0.5, -o) * freq * (30.0 / 16.0 * sqrt(3.0) + 8 * n.pixel_angle);
            }
            draw(&s, &cams[c], W, H, 1, NULL, aov, NULL);
            for (int row = 0; row < H; row++)
                for (int x = 0; x < W; x++) {
                    dray r = pixel_ray(&cams[c], x, row, W, H);
                    ref[row * W + x] = noise_ref_hit(&n, &r, s.quality.max_dist);
                }
            int hits = 0, wrong_class = 0, at_edges = 0, undecided = 0, deep = 0, thin = 0, grazes = 0;
            for (int i = 0; i < W * H; i++) {
                double zr = ref[i];
                float zt = aov[i * AOV + AOV_SLOT_DEPTH];
                if (isnan(zr) || fabs(zr - s.quality.max_dist) < 0.01 * s.quality.max_dist) {
                    undecided++; /* the reference gave up, or the crossing sits on max_dist itself */
                    continue;
                }
                hits += !isinf(zr);
                if (isinf(zr) != isinf(zt)) {
                    /* a silhouette pixel: a neighbour's reference depth jumps or misses */
                    bool edge = false;
                    for (int k = 0; k < 4 && !edge; k++) {
                        int u = i % W + (k == 0) - (k == 1), v = i / W + (k == 2) - (k == 3);
                        if (u >= 0 && v >= 0 && u < W && v < H)
                            edge = isinf(ref[v * W + u]) != isinf(zr) || fabs(ref[v * W + u] - zr) > 0.05 * zr;
                    }
                    at_edges += edge;
                    wrong_class += !edge;
                    continue;
                }
                if (!isinf(zr)) {
                    /* shorter: only a graze within float resolution of the surface (a touch the reference,
                     * stopping at 1e-6 m, went past); behind: only past a chord thinner than the march's
                     * stated tolerance, one threshold (a rim the ray crossed between two samples) */
                    double rel = (zt - zr) / zr;
                    dray r = pixel_ray(&cams[c], i % W, i / W, W, H);
                    double q[3] = {r.o[0] + r.d[0] * zt, r.o[1] + r.d[1] * zt, r.o[2] + r.d[2] * zt};
                    double eps = s.quality.hit_k * n.pixel_angle * zr, chord = 0;
                    if (rel < -0.01 && fabs(noise_ref_f(&n, q)) > 1e-3)
                        deep++;
                    else if (rel < -0.01)
                        grazes++;
                    else if (rel > 0.01) {
                        for (chord = 0; chord < 2 * eps; chord += eps / 64) {
                            double u = zr + chord + eps / 64;
                            double pu[3] = {r.o[0] + r.d[0] * u, r.o[1] + r.d[1] * u, r.o[2] + r.d[2] * u};
                            if (noise_ref_f(&n, pu) > 0)
                                break;
                        }
                        if (chord < eps)
                            thin++;
                        else
                            deep++;
                    }
                    if (fabs(rel) > 0.01)
                        fprintf(stderr, "    pixel (%d, %d): depth %.6g, the reference %.6g (steps %g), f there %.2g, "
                                "chord %.3g m (a threshold %.3g m)\n", i % W, i / W, zt, zr, aov[i * AOV + AOV_SLOT_STEPS],
                                noise_ref_f(&n, q), chord, eps);
                }
            }
            fprintf(stderr, "  noise %s view %d: %d hits in the double reference (%d undecided); %d hit or missed "
                    "against it off the silhouettes (%d on them); %d depths more than 1 %% off, %d of them past a chord "
                    "thinner than a threshold, %d short at a graze within 1 mm\n", preset_name((quality_preset)p), c, hits,
                    undecided, wrong_class, at_edges, deep + thin + grazes, thin, grazes);
            assert_true(hits > W * H / 4);
            assert_true(undecided < W * H / 100);
            assert_int_equal(wrong_class, 0);
            assert_int_equal(deep, 0);
            assert_true(thin <= hits / 1000);
            assert_true(at_edges <= W * H / 100);
        }
        scene_free(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(changed_file_is_read_again),
        cmocka_unit_test(ground_height_probe),
        cmocka_unit_test(ridges_have_no_black_dashes),
        cmocka_unit_test(fog_against_quadrature),
        cmocka_unit_test(noise_against_double_reference),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='far*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
