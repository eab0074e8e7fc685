/* mesh_job — `fathom mesh` (jobs/mesh/mesh_job.h). */
#include "jobs/mesh/mesh_job.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/resource.h>

#include "data/droplets/droplets.h"
#include "data/mesh/mesh.h"
#include "data/mesh/mesh_dem.h"
#include "data/mesh/mesh_io.h"
#include "gpu/gpu.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "scene/scene.h"

enum { DEFAULT_RES = MESH_JOB_DEFAULT_RES, DEFAULT_DEM_RES = 2048, BAR_WIDTH = 30 };
static const size_t PROBE_BATCH = (size_t)1 << 20;

typedef struct job {
    const mesh_desc *d;
    const scene *s;
    float *out; /* render_probe's (distance, material) pairs */
    double box[6]; /* the box meshed: the field is clipped by it */
    size_t out_cap;
    double t0, shown; /* start; when the progress bar was last drawn */
    droplets drops;   /* the scene's droplets (count 0: none): a layer outside map(), added to its field */
    float iso;        /* the level meshed */
    bool exact;       /* the field is a distance near the level (not a fractal's loose estimate) */
} job;

/* map()'s material for a bound that is not a surface (shaders/common/hit.glsl), and the droplets' here. */
enum { MATERIAL_BOUND_ID = -1, MATERIAL_DROPLET = -2 };

/* map() at n points into j->out, in batches a texture holds (2^20 points each). */
static bool probe(job *j, const float *pts, size_t n, err_t *err)
{
    if (n > j->out_cap) {
        j->out_cap = n;
        j->out = util_realloc(j->out, 2 * n * sizeof(float), "mesh probes");
    }
    for (size_t at = 0; at < n; at += PROBE_BATCH)
        if (!render_probe(j->s, NULL, pts + 3 * at, (int)(n - at < PROBE_BATCH ? n - at : PROBE_BATCH), j->out + 2 * at, err))
            return false;
    for (size_t i = 0; j->drops.count && i < n; i++) { /* the union with the droplets (grey) */
        double dd = droplets_distance(&j->drops, pts + 3 * i);
        if (dd < j->out[2 * i])
            j->out[2 * i] = (float)dd, j->out[2 * i + 1] = MATERIAL_DROPLET;
    }
    return true;
}

/* The field meshed. Where map() answers with a bound (a fractal's bounding sphere, MATERIAL_BOUND) no
 * surface is: a bound below the level (the sphere's distance within the level of it: the level is half a
 * voxel, the sphere's margin 0.1) would mesh a thin shell around the sphere, inside out at its inner
 * face (the Mandelbox at 64 cells: 96 such shells). The set grown by the level is cut there at the
 * sphere's margin instead, at most the level minus the margin from where it would reach. */
static bool field(void *user, const float *pts, size_t n, float *dist, err_t *err)
{
    job *j = user;
    if (!probe(j, pts, n, err))
        return false;
    for (size_t i = 0; i < n; i++)
        dist[i] = j->out[2 * i + 1] == MATERIAL_BOUND_ID ? fmaxf(j->out[2 * i], nextafterf(j->iso, INFINITY))
                                                          : j->out[2 * i];
    return true;
}

static void progress(void *user, double done)
{
    job *j = user;
    double now = util_now();
    if (j->d->quiet || (done < 1 && now - j->shown < 0.25))
        return;
    j->shown = now;
    int fill = (int)(done * BAR_WIDTH);
    char bar[BAR_WIDTH + 1];
    for (int i = 0; i < BAR_WIDTH; i++)
        bar[i] = i < fill ? '#' : '-';
    bar[BAR_WIDTH] = '\0';
    double t = now - j->t0;
    fprintf(stderr, "\rmeshing [%s] %3.0f%%  %.1f s  (eta %.1f s) ", bar, 100 * done, t, done > 0 ? t / done * (1 - done) : 0);
    if (done >= 1)
        fputc('\n', stderr);
    fflush(stderr);
}

/* The box meshed when none is given: a fractal's bounding sphere's cube; otherwise the cube the camera
 * frames at its look-at point (the width of a 16:9 view there). */
static void default_box(const scene *s, double box[6])
{
    double c[3] = {0, 0, 0}, half;
    if (program_is_fractal(s->program)) {
        half = s->fractal.bound_radius;
    } else {
        double dist = 0;
        for (int k = 0; k < 3; k++) {
            c[k] = s->cam_look_at[k];
            dist += (s->cam_position[k] - c[k]) * (s->cam_position[k] - c[k]);
        }
        half = sqrt(dist) * tan(0.5 * s->cam_fov_deg * 3.14159265358979 / 180) * 16 / 9;
    }
    for (int k = 0; k < 3; k++) {
        box[k] = c[k] - half;
        box[3 + k] = c[k] + half;
    }
}

/* Each vertex's colour: its material's base colour (linear), by the material map() names there. */
static bool colour(job *j, mesh *m, err_t *err)
{
    if (!probe(j, m->pos, m->nv, err))
        return false;
    m->col = util_alloc((m->nv ? m->nv : 1) * 3 * sizeof(float), "mesh colours");
    for (size_t v = 0; v < m->nv; v++) {
        int id = (int)j->out[2 * v + 1];
        const float grey[3] = {0.7f, 0.7f, 0.7f};
        memcpy(m->col + 3 * v, id >= 0 && id < j->s->material_count ? j->s->materials[id].base_color : grey,
               3 * sizeof(float));
    }
    return true;
}

/* Points' distance to the level meshed, by the field clipped by the box (max and mean, in voxels). */
static bool points_error(job *j, const float *pts, size_t n, float iso, double voxel, double *worst, double *mean,
                         err_t *err)
{
    *worst = *mean = 0;
    if (!probe(j, pts, n, err))
        return false;
    for (size_t v = 0; v < n; v++) {
        double f = fmax((double)j->out[2 * v] - iso, mesh_box_distance(j->box, j->box + 3, pts + 3 * v));
        double e = fabs(f) / voxel;
        *worst = fmax(*worst, e);
        *mean += e / (double)n;
    }
    return true;
}

/* The vertices' distance to the level meshed (max and mean, in voxels). */
static bool vertex_error(job *j, const mesh *m, float iso, double voxel, double *worst, double *mean, err_t *err)
{
    return points_error(j, m->pos, m->nv, iso, voxel, worst, mean, err);
}

/* The surface's distance to the level, in voxels, by the field at every corner, edge midpoint and face
 * centre: a simplification's faces can stray between corners that lie on it. */
static bool surface_error(job *j, const mesh *m, float iso, double voxel, double *worst, err_t *err)
{
    size_t n = m->nt * 4 + m->nv; /* each face's centre and edge midpoints, then the corners: one probe */
    float *pts = util_alloc((n + 1) * 3 * sizeof(float), "mesh error points");
    for (size_t f = 0; f < m->nt; f++) {
        const float *c[3];
        for (int i = 0; i < 3; i++)
            c[i] = m->pos + 3 * (size_t)m->tri[3 * f + (size_t)i];
        for (int k = 0; k < 3; k++) {
            pts[12 * f + (size_t)k] = (c[0][k] + c[1][k] + c[2][k]) / 3;
            for (int i = 0; i < 3; i++)
                pts[12 * f + 3 * (size_t)(i + 1) + (size_t)k] = 0.5f * (c[i][k] + c[(i + 1) % 3][k]);
        }
    }
    memcpy(pts + 12 * m->nt, m->pos, m->nv * 3 * sizeof(float));
    double mean;
    bool ok = points_error(j, pts, n, iso, voxel, worst, &mean, err);
    free(pts);
    return ok;
}

static void describe(const mesh *m, const char *what)
{
    mesh_topology t;
    mesh_check(m, &t);
    long long crossing = mesh_crossing_faces(m, NULL);
    printf("%s: %zu triangles, %zu vertices; %s (open edges %lld, non-manifold edges %lld, vertices %lld), "
           "%lld shell%s, Euler characteristic %lld; area %.6g, volume %.6g; %s\n", what, m->nt, m->nv,
           t.closed_manifold ? "closed and manifold" : "NOT closed and manifold", t.open_edges, t.nonmanifold_edges,
           t.nonmanifold_vertices, t.components, t.components == 1 ? "" : "s", t.euler, t.area, t.volume,
           crossing == 0 ? "no faces cross" : crossing < 0 ? "crossings not checked (out of memory)" : "FACES CROSS");
    if (crossing > 0)
        printf("crossing: %lld pairs of faces cross each other: the mesh intersects itself (not printable as it is)\n",
               crossing);
}

/* Before a long extraction starts, what it will take: its grid's samples at the rate this machine evaluates
 * the field (timed on 65,536 points across the box: an upper bound, as the bound skips empty blocks) and its
 * working memory (a 4096-cell csg once sat at 0 % with 1.9 GB and no word of the day it would take). */
static void estimate(job *j, const mesh_grid *g, err_t *err)
{
    double samples, bytes;
    enum { N = 65536 };
    if (!mesh_extract_size(g, &samples, &bytes) || samples < 1e8)
        return;
    float *pts = util_alloc(3 * N * sizeof(float), "the estimate's points"), *dist = NULL;
    uint32_t r = 12345;
    for (int i = 0; i < 3 * N; i++) { /* a fixed LCG (Numerical Recipes'): the same points every run */
        r = r * 1664525u + 1013904223u;
        pts[i] = (float)(g->lo[i % 3] + (g->hi[i % 3] - g->lo[i % 3]) * (r >> 8) / 16777216.0);
    }
    dist = util_alloc(2 * N * sizeof(float), "the estimate's distances");
    double t0 = util_now();
    bool ok = field(j, pts, N, dist, err);
    double rate = N / fmax(util_now() - t0, 1e-6);
    free(pts);
    free(dist);
    if (ok)
        printf("estimate: %.3g samples at most, %.1f h at most at the %.3g samples a second measured here; working "
               "memory from %.2f GB, and the mesh's (about 100 bytes a triangle)\n", samples, samples / rate / 3600, rate,
               bytes / 1e9);
    fflush(stdout); /* before the hours it announces */
}

/* A fractal, fragment, csg or other field scene: extracted on the GPU's map(). */
static bool mesh_field(job *j, mesh *m, double *voxel, float *iso, err_t *err)
{
    const scene *s = j->s;
    const mesh_desc *d = j->d;
    mesh_grid g = {.res = d->resolution ? d->resolution : DEFAULT_RES, .field = field, .user = j, .progress = progress,
                   .step = s->quality.step_factor > 0 ? s->quality.step_factor : 1.0f};
    double *box = j->box;
    if (d->has_box)
        memcpy(box, d->box, sizeof j->box);
    else
        default_box(s, box);
    memcpy(g.lo, box, sizeof g.lo);
    memcpy(g.hi, box + 3, sizeof g.hi);
    double ext = fmax(box[3] - box[0], fmax(box[4] - box[1], box[5] - box[2]));
    *voxel = ext / g.res;
    bool fractal = program_is_fractal(s->program);
    /* a fractal's estimate is trusted only near the surface: its level is the renderer's hit distance, unless
     * the formula declares an exact distance (@exact, the Menger sponge: half a voxel out gave +52 % volume) */
    bool exact = fractal && s->fractal.formula.exact && !s->fractal.has_hybrid;
    j->exact = !fractal || exact;
    g.iso = j->iso = *iso = !fractal || exact ? 0.0f
                   : s->fractal.hit_distance > 0 ? s->fractal.hit_distance
                                                 : (float)(0.5 * *voxel);
    mesh_stats st;
    estimate(j, &g, err);
    if (!mesh_extract(&g, m, &st, err))
        return false;
    printf("grid: %d x %d x %d cells of %.4g (box %.4g %.4g %.4g to %.4g %.4g %.4g%s), level %.3g; %lld of %lld "
           "samples evaluated (%lld of %lld blocks skipped by the bound), %lld crossings, working memory %.1f MB\n",
           st.cells[0], st.cells[1], st.cells[2], st.voxel, box[0], box[1], box[2], box[3], box[4], box[5],
           d->has_box ? "" : ", the default: --box to choose", (double)g.iso, st.evaluated, st.samples, st.skipped,
           st.blocks, st.crossings, (double)st.peak_bytes / 1e6);
    if (st.thin)
        printf("thin: %lld edges cross the surface twice within a voxel: features thinner than a voxel are lost there "
               "(raise --resolution)\n", st.thin);
    if (st.crossing > 0)
        printf("untangled: %lld pairs of faces crossed where the quadric placed their corners; %lld corners moved to "
               "their crossings' centroid, %lld pairs left\n", st.crossing, st.untangled, st.crossing_left);
    if (st.unbounded)
        printf("note: %lld crossings met a sample the field's bound had skipped: its distance bound is wrong there "
               "(the mesh is closed; lower quality.step_factor for the exact surface)\n", st.unbounded);
    return true;
}

/* A DEM scene: its solid. */
static bool mesh_terrain(job *j, mesh *m, double *texel, err_t *err)
{
    const scene *s = j->s;
    heightfield_desc hd = {.path = s->terrain.heightmap, .spacing = {s->terrain.spacing[0], s->terrain.spacing[1]},
                           .height_min = s->terrain.height_min, .height_max = s->terrain.height_max,
                           .exaggeration = s->terrain.exaggeration, .fill_nodata = s->terrain.fill_nodata};
    heightfield hf;
    if (!heightfield_load(&hd, &hf, err))
        return false;
    int side = hf.width > hf.height ? hf.width : hf.height;
    int res = j->d->resolution ? j->d->resolution : DEFAULT_DEM_RES, step = (side - 1 + res - 1) / res;
    step = step < 1 ? 1 : step;
    double relief = hf.hmax - hf.hmin;
    double below = j->d->base > 0 ? j->d->base : fmax(0.1 * relief, 1e-3 * side * fmax(hf.dx, hf.dz));
    mesh_dem_stats st;
    bool ok = mesh_dem_solid(&hf, step, hf.hmin - below, m, &st, err);
    *texel = step * fmax(hf.dx, hf.dz);
    if (ok)
        printf("dem: %dx%d texels (%s), a vertex every %d texel%s: %zu surface vertices, base %.4g below the lowest "
               "point (%.4g)%s\n", hf.width, hf.height, hf.about, step, step == 1 ? "" : "s", st.top_vertices, below,
               (double)hf.hmin, st.holes ? ", nodata texels at the lowest height" : "");
    heightfield_free(&hf);
    return ok;
}

/* Print size and axes: the longest side to print_mm millimetres, and +Z up for STL and 3MF (a slicer's
 * up; fathom's world is +Y up). */
static void place(const mesh_desc *d, mesh *m)
{
    const char *dot = strrchr(d->output, '.');
    bool z_up = dot && (!strcasecmp(dot, ".stl") || !strcasecmp(dot, ".3mf"));
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < m->nv; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->pos[3 * v + (size_t)k]);
            hi[k] = fmax(hi[k], m->pos[3 * v + (size_t)k]);
        }
    double ext = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    bool printed = d->print_mm > 0 && ext > 0;
    /* 3MF and STEP say millimetres (assimp writes them so): a scene's metres are written as 1000 of them */
    bool mm = dot && (!strcasecmp(dot, ".3mf") || !strcasecmp(dot, ".stp"));
    double scale = printed ? d->print_mm / ext : mm ? 1000 : 1, origin[3] = {0, 0, 0};
    if (printed) /* printed: the lowest corner at the origin */
        memcpy(origin, lo, sizeof origin);
    for (size_t v = 0; v < m->nv; v++) {
        float *p = m->pos + 3 * v, *n = m->nrm + 3 * v;
        for (int k = 0; k < 3 && scale != 1; k++)
            p[k] = (float)((p[k] - origin[k]) * scale);
        if (z_up) { /* (x, y, z) → (x, −z, y): a quarter turn about x; printed, moved back onto the origin */
            float y = p[1], ny = n[1];
            p[1] = (printed ? (float)((hi[2] - lo[2]) * scale) : 0.0f) - p[2], p[2] = y;
            n[1] = -n[2], n[2] = ny;
        }
    }
    if (printed)
        printf("print: scaled by %.6g, the longest side %.4g mm%s\n", scale, d->print_mm, z_up ? ", +Z up" : "");
    else if (mm)
        printf("units: the file's are millimetres: the scene's units written as metres, 1000 to one (--print-size MM "
               "for a size)\n");
}

static void copy_mesh(mesh *to, const mesh *from)
{
    mesh_free(to);
    for (size_t v = 0; v < from->nv; v++)
        mesh_add_vertex(to, from->pos + 3 * v, from->nrm + 3 * v);
    for (size_t f = 0; f < from->nt; f++)
        mesh_add_triangle(to, from->tri[3 * f], from->tri[3 * f + 1], from->tri[3 * f + 2]);
}

/* Faces folded back to back or collapsed dropped; if that leaves it not closed and manifold, vertices where
 * sheets touch parted and holes closed. The counts in r: fins, pinches, holes. */
static void repair(mesh *m, mesh_topology *top, long long r[3])
{
    r[0] = mesh_drop_fins(m), r[1] = r[2] = 0;
    mesh_check(m, top);
    if (!top->closed_manifold) { /* sheets touching: parted at their vertices; holes left: closed */
        r[1] = mesh_split_pinches(m);
        mesh_check(m, top);
        r[2] = top->open_edges ? mesh_fill_holes(m) : 0;
        if (r[2])
            mesh_check(m, top);
    }
    mesh_compact(m); /* a dropped face's corners may belong to no face now */
}

/* Toward d->triangles within the tolerance; meshoptimizer's collapses keep no promise of a manifold, so
 * faces folded back to back are dropped, vertices where sheets came to touch are parted and faces made to
 * cross are untangled; a result still not closed, manifold and uncrossed, or (a field that is a distance:
 * not a fractal's estimate, which puts the unsimplified Mandelbulb's own vertices 3.4 voxels off) whose
 * surface strays from the level by more than the tolerance as the field measures it (meshoptimizer's own
 * measure is an estimate: a torus it put at 0.97 voxels was 2.4 off), is tried again with a quarter more
 * triangles (up to 8 times), and the mesh is kept whole if none is. */
static bool simplify(job *j, mesh *m, double unit, float iso, bool field_scene, err_t *err)
{
    const mesh_desc *d = j->d;
    double tol = (d->tolerance > 0 ? d->tolerance : 1.0) * unit, e = 0, measured = 0;
    const char *u = field_scene ? "voxels" : "texels";
    mesh whole = {0}, t = {0};
    copy_mesh(&whole, m);
    size_t target = d->triangles;
    mesh_topology top = {0};
    long long r[3] = {0, 0, 0}, crossed = 0, moved = 0, left = 0;
    bool failed = false, ok = false;
    for (int round = 0; round < 8 && target < whole.nt && !failed && !ok; round++, target += ok ? 0 : target / 4) {
        copy_mesh(&t, &whole);
        if ((failed = !mesh_io_simplify(&t, target, tol, &e, err)))
            break;
        repair(&t, &top, r);
        moved = mesh_untangle(&t, NULL, &crossed, &left);
        ok = top.closed_manifold && left == 0;
        if (ok && field_scene && j->exact) {
            failed = !surface_error(j, &t, iso, unit, &measured, err);
            ok = !failed && measured <= tol / unit;
        }
    }
    if (ok) {
        mesh_free(m);
        *m = t;
        t = (mesh){0};
        printf("simplified: toward %zu triangles within %.4g (%.3g %s): %zu%s, deviation %.4g (%.3f %s)", d->triangles,
               tol, tol / unit, u, m->nt, target > d->triangles ? " (more than asked: fewer broke the manifold or the "
               "tolerance)" : "", e, e / unit, u);
        if (field_scene && j->exact)
            printf(" by meshoptimizer's estimate, %.3f voxels by the field at corners, edge midpoints and centres", measured);
        else if (field_scene)
            printf(" by meshoptimizer's estimate (a fractal's estimate is no distance to measure it by)");
        printf("\n");
        if (r[0] || r[1] || r[2])
            printf("repaired: %lld faces back to back dropped, %lld vertices where sheets touched parted, %lld holes "
                   "closed\n", r[0], r[1], r[2]);
        if (crossed > 0)
            printf("untangled: %lld pairs of faces crossed after the simplification; %lld corners moved toward their "
                   "neighbours, 0 pairs left\n", crossed, moved);
    } else if (!failed) {
        printf("simplified: no simplification toward %zu triangles within %.3g %s stayed closed, manifold, uncrossed "
               "and within the tolerance: the mesh is kept whole\n", d->triangles, tol / unit, u);
    }
    mesh_free(&t);
    mesh_free(&whole);
    return !failed;
}

/* Faces the weld or the repairs made cross: their corners moved toward their neighbours. */
static void untangle(mesh *m, const char *after)
{
    long long before, left, moved = mesh_untangle(m, NULL, &before, &left);
    if (before > 0)
        printf("untangled: %lld pairs of faces crossed after %s; %lld corners moved toward their neighbours, %lld "
               "pairs left\n", before, after, moved, left);
}

static bool finish(job *j, mesh *m, double unit, float iso, bool field_scene, err_t *err)
{
    const mesh_desc *d = j->d;
    double worst, mean;
    /* one vertex a position, so an STL (no indices) or a reader that merges positions has the topology reported
     * here: coincident vertices merged, the faces that collapses (zero area on the --box's faces) dropped */
    long long merged = mesh_weld(m), r[3] = {0, 0, 0};
    mesh_topology top;
    if (merged) {
        repair(m, &top, r);
        printf("welded: %lld vertices at a position another held merged; %lld faces collapsed or back to back "
               "dropped, %lld vertices where sheets touched parted, %lld holes closed\n", merged, r[0], r[1], r[2]);
    }
    untangle(m, "the weld and repairs");
    describe(m, "mesh");
    if (field_scene && vertex_error(j, m, iso, unit, &worst, &mean, err))
        printf("error: vertices within %.3f voxels of the surface by the field (mean %.3f)\n", worst, mean);
    if (d->one_shell) {
        long long dropped = mesh_keep_largest(m);
        printf("one shell: %lld smaller piece%s dropped\n", dropped, dropped == 1 ? "" : "s");
    }
    if (d->triangles && d->triangles < m->nt) {
        if (!simplify(j, m, unit, iso, field_scene, err))
            return false;
        describe(m, "mesh");
        if (field_scene && vertex_error(j, m, iso, unit, &worst, &mean, err))
            printf("error: vertices within %.3f voxels of the surface by the field (mean %.3f)\n", worst, mean);
    }
    if (field_scene && !colour(j, m, err))
        return false;
    place(d, m);
    if (!mesh_io_write(m, d->output, err))
        return false;
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    printf("wrote %s: %zu triangles in %.2f s, peak memory %.0f MB (the process, GL driver included)\n", d->output,
           m->nt, util_now() - j->t0, (double)ru.ru_maxrss / 1024.0);
    return true;
}

bool mesh_job_scene(const mesh_desc *d, const scene *s, err_t *err)
{
    const char *exporter = NULL;
    if (!mesh_io_format(d->output, &exporter, err))
        return false;
    bool dem = s->terrain.heightmap[0] != '\0';
    if (dem && d->has_box) /* each option is one kind's: given to the other it would do nothing, silently */
        return err_set(err, "--box chooses the part of a distance-field scene to mesh; a DEM's solid is its whole grid "
                            "(cut the DEM first: gdal_translate -projwin)");
    if (!dem && d->base > 0)
        return err_set(err, "--base sets how far a DEM's solid reaches below its lowest point; '%s' is not a DEM scene "
                            "(its solid is the surface itself)", s->name);
    job j = {.d = d, .s = s, .t0 = util_now()};
    if (!dem && s->has_droplets &&
        !(droplets_read(s->droplets.file, s->droplets.scale, &j.drops, err) && droplets_build_grid(&j.drops, err))) {
        droplets_free(&j.drops);
        return false;
    }
    mesh m = {0};
    double unit = 0;
    float iso = 0;
    bool ok = dem ? mesh_terrain(&j, &m, &unit, err) && finish(&j, &m, unit, 0, false, err)
                                              : mesh_field(&j, &m, &unit, &iso, err) && finish(&j, &m, unit, iso, true, err);
    mesh_free(&m);
    free(j.out);
    droplets_free(&j.drops);
    return ok;
}

bool mesh_job_run(const mesh_desc *d, err_t *err)
{
    const char *exporter = NULL;
    if (!mesh_io_format(d->output, &exporter, err))
        return false;
    scene s;
    if (!scene_load(d->scene, d->sets, d->set_count, &s, err))
        return false;
    bool ok = true;
    if (s.terrain.heightmap[0]) { /* a DEM solid: no GL */
        ok = mesh_job_scene(d, &s, err);
    } else if ((ok = gpu_open(&(gpu_desc){.headless = true}, err))) {
        ok = render_init(err) && render_set_scene(&s, NULL, err) && mesh_job_scene(d, &s, err);
        render_shutdown();
        gpu_close();
    }
    scene_free(&s);
    return ok;
}
