/* bench — what accuracy costs in time. Headless.
 *
 * For fixed views of a scene (its start camera, and the same camera turned 40° about the look-at
 * point), each accuracy knob is swept on its own around the scene's preset, then the presets, then
 * every effect compiled out / compiled in / compiled in but off at run time. Time: median of `runs`
 * images (all of a setting's samples) after one warm-up, wall clock around glFinish (GL timer
 * queries are wrong on llvmpipe). Error: against a reference render of the same view (the reference
 * preset with REF_SPP samples), whose own convergence is checked against a stricter render
 * (metrics.h says what is measured). Writes CSV, a gnuplot plot of error against time with the
 * Pareto front, and a markdown summary. */
#ifndef FATHOM_BENCH_H
#define FATHOM_BENCH_H

#include <stdbool.h>

#include "jobs/bench/bench_desc.h"
#include "scene/scene.h"
#include "view/camera.h"
#include "util.h"

bool bench_run(const bench_desc *opt, err_t *err);

/* bench --frame-times (bench_frames.c): whole-process start-up times, then each preset's frame time
 * (one sample per pixel) at the start view at w × h, on both backends side by side. */
bool bench_frame_times(const bench_desc *opt, int w, int h, err_t *err);

/* bench --final-frame (bench_final.c): the final preset's whole shot at w × h (1920×1080 by default), as
 * a user's process takes it, every pixel sampled against adaptive sampling, side by side. */
bool bench_final_frame(const bench_desc *opt, int w, int h, err_t *err);

/* bench --interactive (bench_interactive.c): a scripted flight at window size w × h under the window's
 * resolution controller; prints frame times, internal size, moving-frame error and time to converge. */
bool bench_interactive(const bench_desc *opt, int w, int h, err_t *err);

/* bench --terrain-scale (bench_terrain.c): load time, peak memory, frame time and height samples per
 * pixel of generated DEMs from 256² up (--knob side=N1,N2,...), for maxmip and linear. */
bool bench_terrain_scale(const bench_desc *opt, int w, int h, err_t *err);

/* bench --terrain-stream (bench_stream.c): DEMs past memory, VRT mosaics of a generated tile (--knob
 * side=...), streamed from disk: open (cold and warm), first image, the shot, warm frames against the same
 * view in core where it fits, peak memory and bytes read. And the process's memory in kB (VmRSS:, VmHWM:),
 * and its peak reset to now (bench_terrain.c). */
bool bench_terrain_stream(const bench_desc *opt, int w, int h, err_t *err);
long bench_status_kb(const char *key);
/* One frame (one sample a pixel) at w × h, wall clock around glFinish, in ms. */
double bench_frame_ms(int w, int h, const camera *cam);
/* The DEM benches' sides: --knob side=N1,N2,... (else `sides`), each a whole number from lo to hi and a
 * multiple of step (*out: the list); false with a message naming the bench's mode. With --out, the CSV
 * (csv_path: the folder's `name`) is started with its header. */
bool bench_sides(const bench_desc *opt, const char *mode, const char *sides, long lo, long hi, long step,
                 const char **out, const char *name, const char *header, char csv_path[PATH_MAX_LEN], err_t *err);
/* Runs side(n, r) for each side of the list, each in a process of its own (forked: a fresh heap and GPU
 * context, so the peak memory is that side's alone). */
typedef struct bench_side_run {
    const char *dir; /* a temporary folder for its files */
    int w, h, runs;
    const char *csv; /* the CSV its row is appended to (NULL: none) */
} bench_side_run;
bool bench_fork_sides(const char *sides, const char *mode, bool (*side)(int n, const bench_side_run *r, err_t *err),
                      const bench_side_run *r, err_t *err);
void bench_reset_peak(void);

/* bench --viewshed (bench_viewshed.c): the exact viewshed's time on generated DEMs (--knob side=...),
 * side by side with GDAL's, and where GDAL's answer differs. */
bool bench_viewshed(const bench_desc *opt, err_t *err);

#endif
