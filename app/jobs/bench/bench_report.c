/* bench_report — the bench's results as a console table, CSV files, a markdown summary and an HTML page (bench_report.h); the plots are bench_plot.c's. */
#include "jobs/bench/bench_report.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/media/image_io.h"
#include "gpu/gpu.h"
#include "scene/program.h"
#include "scene/quality.h"

/* "+3.1 ms" where b's interval lies wholly above or below a's, else "not measurable". */
static const char *bench_difference(double a_lo, double a_hi, double b_lo, double b_hi, double a, double b, char *buf,
                                    int size)
{
    if (b_lo > a_hi || b_hi < a_lo)
        snprintf(buf, (size_t)size, "%+.1f ms", b - a);
    else
        snprintf(buf, (size_t)size, "not measurable");
    return buf;
}

static const char *scene_label(const bench_results *r);

void bench_print(const bench_results *r)
{
    printf("%s, %dx%d, %s; reference converged to RMSE %.5f\n", scene_label(r), r->w, r->h, gpu_describe(),
           r->conv->rmse);
    printf("%-16s %-10s %10s %8s %8s %8s %10s %10s %7s %8s %8s %7s %7s\n", "knob", "value", "ms/image", "RMSE",
           "edgeRMSE", "PSNR", "depth fp", "max fp", "flips%", "IoU", "edge px", "steps", "out%");
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        char knob[sizeof w->knob], value[sizeof w->value];
        util_printable(w->knob, knob, sizeof knob), util_printable(w->value, value, sizeof value);
        printf("%-16s %-10s %10.1f %8.4f %8.4f %8.1f %10.3f %10.2f %7.2f %8.4f %8.1f %7.1f %7.2f%s\n", knob,
               value, w->ms, w->m.rmse, w->m.edge_rmse, w->m.psnr_db, w->m.depth_mean_fp, w->m.depth_max_fp,
               100 * w->m.flip_share, w->m.iou, w->m.edge_max_px, w->m.mean_steps, 100 * w->m.exhausted_share,
               w->front ? "  *" : "");
    }
    for (int i = 0; i < EFFECT_COUNT; i++) {
        const effect_row *x = &r->fx[i];
        char d[48];
        printf("effect %-13s in scene %-3s  out %7.1f ms  in %7.1f ms  in, off %7.1f ms  in vs out: %s\n",
               effect_name(x->e), x->in_scene ? "yes" : "no", x->out_ms, x->in_ms, x->in_off_ms,
               bench_difference(x->out_lo, x->out_hi, x->in_lo, x->in_hi, x->out_ms, x->in_ms, d, sizeof d));
    }
}


void bench_safe_name(const char *s, char *out, size_t n)
{
    size_t k = 0;
    for (; *s && k + 1 < n; s++) {
        char c = *s;
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                  c == '_' || (c == '.' && k > 0);
        out[k++] = ok ? c : '_';
    }
    out[k] = '\0';
    if (k == 0)
        snprintf(out, n, "bench");
}

void bench_prefix(const bench_desc *o, char *out, size_t n)
{
    const char *s = o->name ? o->name : o->scene, *slash = strrchr(s, '/'), *base = slash ? slash + 1 : s;
    const char *dot = strrchr(base, '.');
    char stem[BENCH_PREFIX_MAX];
    snprintf(stem, sizeof stem, "%.*s", (int)(dot && dot > base && !o->name ? dot - base : (long)strlen(base)),
             base);
    bench_safe_name(stem, out, n);
}

const char *bench_run_prefix(const bench_results *r)
{
    static char p[BENCH_PREFIX_MAX];
    bench_prefix(r->opt, p, sizeof p);
    return p;
}

/* The scene in the CSV files and the table: its base name made safe, whatever --name says */
static const char *scene_label(const bench_results *r)
{
    static char p[BENCH_PREFIX_MAX];
    bench_desc o = {.scene = r->opt->scene};
    bench_prefix(&o, p, sizeof p);
    return p;
}

bool bench_open_out(const bench_results *r, const char *name, util_atomic *a, err_t *err)
{
    char path[PATH_MAX_LEN];
    if (snprintf(path, sizeof path, "%s/%s-%s", r->opt->out, bench_run_prefix(r), name) >= (int)sizeof path)
        return err_set(err, "--out '%s': the path is too long", r->opt->out);
    return util_atomic_open(a, path, err);
}

static void knob_csv(const bench_results *r, FILE *f)
{
    fprintf(f, "scene,width,height,views,knob,value,ms_per_image,rmse,psnr_db,depth_mean_fp,depth_max_fp,"
               "flip_share,iou,edge_max_px,mean_steps,out_of_steps_share,edge_rmse,pareto,ms_lo,ms_hi\n");
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        fprintf(f, "%s,%d,%d,%d,%s,%s,%.3f,%.6f,%.3f,%.4f,%.4f,%.6f,%.6f,%.2f,%.3f,%.6f,%.6f,%d,%.3f,%.3f\n",
                scene_label(r), r->w, r->h, r->views, w->knob, w->value, w->ms, w->m.rmse,
                isinf(w->m.psnr_db) ? 999.0 : w->m.psnr_db, w->m.depth_mean_fp, w->m.depth_max_fp, w->m.flip_share,
                w->m.iou, w->m.edge_max_px, w->m.mean_steps, w->m.exhausted_share, w->m.edge_rmse, w->front, w->ms_lo,
                w->ms_hi);
    }
}

bool bench_write_rows(const bench_results *r, err_t *err)
{
    util_atomic a;
    if (!bench_open_out(r, "knobs.csv", &a, err))
        return false;
    knob_csv(r, a.f);
    return util_atomic_commit(&a, err);
}

bool bench_write_csv(const bench_results *r, err_t *err)
{
    util_atomic a;
    if (!bench_write_rows(r, err) || !bench_open_out(r, "effects.csv", &a, err))
        return false;
    fprintf(a.f, "scene,effect,in_scene,ms_compiled_out,ms_compiled_in,ms_compiled_in_switched_off,out_lo,out_hi,"
                 "in_lo,in_hi,in_off_lo,in_off_hi\n");
    for (int e = 0; e < EFFECT_COUNT; e++)
        fprintf(a.f, "%s,%s,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n", scene_label(r), effect_name(r->fx[e].e),
                r->fx[e].in_scene, r->fx[e].out_ms, r->fx[e].in_ms, r->fx[e].in_off_ms, r->fx[e].out_lo,
                r->fx[e].out_hi, r->fx[e].in_lo, r->fx[e].in_hi, r->fx[e].in_off_lo, r->fx[e].in_off_hi);
    return util_atomic_commit(&a, err);
}

/* The value the scene's own preset gives a sweep ("" when the bench does not know it): the operating
 * point each small multiple rings, and the value a sweep always holds. */
void bench_base_value(const scene *s, const char *knob, char *out, size_t n)
{
    knob_id k;
    const bench_approximation *a = bench_approximation_of(knob);
    out[0] = '\0';
    if (!strcmp(knob, "preset"))
        snprintf(out, n, "%s", preset_name(s->preset));
    else if (!strcmp(knob, "resolution_scale"))
        snprintf(out, n, "1");
    else if (!strcmp(knob, "method") && s->program == PROGRAM_TERRAIN)
        snprintf(out, n, "%s", s->terrain.maxmip ? "maxmip" : "linear");
    else if (!strcmp(knob, "iterations") && program_is_fractal(s->program))
        snprintf(out, n, "%d", s->fractal.iterations);
    else if (!strcmp(knob, "hit_rule") && program_is_fractal(s->program))
        snprintf(out, n, "%s", s->fractal.hit_rule == HIT_RULE_FRAGMENT ? "fragment" : "footprint");
    else if (!strcmp(knob, "detail") && program_is_fractal(s->program))
        snprintf(out, n, "%g", (double)s->fractal.detail);
    else if (a && !strncmp(knob, "fx_", 3))
        snprintf(out, n, "%s", a->on); /* swept only where the scene uses it */
    else if (knob_from_name(knob, &k))
        snprintf(out, n, "%g", knob_value(&s->quality, k));
}

bool bench_same_value(const char *a, const char *b)
{
    char *ea, *eb;
    double x = strtod(a, &ea), y = strtod(b, &eb);
    return *a && *b && (!strcmp(a, b) || (!*ea && !*eb && ea != a && eb != b && x == y));
}

static void summary_header(const bench_results *r, FILE *f)
{
    const bench_desc *o = r->opt;
    const metrics *c = r->conv;
    fprintf(f, "# What accuracy costs: %s\n\n", bench_run_prefix(r));
    strbuf sets = {0};
    for (int i = 0; i < o->set_count; i++)
        sb_printf(&sets, " --set %s", o->sets[i]);
    for (int i = 0; i < o->knob_count; i++)
        sb_printf(&sets, " --knob %s", o->knobs[i]);
    if (o->path_truth)
        sb_append(&sets, " --truth path");
    char title[256], name[PATH_MAX_LEN];
    util_printable(r->base->title, title, sizeof title), util_printable(o->scene, name, sizeof name);
    for (char *ch = sets.data; ch && *ch; ch++)
        *ch = (unsigned char)*ch < 0x20 ? '?' : *ch;
    fprintf(f, "%s. %dx%d, %d views (the start camera, and turned %.0f° about the look-at point), median of %d "
               "images after a warm-up, on %s. Made by `fathom bench --scene %s --size %dx%d --runs %d%s --out DIR`.\n\n",
            title, r->w, r->h, r->views, (double)r->view_turn_deg, o->runs, gpu_describe(), name, r->w,
            r->h, o->runs, sets.data ? sets.data : "");
    sb_free(&sets);
    if (o->path_truth)
        fprintf(f, "**Reference: the truth**, the path tracer (`quality.integrator=1`: unbiased light transport through "
                   "the same map() and materials, tested against closed forms in tests/gpu/test_pathtrace.c) at %d spp, "
                   "hit threshold 0.0625 footprints, 16 bounces (%.0f ms per image): every error below is what the "
                   "model's approximations (direct light, AO, soft-shadow penumbrae, one-level glass, constant "
                   "ambient) and its knobs cost against light transport. **Converged?** A path-traced render with "
                   "twice the samples, half the threshold and 32 bounces differs from it by RMSE %.5f (PSNR %.1f dB), "
                   "mean depth %.3f / max %.2f pixel footprints, %.3f %% flipped pixels: Monte Carlo noise, below "
                   "which no error here is real.\n\n",
                r->ref_spp, r->ref_ms, c->rmse, c->psnr_db, c->depth_mean_fp, c->depth_max_fp, 100 * c->flip_share);
    else
        fprintf(f, "**Reference**: the `reference` preset at %d spp with hits refined to float resolution "
                   "(`quality.refine=64` where the program refines: not the fractals, whose surface the footprint "
                   "defines) (%.0f ms per image). **Converged?** A render four "
                   "times stricter in hit threshold, twice in samples and steps, and with 16 bounces differs from it "
                   "by RMSE %.5f (PSNR %.1f dB), mean depth %.3f / max %.2f pixel footprints, %.3f %% flipped pixels: "
                   "errors well above these are the knobs', not the reference's.\n\n",
                r->ref_spp, r->ref_ms, c->rmse, c->psnr_db, c->depth_mean_fp, c->depth_max_fp, 100 * c->flip_share);
    fprintf(f, "Error: colour RMSE and PSNR of the 8-bit display image; depth error in pixel footprints over pixels "
               "both renders hit; edge RMSE: colour RMSE over the reference's silhouette pixels alone (where anti-aliasing "
               "shows); flips: pixels that hit in one and miss in the other; IoU: of the two hit masks (worst "
               "view); edge px: how far the farthest flipped pixel lies from the reference's silhouette; out of "
               "steps: pixels whose primary ray was left unresolved (its steps and their tail ran out; drawn as a miss). Every knob row starts from "
               "the scene's `%s` preset. ms/image: the median [and its 95 %% interval]. `*` marks the Pareto front, "
               "built from the intervals: a setting leaves it for one measurably faster and no worse, or better and "
               "not measurably slower. Settings of 64 spp or more are timed once per view.\n\n",
            preset_name(r->base->preset));
}

/* The difference images' scale in words (bench.c's diff_colour) */
#define DIFF_LEGEND                                                                                                    \
    "black 0, purple 0.06, red 0.12, orange 0.19, yellow 0.25 of the display's full scale, white 0.31 and more"

static const bench_approximation APPROXIMATIONS[] = {
#define X(knob, off, on, what) {knob, off, on, what},
    BENCH_APPROXIMATIONS(X)
#undef X
};
enum { APPROXIMATION_COUNT = sizeof APPROXIMATIONS / sizeof APPROXIMATIONS[0] };

const bench_approximation *bench_approximation_of(const char *knob)
{
    for (int k = 0; k < APPROXIMATION_COUNT; k++)
        if (!strcmp(APPROXIMATIONS[k].knob, knob))
            return &APPROXIMATIONS[k];
    return NULL;
}

/* The rows of approximation a's sweep: its off and on settings, or NULL. */
static void approximation_rows(const bench_results *r, const bench_approximation *a, const bench_row **off,
                               const bench_row **on)
{
    *off = *on = NULL;
    for (int i = 0; i < r->nrows; i++)
        if (!strcmp(r->rows[i].knob, a->knob)) {
            if (!strcmp(r->rows[i].value, a->off))
                *off = &r->rows[i];
            else if (!strcmp(r->rows[i].value, a->on))
                *on = &r->rows[i];
        }
}

/* One sentence per model approximation the run priced (those with both rows), into s[k]: what switching
 * it on costs in time and what it does to the error against the reference (the truth with --truth
 * path); off[k] and on[k] get its rows. Returns how many. */
typedef char sentence[512];
static int approximation_sentences(const bench_results *r, sentence *s, const bench_row **offs, const bench_row **ons)
{
    int n = 0;
    for (int k = 0; k < APPROXIMATION_COUNT; k++) {
        const bench_row *off, *on;
        approximation_rows(r, &APPROXIMATIONS[k], &off, &on);
        if (!off || !on)
            continue;
        char d[48], cost[64];
        bench_difference(off->ms_lo, off->ms_hi, on->ms_lo, on->ms_hi, off->ms, on->ms, d, sizeof d);
        if (strcmp(d, "not measurable"))
            snprintf(cost, sizeof cost, "costs %s an image", d);
        else
            snprintf(cost, sizeof cost, "costs no measurable time");
        double change = off->m.rmse > 0 ? 100 * (on->m.rmse - off->m.rmse) / off->m.rmse : 0;
        snprintf(s[n], sizeof s[n],
                 "%s (%s=%s) %s (%.1f ms [%.1f–%.1f] against %.1f [%.1f–%.1f] without); its image is RMSE %.4f "
                 "from %s, without %.4f: with it %.0f %% %s",
                 APPROXIMATIONS[k].what, APPROXIMATIONS[k].knob, APPROXIMATIONS[k].on, cost, on->ms, on->ms_lo,
                 on->ms_hi, off->ms, off->ms_lo, off->ms_hi, on->m.rmse,
                 r->opt->path_truth ? "the truth" : "the reference", off->m.rmse, fabs(change),
                 change <= 0 ? "nearer" : "further");
        offs[n] = off;
        ons[n++] = on;
    }
    return n;
}

static void approximations_md(const bench_results *r, FILE *f)
{
    sentence s[APPROXIMATION_COUNT];
    const bench_row *off[APPROXIMATION_COUNT], *on[APPROXIMATION_COUNT];
    int n = approximation_sentences(r, s, off, on);
    if (n == 0)
        return;
    fprintf(f, "## The model's approximations against %s\n\n",
            r->opt->path_truth ? "the truth (the path tracer)" : "the reference");
    for (int k = 0; k < n; k++) {
        fprintf(f, "- %s.", s[k]);
        if (on[k]->diff[0] && off[k]->diff[0])
            fprintf(f, " Where it differs, without and with: ![without](%s) ![with](%s)", off[k]->diff, on[k]->diff);
        fprintf(f, "\n");
    }
    fprintf(f, "\nDifference images: the largest channel's difference per pixel of the first view, %s; against "
               "![the reference](%s-reference.png).\n\n", DIFF_LEGEND, bench_run_prefix(r));
}

static bool write_summary(const bench_results *r, err_t *err)
{
    util_atomic a;
    if (!bench_open_out(r, "summary.md", &a, err))
        return false;
    FILE *f = a.f;
    summary_header(r, f);
    fprintf(f, "![the presets and the Pareto front](%s-overview.png)\n\n![each knob alone](%s-plot.png)\n\n",
            bench_run_prefix(r), bench_run_prefix(r));
    approximations_md(r, f);
    fprintf(f, "| knob | value | ms/image | RMSE | edge RMSE | PSNR dB | depth mean (fp) | depth max (fp) | flips %% | "
               "IoU | edge px | steps/px | out of steps %% |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        fprintf(f, "| %s | %s%s | %.1f [%.1f–%.1f] | %.4f | %.4f | %.1f | %.3f | %.2f | %.2f | %.4f | %.1f | %.1f | %.2f |\n",
                w->knob, w->value, w->front ? " *" : "", w->ms, w->ms_lo, w->ms_hi, w->m.rmse, w->m.edge_rmse, w->m.psnr_db,
                w->m.depth_mean_fp, w->m.depth_max_fp, 100 * w->m.flip_share, w->m.iou, w->m.edge_max_px,
                w->m.mean_steps, 100 * w->m.exhausted_share);
    }
    fprintf(f, "\n## Effects: compiled in, compiled out, compiled in but switched off\n\n"
               "ms per 1-spp frame at the start view: the median of %d runs, the three timed in turn run after run, "
               "and [the interval that holds the median with at least 95 %% confidence; the whole range below 6 "
               "runs]. A difference is given only where the intervals part. *In scene*: the scene calls for it (so "
               "fathom compiles it).\n\n"
               "| effect | in scene | compiled out | compiled in | compiled in, off at run time | in vs out | "
               "in, off vs out |\n|---|---|---|---|---|---|---|\n",
            r->opt->runs);
    for (int e = 0; e < EFFECT_COUNT; e++) {
        const effect_row *x = &r->fx[e];
        char d1[48], d2[48];
        fprintf(f, "| %s | %s | %.1f [%.1f–%.1f] | %.1f [%.1f–%.1f] | %.1f [%.1f–%.1f] | %s | %s |\n", effect_name(x->e),
                x->in_scene ? "yes" : "no", x->out_ms, x->out_lo, x->out_hi, x->in_ms, x->in_lo, x->in_hi, x->in_off_ms,
                x->in_off_lo, x->in_off_hi,
                bench_difference(x->out_lo, x->out_hi, x->in_lo, x->in_hi, x->out_ms, x->in_ms, d1, sizeof d1),
                bench_difference(x->out_lo, x->out_hi, x->in_off_lo, x->in_off_hi, x->out_ms, x->in_off_ms, d2,
                                 sizeof d2));
    }
    return util_atomic_commit(&a, err);
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

void bench_write_difference(const bench_desc *opt, int w, int h, const char *knob, const char *value,
                            const uint8_t *test, const uint8_t *ref, char *name, size_t n)
{
    char prefix[BENCH_PREFIX_MAX], k[sizeof ((bench_row *)0)->knob], v[sizeof ((bench_row *)0)->value];
    char path[PATH_MAX_LEN];
    bench_prefix(opt, prefix, sizeof prefix);
    bench_safe_name(knob, k, sizeof k), bench_safe_name(value, v, sizeof v); /* "../x" is a file name here */
    snprintf(name, n, "%s-diff-%s-%s.png", prefix, k, v);
    snprintf(path, sizeof path, "%s/%s", opt->out, name);
    size_t px = (size_t)w * (size_t)h;
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
    if (!image_write_u8(path, w, h, 3, img, &err)) {
        fprintf(stderr, "\nfathom bench: %s (the report goes on without it)\n", err.msg);
        name[0] = 0;
    }
    free(img);
}

/* ---- the HTML report: one self-contained page (its plots inline) --------------------------------- */

/* The file at path as an <img> with a base64 data URI (RFC 4648); nothing when it cannot be read. */
static void inline_png(FILE *f, const char *path, const char *alt)
{
    static const char B64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *data = NULL;
    size_t n = 0;
    err_t e;
    if (!util_read_file(path, &data, &n, &e))
        return;
    fprintf(f, "<img alt=\"%s\" src=\"data:image/png;base64,", alt);
    const unsigned char *b = (const unsigned char *)data;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)b[i] << 16 | (i + 1 < n ? (unsigned)b[i + 1] << 8 : 0) | (i + 2 < n ? b[i + 2] : 0);
        fputc(B64[v >> 18 & 63], f);
        fputc(B64[v >> 12 & 63], f);
        fputc(i + 1 < n ? B64[v >> 6 & 63] : '=', f);
        fputc(i + 2 < n ? B64[v & 63] : '=', f);
    }
    fprintf(f, "\">\n");
    free(data);
}

/* Text into HTML: & < > escaped. */
static void html_text(FILE *f, const char *s)
{
    for (; *s; s++)
        fputs(*s == '&' ? "&amp;" : *s == '<' ? "&lt;" : *s == '>' ? "&gt;" : (char[]){*s, 0}, f);
}

static void html_tables(const bench_results *r, FILE *f)
{
    fprintf(f, "<h2>Each knob alone, and the presets</h2>\n<p>Time: the median [and its 95 %% interval] of %d "
               "images. &#9733;: on the Pareto front (no setting measurably faster and no worse, or better and not "
               "measurably slower).</p>\n<table>\n<tr><th>knob</th><th>value</th><th>ms per image</th><th>RMSE</th>"
               "<th>edge RMSE</th><th>PSNR dB</th><th>depth mean / max (fp)</th><th>flips %%</th><th>IoU</th>"
               "<th>steps/px</th><th>out of steps %%</th></tr>\n",
            r->opt->runs);
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        fprintf(f, "<tr%s><td>", w->front ? " class=\"front\"" : "");
        html_text(f, w->knob);
        fprintf(f, "</td><td>");
        html_text(f, w->value);
        fprintf(f, "%s</td><td>%.1f [%.1f&ndash;%.1f]</td><td>%.4f</td><td>%.4f</td><td>%.1f</td><td>%.3f / %.2f</td>"
                   "<td>%.2f</td><td>%.4f</td><td>%.1f</td><td>%.2f</td></tr>\n",
                w->front ? " &#9733;" : "", w->ms, w->ms_lo, w->ms_hi, w->m.rmse, w->m.edge_rmse, w->m.psnr_db,
                w->m.depth_mean_fp, w->m.depth_max_fp, 100 * w->m.flip_share, w->m.iou, w->m.mean_steps,
                100 * w->m.exhausted_share);
    }
    fprintf(f, "</table>\n<h2>Effects: compiled out, compiled in, compiled in but off</h2>\n<p>ms per 1-spp frame, "
               "median [95 %% interval] of %d runs taken in turn; a difference only where the intervals part.</p>\n"
               "<table>\n<tr><th>effect</th><th>in scene</th><th>out</th><th>in</th><th>in, off</th>"
               "<th>in vs out</th></tr>\n",
            r->opt->runs);
    for (int e = 0; e < EFFECT_COUNT; e++) {
        const effect_row *x = &r->fx[e];
        char d[48];
        fprintf(f, "<tr><td>%s</td><td>%s</td><td>%.1f [%.1f&ndash;%.1f]</td><td>%.1f [%.1f&ndash;%.1f]</td>"
                   "<td>%.1f [%.1f&ndash;%.1f]</td><td>%s</td></tr>\n",
                effect_name(x->e), x->in_scene ? "yes" : "no", x->out_ms, x->out_lo, x->out_hi, x->in_ms, x->in_lo,
                x->in_hi, x->in_off_ms, x->in_off_lo, x->in_off_hi,
                bench_difference(x->out_lo, x->out_hi, x->in_lo, x->in_hi, x->out_ms, x->in_ms, d, sizeof d));
    }
    fprintf(f, "</table>\n");
}

/* The model's approximations in sentences, then the reference beside every difference image. */
static void html_differences(const bench_results *r, FILE *f)
{
    sentence s[APPROXIMATION_COUNT];
    const bench_row *off[APPROXIMATION_COUNT], *on[APPROXIMATION_COUNT];
    int n = approximation_sentences(r, s, off, on);
    if (n > 0)
        fprintf(f, "<h2>The model's approximations against %s</h2>\n<ul>\n",
                r->opt->path_truth ? "the truth (the path tracer)" : "the reference");
    for (int k = 0; k < n; k++) {
        fprintf(f, "<li>");
        html_text(f, s[k]);
        fprintf(f, ".</li>\n");
    }
    if (n > 0)
        fprintf(f, "</ul>\n");
    bool diffs = false;
    for (int i = 0; i < r->nrows && !diffs; i++)
        diffs = r->rows[i].diff[0] != 0;
    if (!diffs)
        return;
    char png[PATH_MAX_LEN];
    fprintf(f, "<h2>Where the error goes</h2>\n<p>The first view: the reference, then per setting the largest "
               "channel's difference from it per pixel (%s) and its RMSE.</p>\n<div class=\"grid\"><figure>",
            DIFF_LEGEND);
    snprintf(png, sizeof png, "%s/%s-reference.png", r->opt->out, bench_run_prefix(r));
    inline_png(f, png, "the reference");
    fprintf(f, "<figcaption>the reference</figcaption></figure>\n");
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        if (!w->diff[0])
            continue;
        fprintf(f, "<figure>");
        snprintf(png, sizeof png, "%s/%s", r->opt->out, w->diff);
        inline_png(f, png, w->diff);
        fprintf(f, "<figcaption>");
        html_text(f, w->knob);
        fprintf(f, " = ");
        html_text(f, w->value);
        fprintf(f, ": RMSE %.4f, %.1f ms</figcaption></figure>\n", w->m.rmse, w->ms);
    }
    fprintf(f, "</div>\n");
}

static bool write_html(const bench_results *r, err_t *err)
{
    char png[PATH_MAX_LEN];
    util_atomic a;
    if (!bench_open_out(r, "report.html", &a, err))
        return false;
    FILE *f = a.f;
    fprintf(f, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>What accuracy costs: ");
    html_text(f, bench_run_prefix(r));
    fprintf(f, "</title>\n<style>body{font:14px sans-serif;margin:2em;max-width:1200px}"
               "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:2px 8px;"
               "text-align:right}td:first-child,th:first-child{text-align:left}tr.front{background:#eef5e9}"
               "img{max-width:100%%;display:block;margin:1em 0}.grid{display:flex;flex-wrap:wrap;gap:12px}"
               ".grid figure{margin:0;width:320px}.grid img{margin:0;width:100%%;image-rendering:pixelated}"
               "figcaption{font-size:12px}</style></head><body>\n<h1>What accuracy costs: ");
    html_text(f, bench_run_prefix(r));
    fprintf(f, "</h1>\n<p>");
    html_text(f, r->base->title);
    fprintf(f, ". %dx%d, %d views, fathom %s, ", r->w, r->h, r->views, FATHOM_VERSION);
    html_text(f, gpu_describe());
    fprintf(f, ". Error against %s at %d spp (%.0f ms per image), which a stricter render matches to RMSE %.5f. "
               "Every knob starts from the scene's <code>%s</code> preset.</p>\n",
            r->opt->path_truth ? "the path tracer (the truth: <code>quality.integrator=1</code>)"
                               : "the <code>reference</code> preset",
            r->ref_spp, r->ref_ms, r->conv->rmse, preset_name(r->base->preset));
    snprintf(png, sizeof png, "%s/%s-overview.png", r->opt->out, bench_run_prefix(r));
    inline_png(f, png, "the presets and the Pareto front");
    snprintf(png, sizeof png, "%s/%s-plot.png", r->opt->out, bench_run_prefix(r));
    inline_png(f, png, "each knob alone");
    html_differences(r, f);
    html_tables(r, f);
    fprintf(f, "</body></html>\n");
    return util_atomic_commit(&a, err);
}

bool bench_write_pages(const bench_results *r, err_t *err) { return write_summary(r, err) && write_html(r, err); }
