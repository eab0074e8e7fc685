#include "jobs/bench_report.h"

#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/gpu.h"

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

void bench_print(const bench_results *r)
{
    printf("%s, %dx%d, %s; reference converged to RMSE %.5f\n", r->opt->scene, r->w, r->h, gpu_describe(),
           r->conv->rmse);
    printf("%-16s %-10s %10s %8s %8s %8s %10s %10s %7s %8s %8s %7s %7s\n", "knob", "value", "ms/image", "RMSE",
           "edgeRMSE", "PSNR", "depth fp", "max fp", "flips%", "IoU", "edge px", "steps", "out%");
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        printf("%-16s %-10s %10.1f %8.4f %8.4f %8.1f %10.3f %10.2f %7.2f %8.4f %8.1f %7.1f %7.2f%s\n", w->knob,
               w->value, w->ms, w->m.rmse, w->m.edge_rmse, w->m.psnr_db, w->m.depth_mean_fp, w->m.depth_max_fp,
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


static const char *prefix(const bench_results *r) { return r->opt->name ? r->opt->name : r->opt->scene; }

static FILE *open_out(const bench_results *r, const char *name, char *path, err_t *err)
{
    snprintf(path, PATH_MAX_LEN, "%s/%s-%s", r->opt->out, prefix(r), name);
    FILE *f = fopen(path, "w");
    if (!f)
        err_set(err, "cannot write '%s': check that --out '%s' is a writable folder", path, r->opt->out);
    return f;
}

static void knob_csv(const bench_results *r, FILE *f)
{
    fprintf(f, "scene,width,height,views,knob,value,ms_per_image,rmse,psnr_db,depth_mean_fp,depth_max_fp,"
               "flip_share,iou,edge_max_px,mean_steps,out_of_steps_share,edge_rmse,pareto\n");
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        fprintf(f, "%s,%d,%d,%d,%s,%s,%.3f,%.6f,%.3f,%.4f,%.4f,%.6f,%.6f,%.2f,%.3f,%.6f,%.6f,%d\n", r->opt->scene,
                r->w, r->h, r->views, w->knob, w->value, w->ms, w->m.rmse, isinf(w->m.psnr_db) ? 999.0 : w->m.psnr_db,
                w->m.depth_mean_fp, w->m.depth_max_fp, w->m.flip_share, w->m.iou, w->m.edge_max_px, w->m.mean_steps,
                w->m.exhausted_share, w->m.edge_rmse, w->front);
    }
}

bool bench_write_rows(const bench_results *r, err_t *err)
{
    char path[PATH_MAX_LEN], part[PATH_MAX_LEN + 8];
    FILE *f = open_out(r, "knobs.csv.part", part, err);
    if (!f)
        return false;
    knob_csv(r, f);
    bool ok = fclose(f) == 0;
    snprintf(path, sizeof path, "%s/%s-knobs.csv", r->opt->out, prefix(r));
    if (!ok || rename(part, path) != 0) {
        remove(part);
        return err_set(err, "cannot write '%s': is the disk full?", path);
    }
    return true;
}

static bool write_csv(const bench_results *r, err_t *err)
{
    char path[PATH_MAX_LEN];
    if (!bench_write_rows(r, err))
        return false;
    FILE *f = open_out(r, "effects.csv", path, err);
    if (!f)
        return false;
    fprintf(f, "scene,effect,in_scene,ms_compiled_out,ms_compiled_in,ms_compiled_in_switched_off,out_lo,out_hi,in_lo,"
               "in_hi,in_off_lo,in_off_hi\n");
    for (int e = 0; e < EFFECT_COUNT; e++)
        fprintf(f, "%s,%s,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n", r->opt->scene, effect_name(r->fx[e].e),
                r->fx[e].in_scene, r->fx[e].out_ms, r->fx[e].in_ms, r->fx[e].in_off_ms, r->fx[e].out_lo, r->fx[e].out_hi,
                r->fx[e].in_lo, r->fx[e].in_hi, r->fx[e].in_off_lo, r->fx[e].in_off_hi);
    fclose(f);
    return true;
}

static int by_time(const void *a, const void *b)
{
    double ta = (*(const bench_row *const *)a)->ms, tb = (*(const bench_row *const *)b)->ms;
    return (ta > tb) - (ta < tb);
}

/* gnuplot data: one block per knob, the Pareto front (sorted by time) last. Returns the knob count. */
static int write_plot_data(const bench_results *r, FILE *f, char (*knobs)[32], int max_knobs)
{
    int nk = 0;
    for (int i = 0; i < r->nrows; i++) {
        if ((nk == 0 || strcmp(knobs[nk - 1], r->rows[i].knob)) && nk < max_knobs) {
            if (nk)
                fprintf(f, "\n\n");
            snprintf(knobs[nk++], 32, "%s", r->rows[i].knob);
        }
        fprintf(f, "%.4f %.6f %s\n", r->rows[i].ms, fmax(r->rows[i].m.rmse, 1e-5), r->rows[i].value);
    }
    fprintf(f, "\n\n");
    const bench_row **front = util_alloc(sizeof *front * (size_t)(r->nrows + 1), "the bench report");
    int n = 0;
    for (int i = 0; i < r->nrows; i++)
        if (r->rows[i].front)
            front[n++] = &r->rows[i];
    qsort(front, (size_t)n, sizeof *front, by_time);
    for (int i = 0; i < n; i++)
        fprintf(f, "%.4f %.6f %s=%s\n", front[i]->ms, fmax(front[i]->m.rmse, 1e-5), front[i]->knob, front[i]->value);
    free(front);
    return nk;
}

static bool write_plot(const bench_results *r, err_t *err)
{
    enum { MAX_KNOBS = 64 };
    char dat[PATH_MAX_LEN], gp[PATH_MAX_LEN], png[PATH_MAX_LEN], knobs[MAX_KNOBS][32];
    FILE *f = open_out(r, "plot.dat", dat, err);
    if (!f)
        return false;
    int nk = write_plot_data(r, f, knobs, MAX_KNOBS);
    fclose(f);
    f = open_out(r, "plot.gp", gp, err);
    if (!f)
        return false;
    snprintf(png, sizeof png, "%s/%s-plot.png", r->opt->out, prefix(r));
    fprintf(f, "set terminal pngcairo size 960,620 font ',10'\nset output '%s'\n", png);
    fprintf(f, "set title \"%s: error against time, each knob swept alone (%dx%d, %.40s)\" noenhanced\n",
            r->opt->scene, r->w, r->h, (const char *)glGetString(GL_RENDERER));
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
    return true;
}

static void summary_header(const bench_results *r, FILE *f)
{
    const cli_options *o = r->opt;
    const metrics *c = r->conv;
    fprintf(f, "# What accuracy costs: %s\n\n", prefix(r));
    strbuf sets = {0};
    for (int i = 0; i < o->set_count; i++)
        sb_printf(&sets, " --set %s", o->sets[i]);
    fprintf(f, "%s. %dx%d, %d views (the start camera, and turned %.0f° about the look-at point), median of %d "
               "images after a warm-up, on %s. Made by `fathom bench --scene %s --size %dx%d --runs %d%s --out DIR`.\n\n",
            r->base->title, r->w, r->h, r->views, (double)r->view_turn_deg, o->runs, gpu_describe(), o->scene, r->w,
            r->h, o->runs, sets.data ? sets.data : "");
    sb_free(&sets);
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
               "the scene's `%s` preset. `*` marks the Pareto front (no setting is both faster and closer). Settings "
               "of 64 spp or more are timed once per view.\n\n",
            preset_name(r->base->preset));
}

static bool write_summary(const bench_results *r, err_t *err)
{
    char path[PATH_MAX_LEN];
    FILE *f = open_out(r, "summary.md", path, err);
    if (!f)
        return false;
    summary_header(r, f);
    fprintf(f, "![error against time](%s-plot.png)\n\n", prefix(r));
    fprintf(f, "| knob | value | ms/image | RMSE | edge RMSE | PSNR dB | depth mean (fp) | depth max (fp) | flips %% | "
               "IoU | edge px | steps/px | out of steps %% |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        fprintf(f, "| %s | %s%s | %.1f | %.4f | %.4f | %.1f | %.3f | %.2f | %.2f | %.4f | %.1f | %.1f | %.2f |\n",
                w->knob, w->value, w->front ? " *" : "", w->ms, w->m.rmse, w->m.edge_rmse, w->m.psnr_db,
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
    fclose(f);
    return true;
}

bool bench_write(const bench_results *r, err_t *err)
{
    return write_csv(r, err) && write_plot(r, err) && write_summary(r, err);
}
