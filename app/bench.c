#include "bench.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "aov.h"
#include "gpu.h"
#include "image_io.h"
#include "metrics.h"
#include "render.h"
#include "scene.h"

enum { DEFAULT_WIDTH = 320, DEFAULT_HEIGHT = 180, VIEWS = 2, REF_SPP = 64, STRICT_SPP = 128, LONG_SPP = 64,
       MAX_ROWS = 512 };
static const float VIEW_TURN_DEG = 40.0f;

/* A knob: its --set key (or a bench-only setting), the default sweep, which programs it applies to. */
typedef struct knob {
    const char *name, *key, *values;
    bool (*applies)(const scene *s);
} knob;

static bool any(const scene *s) { (void)s; return true; }
static bool shadows(const scene *s) { return s->effects & (1u << EFFECT_SHADOWS); }
static bool ao(const scene *s) { return s->effects & (1u << EFFECT_AO); }
static bool bounces(const scene *s) { return s->effects & ((1u << EFFECT_REFLECTIONS) | (1u << EFFECT_REFRACTION)); }
static bool textured(const scene *s) { return s->effects & (1u << EFFECT_TEXTURES); }
static bool fractal(const scene *s) { return program_is_fractal(s->program); }
static bool terrain(const scene *s) { return s->program == PROGRAM_TERRAIN; }
static bool searched(const scene *s) /* the lab's search runs: linear terrain, or relief materials */
{
    return (s->program == PROGRAM_TERRAIN && !s->terrain.maxmip) || (s->effects & (1u << EFFECT_RELIEF));
}

static const knob KNOBS[] = {
    {"max_steps", "quality.max_steps", "16,32,64,128,256,512", any},
    {"hit_k", "quality.hit_k", "8,4,2,1,0.5", any},
    {"step_factor", "quality.step_factor", "0.6,0.8,0.9,1", any},
    {"over_relax", "quality.over_relax", "1,1.2,1.3,1.4,1.6", any},
    {"iterations", "fractal.iterations", NULL, fractal}, /* per program, below */
    {"method", "terrain.method", "linear,maxmip", terrain},
    {"linear_step", "quality.linear_step", "4,2,1,0.5,0.25", searched},
    {"step_growth", "quality.step_growth", "1.1,1.05,1.02,1", searched},
    {"binary_steps", "quality.binary_steps", "0,2,4,8,12", searched},
    {"shadow_steps", "quality.shadow_steps", "8,16,32,64,128", shadows},
    {"ao_samples", "quality.ao_samples", "0,2,3,5,8", ao},
    {"bounces", "quality.bounces", "0,1,2,3,6", bounces},
    {"aniso_taps", "quality.aniso_taps", "1,2,4,8", textured},
    {"spp", "quality.spp", "1,2,4,8,16", any},
    {"resolution_scale", NULL, "0.25,0.5,0.75,1", any},
};

static const char *iteration_values(program_kind p)
{
    return p == PROGRAM_MENGER ? "1,2,3,4,5" : p == PROGRAM_MANDELBULB ? "3,4,6,8,10,12" : "4,6,8,10,12,16";
}

typedef struct row {
    char knob[32], value[32];
    double ms;  /* median time of one image (all its samples), mean over views */
    metrics m;  /* mean over views (max depth: max) */
    bool front;
} row;

typedef struct ref_view {
    camera cam;
    uint8_t *srgb;
    float *aov;
} ref_view;

static struct {
    const cli_options *opt;
    int w, h;
    ref_view views[VIEWS];
    row rows[MAX_ROWS];
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

static void read_back(int w, int h, uint8_t **srgb, float **aov)
{
    *srgb = malloc((size_t)w * (size_t)h * 4);
    *aov = malloc(sizeof(float) * (size_t)w * (size_t)h * AOV_FLOATS);
    render_read_srgb8(*srgb, 1.0f);
    render_read_aovs(*aov);
}

/* Times and measures one setting over every view. scale < 1 renders smaller and upscales. */
static bool measure(const char *knob_name, const char *value, const char *const *sets, int nsets, double scale,
                    row *out, err_t *err)
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
    *out = (row){0};
    snprintf(out->knob, sizeof out->knob, "%s", knob_name);
    snprintf(out->value, sizeof out->value, "%s", value);
    /* an image of LONG_SPP samples or more is long enough to time once, and needs no warm-up */
    int runs = s.quality.spp >= LONG_SPP ? 1 : B.opt->runs;
    double *ms = malloc(sizeof *ms * (size_t)B.opt->runs);
    for (int v = 0; v < VIEWS; v++) {
        if (runs > 1)
            image(&s, &B.views[v].cam, w, h); /* warm-up: compiles and caches */
        for (int r = 0; r < runs; r++)
            ms[r] = image(&s, &B.views[v].cam, w, h);
        out->ms += util_median(ms, runs) / VIEWS;
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
        if (scale != 1.0) /* steps were counted at the smaller size: per output pixel they are fewer */
            m.mean_steps *= scale * scale;
        out->m.rmse += m.rmse * m.rmse / VIEWS; /* mean square, rooted below */
        out->m.depth_mean_fp += m.depth_mean_fp / VIEWS;
        out->m.depth_max_fp = fmax(out->m.depth_max_fp, m.depth_max_fp);
        out->m.flip_share += m.flip_share / VIEWS;
        out->m.mean_steps += m.mean_steps / VIEWS;
        free(srgb);
        free(aov);
    }
    out->m.rmse = sqrt(out->m.rmse);
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
    snprintf(spp, sizeof spp, "quality.spp=%d", REF_SPP);
    /* a scene that pins max_steps (for its presets) must not truncate its reference: lift it */
    const char *ref_sets[] = {"quality.preset=reference", spp, "quality.max_steps=4096"};
    scene ref;
    if (!load(ref_sets, 3, &ref, err) || !render_set_scene(&ref, NULL, err))
        return false;
    camera start = camera_look_at(base->cam_position, base->cam_look_at, base->cam_fov_deg * GLM_PIf / 180.0f);
    for (int v = 0; v < VIEWS; v++) {
        /* turn the camera about the vertical through the look-at point */
        float a = (float)v * VIEW_TURN_DEG * GLM_PIf / 180.0f, ca = cosf(a), sa = sinf(a);
        float d[3], pos[3];
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
        B.done++;
        progress("reference");
    }
    scene_free(&ref);
    /* Has the reference converged? Compare it with a render four times stricter in threshold and
     * twice in samples, steps and bounces: its error must be far below what the knobs show. */
    char strict_spp[32];
    snprintf(strict_spp, sizeof strict_spp, "quality.spp=%d", STRICT_SPP);
    /* (AO samples stay: the AO estimate is a different function of its sample count, not a converging sum) */
    const char *strict_sets[] = {"quality.preset=reference", strict_spp, "quality.hit_k=0.0625",
                                 "quality.max_steps=8192", "quality.shadow_steps=512", "quality.bounces=16"};
    scene strict;
    if (!load(strict_sets, 6, &strict, err) || !render_set_scene(&strict, NULL, err))
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

typedef struct effect_row {
    effect e;
    bool in_scene;
    double out_ms, in_ms, in_off_ms;
} effect_row;

static double effect_time(const char *set, unsigned runtime, err_t *err, bool *ok)
{
    const char *sets[] = {set, "quality.spp=1"};
    scene s;
    *ok = load(sets, 2, &s, err) && render_set_scene(&s, NULL, err);
    if (!*ok)
        return 0;
    render_set_runtime_effects(runtime);
    double *ms = malloc(sizeof *ms * (size_t)B.opt->runs);
    image(&s, &B.views[0].cam, B.w, B.h);
    for (int r = 0; r < B.opt->runs; r++)
        ms[r] = image(&s, &B.views[0].cam, B.w, B.h);
    double m = util_median(ms, B.opt->runs);
    free(ms);
    render_set_runtime_effects(~0u);
    scene_free(&s);
    return m;
}

static bool measure_effects(const scene *base, effect_row *rows, err_t *err)
{
    for (int e = 0; e < EFFECT_COUNT; e++) {
        char off[64], on[64];
        snprintf(off, sizeof off, "effects.%s=off", effect_name((effect)e));
        snprintf(on, sizeof on, "effects.%s=on", effect_name((effect)e));
        bool ok;
        rows[e] = (effect_row){.e = (effect)e, .in_scene = base->effects & (1u << e)};
        rows[e].out_ms = effect_time(off, ~0u, err, &ok);
        if (ok)
            rows[e].in_ms = effect_time(on, ~0u, err, &ok);
        if (ok)
            rows[e].in_off_ms = effect_time(on, ~(1u << e), err, &ok);
        if (!ok)
            return false;
        B.done++;
        progress(effect_name((effect)e));
    }
    return true;
}

/* ---- output ------------------------------------------------------------------------------------- */

static const char *prefix(void) { return B.opt->name ? B.opt->name : B.opt->scene; }

static FILE *open_out(const char *name, char *path, err_t *err)
{
    snprintf(path, PATH_MAX_LEN, "%s/%s-%s", B.opt->out, prefix(), name);
    FILE *f = fopen(path, "w");
    if (!f)
        err_set(err, "cannot write '%s': check that --out '%s' is a writable folder", path, B.opt->out);
    return f;
}

static bool write_outputs(const scene *base, const metrics *conv, double ref_ms, const effect_row *fx, err_t *err)
{
    char path[PATH_MAX_LEN], csv[PATH_MAX_LEN], png[PATH_MAX_LEN];
    FILE *f = open_out("knobs.csv", csv, err);
    if (!f)
        return false;
    fprintf(f, "scene,width,height,views,knob,value,ms_per_image,rmse,psnr_db,depth_mean_fp,depth_max_fp,"
               "flip_share,mean_steps,pareto\n");
    for (int i = 0; i < B.nrows; i++) {
        const row *r = &B.rows[i];
        fprintf(f, "%s,%d,%d,%d,%s,%s,%.3f,%.6f,%.3f,%.4f,%.4f,%.6f,%.3f,%d\n", B.opt->scene, B.w, B.h, VIEWS, r->knob,
                r->value, r->ms, r->m.rmse, isinf(r->m.psnr_db) ? 999.0 : r->m.psnr_db, r->m.depth_mean_fp,
                r->m.depth_max_fp, r->m.flip_share, r->m.mean_steps, r->front);
    }
    fclose(f);
    f = open_out("effects.csv", path, err);
    if (!f)
        return false;
    fprintf(f, "scene,effect,in_scene,ms_compiled_out,ms_compiled_in,ms_compiled_in_switched_off\n");
    for (int e = 0; e < EFFECT_COUNT; e++)
        fprintf(f, "%s,%s,%d,%.3f,%.3f,%.3f\n", B.opt->scene, effect_name(fx[e].e), fx[e].in_scene, fx[e].out_ms,
                fx[e].in_ms, fx[e].in_off_ms);
    fclose(f);

    /* gnuplot: one data block per knob, the front last */
    char dat[PATH_MAX_LEN], gp[PATH_MAX_LEN];
    f = open_out("plot.dat", dat, err);
    if (!f)
        return false;
    char knobs[64][32];
    int nk = 0;
    for (int i = 0; i < B.nrows; i++) {
        if (nk == 0 || strcmp(knobs[nk - 1], B.rows[i].knob)) {
            if (nk)
                fprintf(f, "\n\n");
            snprintf(knobs[nk++], 32, "%s", B.rows[i].knob);
        }
        fprintf(f, "%.4f %.6f %s\n", B.rows[i].ms, fmax(B.rows[i].m.rmse, 1e-5), B.rows[i].value);
    }
    fprintf(f, "\n\n");
    /* the front, sorted by time */
    int order[MAX_ROWS], n = 0;
    for (int i = 0; i < B.nrows; i++)
        if (B.rows[i].front)
            order[n++] = i;
    for (int a = 1; a < n; a++)
        for (int b = a; b > 0 && B.rows[order[b]].ms < B.rows[order[b - 1]].ms; b--) {
            int t = order[b];
            order[b] = order[b - 1];
            order[b - 1] = t;
        }
    for (int i = 0; i < n; i++)
        fprintf(f, "%.4f %.6f %s=%s\n", B.rows[order[i]].ms, fmax(B.rows[order[i]].m.rmse, 1e-5),
                B.rows[order[i]].knob, B.rows[order[i]].value);
    fclose(f);
    f = open_out("plot.gp", gp, err);
    if (!f)
        return false;
    snprintf(png, sizeof png, "%s/%s-plot.png", B.opt->out, prefix());
    fprintf(f, "set terminal pngcairo size 960,620 font ',10'\nset output '%s'\n", png);
    fprintf(f, "set title \"%s: error against time, each knob swept alone (%dx%d, %.40s)\" noenhanced\n",
            B.opt->scene, B.w, B.h, (const char *)glGetString(GL_RENDERER));
    fprintf(f, "set logscale xy\nset xlabel 'ms per image (median)'\nset ylabel 'colour RMSE against the reference'\n"
               "set key outside right top noenhanced\nset grid\n");
    fprintf(f, "plot ");
    for (int k = 0; k < nk; k++)
        fprintf(f, "'%s' index %d using 1:2 with linespoints pt 7 ps 0.8 title '%s', ", dat, k, knobs[k]);
    fprintf(f, "'%s' index %d using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front'\n", dat, nk);
    fclose(f);
    char cmd[PATH_MAX_LEN * 2];
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>&1", gp);
    if (system(cmd) != 0)
        return err_set(err, "gnuplot failed on '%s' (is gnuplot installed? apt-get install gnuplot-nox); the CSV "
                            "files are written", gp);

    f = open_out("summary.md", path, err);
    if (!f)
        return false;
    fprintf(f, "# What accuracy costs: %s\n\n", prefix());
    strbuf sets = {0};
    for (int i = 0; i < B.opt->set_count; i++)
        sb_printf(&sets, " --set %s", B.opt->sets[i]);
    fprintf(f, "%s. %dx%d, %d views (the start camera, and turned %.0f° about the look-at point), median of %d "
               "images after a warm-up, on %s. Made by `fathom bench --scene %s --size %dx%d --runs %d%s --out DIR`.\n\n",
            base->title, B.w, B.h, VIEWS, (double)VIEW_TURN_DEG, B.opt->runs, gpu_describe(), B.opt->scene, B.w, B.h,
            B.opt->runs, sets.data ? sets.data : "");
    sb_free(&sets);
    fprintf(f, "**Reference**: the `reference` preset at %d spp (%.0f ms per image). **Converged?** A render four "
               "times stricter in hit threshold, twice in samples and steps, and with 16 bounces differs from it "
               "by RMSE %.5f (PSNR %.1f dB), mean depth %.3f / max %.2f pixel footprints, %.3f %% flipped pixels: "
               "errors well above these are the knobs', not the reference's.\n\n",
            REF_SPP, ref_ms, conv->rmse, conv->psnr_db, conv->depth_mean_fp, conv->depth_max_fp, 100 * conv->flip_share);
    fprintf(f, "Error: colour RMSE and PSNR of the 8-bit display image; depth error in pixel footprints over pixels "
               "both renders hit; flips: pixels that hit in one and miss in the other. Every knob row starts from "
               "the scene's `%s` preset. `*` marks the Pareto front (no setting is both faster and closer). Settings "
               "of 64 spp or more are timed once per view.\n\n",
            preset_name(base->preset));
    fprintf(f, "![error against time](%s-plot.png)\n\n", prefix());
    fprintf(f, "| knob | value | ms/image | RMSE | PSNR dB | depth mean (fp) | depth max (fp) | flips %% | steps/px |\n"
               "|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < B.nrows; i++) {
        const row *r = &B.rows[i];
        fprintf(f, "| %s | %s%s | %.1f | %.4f | %.1f | %.3f | %.2f | %.2f | %.1f |\n", r->knob, r->value,
                r->front ? " *" : "", r->ms, r->m.rmse, r->m.psnr_db, r->m.depth_mean_fp, r->m.depth_max_fp,
                100 * r->m.flip_share, r->m.mean_steps);
    }
    fprintf(f, "\n## Effects: compiled in, compiled out, compiled in but switched off\n\n"
               "ms per 1-spp frame at the start view. *In scene*: the scene calls for it (so fathom compiles it).\n\n"
               "| effect | in scene | compiled out | compiled in | compiled in, off at run time |\n|---|---|---|---|---|\n");
    for (int e = 0; e < EFFECT_COUNT; e++)
        fprintf(f, "| %s | %s | %.1f | %.1f | %.1f |\n", effect_name(fx[e].e), fx[e].in_scene ? "yes" : "no",
                fx[e].out_ms, fx[e].in_ms, fx[e].in_off_ms);
    fclose(f);
    return true;
}

/* ---- the run ------------------------------------------------------------------------------------ */

static bool add_knob_rows(const scene *base, const knob *k, const char *values, err_t *err)
{
    char list[512];
    snprintf(list, sizeof list, "%s", values);
    char *save = NULL;
    for (char *v = strtok_r(list, ",", &save); v; v = strtok_r(NULL, ",", &save)) {
        if (B.nrows == MAX_ROWS)
            return err_set(err, "too many bench settings (at most %d)", MAX_ROWS);
        char set[96];
        const char *sets[1];
        int n = 0;
        double scale = 1.0;
        if (k->key) {
            snprintf(set, sizeof set, "%s=%s", k->key, v);
            sets[n++] = set;
        } else {
            char *end;
            scale = strtod(v, &end);
            if (*end || scale <= 0 || scale > 1)
                return err_set(err, "bad --knob resolution_scale value '%s': expected a number in (0, 1]", v);
        }
        if (!measure(k->name, v, sets, n, scale, &B.rows[B.nrows], err))
            return false;
        B.nrows++;
    }
    (void)base;
    return true;
}

static int count_values(const char *v)
{
    int n = 1;
    for (; *v; v++)
        n += *v == ',';
    return n;
}

/* Each preset's frame time (one sample per pixel) at the start view: what the window costs. */
static bool frame_times(const cli_options *opt, err_t *err)
{
    if (!gpu_open(&(gpu_desc){.headless = true}, err))
        return false;
    bool ok = render_init(err);
    printf("%s, %dx%d, %s: ms per frame (1 sample per pixel), median of %d after a warm-up\n", opt->scene, B.w, B.h,
           gpu_describe(), opt->runs);
    for (int p = 0; ok && p < PRESET_COUNT; p++) {
        char set[64];
        snprintf(set, sizeof set, "quality.preset=%s", preset_name((quality_preset)p));
        const char *sets[] = {set, "quality.spp=1"};
        scene s;
        ok = load(sets, 2, &s, err) && render_set_scene(&s, NULL, err);
        if (!ok)
            break;
        camera cam = camera_look_at(s.cam_position, s.cam_look_at, s.cam_fov_deg * GLM_PIf / 180.0f);
        double *ms = malloc(sizeof *ms * (size_t)opt->runs);
        image(&s, &cam, B.w, B.h);
        for (int r = 0; r < opt->runs; r++)
            ms[r] = image(&s, &cam, B.w, B.h);
        float *aov = malloc(sizeof(float) * (size_t)B.w * (size_t)B.h * AOV_FLOATS);
        render_read_aovs(aov);
        double steps = 0;
        for (int i = 0; i < B.w * B.h; i++)
            steps += aov[(size_t)i * AOV_FLOATS + AOV_SLOT_STEPS];
        printf("  %-12s %8.1f ms   %6.1f steps (height samples) per pixel\n", preset_name((quality_preset)p),
               util_median(ms, opt->runs), steps / (B.w * B.h));
        free(aov);
        free(ms);
        scene_free(&s);
    }
    render_shutdown();
    gpu_close();
    return ok;
}

bool bench_run(const cli_options *opt, err_t *err)
{
    memset(&B, 0, sizeof B);
    B.opt = opt;
    B.w = opt->width ? opt->width : DEFAULT_WIDTH;
    B.h = opt->height ? opt->height : DEFAULT_HEIGHT;
    if (opt->frame_times)
        return frame_times(opt, err);
    if (opt->out) {
        struct stat st;
        if (stat(opt->out, &st) != 0 || !S_ISDIR(st.st_mode))
            return err_set(err, "--out '%s' is not a folder: create it first", opt->out);
    }
    scene base;
    if (!load(NULL, 0, &base, err))
        return false;
    /* which knobs, with which values */
    const char *values[sizeof KNOBS / sizeof KNOBS[0]] = {0};
    for (int i = 0; i < opt->knob_count; i++) {
        const char *eq = strchr(opt->knobs[i], '=');
        bool found = false;
        for (size_t k = 0; k < sizeof KNOBS / sizeof KNOBS[0]; k++)
            if ((size_t)(eq - opt->knobs[i]) == strlen(KNOBS[k].name) && !strncmp(opt->knobs[i], KNOBS[k].name, (size_t)(eq - opt->knobs[i]))) {
                values[k] = eq + 1;
                found = true;
            }
        if (!found) {
            scene_free(&base);
            return err_set(err, "unknown --knob '%.*s' (known: max_steps, hit_k, step_factor, over_relax, iterations, "
                                "method, linear_step, step_growth, binary_steps, shadow_steps, ao_samples, bounces, "
                                "aniso_taps, spp, resolution_scale)",
                           (int)(eq - opt->knobs[i]), opt->knobs[i]);
        }
    }
    B.total = VIEWS + 1 + PRESET_COUNT + EFFECT_COUNT;
    for (size_t k = 0; k < sizeof KNOBS / sizeof KNOBS[0]; k++) {
        if (!opt->knob_count) {
            if (!KNOBS[k].applies(&base))
                continue;
            values[k] = KNOBS[k].values ? KNOBS[k].values : iteration_values(base.program);
        }
        if (values[k])
            B.total += count_values(values[k]);
    }
    if (!gpu_open(&(gpu_desc){.headless = true}, err)) {
        scene_free(&base);
        return false;
    }
    B.t0 = util_now();
    metrics conv;
    double ref_ms = 0;
    effect_row fx[EFFECT_COUNT];
    bool ok = render_init(err) && make_references(&base, &conv, &ref_ms, err);
    for (size_t k = 0; ok && k < sizeof KNOBS / sizeof KNOBS[0]; k++)
        if (values[k])
            ok = add_knob_rows(&base, &KNOBS[k], values[k], err);
    for (int p = 0; ok && p < PRESET_COUNT; p++) {
        char set[64];
        snprintf(set, sizeof set, "quality.preset=%s", preset_name((quality_preset)p));
        const char *sets[] = {set};
        ok = measure("preset", preset_name((quality_preset)p), sets, 1, 1.0, &B.rows[B.nrows], err);
        B.nrows += ok;
    }
    ok = ok && measure_effects(&base, fx, err);
    if (!opt->quiet)
        fputc('\n', stderr);
    if (ok) {
        double t[MAX_ROWS], e[MAX_ROWS];
        bool front[MAX_ROWS];
        for (int i = 0; i < B.nrows; i++)
            t[i] = B.rows[i].ms, e[i] = B.rows[i].m.rmse;
        metrics_pareto(t, e, B.nrows, front);
        for (int i = 0; i < B.nrows; i++)
            B.rows[i].front = front[i];
        printf("%s, %dx%d, %s; reference converged to RMSE %.5f\n", opt->scene, B.w, B.h, gpu_describe(), conv.rmse);
        printf("%-16s %-10s %10s %8s %8s %10s %10s %7s %8s\n", "knob", "value", "ms/image", "RMSE", "PSNR", "depth fp",
               "max fp", "flips%", "steps");
        for (int i = 0; i < B.nrows; i++) {
            const row *r = &B.rows[i];
            printf("%-16s %-10s %10.1f %8.4f %8.1f %10.3f %10.2f %7.2f %8.1f%s\n", r->knob, r->value, r->ms, r->m.rmse,
                   r->m.psnr_db, r->m.depth_mean_fp, r->m.depth_max_fp, 100 * r->m.flip_share, r->m.mean_steps,
                   r->front ? "  *" : "");
        }
        for (int i = 0; i < EFFECT_COUNT; i++)
            printf("effect %-13s in scene %-3s  out %7.1f ms  in %7.1f ms  in, off %7.1f ms\n", effect_name(fx[i].e),
                   fx[i].in_scene ? "yes" : "no", fx[i].out_ms, fx[i].in_ms, fx[i].in_off_ms);
        if (opt->out)
            ok = write_outputs(&base, &conv, ref_ms, fx, err);
    }
    for (int v = 0; v < VIEWS; v++) {
        free(B.views[v].srgb);
        free(B.views[v].aov);
    }
    scene_free(&base);
    render_shutdown();
    gpu_close();
    return ok;
}
