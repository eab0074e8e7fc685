/* bench_plot — the bench's plots (bench_plot.h). */
#include "jobs/bench/bench_plot.h"

#include <errno.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "data/media/image_io.h"
#include "jobs/bench/gnuplot.h"
#include "scene/quality.h"

static int by_time(const void *a, const void *b)
{
    double ta = (*(const bench_row *const *)a)->ms, tb = (*(const bench_row *const *)b)->ms;
    return (ta > tb) - (ta < tb);
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
    fprintf(f, "set terminal pngcairo size %d,%d font ',9'\nset output ", 380 * cols, 300 * rows + 70);
    gnuplot_string(f, png);
    char title[512]; /* each line fits two panels' width (a run of one knob and the presets) */
    snprintf(title, sizeof title, "%s, %dx%d, %.40s:\ncolour error against time, each knob swept alone from the %s "
             "preset\nBetter: down and left. Ring: the preset's value. Bars: the time's 95 %% interval.\nCompare "
             "times within a panel (its settings were timed in turn); between panels the machine's load drifts.",
             bench_run_prefix(r), r->w, r->h, (const char *)glGetString(GL_RENDERER), preset_name(r->base->preset));
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
             "slower). Better: down and left.", bench_run_prefix(r), r->w, r->h);
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
    snprintf(to, sizeof to, "%s/%s-%s", r->opt->out, bench_run_prefix(r), name);
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
bool bench_plot_write(const bench_results *r, err_t *err)
{
    enum { MAX_KNOBS = 64 };
    char knobs[MAX_KNOBS][32], dir[PATH_MAX_LEN], dat[BENCH_PREFIX_MAX + 16], png[BENCH_PREFIX_MAX + 16],
        over[BENCH_PREFIX_MAX + 16];
    util_atomic a;
    if (!bench_open_out(r, "plot.dat", &a, err))
        return false;
    int nk = write_plot_data(r, a.f, knobs, MAX_KNOBS);
    if (!util_atomic_commit(&a, err) || !bench_open_out(r, "plot.gp", &a, err))
        return false;
    snprintf(dat, sizeof dat, "%s-plot.dat", bench_run_prefix(r));
    snprintf(png, sizeof png, "%s-plot.png", bench_run_prefix(r));
    snprintf(over, sizeof over, "%s-overview.png", bench_run_prefix(r));
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

