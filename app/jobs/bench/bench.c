/* bench — what accuracy costs in time (bench.h): the run, its references and its measured rows; the sweeps are bench_sweeps.c's, the files bench_report.c's and bench_plot.c's, --frame-times bench_frames.c's. */
#include "jobs/bench/bench.h"
#include "jobs/bench/bench_load.h"
#include "data/droplets/droplets.h"

#include <assert.h>
#include <errno.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "view/aov.h"
#include "cli/cli.h"
#include "jobs/bench/bench_plot.h"
#include "jobs/bench/bench_report.h"
#include "jobs/bench/bench_sweeps.h"
#include "gpu/gpu.h"
#include "data/media/image_io.h"
#include "jobs/bench/metrics.h"
#include "gpu/render.h"
#include "scene/scene.h"

/* Image sizes: the default run takes 3–5 minutes on 2 llvmpipe cores (csg 4.3, himalaya 3.3, the
 * reference renders most of it), --quick one or two, --full about seven times the default. */
enum { DEFAULT_WIDTH = 240, DEFAULT_HEIGHT = 135, QUICK_WIDTH = 160, QUICK_HEIGHT = 90, FULL_WIDTH = 640,
       FULL_HEIGHT = 360, VIEWS = 2, REF_SPP = 64, STRICT_SPP = 128, LONG_SPP = 64, PATH_REF_SPP = 256,
       PATH_STRICT_SPP = 512, MAX_ROWS = 512 };
static const float VIEW_TURN_DEG = 40.0f;
#define REF_REFINE "quality.refine=64" /* the knob's maximum: regula falsi to float resolution */

typedef struct ref_view {
    camera cam;
    uint8_t *srgb;
    float *aov;
} ref_view;

static struct {
    const bench_desc *opt;
    int w, h;
    ref_view views[VIEWS];
    bench_row rows[MAX_ROWS];
    int nrows;
    int total, done;
    double t0;
} B;

static void progress(const char *what)
{
    if (B.opt->quiet)
        return;
    int bar = 30, fill = B.total ? B.done * bar / B.total : 0;
    fprintf(stderr, "\rbench %s [", B.opt->scene);
    for (int i = 0; i < bar; i++)
        fputc(i < fill ? '#' : '-', stderr);
    fprintf(stderr, "] %d/%d  %.0f s  %-28.28s", B.done, B.total, util_now() - B.t0, what);
    fflush(stderr);
}

/* Which rows get a difference image: the presets, and the model's approximations against the truth. */
static bool wants_difference(const char *knob)
{
    return B.opt->out && (!strcmp(knob, "preset") || (B.opt->path_truth && bench_approximation_of(knob)));
}

static void read_back(int w, int h, uint8_t **srgb, float **aov)
{
    *srgb = util_alloc((size_t)w * (size_t)h * 4, "a bench image");
    *aov = util_alloc(sizeof(float) * (size_t)w * (size_t)h * AOV_FLOATS, "a bench image");
    render_read_srgb8(*srgb, 1.0f);
    render_read_aovs(*aov);
}

/* Times and measures one setting over every view. scale < 1 renders smaller and upscales. */
static bool measure(const char *knob_name, const char *value, const char *const *sets, int nsets, double scale,
                    bench_row *out, err_t *err)
{
    scene s;
    if (!bench_load(B.opt, sets, nsets, &s, err))
        return false;
    if (!render_set_scene(&s, NULL, err)) {
        scene_free(&s);
        return false;
    }
    int w = (int)lround(B.w * scale), h = (int)lround(B.h * scale);
    w = w < 1 ? 1 : w;
    h = h < 1 ? 1 : h;
    *out = (bench_row){0};
    snprintf(out->knob, sizeof out->knob, "%s", knob_name);
    snprintf(out->value, sizeof out->value, "%s", value);
    /* an image of LONG_SPP samples or more is long enough to time once, and needs no warm-up */
    int runs = s.quality.spp >= LONG_SPP ? 1 : B.opt->runs;
    double *ms = util_alloc(sizeof *ms * (size_t)B.opt->runs, "bench timings");
    for (int v = 0; v < VIEWS; v++) {
        if (s.quality.spp < LONG_SPP)
            bench_image_ms(&s, &B.views[v].cam, w, h); /* warm-up: compiles and caches (with --runs 1 too) */
        for (int r = 0; r < runs; r++)
            ms[r] = bench_image_ms(&s, &B.views[v].cam, w, h);
        double lo, hi;
        out->ms += metrics_median_interval(ms, runs, &lo, &hi) / VIEWS;
        out->ms_lo += lo / VIEWS; /* the views' intervals, averaged as their medians are */
        out->ms_hi += hi / VIEWS;
        uint8_t *srgb;
        float *aov;
        read_back(w, h, &srgb, &aov);
        double t0 = camera_footprint_t0(&B.views[v].cam);
        image_view test = {w, h, srgb, aov, t0}, ref = {B.w, B.h, B.views[v].srgb, B.views[v].aov, t0};
        if (w != B.w || h != B.h) {
            uint8_t *up;
            float *up_aov;
            metrics_upscale(&test, B.w, B.h, &up, &up_aov);
            free(srgb);
            free(aov);
            srgb = up;
            aov = up_aov;
            test = (image_view){B.w, B.h, srgb, aov, t0};
        }
        metrics m = metrics_compare(&test, &ref, camera_pixel_angle(&B.views[v].cam, B.h));
        if (v == 0 && wants_difference(knob_name))
            bench_write_difference(B.opt, B.w, B.h, knob_name, value, srgb, B.views[v].srgb, out->diff, sizeof out->diff);
        if (scale != 1.0) /* steps were counted at the smaller size: per output pixel they are fewer */
            m.mean_steps *= scale * scale;
        out->m.rmse += m.rmse * m.rmse / VIEWS; /* mean square, rooted below */
        out->m.edge_rmse += m.edge_rmse * m.edge_rmse / VIEWS;
        out->m.edge_pixels += m.edge_pixels;
        out->m.depth_mean_fp += m.depth_mean_fp / VIEWS;
        out->m.depth_max_fp = fmax(out->m.depth_max_fp, m.depth_max_fp);
        out->m.flip_share += m.flip_share / VIEWS;
        out->m.mean_steps += m.mean_steps / VIEWS;
        out->m.iou = v == 0 ? m.iou : fmin(out->m.iou, m.iou); /* silhouettes: the worst view */
        out->m.edge_max_px = fmax(out->m.edge_max_px, m.edge_max_px);
        out->m.exhausted_share += m.exhausted_share / VIEWS;
        free(srgb);
        free(aov);
    }
    out->m.rmse = sqrt(out->m.rmse);
    out->m.edge_rmse = sqrt(out->m.edge_rmse);
    out->m.psnr_db = out->m.rmse > 0 ? 20 * log10(1 / out->m.rmse) : INFINITY;
    free(ms);
    scene_free(&s);
    B.done++;
    progress(knob_name);
    return true;
}

static bool make_references(const scene *base, metrics *convergence, double *ref_ms, err_t *err)
{
    char spp[32];
    snprintf(spp, sizeof spp, "quality.spp=%d", B.opt->path_truth ? PATH_REF_SPP : REF_SPP);
    /* The reference must not share the bias of what it judges: hits located at float resolution
     * (refine at its maximum, where the program refines), a long step budget, many samples. With
     * --truth path it is the path tracer, with a tight hit threshold (a secondary ray's threshold
     * grows with its path: hit_k 1 grew a lamp's light 10 %, test_pathtrace) and deep paths. */
    const char *ref_sets[] = {"quality.preset=reference", spp, "quality.max_steps=4096", REF_REFINE,
                              "quality.integrator=1", "quality.hit_k=0.0625", "quality.bounces=16"};
    scene ref;
    if (!bench_load(B.opt, ref_sets, B.opt->path_truth ? 7 : 4, &ref, err) || !render_set_scene(&ref, NULL, err))
        return false;
    camera start = scene_camera(base, base->cam_position, base->cam_look_at, base->cam_fov_deg);
    for (int v = 0; v < VIEWS; v++) {
        /* turn the camera about the vertical through the look-at point */
        double a = glm_rad((float)v * VIEW_TURN_DEG), ca = cos(a), sa = sin(a);
        double d[3], pos[3];
        for (int k = 0; k < 3; k++)
            d[k] = base->cam_position[k] - base->cam_look_at[k];
        pos[0] = base->cam_look_at[0] + ca * d[0] + sa * d[2];
        pos[1] = base->cam_position[1];
        pos[2] = base->cam_look_at[2] - sa * d[0] + ca * d[2];
        B.views[v].cam = v == 0 ? start : scene_camera(base, pos, base->cam_look_at, base->cam_fov_deg);
        double ms = bench_image_ms(&ref, &B.views[v].cam, B.w, B.h);
        if (v == 0)
            *ref_ms = ms;
        read_back(B.w, B.h, &B.views[v].srgb, &B.views[v].aov);
        if (v == 0 && B.opt->out) { /* what the difference images are against */
            char path[PATH_MAX_LEN], prefix[BENCH_PREFIX_MAX];
            bench_prefix(B.opt, prefix, sizeof prefix);
            snprintf(path, sizeof path, "%s/%s-reference.png", B.opt->out, prefix);
            if (!image_write_u8(path, B.w, B.h, 4, B.views[v].srgb, err))
                return false;
        }
        B.done++;
        progress("reference");
    }
    scene_free(&ref);
    /* Has the reference converged? Compare it with a render four times stricter in threshold and
     * twice in samples, steps and bounces: its error must be far below what the knobs show. */
    char strict_spp[32];
    snprintf(strict_spp, sizeof strict_spp, "quality.spp=%d", B.opt->path_truth ? PATH_STRICT_SPP : STRICT_SPP);
    /* (AO samples stay: the AO estimate is a different function of its sample count, not a converging sum) */
    const char *strict_sets[] = {"quality.preset=reference", strict_spp, REF_REFINE, "quality.hit_k=0.0625",
                                 "quality.max_steps=8192", "quality.shadow_steps=512", "quality.bounces=16",
                                 "quality.integrator=1", "quality.hit_k=0.03125", "quality.bounces=32"};
    scene strict;
    if (!bench_load(B.opt, strict_sets, B.opt->path_truth ? 10 : 7, &strict, err) || !render_set_scene(&strict, NULL, err))
        return false;
    bench_image_ms(&strict, &B.views[0].cam, B.w, B.h);
    uint8_t *srgb;
    float *aov;
    read_back(B.w, B.h, &srgb, &aov);
    double t0 = camera_footprint_t0(&B.views[0].cam);
    image_view a = {B.w, B.h, B.views[0].srgb, B.views[0].aov, t0}, b = {B.w, B.h, srgb, aov, t0};
    *convergence = metrics_compare(&a, &b, camera_pixel_angle(&B.views[0].cam, B.h));
    free(srgb);
    free(aov);
    scene_free(&strict);
    B.done++;
    progress("convergence check");
    return true;
}

/* ---- effects ------------------------------------------------------------------------------------ */

/* One effect compiled out, compiled in, and compiled in but switched off at run time: the three are
 * timed in turn, run after run (out, in, in-off, out, …), so drift in a shared machine's speed falls
 * on all three alike; each gets its median and interval. */
static bool effect_times(effect e, effect_row *row, err_t *err)
{
    char off[64], on[64];
    snprintf(off, sizeof off, "effects.%s=off", effect_name(e));
    snprintf(on, sizeof on, "effects.%s=on", effect_name(e));
    scene s[2];
    if (!bench_load(B.opt, (const char *const[]){off, "quality.spp=1"}, 2, &s[0], err))
        return false;
    if (!bench_load(B.opt, (const char *const[]){on, "quality.spp=1"}, 2, &s[1], err)) {
        scene_free(&s[0]);
        return false;
    }
    int runs = B.opt->runs;
    double *ms = util_alloc(sizeof *ms * 3 * (size_t)runs, "bench timings");
    bool ok = true;
    for (int r = -1; ok && r < runs; r++) /* r = -1: the warm-up of each */
        for (int k = 0; ok && k < 3; k++) {
            ok = render_set_scene(&s[k > 0], NULL, err);
            render_set_runtime_effects(k == 2 ? ~(1u << e) : ~0u);
            double t = ok ? bench_image_ms(&s[k > 0], &B.views[0].cam, B.w, B.h) : 0;
            if (r >= 0)
                ms[k * runs + r] = t;
        }
    render_set_runtime_effects(~0u);
    if (ok) {
        row->out_ms = metrics_median_interval(ms, runs, &row->out_lo, &row->out_hi);
        row->in_ms = metrics_median_interval(ms + runs, runs, &row->in_lo, &row->in_hi);
        row->in_off_ms = metrics_median_interval(ms + 2 * runs, runs, &row->in_off_lo, &row->in_off_hi);
    }
    free(ms);
    scene_free(&s[0]);
    scene_free(&s[1]);
    return ok;
}

static bool measure_effects(const scene *base, effect_row *rows, err_t *err)
{
    for (int e = 0; e < EFFECT_COUNT; e++) {
        rows[e] = (effect_row){.e = (effect)e, .in_scene = base->effects & (1u << e)};
        if (!effect_times((effect)e, &rows[e], err))
            return false;
        B.done++;
        progress(effect_name((effect)e));
    }
    return true;
}

/* ---- the run ------------------------------------------------------------------------------------ */

/* Marks the Pareto front among the rows measured so far. */
static void mark_front(void)
{
    double lo[MAX_ROWS], hi[MAX_ROWS], e[MAX_ROWS];
    bool front[MAX_ROWS];
    for (int i = 0; i < B.nrows; i++)
        lo[i] = B.rows[i].ms_lo, hi[i] = B.rows[i].ms_hi, e[i] = B.rows[i].m.rmse;
    metrics_pareto(lo, hi, e, B.nrows, front);
    for (int i = 0; i < B.nrows; i++)
        B.rows[i].front = front[i];
}

/* A row is measured: with --out, the knob CSV so far goes to disk (a stopped run keeps it). */
static bool row_done(err_t *err)
{
    B.nrows++;
    if (!B.opt->out)
        return true;
    mark_front();
    bench_results res = {.opt = B.opt, .w = B.w, .h = B.h, .views = VIEWS, .rows = B.rows, .nrows = B.nrows};
    return bench_write_rows(&res, err);
}

/* One value of sweep k as the override it sets (into set; *n is 0 or 1) and the render scale */
static bool sweep_setting(const bench_sweep *k, const char *v, char *set, size_t size, int *n, double *scale, err_t *err)
{
    *n = 0, *scale = 1.0;
    if (!k->own) {
        if (snprintf(set, size, "%s=%s", k->key, v) >= (int)size)
            return err_set(err, "bad --knob %s value '%.40s...': too long", k->name, v);
        *n = 1;
        return true;
    }
    char *end;
    *scale = strtod(v, &end);
    if (*end || !(*scale > 0 && *scale <= 1))
        return err_set(err, "bad --knob resolution_scale value '%s': expected a number in (0, 1]", v);
    return true;
}

/* Each value of sweep k: with render, measured as a row; else only checked (its override loads, and
 * *rows, counted up, stays within MAX_ROWS), so a bad value is refused before the first image. */
static bool each_value(const bench_sweep *k, const char *values, bool render, int *rows, err_t *err)
{
    if (strlen(values) >= 512)
        return err_set(err, "--knob %s: the values are longer than 511 characters", k->name);
    char list[512];
    snprintf(list, sizeof list, "%s", values);
    char *save = NULL;
    for (char *v = strtok_r(list, ",", &save); v; v = strtok_r(NULL, ",", &save)) {
        char set[128];
        const char *sets[1] = {set};
        int n;
        double scale;
        scene s;
        if (!render && ++*rows > MAX_ROWS)
            return err_set(err, "too many bench settings (at most %d): sweep fewer values", MAX_ROWS);
        if (!sweep_setting(k, v, set, sizeof set, &n, &scale, err))
            return false;
        if (render && (!measure(k->name, v, sets, n, scale, &B.rows[B.nrows], err) || !row_done(err)))
            return false;
        if (!render && n && !bench_load(B.opt, sets, n, &s, err))
            return false;
        if (!render && n)
            scene_free(&s);
    }
    return true;
}

/* Every value of every sweep, checked before the first image: a bad one is refused at once, not after
 * minutes of rendering the others. The rows must fit too. */
static bool check_sweeps(const bench_sweep *sweeps, const char *const *values, int nsweeps, err_t *err)
{
    int rows = PRESET_COUNT;
    for (int k = 0; k < nsweeps; k++)
        if (values[k] && !each_value(&sweeps[k], values[k], false, &rows, err))
            return false;
    return true;
}

/* Which sweeps run, with which values: --knob NAME=… picks (only those), else every one that applies. */
static bool pick_sweeps(const scene *base, bench_sweep *sweeps, const char **values, int *n, err_t *err)
{
    bool applies[BENCH_MAX_SWEEPS];
    *n = bench_list_sweeps(base, sweeps, applies);
    static char chosen[BENCH_MAX_SWEEPS][256];
    for (int k = 0; k < *n && !B.opt->knob_count; k++) {
        char keep[64];
        bench_base_value(base, sweeps[k].name, keep, sizeof keep);
        values[k] = !applies[k] ? NULL
                                : bench_sweep_values(sweeps[k].values, keep, B.opt->quick, chosen[k], sizeof chosen[k]);
    }
    for (int i = 0; i < B.opt->knob_count; i++) {
        const char *arg = B.opt->knobs[i], *eq = strchr(arg, '=');
        bool found = false;
        for (int k = 0; k < *n; k++)
            if ((size_t)(eq - arg) == strlen(sweeps[k].name) && !strncmp(arg, sweeps[k].name, (size_t)(eq - arg))) {
                values[k] = eq + 1;
                found = true;
            }
        if (!found) {
            strbuf known = {0};
            for (int k = 0; k < *n; k++)
                sb_printf(&known, "%s%s", k ? ", " : "", sweeps[k].name);
            err_set(err, "unknown --knob '%.*s' for scene %s (known here: %s)", (int)(eq - arg), arg, base->name,
                    known.data);
            sb_free(&known);
            return false;
        }
    }
    return true;
}

/* --out: a folder made when it does not exist (its parent must); *created says whether it was */
static bool make_out(const char *out, bool *created, err_t *err)
{
    struct stat st;
    if (!out)
        return true;
    if (stat(out, &st) != 0) {
        if (mkdir(out, 0777) != 0)
            return err_set(err, "--out '%s': cannot make the folder (%s): does its parent exist?", out,
                           strerror(errno));
        *created = true;
    } else if (!S_ISDIR(st.st_mode)) {
        return err_set(err, "--out '%s' is not a folder: name a folder for the results", out);
    }
    return true;
}

bool bench_run(const bench_desc *desc, err_t *err)
{
    bench_desc d = *desc; /* its zero fields: the defaults */
    d.runs = d.runs ? d.runs : d.quick ? 3 : d.full ? 9 : 5;
    const bench_desc *opt = &d;
    memset(&B, 0, sizeof B);
    B.opt = opt;
    B.w = opt->width ? opt->width : opt->quick ? QUICK_WIDTH : opt->full ? FULL_WIDTH : DEFAULT_WIDTH;
    B.h = opt->height ? opt->height : opt->quick ? QUICK_HEIGHT : opt->full ? FULL_HEIGHT : DEFAULT_HEIGHT;
    if (opt->frame_times)
        return bench_frame_times(opt, B.w, B.h, err);
    if (opt->final_frame)
        return bench_final_frame(opt, opt->width ? opt->width : 1920, opt->height ? opt->height : 1080, err);
    if (opt->viewshed)
        return bench_viewshed(opt, err);
    if (opt->terrain_stream)
        return bench_terrain_stream(opt, opt->width ? opt->width : 640, opt->height ? opt->height : 360, err);
    if (opt->terrain_scale)
        return bench_terrain_scale(opt, opt->width ? opt->width : 640, opt->height ? opt->height : 360, err);
    if (opt->interactive)
        return bench_interactive(opt, opt->width ? opt->width : GPU_DEFAULT_WIDTH,
                                 opt->height ? opt->height : GPU_DEFAULT_HEIGHT, err);
    scene base;
    if (!bench_load(B.opt, NULL, 0, &base, err))
        return false;
    bench_sweep sweeps[BENCH_MAX_SWEEPS];
    const char *values[BENCH_MAX_SWEEPS] = {0};
    int nsweeps;
    bool created = false;
    if (!pick_sweeps(&base, sweeps, values, &nsweeps, err) || !check_sweeps(sweeps, values, nsweeps, err) ||
        !make_out(opt->out, &created, err)) {
        scene_free(&base);
        return false;
    }
    B.total = VIEWS + 1 + PRESET_COUNT + EFFECT_COUNT;
    for (int k = 0; k < nsweeps; k++)
        if (values[k])
            B.total += bench_count_values(values[k]);
    if (!gpu_open(&(gpu_desc){.headless = true}, err)) {
        scene_free(&base);
        return false;
    }
    B.t0 = util_now();
    metrics conv;
    double ref_ms = 0;
    effect_row fx[EFFECT_COUNT];
    bool ok = render_init(err) && make_references(&base, &conv, &ref_ms, err);
    for (int k = 0; ok && k < nsweeps; k++)
        if (values[k])
            ok = each_value(&sweeps[k], values[k], true, NULL, err);
    for (int p = 0; ok && p < PRESET_COUNT; p++) {
        char set[64];
        snprintf(set, sizeof set, "quality.preset=%s", preset_name((quality_preset)p));
        const char *sets[] = {set};
        ok = measure("preset", preset_name((quality_preset)p), sets, 1, 1.0, &B.rows[B.nrows], err) && row_done(err);
    }
    ok = ok && measure_effects(&base, fx, err);
    if (!opt->quiet)
        fputc('\n', stderr);
    if (ok) {
        mark_front();
        bench_results res = {.opt = opt, .base = &base, .w = B.w, .h = B.h, .views = VIEWS,
                             .ref_spp = opt->path_truth ? PATH_REF_SPP : REF_SPP,
                             .view_turn_deg = VIEW_TURN_DEG, .rows = B.rows, .nrows = B.nrows, .fx = fx,
                             .conv = &conv, .ref_ms = ref_ms};
        bench_print(&res);
        if (opt->out)
            ok = bench_write_csv(&res, err) && bench_plot_write(&res, err) && bench_write_pages(&res, err);
    }
    for (int v = 0; v < VIEWS; v++) {
        free(B.views[v].srgb);
        free(B.views[v].aov);
    }
    scene_free(&base);
    render_shutdown();
    gpu_close();
    if (!ok && created)
        util_remove_folder(opt->out);
    return ok;
}
