#include "jobs/bench.h"
#include "data/droplets.h"

#include <assert.h>
#include <errno.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "gpu/aov.h"
#include "jobs/bench_report.h"
#include "gpu/gpu.h"
#include "data/image_io.h"
#include "jobs/metrics.h"
#include "gpu/render.h"
#include "scene/scene.h"

/* Image sizes: the default run takes 3–5 minutes on 2 llvmpipe cores (csg 4.3, himalaya 3.3, the
 * reference renders most of it), --quick one or two, --full about seven times the default. */
enum { DEFAULT_WIDTH = 240, DEFAULT_HEIGHT = 135, QUICK_WIDTH = 160, QUICK_HEIGHT = 90, FULL_WIDTH = 640,
       FULL_HEIGHT = 360, VIEWS = 2, REF_SPP = 64, STRICT_SPP = 128, LONG_SPP = 64, PATH_REF_SPP = 256,
       PATH_STRICT_SPP = 512, MAX_ROWS = 512 };
static const float VIEW_TURN_DEG = 40.0f;
#define REF_REFINE "quality.refine=64" /* the knob's maximum: regula falsi to float resolution */

/* A sweep: a knob's --set key (NULL: the bench's own resolution_scale) and its values. Built at run
 * time from QUALITY_KNOBS, the program's row of PROGRAM_LIST, and resolution_scale. */
typedef struct sweep {
    char name[32], key[64], values[256];
    bool own; /* resolution_scale: rendered smaller and upscaled, no --set */
} sweep;
enum { MAX_SWEEPS = KNOB_COUNT + 8 };

/* A fractal's iterations from a third of its default to a third past it (within the range its formula
 * declares, formula.h), the default among them: where detail stops paying for its time. */
static void fractal_iterations_sweep(const formula *f, sweep *out)
{
    enum { POINTS = 5 };
    *out = (sweep){.name = "iterations", .key = "fractal.iterations"};
    int lo = f->iterations / 3 > f->iterations_lo ? f->iterations / 3 : f->iterations_lo;
    int hi = f->iterations + f->iterations / 3 < f->iterations_hi ? f->iterations + f->iterations / 3 : f->iterations_hi;
    int last = 0;
    bool def_done = false;
    for (int i = 0; i < POINTS; i++) {
        int v = lo + (int)lround((double)(hi - lo) * i / (POINTS - 1));
        for (int pass = 0; pass < 2; pass++) { /* the default in its place */
            int w = pass == 0 && !def_done && f->iterations <= v ? f->iterations : v;
            def_done |= w == f->iterations;
            if (w > last) {
                size_t len = strlen(out->values);
                snprintf(out->values + len, sizeof out->values - len, "%s%d", len ? "," : "", w);
                last = w;
            }
        }
    }
}

/* Every sweep the bench knows for scene s; `applies` says which run by default. */
static int list_sweeps(const scene *s, sweep *out, bool *applies)
{
    int n = 0;
    for (int k = 0; k < KNOB_COUNT; k++) {
        const knob_def *d = knob_get_def((knob_id)k);
        if (!d->sweep)
            continue;
        out[n] = (sweep){0};
        snprintf(out[n].name, sizeof out[n].name, "%s", d->name);
        snprintf(out[n].key, sizeof out[n].key, "quality.%s", d->name);
        snprintf(out[n].values, sizeof out[n].values, "%s", d->sweep);
        applies[n++] = scene_knob_applies(s, (knob_id)k);
    }
    /* the program's own: "key=v1,v2;key2=…", named by the key's last part */
    const char *own = program_get(s->program)->bench;
    for (const char *p = own; p && *p && n < MAX_SWEEPS - 1;) {
        size_t len = strcspn(p, ";"), eq = strcspn(p, "=");
        assert(eq < len);
        out[n] = (sweep){0};
        snprintf(out[n].key, sizeof out[n].key, "%.*s", (int)eq, p);
        const char *dot = strrchr(out[n].key, '.');
        snprintf(out[n].name, sizeof out[n].name, "%s", dot ? dot + 1 : out[n].key);
        snprintf(out[n].values, sizeof out[n].values, "%.*s", (int)(len - eq - 1), p + eq + 1);
        applies[n++] = true;
        p += len + (p[len] == ';');
    }
    if (program_is_fractal(s->program) && n < MAX_SWEEPS - 1)
        fractal_iterations_sweep(&s->fractal.formula, &out[n]), applies[n++] = true;
    /* the model's approximations of light transport that are effects (fx_NAME), off and on (each
     * priced against the path tracer by bench --truth path): only those the scene uses */
    static const bench_approximation MODEL[] = {
#define X(knob, off, on, what) {knob, off, on, what},
        BENCH_APPROXIMATIONS(X)
#undef X
    };
    for (size_t i = 0; i < sizeof MODEL / sizeof MODEL[0] && n < MAX_SWEEPS - 1; i++) {
        effect e;
        if (strncmp(MODEL[i].knob, "fx_", 3) || !effect_from_name(MODEL[i].knob + 3, &e))
            continue; /* a quality knob: swept with the others */
        out[n] = (sweep){0};
        snprintf(out[n].name, sizeof out[n].name, "%s", MODEL[i].knob);
        snprintf(out[n].key, sizeof out[n].key, "effects.%s", effect_name(e));
        snprintf(out[n].values, sizeof out[n].values, "%s,%s", MODEL[i].off, MODEL[i].on);
        applies[n++] = (s->effects & (1u << e)) != 0;
    }
    out[n] = (sweep){.name = "resolution_scale", .values = "0.25,0.5,0.75,1", .own = true};
    applies[n++] = true;
    return n;
}

typedef struct ref_view {
    camera cam;
    uint8_t *srgb;
    float *aov;
} ref_view;

static struct {
    const cli_options *opt;
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

/* The scene with the command line's --set, then `extra` more. */
static bool load(const char *const *extra, int n_extra, scene *s, err_t *err)
{
    const char *sets[2 * CLI_MAX_SETS];
    int n = 0;
    for (int i = 0; i < B.opt->set_count; i++)
        sets[n++] = B.opt->sets[i];
    for (int i = 0; i < n_extra && n < 2 * CLI_MAX_SETS; i++)
        sets[n++] = extra[i];
    return scene_load(B.opt->scene, sets, n, s, err);
}

/* Renders all of s's samples from cam at w × h; returns the image time (ms). */
static double image(const scene *s, const camera *cam, int w, int h)
{
    render_resize(w, h);
    render_begin(cam);
    glFinish();
    double t0 = util_now();
    for (int i = 0; i < s->quality.spp; i++)
        render_sample();
    glFinish();
    return (util_now() - t0) * 1000.0;
}

/* A difference image's colour for an error e of full scale (0–1 of the 8-bit display): black at 0,
 * through purple, red and orange to yellow at BENCH_DIFF_YELLOW and white past it; a ramp that darkens
 * nowhere, so more error is always brighter. */
static void diff_colour(double e, uint8_t out[3])
{
    static const double STOPS[][3] = {{0, 0, 0}, {0.35, 0.05, 0.45}, {0.85, 0.15, 0.2}, {1, 0.55, 0}, {1, 0.95, 0.3},
                                      {1, 1, 1}};
    enum { N = sizeof STOPS / sizeof STOPS[0] };
    double x = e / BENCH_DIFF_YELLOW * (N - 2);
    x = x < 0 ? 0 : x > N - 1 ? N - 1 : x;
    int i = (int)x < N - 1 ? (int)x : N - 2;
    double f = x - i;
    for (int c = 0; c < 3; c++)
        out[c] = (uint8_t)lround(255 * (STOPS[i][c] + f * (STOPS[i + 1][c] - STOPS[i][c])));
}

/* With --out, where a setting's image differs from the reference (view 1): OUT/PREFIX-diff-KNOB-VALUE.png,
 * the largest channel's difference per pixel; its file name into name (empty when not written). */
static void write_difference(const char *knob, const char *value, const uint8_t *test, const uint8_t *ref, char *name,
                             size_t n)
{
    char prefix[BENCH_PREFIX_MAX], k[sizeof ((bench_row *)0)->knob], v[sizeof ((bench_row *)0)->value];
    char path[PATH_MAX_LEN];
    bench_prefix(B.opt, prefix, sizeof prefix);
    bench_safe_name(knob, k, sizeof k), bench_safe_name(value, v, sizeof v); /* "../x" is a file name here */
    snprintf(name, n, "%s-diff-%s-%s.png", prefix, k, v);
    snprintf(path, sizeof path, "%s/%s", B.opt->out, name);
    size_t px = (size_t)B.w * (size_t)B.h;
    uint8_t *img = util_alloc(px * 3, "a difference image");
    for (size_t i = 0; i < px; i++) {
        int e = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)test[i * 4 + (size_t)c] - (int)ref[i * 4 + (size_t)c]);
            e = d > e ? d : e;
        }
        diff_colour(e / 255.0, img + i * 3);
    }
    err_t err;
    if (!image_write_u8(path, B.w, B.h, 3, img, &err)) {
        fprintf(stderr, "\nfathom bench: %s (the report goes on without it)\n", err.msg);
        name[0] = 0;
    }
    free(img);
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
    if (!load(sets, nsets, &s, err))
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
            image(&s, &B.views[v].cam, w, h); /* warm-up: compiles and caches (with --runs 1 too) */
        for (int r = 0; r < runs; r++)
            ms[r] = image(&s, &B.views[v].cam, w, h);
        double lo, hi;
        out->ms += metrics_median_interval(ms, runs, &lo, &hi) / VIEWS;
        out->ms_lo += lo / VIEWS; /* the views' intervals, averaged as their medians are */
        out->ms_hi += hi / VIEWS;
        uint8_t *srgb;
        float *aov;
        read_back(w, h, &srgb, &aov);
        image_view test = {w, h, srgb, aov}, ref = {B.w, B.h, B.views[v].srgb, B.views[v].aov};
        if (w != B.w || h != B.h) {
            uint8_t *up;
            float *up_aov;
            metrics_upscale(&test, B.w, B.h, &up, &up_aov);
            free(srgb);
            free(aov);
            srgb = up;
            aov = up_aov;
            test = (image_view){B.w, B.h, srgb, aov};
        }
        metrics m = metrics_compare(&test, &ref, camera_pixel_angle(&B.views[v].cam, B.h));
        if (v == 0 && wants_difference(knob_name))
            write_difference(knob_name, value, srgb, B.views[v].srgb, out->diff, sizeof out->diff);
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
    if (!load(ref_sets, B.opt->path_truth ? 7 : 4, &ref, err) || !render_set_scene(&ref, NULL, err))
        return false;
    camera start = camera_look_at_deg(base->cam_position, base->cam_look_at, base->cam_fov_deg);
    for (int v = 0; v < VIEWS; v++) {
        /* turn the camera about the vertical through the look-at point */
        double a = glm_rad((float)v * VIEW_TURN_DEG), ca = cos(a), sa = sin(a);
        double d[3], pos[3];
        for (int k = 0; k < 3; k++)
            d[k] = base->cam_position[k] - base->cam_look_at[k];
        pos[0] = base->cam_look_at[0] + ca * d[0] + sa * d[2];
        pos[1] = base->cam_position[1];
        pos[2] = base->cam_look_at[2] - sa * d[0] + ca * d[2];
        B.views[v].cam = v == 0 ? start : camera_look_at(pos, base->cam_look_at, start.fov_y);
        double ms = image(&ref, &B.views[v].cam, B.w, B.h);
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
    if (!load(strict_sets, B.opt->path_truth ? 10 : 7, &strict, err) || !render_set_scene(&strict, NULL, err))
        return false;
    image(&strict, &B.views[0].cam, B.w, B.h);
    uint8_t *srgb;
    float *aov;
    read_back(B.w, B.h, &srgb, &aov);
    image_view a = {B.w, B.h, B.views[0].srgb, B.views[0].aov}, b = {B.w, B.h, srgb, aov};
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
    if (!load((const char *const[]){off, "quality.spp=1"}, 2, &s[0], err))
        return false;
    if (!load((const char *const[]){on, "quality.spp=1"}, 2, &s[1], err)) {
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
            double t = ok ? image(&s[k > 0], &B.views[0].cam, B.w, B.h) : 0;
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
static bool sweep_setting(const sweep *k, const char *v, char *set, size_t size, int *n, double *scale, err_t *err)
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
static bool each_value(const sweep *k, const char *values, bool render, int *rows, err_t *err)
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
        if (!render && n && !load(sets, n, &s, err))
            return false;
        if (!render && n)
            scene_free(&s);
    }
    return true;
}

/* Every value of every sweep, checked before the first image: a bad one is refused at once, not after
 * minutes of rendering the others. The rows must fit too. */
static bool check_sweeps(const sweep *sweeps, const char *const *values, int nsweeps, err_t *err)
{
    int rows = PRESET_COUNT;
    for (int k = 0; k < nsweeps; k++)
        if (values[k] && !each_value(&sweeps[k], values[k], false, &rows, err))
            return false;
    return true;
}

/* A default sweep's values with the scene's own value among them, so each panel rings its operating
 * point: v as it is where it holds keep (or keep is ""), else keep put where it falls in v's order
 * (appended where v is not numbers in order). With quick, three of them: the first, keep (or the
 * middle) and the last. Into out. */
static const char *sweep_values(const char *v, const char *keep, bool quick, char *out, size_t n)
{
    char list[512];
    snprintf(list, sizeof list, "%s", v);
    const char *vals[65];
    int k = 0, at = -1;
    char *save = NULL;
    for (char *t = strtok_r(list, ",", &save); t && k < 64; t = strtok_r(NULL, ",", &save)) {
        if (*keep && bench_same_value(t, keep))
            at = k;
        vals[k++] = t;
    }
    if (*keep && at < 0) {
        char *e;
        double x = strtod(keep, &e);
        double dir = k > 1 ? strtod(vals[k - 1], NULL) - strtod(vals[0], NULL) : 1;
        at = k;
        for (int i = 0; !*e && i < k; i++) { /* before the first value it precedes, in v's direction */
            double a = strtod(vals[i], NULL);
            if ((dir >= 0 && x < a) || (dir < 0 && x > a)) {
                at = i;
                break;
            }
        }
        memmove(&vals[at + 1], &vals[at], sizeof vals[0] * (size_t)(k - at));
        vals[at] = keep;
        k++;
    }
    if (quick && k > 3) {
        int mid = at > 0 && at < k - 1 ? at : k / 2;
        snprintf(out, n, "%s,%s,%s", vals[0], vals[mid], vals[k - 1]);
        return out;
    }
    out[0] = '\0';
    for (int i = 0; i < k; i++) {
        size_t len = strlen(out);
        snprintf(out + len, n - len, "%s%s", i ? "," : "", vals[i]);
    }
    return out;
}

static int count_values(const char *v)
{
    int n = 1;
    for (; *v; v++)
        n += *v == ',';
    return n;
}

/* One preset's frame times on each backend, taken in turn (fragment, compute, fragment, ...) after a
 * warm-up of each, so both see the same machine load. */
static bool time_backends(const scene *s, const camera *cam, int nb, const render_backend *backends, double *ms,
                          int runs, err_t *err)
{
    for (int r = -1; r < runs; r++) /* r = -1: the warm-up (compiles) */
        for (int b = 0; b < nb; b++) {
            if (!render_switch_backend(backends[b], err) || !render_set_scene(s, NULL, err))
                return false;
            double t = image(s, cam, B.w, B.h);
            if (r >= 0)
                ms[b * runs + r] = t;
        }
    return true;
}

/* The wall time of one whole fathom process (this binary) with these arguments, its output to
 * /dev/null; negative when it could not run or failed. */
static double process_ms(char *const *argv)
{
    double t0 = util_now();
    pid_t pid = fork();
    if (pid == 0) {
        int null = open("/dev/null", O_WRONLY);
        if (null >= 0) {
            dup2(null, 1);
            dup2(null, 2);
        }
        execv("/proc/self/exe", argv);
        _exit(127);
    }
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return -1;
    return (util_now() - t0) * 1000.0;
}

/* Start-up as a user meets it: whole-process times of `fathom --version` and of a 64x36 shot of the
 * scene, taken in turn (the image and DEM libraries load only when a run needs them: data/lazy.h). */
static void startup_times(const cli_options *opt)
{
    char dir[] = "/tmp/fathom-bench-startup-XXXXXX", shot[sizeof dir + 16];
    if (!mkdtemp(dir))
        return;
    snprintf(shot, sizeof shot, "%s/shot.png", dir);
    char *version[] = {"fathom", "--version", NULL};
    char *image[] = {"fathom", "--scene", (char *)opt->scene, "--size", "64x36", "--quiet", "--output", shot, NULL};
    double *ms = util_alloc(sizeof *ms * 2 * (size_t)opt->runs, "bench timings");
    bool ok = process_ms(image) >= 0; /* a warm-up: the shader cache and the page cache */
    for (int r = 0; ok && r < opt->runs; r++) {
        ms[r] = process_ms(version);
        ms[opt->runs + r] = process_ms(image);
        ok = ms[r] >= 0 && ms[opt->runs + r] >= 0;
    }
    unlink(shot);
    rmdir(dir);
    double lo[2], hi[2], med[2];
    for (int k = 0; ok && k < 2; k++)
        med[k] = metrics_median_interval(ms + k * opt->runs, opt->runs, &lo[k], &hi[k]);
    if (ok)
        printf("start-up (whole process, median [95 %% interval] of %d): fathom --version %.0f ms [%.0f-%.0f], "
               "a 64x36 shot of %s %.0f ms [%.0f-%.0f]\n",
               opt->runs, med[0], lo[0], hi[0], opt->scene, med[1], lo[1], hi[1]);
    else
        printf("start-up: a whole fathom process failed to run\n");
    free(ms);
}

/* Each preset's frame time (one sample per pixel) at the start view: what the window costs, on both
 * backends side by side where the GL has compute shaders. */
static bool frame_times(const cli_options *opt, err_t *err)
{
    startup_times(opt);
    if (!gpu_open(&(gpu_desc){.headless = true}, err))
        return false;
    bool ok = render_init(err);
    render_backend backends[2] = {BACKEND_FRAGMENT, BACKEND_COMPUTE};
    int nb = render_has_compute() ? 2 : 1;
    printf("%s, %dx%d, %s: ms per frame (1 sample per pixel), median [95 %% interval] of %d, the backends "
           "taken in turn after a warm-up; auto takes %s\n",
           opt->scene, B.w, B.h, gpu_describe(), opt->runs, render_backend_name(render_backend_used()));
    printf("  %-12s %-24s %-24s %-22s %s\n", "preset", "fragment ms", nb > 1 ? "compute ms" : "(no compute)",
           "compute / fragment", "steps per pixel");
    for (int p = 0; ok && p < PRESET_COUNT; p++) {
        char set[64];
        snprintf(set, sizeof set, "quality.preset=%s", preset_name((quality_preset)p));
        const char *sets[] = {set, "quality.spp=1"};
        scene s;
        ok = load(sets, 2, &s, err) && render_set_scene(&s, NULL, err);
        if (!ok)
            break;
        double read_s, grid_s;
        const droplets *d = render_droplets(&read_s, &grid_s);
        if (d && p == 0 && d->nodes)
            printf("  droplets     %d: read %.3f s, bvh %.3f s (%d nodes, %zu listings, %.1f MB)\n", d->count, read_s,
                   grid_s, d->node_count, d->refs, (double)droplets_bytes(d) / 1e6);
        else if (d && p == 0)
            printf("  droplets     %d: read %.3f s, grid %.3f s (%dx%dx%d cells, %zu listings, %.1f MB)\n", d->count,
                   read_s, grid_s, d->dims[0], d->dims[1], d->dims[2], d->refs, (double)droplets_bytes(d) / 1e6);
        camera cam = camera_look_at_deg(s.cam_position, s.cam_look_at, s.cam_fov_deg);
        double *ms = util_alloc(sizeof *ms * (size_t)opt->runs * 2, "bench timings");
        ok = time_backends(&s, &cam, nb, backends, ms, opt->runs, err);
        if (ok) {
            float *aov = util_alloc(sizeof(float) * (size_t)B.w * (size_t)B.h * AOV_FLOATS, "a bench image");
            render_read_aovs(aov);
            double steps = 0;
            for (int i = 0; i < B.w * B.h; i++)
                steps += fabsf(aov[(size_t)i * AOV_FLOATS + AOV_SLOT_STEPS]); /* negative: ran out of steps */
            free(aov);
            char cell[2][64], ratio[64] = "";
            double med[2], lo[2], hi[2];
            for (int b = 0; b < nb; b++) {
                med[b] = metrics_median_interval(ms + b * opt->runs, opt->runs, &lo[b], &hi[b]);
                snprintf(cell[b], sizeof cell[b], "%.1f [%.1f-%.1f]", med[b], lo[b], hi[b]);
            }
            if (nb > 1 && (lo[1] > hi[0] || lo[0] > hi[1]))
                snprintf(ratio, sizeof ratio, "%.2f", med[1] / med[0]);
            else if (nb > 1)
                snprintf(ratio, sizeof ratio, "not measurable");
            printf("  %-12s %-24s %-24s %-22s %.1f\n", preset_name((quality_preset)p), cell[0], nb > 1 ? cell[1] : "",
                   ratio, steps / (B.w * B.h));
        }
        free(ms);
        scene_free(&s);
    }
    render_shutdown();
    gpu_close();
    return ok;
}

/* Which sweeps run, with which values: --knob NAME=… picks (only those), else every one that applies. */
static bool pick_sweeps(const scene *base, sweep *sweeps, const char **values, int *n, err_t *err)
{
    bool applies[MAX_SWEEPS];
    *n = list_sweeps(base, sweeps, applies);
    static char chosen[MAX_SWEEPS][256];
    for (int k = 0; k < *n && !B.opt->knob_count; k++) {
        char keep[64];
        bench_base_value(base, sweeps[k].name, keep, sizeof keep);
        values[k] = !applies[k] ? NULL
                                : sweep_values(sweeps[k].values, keep, B.opt->quick, chosen[k], sizeof chosen[k]);
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

bool bench_run(const cli_options *opt, err_t *err)
{
    memset(&B, 0, sizeof B);
    B.opt = opt;
    B.w = opt->width ? opt->width : opt->quick ? QUICK_WIDTH : opt->full ? FULL_WIDTH : DEFAULT_WIDTH;
    B.h = opt->height ? opt->height : opt->quick ? QUICK_HEIGHT : opt->full ? FULL_HEIGHT : DEFAULT_HEIGHT;
    if (opt->frame_times)
        return frame_times(opt, err);
    if (opt->terrain_scale)
        return bench_terrain_scale(opt, opt->width ? opt->width : 640, opt->height ? opt->height : 360, err);
    if (opt->interactive)
        return bench_interactive(opt, opt->width ? opt->width : GPU_DEFAULT_WIDTH,
                                 opt->height ? opt->height : GPU_DEFAULT_HEIGHT, err);
    scene base;
    if (!load(NULL, 0, &base, err))
        return false;
    sweep sweeps[MAX_SWEEPS];
    const char *values[MAX_SWEEPS] = {0};
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
            B.total += count_values(values[k]);
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
            ok = bench_write(&res, err);
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
