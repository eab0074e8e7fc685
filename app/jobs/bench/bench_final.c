/* bench_final — bench --final-frame (bench.h): the final preset's whole shot as a user's process takes
 * it (start, load, compile, every sample, the file written), each variant in turn run after run so all
 * see the same machine load: every pixel sampled (quality.tolerance=0, as before adaptive sampling),
 * then adaptive sampling at the preset's tolerance. The difference between their images is what the
 * adaptive stop costs in accuracy. */
#include "jobs/bench/bench.h"
#include "jobs/bench/bench_load.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "data/media/image_io.h"
#include "jobs/bench/metrics.h"

enum { VARIANTS = 2, MAX_ARGS = 16 + 2 * 64 };

static const char *const VARIANT_SET[VARIANTS] = {"quality.tolerance=0", NULL};
static const char *const VARIANT_NAME[VARIANTS] = {"every pixel", "adaptive"};

typedef struct final_run {
    char dir[40], image[VARIANTS][64], log[VARIANTS][64], size[32];
    double ms[VARIANTS][64];
    double samples[VARIANTS]; /* a pixel, on average, as the shot's own message says */
} final_run;

/* The shot's command line for variant v (at `size`, into `image`). */
static int shot_args(const bench_desc *opt, int v, const char *size, const char *image, char **argv)
{
    int n = 0;
    argv[n++] = "fathom";
    argv[n++] = "--scene";
    argv[n++] = (char *)opt->scene;
    argv[n++] = "--quality";
    argv[n++] = "final";
    for (int i = 0; i < opt->set_count && n < MAX_ARGS - 8; i++) {
        argv[n++] = "--set";
        argv[n++] = (char *)opt->sets[i];
    }
    if (VARIANT_SET[v]) {
        argv[n++] = "--set";
        argv[n++] = (char *)VARIANT_SET[v];
    }
    argv[n++] = "--size";
    argv[n++] = (char *)size;
    argv[n++] = "--output";
    argv[n++] = (char *)image;
    argv[n] = NULL;
    return n;
}

/* The samples a pixel took, from the shot's "wrote ... (WxH, N spp, M a pixel, ...)" line. */
static double samples_from_log(const char *log)
{
    FILE *f = fopen(log, "r");
    char line[4096];
    double spp = -1, mean = -1;
    while (f && fgets(line, sizeof line, f)) {
        const char *w = strstr(line, "wrote ");
        const char *p = w ? strstr(w, " spp") : NULL;
        if (!p)
            continue;
        while (p > w && (p[-1] >= '0' && p[-1] <= '9'))
            p--;
        spp = strtod(p, NULL);
        const char *a = strstr(p, " spp, ");
        if (a && strstr(a, " a pixel"))
            mean = strtod(a + 6, NULL);
    }
    if (f)
        fclose(f);
    return mean >= 0 ? mean : spp;
}

/* How far the adaptive image is from every pixel's: RMSE and worst difference in 8-bit levels, the
 * 99.99th percentile of the pixels' differences (a pixel's: its largest channel's), and the share of
 * pixels more than 2 levels off in any channel. */
static bool compare(const char *a, const char *b, double *rmse, int *worst, int *p9999, double *off, err_t *err)
{
    long hist[256] = {0};
    int w[2], h[2];
    uint8_t *px[2] = {NULL, NULL};
    bool ok = image_read_u8(a, 3, 16384, &w[0], &h[0], &px[0], err) && image_read_u8(b, 3, 16384, &w[1], &h[1], &px[1], err);
    if (ok && (w[0] != w[1] || h[0] != h[1]))
        ok = err_set(err, "bench --final-frame: the two shots differ in size");
    double sum = 0;
    long far = 0;
    *worst = 0;
    size_t n = ok ? (size_t)w[0] * (size_t)h[0] : 0;
    for (size_t i = 0; i < n; i++) {
        int pixel = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs((int)px[0][i * 3 + (size_t)c] - (int)px[1][i * 3 + (size_t)c]);
            sum += (double)d * d;
            pixel = d > pixel ? d : pixel;
        }
        *worst = pixel > *worst ? pixel : *worst;
        far += pixel > 2;
        hist[pixel]++;
    }
    long above = (long)n; /* pixels more than *p9999 levels off, down to one in 10,000 */
    for (*p9999 = 0; *p9999 < 255 && (above -= hist[*p9999]) > (long)n / 10000;)
        ++*p9999;
    *rmse = n ? sqrt(sum / (3.0 * (double)n)) : 0;
    *off = n ? 100.0 * (double)far / (double)n : 0;
    free(px[0]);
    free(px[1]);
    return ok;
}

static bool run_all(const bench_desc *opt, final_run *R, err_t *err)
{
    char *argv[MAX_ARGS];
    for (int v = 0; v < VARIANTS; v++) { /* a warm-up of each: the shader cache and the page cache */
        shot_args(opt, v, "64x36", R->image[v], argv);
        if (bench_process_ms(argv, R->log[v]) < 0)
            return err_set(err, "bench --final-frame: a shot of %s failed (%s): run it as fathom --scene %s "
                                "--quality final to see why", opt->scene, VARIANT_NAME[v], opt->scene);
    }
    for (int r = 0; r < opt->runs; r++)
        for (int v = 0; v < VARIANTS; v++) {
            shot_args(opt, v, R->size, R->image[v], argv);
            R->ms[v][r] = bench_process_ms(argv, R->log[v]);
            if (R->ms[v][r] < 0)
                return err_set(err, "bench --final-frame: a %s shot of %s failed (%s)", R->size, opt->scene,
                               VARIANT_NAME[v]);
            R->samples[v] = samples_from_log(R->log[v]);
            if (!opt->quiet)
                fprintf(stderr, "\rbench --final-frame %s: run %d of %d, %s %.1f s      ", opt->scene, r + 1, opt->runs,
                        VARIANT_NAME[v], R->ms[v][r] / 1000.0);
        }
    if (!opt->quiet)
        fputc('\n', stderr);
    return true;
}

bool bench_final_frame(const bench_desc *opt, int w, int h, err_t *err)
{
    final_run *R = util_alloc(sizeof *R, "bench state");
    memset(R, 0, sizeof *R);
    snprintf(R->dir, sizeof R->dir, "/tmp/fathom-bench-final-XXXXXX");
    if (!mkdtemp(R->dir)) {
        free(R);
        return err_set(err, "bench --final-frame: cannot make a temporary folder in /tmp");
    }
    snprintf(R->size, sizeof R->size, "%dx%d", w, h);
    for (int v = 0; v < VARIANTS; v++) {
        snprintf(R->image[v], sizeof R->image[v], "%s/%d.png", R->dir, v);
        snprintf(R->log[v], sizeof R->log[v], "%s/%d.log", R->dir, v);
    }
    int runs = opt->runs > 64 ? 64 : opt->runs;
    bench_desc o = *opt;
    o.runs = runs;
    double rmse = 0, off = 0;
    int worst = 0, p9999 = 0;
    bool ok = run_all(&o, R, err) && compare(R->image[1], R->image[0], &rmse, &worst, &p9999, &off, err);
    if (ok) {
        double med[VARIANTS], lo[VARIANTS], hi[VARIANTS];
        for (int v = 0; v < VARIANTS; v++)
            med[v] = metrics_median_interval(R->ms[v], runs, &lo[v], &hi[v]) / 1000.0;
        printf("| %s | %s | %.1f [%.1f-%.1f] | %.1f [%.1f-%.1f] | %.2f | %.1f | %.2f | %d | %d | %.3f |\n", opt->scene,
               R->size, med[0], lo[0] / 1000.0, hi[0] / 1000.0, med[1], lo[1] / 1000.0, hi[1] / 1000.0, med[0] / med[1],
               R->samples[1], rmse, worst, p9999, off);
    }
    for (int v = 0; v < VARIANTS; v++) {
        unlink(R->image[v]);
        unlink(R->log[v]);
    }
    rmdir(R->dir);
    free(R);
    return ok;
}
