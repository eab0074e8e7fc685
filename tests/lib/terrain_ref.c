/* terrain_ref — the terrain tests' exact reference and fixtures (terrain_ref.h). */
#include "terrain_ref.h"

/* ---- the reference: a ray against the solid column under a bilinear heightfield, in double ------- */

double texel(const heightfield *hf, int i, int j) { return hf->h[j * hf->width + i]; }

double height_cell(const heightfield *hf, double cx, double cz)
{
    cx = fmin(fmax(cx, 0), hf->width - 1);
    cz = fmin(fmax(cz, 0), hf->height - 1);
    int i = (int)fmin(floor(cx), hf->width - 2), j = (int)fmin(floor(cz), hf->height - 2);
    double a = cx - i, b = cz - j;
    return (1 - b) * ((1 - a) * texel(hf, i, j) + a * texel(hf, i + 1, j)) +
           b * ((1 - a) * texel(hf, i, j + 1) + a * texel(hf, i + 1, j + 1));
}

/* Smallest s in [0, s_end] with y(s) = h(s) on cell (i, j), or −1. */
static double cell_root(const heightfield *hf, int i, int j, double cx, double cz, double ux, double uz,
                        double y, double dy, double s_end)
{
    double h00 = texel(hf, i, j), h10 = texel(hf, i + 1, j), h01 = texel(hf, i, j + 1), h11 = texel(hf, i + 1, j + 1);
    if (TERRAIN_IS_HOLE(fmin(fmin(h00, h10), fmin(h01, h11))))
        return -1; /* nodata: no surface in this cell */
    double a = h10 - h00, b = h01 - h00, c = h00 - h10 - h01 + h11, u = cx - i, v = cz - j;
    double A = -c * ux * uz, B = dy - (a * ux + b * uz + c * (u * uz + v * ux)), C = y - (h00 + a * u + b * v + c * u * v);
    if (C <= 0)
        return 0;
    double roots[2];
    int n = 0;
    if (fabs(A) < 1e-300) {
        if (B != 0)
            roots[n++] = -C / B;
    } else {
        double disc = B * B - 4 * A * C;
        if (disc >= 0) {
            double q = -0.5 * (B + copysign(sqrt(disc), B));
            roots[n++] = q / A;
            if (q != 0)
                roots[n++] = C / q;
        }
    }
    double best = -1;
    for (int k = 0; k < n; k++)
        if (roots[k] >= 0 && roots[k] <= s_end * (1 + 1e-12) + 1e-9 && (best < 0 || roots[k] < best)) /* flat at the slab's floor */
            best = roots[k];
    return best;
}

bool ref_terrain(const heightfield *hf, const dray *r, double *t_hit)
{
    double lo[3] = {hf->x0 + 0.5 * hf->dx, hf->hmin, hf->z0 + 0.5 * hf->dz};
    double hi[3] = {hf->x0 + (hf->width - 0.5) * hf->dx, hf->hmax, hf->z0 + (hf->height - 0.5) * hf->dz};
    double t0 = 0, t1 = INFINITY;
    for (int k = 0; k < 3; k++) {
        if (r->d[k] == 0) {
            if (r->o[k] < lo[k] || r->o[k] > hi[k])
                return false;
            continue;
        }
        double a = (lo[k] - r->o[k]) / r->d[k], b = (hi[k] - r->o[k]) / r->d[k];
        t0 = fmax(t0, fmin(a, b));
        t1 = fmin(t1, fmax(a, b));
    }
    if (t0 > t1)
        return false;
    double ux = r->d[0] / hf->dx, uz = r->d[2] / hf->dz; /* cell-space velocity */
    double t = t0;
    for (int guard = 0; guard < 4 * (hf->width + hf->height) && t <= t1; guard++) {
        double cx = (r->o[0] + r->d[0] * t - hf->x0) / hf->dx - 0.5, cz = (r->o[2] + r->d[2] * t - hf->z0) / hf->dz - 0.5;
        double y = r->o[1] + r->d[1] * t;
        /* the cell the ray is in, or about to enter */
        int i = (int)floor(cx + (ux > 0 ? 1e-9 : ux < 0 ? -1e-9 : 0)), j = (int)floor(cz + (uz > 0 ? 1e-9 : uz < 0 ? -1e-9 : 0));
        i = i < 0 ? 0 : i > hf->width - 2 ? hf->width - 2 : i;
        j = j < 0 ? 0 : j > hf->height - 2 ? hf->height - 2 : j;
        /* enters below the surface: the column's side (a cell with a nodata corner has no column) */
        bool solid = !TERRAIN_IS_HOLE(fmin(fmin(texel(hf, i, j), texel(hf, i + 1, j)), fmin(texel(hf, i, j + 1), texel(hf, i + 1, j + 1))));
        if (guard == 0 && solid && y <= height_cell(hf, cx, cz)) {
            *t_hit = t;
            return true;
        }
        double tx = ux > 0 ? (i + 1 - cx) / ux : ux < 0 ? (i - cx) / ux : INFINITY;
        double tz = uz > 0 ? (j + 1 - cz) / uz : uz < 0 ? (j - cz) / uz : INFINITY;
        double s_end = fmin(fmin(tx, tz), t1 - t);
        double s = cell_root(hf, i, j, cx, cz, ux, uz, y, r->d[1], s_end);
        if (s >= 0) {
            *t_hit = t + s;
            return true;
        }
        t += fmax(s_end, 1e-9);
    }
    return false;
}

/* How long the ray stays under the surface after entering it at t (fine steps in double). */
double dip_length(const heightfield *hf, const dray *r, double t)
{
    double step = 0.01 * fmin(hf->dx, hf->dz), s = 0;
    for (; s < 1e6; s += step) {
        double x = r->o[0] + r->d[0] * (t + s + step), z = r->o[2] + r->d[2] * (t + s + step);
        double y = r->o[1] + r->d[1] * (t + s + step);
        if (y > height_cell(hf, (x - hf->x0) / hf->dx - 0.5, (z - hf->z0) / hf->dz - 0.5))
            break;
    }
    return s + step;
}

void check_views_in(const char *scene_name, const char *method, const char *const *sets, int nsets, bool exact,
                    const view *views, int nv)
{
    scene s;
    err_t e;
    if (!scene_load(scene_name, sets, nsets, &s, &e))
        fail_msg("%s", e.msg);
    heightfield hf;
    heightfield_desc d = {.path = s.terrain.heightmap, .spacing = {s.terrain.spacing[0], s.terrain.spacing[1]},
                          .height_min = s.terrain.height_min, .height_max = s.terrain.height_max,
                          .exaggeration = s.terrain.exaggeration};
    if (!heightfield_load(&d, &hf, &e))
        fail_msg("%s", e.msg);
    static float aov[W * H * AOV];
    for (int v = 0; v < nv; v++) {
        camera cam = cam_at(views[v].eye[0], views[v].eye[1], views[v].eye[2], views[v].at[0], views[v].at[1],
                            views[v].at[2], views[v].fov);
        draw(&s, &cam, W, H, 1, NULL, aov, NULL);
        int hits = 0, misses = 0, grazing = 0, disagree = 0, tunnelled = 0;
        double worst = 0, samples = 0;
        for (int row = 0; row < H; row++)
            for (int x = 0; x < W; x++) {
                dray r = pixel_ray(&cam, x, row, W, H);
                double t_ref = INFINITY;
                bool hit = ref_terrain(&hf, &r, &t_ref);
                float t = aov[(row * W + x) * AOV + 3];
                samples += aov[(row * W + x) * AOV + 4];
                grazing += fabs(r.d[1]) < 1e-3;
                if (!hit && isinf(t)) {
                    misses++;
                    continue;
                }
                /* float resolution of a height, spread along the ray by how steeply it meets the surface */
                double tol, step_here = 0;
                if (exact) {
                    tol = 2e-5 * (fabs(t_ref) + hf.hmax) + 0.02 * fmin(hf.dx, hf.dz);
                } else { /* the bracket left after the binary search */
                    double dt = s.quality.linear_step * fmin(hf.dx, hf.dz) / fmax(hypot(r.d[0], r.d[2]), 1e-3);
                    double t_walk = 0, grown = dt;
                    while (t_walk < (hit ? t_ref : 0) && grown < 1e12)
                        t_walk += grown, grown *= s.quality.step_growth;
                    tol = grown / ldexp(1.0, s.quality.binary_steps) + 2e-5 * (fabs(t_ref) + hf.hmax);
                    step_here = grown;
                }
                if (hit != !isinf(t) || (hit && fabs(t - t_ref) > tol)) {
                    /* the lab's method may step over a sliver of surface thinner than its step: allowed */
                    if (!exact && hit && (isinf(t) || t > t_ref) && dip_length(&hf, &r, t_ref) < step_here) {
                        tunnelled++;
                        continue;
                    }
                    disagree++;
                    if (disagree <= 3)
                        fprintf(stderr, "  %s %s pixel (%d,%d): depth %.4f, exact %s%.4f (tol %.3g)\n", method,
                                views[v].what, x, row, (double)t, hit ? "" : "miss ", hit ? t_ref : 0.0, tol);
                    continue;
                }
                worst = fmax(worst, fabs(t - t_ref) / tol);
                hits++;
            }
        fprintf(stderr, "%-7s %-28s %4d hits (worst %.2f of tolerance), %4d misses, %4d grazing rays, "
                "%.1f height samples/px, %d stepped over a sliver thinner than a step, %d disagree\n", method,
                views[v].what, hits, worst, misses, grazing, samples / (W * H), tunnelled, disagree);
        if (disagree)
            fail_msg("%s: %d pixels disagree with the exact intersection", views[v].what, disagree);
    }
    heightfield_free(&hf);
    scene_free(&s);
}

const view VIEWS[] = {
    {"grazing (|dir.y| < 1e-3)", {-3000, 860, 9000}, {9000, 860, -9000}, 0.1},
    {"inside the slab", {3000, 1250, 6000}, {-2000, 500, -3000}, 60},
    {"below the surface", {0, 100, 0}, {3000, 300, 1000}, 60},
    {"footprint edge, from outside", {1000, 900, 20000}, {0, 600, 0}, 35},
    {"leaving the footprint", {-14000, 2600, 2000}, {9000, 1400, -1000}, 50},
};

/* ---- generated DEMs ---------------------------------------------------------------------------- */

/* A w × h float DEM of rolling hills (sum of sines, 0–300 m) with a sea clamped flat at 0, 30 m
 * texels, written as EXR with its scene file; returns the scene's path. */
void synthetic_dem(const char *dir, const char *name, int w, int h, bool holes, char *scene_path, size_t n)
{
    float *heights = malloc(sizeof(float) * (size_t)w * (size_t)h);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double x = i * 0.013, z = j * 0.017;
            double v = 120 + 90 * sin(x) * cos(z * 0.7) + 60 * sin(0.37 * x + 1.3 * z) + 25 * cos(2.9 * x - 2.3 * z);
            /* nodata (NaN): a round hole, a one-texel line and scattered single texels */
            int di = i - w / 2, dj = j - h / 2;
            bool hole = holes && (di * di + dj * dj < (w / 8) * (w / 8) || i == w / 4 || (i * 7 + j * 13) % 97 == 0);
            heights[(size_t)j * (size_t)w + (size_t)i] = hole ? NAN : (float)fmax(v, 0.0); /* sea: exactly the minimum */
        }
    char exr[256];
    snprintf(exr, sizeof exr, "%s/%s.exr", dir, name);
    err_t e;
    if (!image_write_f32(exr, w, h, 1, (const char *const[]){"Y"}, heights, &e))
        fail_msg("%s", e.msg);
    free(heights);
    snprintf(scene_path, n, "%s/%s.json", dir, name);
    FILE *f = fopen(scene_path, "w");
    fprintf(f, "{\"program\": \"terrain\", \"materials\": {\"rock\": {}}, \"quality\": {\"max_dist\": 1e6}, \"terrain\": {\"heightmap\": \"%s.exr\", "
               "\"spacing\": [30, 30]}}", name);
    fclose(f);
}

/* Removes NAME.exr and NAME.json for each name, then the folder. */
void remove_dems(const char *dir, const char *const *names)
{
    char file[320];
    for (int k = 0; names[k]; k++) {
        snprintf(file, sizeof file, "%s/%s.exr", dir, names[k]);
        unlink(file);
        snprintf(file, sizeof file, "%s/%s.json", dir, names[k]);
        unlink(file);
    }
    rmdir(dir);
}

void load_text_file(const char *name, const char *const *sets, int n, scene *s)
{
    err_t e;
    if (!scene_load(name, sets, n, s, &e))
        fail_msg("%s", e.msg);
}
