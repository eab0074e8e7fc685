/* bench_plot — the bench's plots of error against time, drawn by gnuplot (jobs/bench/gnuplot.h): the small
 * multiples (one panel a knob, its values labelled where they can be read, the scene's own operating
 * point ringed) and the overview with the Pareto front. The script and data are kept beside them
 * (PREFIX-plot.gp, PREFIX-plot.dat). Internal to bench. GL (the renderer's name in the title). */
#ifndef FATHOM_BENCH_PLOT_H
#define FATHOM_BENCH_PLOT_H

#include <stdbool.h>

#include "jobs/bench/bench_report.h"
#include "util.h"

/* OUT/PREFIX-plot.png, -overview.png, -plot.gp and -plot.dat. */
bool bench_plot_write(const bench_results *r, err_t *err);

#endif
