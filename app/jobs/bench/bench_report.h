/* bench_report — the bench's results: the console table, and with --out the CSV files, the gnuplot
 * plot of error against time with the Pareto front, and the markdown summary. Internal to bench. */
#ifndef FATHOM_BENCH_REPORT_H
#define FATHOM_BENCH_REPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "jobs/bench/bench_desc.h"
#include "jobs/bench/metrics.h"
#include "scene/scene.h"

typedef struct bench_row {
    char knob[32], value[32];
    double ms;  /* median time of one image (all its samples), mean over views */
    double ms_lo, ms_hi; /* its interval (metrics_median_interval), mean over views */
    metrics m;  /* mean over views (max depth: max) */
    bool front;
    char diff[160]; /* the difference image's file name in the --out folder (view 1), or empty */
} bench_row;

/* Difference images: yellow at this difference (of the display's full scale), white from 1.25× it. */
#define BENCH_DIFF_YELLOW 0.25

/* The model's approximations of light transport a bench prices (against the path tracer with --truth
 * path): a knob, its values without and with the approximation, and what to call it. */
typedef struct bench_approximation {
    const char *knob, *off, *on, *what;
} bench_approximation;
#define BENCH_APPROXIMATIONS(X)                                                                                        \
    X("fx_ao", "off", "on", "ambient occlusion")                                                                       \
    X("fx_soft_shadows", "off", "on", "the soft-shadow rule")                                                          \
    X("fx_fog", "off", "on", "the fog approximation")                                                                  \
    X("ambient", "0", "1", "sky ambient (against one constant, the sky's mean)")
/* The approximation knob names, or NULL. */
const bench_approximation *bench_approximation_of(const char *knob);

/* The value scene s's own preset gives the sweep named knob ("" where the bench does not know it), and
 * whether two sweep values are the same ("0.5" and "0.50" are) */
void bench_base_value(const scene *s, const char *knob, char *out, size_t n);
bool bench_same_value(const char *a, const char *b);

typedef struct effect_row {
    effect e;
    bool in_scene;
    double out_ms, in_ms, in_off_ms; /* medians of the interleaved runs */
    double out_lo, out_hi, in_lo, in_hi, in_off_lo, in_off_hi; /* their intervals (metrics_median_interval) */
} effect_row;

typedef struct bench_results {
    const bench_desc *opt;
    const scene *base; /* the scene as loaded, before any sweep */
    int w, h, views, ref_spp;
    float view_turn_deg;
    const bench_row *rows;
    int nrows;
    const effect_row *fx; /* EFFECT_COUNT rows */
    const metrics *conv;  /* the reference against a stricter render */
    double ref_ms;
} bench_results;

/* File names in --out: PREFIX-what, where PREFIX is --name, else the scene's base name without its
 * extension (a preset's "../../x.json" is "x"), made safe by bench_safe_name: letters, digits, '-',
 * '_' and '.' (not first); anything else '_'. Never a path, never empty. */
enum { BENCH_PREFIX_MAX = 64 };
void bench_prefix(const bench_desc *o, char *out, size_t n);
void bench_safe_name(const char *s, char *out, size_t n);
/* This run's PREFIX (one run at a time), and OUT/PREFIX-name opened as a new temporary file beside it
 * (util_atomic: renamed over it when whole). */
const char *bench_run_prefix(const bench_results *r);
bool bench_open_out(const bench_results *r, const char *name, util_atomic *a, err_t *err);

void bench_print(const bench_results *r);
/* With --out, where a setting's w × h image (RGBA8) differs from the reference's (view 1):
 * OUT/PREFIX-diff-KNOB-VALUE.png, the largest channel's difference per pixel in a ramp that darkens
 * nowhere; its file name into name (empty when not written: said on stderr, the report goes on). */
void bench_write_difference(const bench_desc *opt, int w, int h, const char *knob, const char *value,
                            const uint8_t *test, const uint8_t *ref, char *name, size_t n);
/* With --out: the CSV files (PREFIX-knobs.csv, PREFIX-effects.csv); then, after bench_plot_write (their
 * plots go inline), the markdown summary and the HTML report. */
bool bench_write_csv(const bench_results *r, err_t *err);
bool bench_write_pages(const bench_results *r, err_t *err);
/* The knob CSV with the rows measured so far (Pareto marks among them), written to a temporary file
 * and renamed over PREFIX-knobs.csv: a run stopped half-way keeps every row it finished, never a torn
 * line. bench_write rewrites it whole at the end. */
bool bench_write_rows(const bench_results *r, err_t *err);

#endif
