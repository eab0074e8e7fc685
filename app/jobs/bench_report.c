#include "jobs/bench_report.h"

#include <errno.h>
#include <stdint.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "data/image_io.h"
#include "gpu/gpu.h"
#include "jobs/gnuplot.h"
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

void bench_prefix(const cli_options *o, char *out, size_t n)
{
    const char *s = o->name ? o->name : o->scene, *slash = strrchr(s, '/'), *base = slash ? slash + 1 : s;
    const char *dot = strrchr(base, '.');
    char stem[BENCH_PREFIX_MAX];
    snprintf(stem, sizeof stem, "%.*s", (int)(dot && dot > base && !o->name ? dot - base : (long)strlen(base)),
             base);
    bench_safe_name(stem, out, n);
}

/* The run's file-name prefix (one run at a time) */
static const char *prefix(const bench_results *r)
{
    static char p[BENCH_PREFIX_MAX];
    bench_prefix(r->opt, p, sizeof p);
    return p;
}

/* The scene in the CSV files and the table: its base name made safe, whatever --name says */
static const char *scene_label(const bench_results *r)
{
    static char p[BENCH_PREFIX_MAX];
    cli_options o = {.scene = r->opt->scene};
    bench_prefix(&o, p, sizeof p);
    return p;
}

/* OUT/PREFIX-name, opened as a new temporary file beside it (util_atomic: renamed over it when whole) */
static bool open_out(const bench_results *r, const char *name, util_atomic *a, err_t *err)
{
    char path[PATH_MAX_LEN];
    if (snprintf(path, sizeof path, "%s/%s-%s", r->opt->out, prefix(r), name) >= (int)sizeof path)
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
    if (!open_out(r, "knobs.csv", &a, err))
        return false;
    knob_csv(r, a.f);
    return util_atomic_commit(&a, err);
}

static bool write_csv(const bench_results *r, err_t *err)
{
    util_atomic a;
    if (!bench_write_rows(r, err) || !open_out(r, "effects.csv", &a, err))
        return false;
    fprintf(a.f, "scene,effect,in_scene,ms_compiled_out,ms_compiled_in,ms_compiled_in_switched_off,out_lo,out_hi,"
                 "in_lo,in_hi,in_off_lo,in_off_hi\n");
    for (int e = 0; e < EFFECT_COUNT; e++)
        fprintf(a.f, "%s,%s,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n", scene_label(r), effect_name(r->fx[e].e),
                r->fx[e].in_scene, r->fx[e].out_ms, r->fx[e].in_ms, r->fx[e].in_off_ms, r->fx[e].out_lo,
                r->fx[e].out_hi, r->fx[e].in_lo, r->fx[e].in_hi, r->fx[e].in_off_lo, r->fx[e].in_off_hi);
    return util_atomic_commit(&a, err);
}

static int by_time(const void *a, const void *b)
{
    double ta = (*(const bench_row *const *)a)->ms, tb = (*(const bench_row *const *)b)->ms;
    return (ta > tb) - (ta < tb);
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

/* The rows on the Pareto front, sorted by time (n of them; the caller frees the array) */
static const bench_row **pareto_front(const bench_results *r, int *n)
{
    const bench_row **front = util_alloc(sizeof *front * (size_t)(r->nrows + 1), "the bench report");
    *n = 0;
    for (int i = 0; i < r->nrows; i++)
        if (r->rows[i].front)
            front[(*n)++] = &r->rows[i];
    qsort(front, (size_t)*n, sizeof *front, by_time);
    return front;
}

/* gnuplot data: one block per knob (ms, RMSE, value, ms_lo, ms_hi), then the Pareto front sorted by
 * time (ms, RMSE). Returns the knob count. */
static int write_plot_data(const bench_results *r, FILE *f, char (*knobs)[32], int max_knobs)
{
    int nk = 0;
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        if ((nk == 0 || strcmp(knobs[nk - 1], w->knob)) && nk < max_knobs) {
            if (nk)
                fprintf(f, "\n\n");
            snprintf(knobs[nk++], 32, "%s", w->knob);
        }
        char value[sizeof w->value];
        bench_safe_name(w->value, value, sizeof value); /* one column, whatever the value holds */
        fprintf(f, "%.4f %.6f %s %.4f %.4f\n", w->ms, fmax(w->m.rmse, 1e-5), value, w->ms_lo, w->ms_hi);
    }
    fprintf(f, "\n\n");
    int n;
    const bench_row **front = pareto_front(r, &n);
    for (int i = 0; i < n; i++)
        fprintf(f, "%.4f %.6f\n", front[i]->ms, fmax(front[i]->m.rmse, 1e-5));
    free(front);
    return nk;
}

/* ---- placing labels where they can be read ------------------------------------------------------ */

/* An axis as drawn: its range and whether it is logarithmic. Log only where the values span more than
 * a decade (within one a log axis has no labelled tic); a flat response is drawn flat, not blown up. */
typedef struct axis_range {
    double lo, hi;
    bool log;
} axis_range;

static axis_range axis_fit(double lo, double hi, double pad)
{
    axis_range a = {lo, hi, lo > 0 && hi > 10 * lo};
    if (a.log) {
        double l = log10(lo), h = log10(hi), d = pad * (h - l);
        a.lo = pow(10, l - d), a.hi = pow(10, h + d);
        return a;
    }
    double mid = 0.5 * (lo + hi), span = fmax(hi - lo, 0.16 * fabs(hi));
    span = span > 0 ? span : 1;
    a.lo = mid - (0.5 + pad) * span, a.hi = mid + (0.5 + pad) * span;
    if (a.lo < 0 && lo >= 0) /* times and errors are not negative: the axis starts at 0 */
        a.hi -= a.lo, a.lo = 0;
    return a;
}

static double axis_px(const axis_range *a, double v, double size)
{
    return a->log ? (log10(v) - log10(a->lo)) / (log10(a->hi) - log10(a->lo)) * size
                  : (v - a->lo) / (a->hi - a->lo) * size;
}

static double axis_value(const axis_range *a, double px, double size)
{
    return a->log ? pow(10, log10(a->lo) + px / size * (log10(a->hi) - log10(a->lo)))
                  : a->lo + px / size * (a->hi - a->lo);
}

/* the width of v's tic label in characters */
static int strlen_g(double v)
{
    char t[32];
    return snprintf(t, sizeof t, "%g", v);
}

/* gnuplot commands for one axis ("x" or "y", size pixels long): its range, scale and tics (about four
 * at round steps on a linear axis) */
static void axis_set(FILE *f, const char *name, const axis_range *a, double size)
{
    fprintf(f, "%s logscale %s\nset %srange [%.9g:%.9g]\n", a->log ? "set" : "unset", name, name, a->lo, a->hi);
    if (a->log) { /* each decade, then 5 and 2 of each where their labels have room (size: the axis in pixels) */
        static const int MULT[] = {1, 5, 2};
        bool x = name[0] == 'x'; /* x labels side by side (their width), y labels stacked (a line) */
        double at[64][2];
        int n = 0;
        for (int i = 0; i < 3; i++)
            for (double d = pow(10, floor(log10(a->lo))); d <= a->hi && n < 64; d *= 10) {
                double v = d * MULT[i], px = axis_px(a, v, size), room = x ? 0.5 * (strlen_g(v) * 7 + 14) : 8;
                bool free = v >= a->lo && v <= a->hi;
                for (int k = 0; free && k < n; k++)
                    free = fabs(px - at[k][1]) > room + (x ? 0.5 * (strlen_g(at[k][0]) * 7 + 14) : 8);
                if (free)
                    at[n][0] = v, at[n++][1] = px;
            }
        fprintf(f, "set %stics (", name);
        for (int k = 0; k < n; k++)
            fprintf(f, "%s%.9g", k ? ", " : "", at[k][0]);
        fprintf(f, ")\n");
        return;
    }
    double raw = (a->hi - a->lo) / 4, p = pow(10, floor(log10(raw))), m = raw / p;
    fprintf(f, "set %stics %.9g\n", name, (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p);
}

typedef struct box {
    double x0, y0, x1, y1;
} box;

enum { MAX_BOXES = 4096, MAX_ANCHORS = 512 };
typedef struct label_space {
    double w, h;                   /* the plot area in pixels */
    double cw, ch;                 /* a character's width and a line's height at the labels' font */
    box taken[MAX_BOXES];          /* what a label must not cover: points, lines, labels placed */
    int n;
    double anchor[MAX_ANCHORS][2]; /* the labelled points: a label sits nearer its own than any other */
    int na;
} label_space;

static void take(label_space *ls, double x0, double y0, double x1, double y1)
{
    if (ls->n < MAX_BOXES)
        ls->taken[ls->n++] = (box){fmin(x0, x1), fmin(y0, y1), fmax(x0, x1), fmax(y0, y1)};
}

/* A line drawn from (x0, y0) to (x1, y1): boxes along it every 3 pixels, 2 pixels either side */
static void take_line(label_space *ls, double x0, double y0, double x1, double y1)
{
    int steps = (int)ceil(hypot(x1 - x0, y1 - y0) / 3);
    for (int i = 0; i <= steps; i++) {
        double t = steps ? (double)i / steps : 0, x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
        take(ls, x - 2, y - 2, x + 2, y + 2);
    }
}

static void anchor(label_space *ls, double px, double py)
{
    if (ls->na < MAX_ANCHORS)
        ls->anchor[ls->na][0] = px, ls->anchor[ls->na++][1] = py;
}

/* The first of the places around the point (px, py) where a label of len characters fits inside the
 * plot, over nothing taken, and (with nearest) nearer its point than any other labelled point, so it
 * cannot be read as another's (the presets' names go without: few and far apart): above, below,
 * right, left, the diagonals, then further out. Its centre into (cx, cy), and the place is taken;
 * false where none is (the label is left out: the table has every value). */
static bool place(label_space *ls, double px, double py, int len, double scale, bool nearest, double *cx, double *cy)
{
    double hw = 0.5 * len * ls->cw * scale + 2, hh = 0.5 * ls->ch * scale + 1, g = 5;
    const double at[][2] = {{0, g + hh},          {0, -g - hh},         {g + hw, 0},          {-g - hw, 0},
                            {g + hw, -g - hh},    {g + hw, g + hh},     {-g - hw, -g - hh},   {-g - hw, g + hh},
                            {0, 2 * g + 3 * hh}, {0, -2 * g - 3 * hh}, {2 * g + hw, -2 * hh}, {-2 * g - hw, 2 * hh}};
    for (size_t i = 0; i < sizeof at / sizeof at[0]; i++) {
        double x = px + at[i][0], y = py + at[i][1];
        box b = {x - hw, y - hh, x + hw, y + hh};
        bool free = b.x0 >= 0 && b.y0 >= 0 && b.x1 <= ls->w && b.y1 <= ls->h;
        for (int k = 0; free && k < ls->n; k++)
            free = !(b.x0 < ls->taken[k].x1 && ls->taken[k].x0 < b.x1 && b.y0 < ls->taken[k].y1 &&
                     ls->taken[k].y0 < b.y1);
        /* nearest: from the label's box to each point, its own within a pixel */
        double own = hypot(fmax(0, fabs(x - px) - hw), fmax(0, fabs(y - py) - hh));
        for (int k = 0; free && nearest && k < ls->na; k++) {
            double qx = ls->anchor[k][0], qy = ls->anchor[k][1];
            if (hypot(qx - px, qy - py) > 1)
                free = hypot(fmax(0, fabs(x - qx) - hw), fmax(0, fabs(y - qy) - hh)) > own + 1;
        }
        if (free) {
            *cx = x, *cy = y;
            take(ls, b.x0, b.y0, b.x1, b.y1);
            return true;
        }
    }
    return false;
}

/* A label in data coordinates from its centre in pixels */
static void label_at(FILE *f, const axis_range *ax, const axis_range *ay, const label_space *ls, double cx, double cy,
                     const char *text, const char *style)
{
    fputs("set label ", f);
    gnuplot_string(f, text);
    fprintf(f, " at %.9g,%.9g centre %s noenhanced front\n", axis_value(ax, cx, ls->w),
            axis_value(ay, cy, ls->h), style);
}

/* Small multiples: one panel a knob, each point labelled with its value where the label can be read,
 * the time's interval as a bar, the scene's preset value ringed; lower left is better in every panel.
 * Panels are 380x300 pixels, their plot areas about 300x225. */
static void small_multiples(const bench_results *r, FILE *f, const char *dat, const char *png, char (*knobs)[32],
                            int nk)
{
    static const char *const COLOURS[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02",
                                          "#a6761d", "#666666"};
    int cols = nk < 3 ? nk : 3, rows = (nk + cols - 1) / cols;
    fprintf(f, "set terminal pngcairo size %d,%d font ',9'\nset output ", 380 * cols, 300 * rows + 55);
    gnuplot_string(f, png);
    char title[512];
    snprintf(title, sizeof title, "%s, %dx%d, %.40s: colour error against time, each knob swept alone from the %s "
             "preset\nBetter: down and left. Ring: the preset's value. Bars: the time's 95 %% interval.\nCompare "
             "times within a panel (its settings were timed in turn); between panels the machine's load drifts.",
             prefix(r), r->w, r->h, (const char *)glGetString(GL_RENDERER), preset_name(r->base->preset));
    fprintf(f, "\nset multiplot layout %d,%d title ", rows, cols);
    gnuplot_string(f, title);
    fprintf(f, " noenhanced font ',10'\n");
    fprintf(f, "set grid\nunset key\nset xlabel 'ms per image' offset 0,0.5\nset ylabel 'RMSE' offset 0.5,0\n"
               "set format y '%%g'\nset format x '%%g'\nset lmargin 11\nset rmargin 2\n");
    for (int k = 0; k < nk; k++) {
        const char *c = COLOURS[k % (int)(sizeof COLOURS / sizeof COLOURS[0])];
        char base[64];
        bench_base_value(r->base, knobs[k], base, sizeof base);
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {0, 0}, e_lo = INFINITY, e_hi = 0;
        for (int i = 0; i < r->nrows; i++)
            if (!strcmp(r->rows[i].knob, knobs[k])) {
                const bench_row *w = &r->rows[i];
                lo[0] = fmin(lo[0], fmin(w->ms_lo, w->ms)), hi[0] = fmax(hi[0], fmax(w->ms_hi, w->ms));
                double e = fmax(w->m.rmse, 1e-5);
                lo[1] = fmin(lo[1], e), hi[1] = fmax(hi[1], e);
                e_lo = fmin(e_lo, w->m.rmse), e_hi = fmax(e_hi, w->m.rmse);
            }
        axis_range ax = axis_fit(lo[0], hi[0], 0.1), ay = axis_fit(lo[1], hi[1], 0.2);
        fprintf(f, "unset label\nset title ");
        gnuplot_string(f, knobs[k]);
        fprintf(f, " noenhanced font ',11'\n");
        axis_set(f, "x", &ax, 280);
        axis_set(f, "y", &ay, 225);
        label_space ls = {.w = 300, .h = 225, .cw = 5.2, .ch = 10};
        double last[2] = {NAN, NAN};
        for (int i = 0; i < r->nrows; i++) /* the points, rings and lines first: no label covers them */
            if (!strcmp(r->rows[i].knob, knobs[k])) {
                const bench_row *w = &r->rows[i];
                double px = axis_px(&ax, w->ms, ls.w), py = axis_px(&ay, fmax(w->m.rmse, 1e-5), ls.h);
                anchor(&ls, px, py);
                if (!isnan(last[0]))
                    take_line(&ls, last[0], last[1], px, py);
                last[0] = px, last[1] = py;
                double rad = bench_same_value(w->value, base) ? 11 : 3.5;
                take(&ls, px - rad, py - rad, px + rad, py + rad);
                take(&ls, axis_px(&ax, w->ms_lo, ls.w), py - 2, axis_px(&ax, w->ms_hi, ls.w), py + 2);
                if (rad > 5)
                    fprintf(f, "set label '' at %.9g,%.9g point pt 6 ps 2.4 lw 1.5 lc rgb 'black' front\n", w->ms,
                            fmax(w->m.rmse, 1e-5));
            }
        if (e_hi - e_lo <= 1e-9 * fmax(e_hi, 1e-9)) { /* every value the same image: say so */
            fprintf(f, "set label 'every value: the same image' at graph 0.5, graph 0.1 centre font ',8' "
                       "tc rgb '#555555'\n");
            take(&ls, 0.2 * ls.w, 0, 0.8 * ls.w, 0.18 * ls.h);
        }
        for (int i = 0; i < r->nrows; i++)
            if (!strcmp(r->rows[i].knob, knobs[k])) {
                const bench_row *w = &r->rows[i];
                double cx, cy;
                if (place(&ls, axis_px(&ax, w->ms, ls.w), axis_px(&ay, fmax(w->m.rmse, 1e-5), ls.h),
                          (int)strlen(w->value), 1, strcmp(knobs[k], "preset") != 0, &cx, &cy))
                    label_at(f, &ax, &ay, &ls, cx, cy, w->value, "font ',8'");
            }
        fputs("plot ", f);
        gnuplot_string(f, dat);
        fprintf(f, " index %d using 1:2 with lines lw 1.5 lc rgb '%s', "
                   "'' index %d using 1:2:4:5 with xerrorbars pt 7 ps 0.7 lc rgb '%s'\n",
                k, c, k, c);
    }
    fprintf(f, "unset multiplot\n");
}

/* The overview: every setting in grey, the presets labelled, the Pareto front as a staircase with its
 * settings named where the names can be read. 900x600 pixels, the plot area about 800x470. */
static void overview(const bench_results *r, FILE *f, const char *dat, const char *png, char (*knobs)[32],
                     int nk)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {0, 0};
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        bool preset = !strcmp(w->knob, "preset");
        lo[0] = fmin(lo[0], preset ? w->ms_lo : w->ms), hi[0] = fmax(hi[0], preset ? w->ms_hi : w->ms);
        lo[1] = fmin(lo[1], fmax(w->m.rmse, 1e-5)), hi[1] = fmax(hi[1], fmax(w->m.rmse, 1e-5));
    }
    axis_range ax = axis_fit(lo[0], hi[0], 0.06), ay = axis_fit(lo[1], hi[1], 0.12);
    fprintf(f, "reset\nset terminal pngcairo size 900,600 font ',10'\nset output ");
    gnuplot_string(f, png);
    char title[320];
    snprintf(title, sizeof title, "%s, %dx%d: every setting the bench tried (grey), the presets (blue) and the "
             "Pareto front\n(black: no setting is measurably faster and no worse, or better and not measurably "
             "slower). Better: down and left.", prefix(r), r->w, r->h);
    fprintf(f, "\nset title ");
    gnuplot_string(f, title);
    fprintf(f, " noenhanced\n");
    fprintf(f, "set grid\nunset key\nset xlabel 'ms per image (median)'\nset ylabel 'colour RMSE against %s'\n"
               "set format y '%%g'\nset format x '%%g'\nset lmargin 10\nset rmargin 3\nset tmargin 4\nset bmargin 4\n",
            r->opt->path_truth ? "the path-traced truth" : "the reference");
    axis_set(f, "x", &ax, 800);
    axis_set(f, "y", &ay, 470);
    label_space ls = {.w = 800, .h = 470, .cw = 5.2, .ch = 10};
    for (int i = 0; i < r->nrows; i++) {
        const bench_row *w = &r->rows[i];
        double px = axis_px(&ax, w->ms, ls.w), py = axis_px(&ay, fmax(w->m.rmse, 1e-5), ls.h);
        if (w->front || !strcmp(w->knob, "preset")) {
            take(&ls, px - 4, py - 4, px + 4, py + 4);
            anchor(&ls, px, py);
        }
    }
    int n;
    const bench_row **front = pareto_front(r, &n);
    for (int i = 0; i + 1 < n; i++) { /* the staircase: across at this point's error, down at the next's time */
        double x0 = axis_px(&ax, front[i]->ms, ls.w), x1 = axis_px(&ax, front[i + 1]->ms, ls.w);
        double y0 = axis_px(&ay, fmax(front[i]->m.rmse, 1e-5), ls.h), y1 = axis_px(&ay, fmax(front[i + 1]->m.rmse, 1e-5), ls.h);
        take(&ls, x0, y0 - 3, x1, y0 + 3);
        take(&ls, x1 - 3, y1, x1 + 3, y0);
    }
    for (int i = 0; i < r->nrows; i++) /* the presets' names first, larger and in blue */
        if (!strcmp(r->rows[i].knob, "preset")) {
            const bench_row *w = &r->rows[i];
            double cx, cy;
            if (place(&ls, axis_px(&ax, w->ms, ls.w), axis_px(&ay, fmax(w->m.rmse, 1e-5), ls.h),
                      (int)strlen(w->value), 1.25, false, &cx, &cy))
                label_at(f, &ax, &ay, &ls, cx, cy, w->value, "font ',10' tc rgb '#1f5fbf'");
        }
    for (int i = 0; i < n; i++)
        if (strcmp(front[i]->knob, "preset")) {
            char text[80];
            double cx, cy;
            snprintf(text, sizeof text, "%s=%s", front[i]->knob, front[i]->value);
            if (place(&ls, axis_px(&ax, front[i]->ms, ls.w), axis_px(&ay, fmax(front[i]->m.rmse, 1e-5), ls.h),
                      (int)strlen(text), 1, true, &cx, &cy))
                label_at(f, &ax, &ay, &ls, cx, cy, text, "font ',8'");
        }
    free(front);
    fprintf(f, "plot for [k=0:%d] ", nk - 1);
    gnuplot_string(f, dat);
    fprintf(f, " index k using 1:2 with points pt 7 ps 0.6 lc rgb '#bbbbbb', ");
    gnuplot_string(f, dat);
    fprintf(f, " index %d using 1:2 with steps lw 2 lc rgb 'black'", nk);
    for (int k = 0; k < nk; k++) /* the presets' block, with their intervals */
        if (!strcmp(knobs[k], "preset"))
            fprintf(f, ", '' index %d using 1:2:4:5 with xerrorbars pt 5 ps 1.3 lc rgb '#1f5fbf'", k);
    fprintf(f, "\n");
}

/* The plot script: the data file and the two images named as given (relative to the folder it runs in) */
static void plot_script(const bench_results *r, FILE *f, const char *dat, const char *png, const char *over,
                        char (*knobs)[32], int nk)
{
    small_multiples(r, f, dat, png, knobs, nk);
    overview(r, f, dat, over, knobs, nk);
}

/* A file of the private folder into OUT/PREFIX-name: read back whole as a PNG, then renamed (a link
 * planted at the target is replaced, never followed). */
static bool move_plot(const bench_results *r, const char *dir, const char *file, const char *name, err_t *err)
{
    char from[PATH_MAX_LEN + 32], to[PATH_MAX_LEN];
    int w, h;
    uint8_t *px = NULL;
    snprintf(from, sizeof from, "%s/%s", dir, file);
    snprintf(to, sizeof to, "%s/%s-%s", r->opt->out, prefix(r), name);
    err_t e;
    if (!image_read_u8(from, 3, 16384, &w, &h, &px, &e))
        return err_set(err, "cannot write '%s': gnuplot's image is incomplete (is the disk full?)", to);
    free(px);
    if (rename(from, to) != 0)
        return err_set(err, "cannot write '%s': %s", to, strerror(errno));
    return true;
}

/* The plots: gnuplot runs in a folder of its own inside --out (made by mkdtemp: nothing planted there),
 * on a script and data of constant names, and its images are moved out when whole. The script and data
 * a user keeps (PREFIX-plot.gp, PREFIX-plot.dat: `gnuplot PREFIX-plot.gp` in the --out folder redraws
 * them) are written beside the results. */
static bool write_plot(const bench_results *r, err_t *err)
{
    enum { MAX_KNOBS = 64 };
    char knobs[MAX_KNOBS][32], dir[PATH_MAX_LEN], dat[BENCH_PREFIX_MAX + 16], png[BENCH_PREFIX_MAX + 16],
        over[BENCH_PREFIX_MAX + 16];
    util_atomic a;
    if (!open_out(r, "plot.dat", &a, err))
        return false;
    int nk = write_plot_data(r, a.f, knobs, MAX_KNOBS);
    if (!util_atomic_commit(&a, err) || !open_out(r, "plot.gp", &a, err))
        return false;
    snprintf(dat, sizeof dat, "%s-plot.dat", prefix(r));
    snprintf(png, sizeof png, "%s-plot.png", prefix(r));
    snprintf(over, sizeof over, "%s-overview.png", prefix(r));
    plot_script(r, a.f, dat, png, over, knobs, nk);
    if (!util_atomic_commit(&a, err))
        return false;
    if (snprintf(dir, sizeof dir, "%s/.gnuplot-XXXXXX", r->opt->out) >= (int)sizeof dir || !mkdtemp(dir))
        return err_set(err, "cannot make a folder for gnuplot in '%s': %s", r->opt->out, strerror(errno));
    char path[PATH_MAX_LEN + 32];
    snprintf(path, sizeof path, "%s/plot.dat", dir);
    FILE *f = fopen(path, "w");
    bool ok = f != NULL;
    if (f) {
        write_plot_data(r, f, knobs, MAX_KNOBS);
        ok = fclose(f) == 0;
    }
    snprintf(path, sizeof path, "%s/plot.gp", dir);
    f = ok ? fopen(path, "w") : NULL;
    if (f) {
        plot_script(r, f, "plot.dat", "plot.png", "overview.png", knobs, nk);
        ok = fclose(f) == 0;
    }
    if (!ok || !f)
        err_set(err, "cannot write gnuplot's script in '%s': %s (is the disk full?)", dir, strerror(errno));
    ok = ok && f && gnuplot_run(dir, "plot.gp", err) && move_plot(r, dir, "plot.png", "plot.png", err) &&
         move_plot(r, dir, "overview.png", "overview.png", err);
    util_remove_folder(dir);
    return ok;
}

static void summary_header(const bench_results *r, FILE *f)
{
    const cli_options *o = r->opt;
    const metrics *c = r->conv;
    fprintf(f, "# What accuracy costs: %s\n\n", prefix(r));
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
                   "the same map() and materials, tested against closed forms in tests/test_pathtrace.c) at %d spp, "
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
               "![the reference](%s-reference.png).\n\n", DIFF_LEGEND, prefix(r));
}

static bool write_summary(const bench_results *r, err_t *err)
{
    util_atomic a;
    if (!open_out(r, "summary.md", &a, err))
        return false;
    FILE *f = a.f;
    summary_header(r, f);
    fprintf(f, "![the presets and the Pareto front](%s-overview.png)\n\n![each knob alone](%s-plot.png)\n\n",
            prefix(r), prefix(r));
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
    snprintf(png, sizeof png, "%s/%s-reference.png", r->opt->out, prefix(r));
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
    if (!open_out(r, "report.html", &a, err))
        return false;
    FILE *f = a.f;
    fprintf(f, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>What accuracy costs: ");
    html_text(f, prefix(r));
    fprintf(f, "</title>\n<style>body{font:14px sans-serif;margin:2em;max-width:1200px}"
               "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:2px 8px;"
               "text-align:right}td:first-child,th:first-child{text-align:left}tr.front{background:#eef5e9}"
               "img{max-width:100%%;display:block;margin:1em 0}.grid{display:flex;flex-wrap:wrap;gap:12px}"
               ".grid figure{margin:0;width:320px}.grid img{margin:0;width:100%%;image-rendering:pixelated}"
               "figcaption{font-size:12px}</style></head><body>\n<h1>What accuracy costs: ");
    html_text(f, prefix(r));
    fprintf(f, "</h1>\n<p>");
    html_text(f, r->base->title);
    fprintf(f, ". %dx%d, %d views, fathom %s, ", r->w, r->h, r->views, FATHOM_VERSION);
    html_text(f, gpu_describe());
    fprintf(f, ". Error against %s at %d spp (%.0f ms per image), which a stricter render matches to RMSE %.5f. "
               "Every knob starts from the scene's <code>%s</code> preset.</p>\n",
            r->opt->path_truth ? "the path tracer (the truth: <code>quality.integrator=1</code>)"
                               : "the <code>reference</code> preset",
            r->ref_spp, r->ref_ms, r->conv->rmse, preset_name(r->base->preset));
    snprintf(png, sizeof png, "%s/%s-overview.png", r->opt->out, prefix(r));
    inline_png(f, png, "the presets and the Pareto front");
    snprintf(png, sizeof png, "%s/%s-plot.png", r->opt->out, prefix(r));
    inline_png(f, png, "each knob alone");
    html_differences(r, f);
    html_tables(r, f);
    fprintf(f, "</body></html>\n");
    return util_atomic_commit(&a, err);
}

bool bench_write(const bench_results *r, err_t *err)
{
    return write_csv(r, err) && write_plot(r, err) && write_summary(r, err) && write_html(r, err);
}
