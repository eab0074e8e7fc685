/* bench --viewshed: what the exact viewshed costs, and how far GDAL's own is from it. For each side N
 * (--knob side=A,B,...; 512 to 4096 by default) the bench's generated DEM (an N × N Int16 GeoTIFF,
 * 30 m texels in UTM, hills of 3.75-60 km: data/geo/dem.h dem_write_hills), an observer at its centre 1.7 m
 * above the ground and one 100 m up (a mast), refraction 0.13: fathom's exact viewshed
 * (data/geo/viewshed.h, every core) and GDAL's (GDALViewshedGenerate, edge mode: gdal_viewshed's default,
 * one core, reading the band it is given) in turn, `runs` times each; medians with their 95 % interval.
 * Then the share of texels visible, the pyramid nodes a line of sight visited, and where GDAL's answer
 * differs from the exact one: texels it calls visible that the bilinear surface hides, and the reverse
 * (GDAL tests the line against heights interpolated along cell edges; a grazing line is a tie in
 * either, counted here as a difference). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "data/geo/dem.h"
#include "data/geo/geo.h"
#include "data/geo/terrain.h"
#include "data/geo/viewshed.h"
#include "jobs/bench/bench.h"
#include "jobs/bench/metrics.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

enum { MAX_RUNS = 64 };

/* One DEM, one eye height: a markdown row. */
static bool one_row(const char *path, int n, double eye, int runs, err_t *err)
{
    int w, h;
    float *hts;
    dem_info info;
    if (!dem_read(path, TERRAIN_MAX_SIDE, &w, &h, &hts, &info, err))
        return false;
    size_t texels = (size_t)w * (size_t)h;
    unsigned char *ours = util_alloc(texels, "the exact viewshed"), *theirs = util_alloc(texels, "GDAL's viewshed");
    viewshed_desc d = {.heights = hts, .w = w, .h = h, .dx = info.spacing[0], .dz = info.spacing[1], .col = n / 2,
                       .row = n / 2, .observer_height = eye, .refraction = 0.13, .curvature = true};
    double t_ours[MAX_RUNS], t_gdal[MAX_RUNS];
    viewshed_stats st = {0};
    bool ok = true;
    for (int r = 0; ok && r < runs; r++) {
        double t0 = now_s();
        ok = viewshed_compute(&d, ours, &st, err);
        double t1 = now_s();
        ok = ok && geo_gdal_viewshed(path, n / 2, n / 2, eye, 0, 1 - 0.13, theirs, err);
        t_ours[r] = t1 - t0, t_gdal[r] = now_s() - t1;
    }
    if (ok) {
        size_t more = 0, fewer = 0;
        for (size_t k = 0; k < texels; k++) {
            more += theirs[k] == VIEWSHED_VISIBLE && ours[k] == VIEWSHED_HIDDEN;
            fewer += theirs[k] == VIEWSHED_HIDDEN && ours[k] == VIEWSHED_VISIBLE;
        }
        double lo, hi, glo, ghi;
        double m = metrics_median_interval(t_ours, runs, &lo, &hi), g = metrics_median_interval(t_gdal, runs, &glo, &ghi);
        printf("| %d² | %.1f | %.3f [%.3f-%.3f] | %d | %.1f | %.2f | %.3f [%.3f-%.3f] | %.3f | %.3f |\n", n, eye, m, lo,
               hi, st.threads, st.nodes_per_texel, 100.0 * (double)st.visible / (double)texels, g, glo, ghi,
               100.0 * (double)more / (double)texels, 100.0 * (double)fewer / (double)texels);
        fflush(stdout);
    }
    free(ours);
    free(theirs);
    free(hts);
    return ok;
}

bool bench_viewshed(const bench_desc *opt, err_t *err)
{
    const char *sides = "512,1024,2048,4096";
    for (int i = 0; i < opt->knob_count; i++) {
        if (strncmp(opt->knobs[i], "side=", 5))
            return err_set(err, "bench --viewshed takes --knob side=N1,N2,... only");
        sides = opt->knobs[i] + 5;
    }
    int runs = opt->runs < MAX_RUNS ? opt->runs : MAX_RUNS;
    char dir[] = "/tmp/fathom-viewshed-XXXXXX";
    if (!mkdtemp(dir))
        return err_set(err, "bench --viewshed: cannot make a temporary folder in /tmp");
    printf("| side | eye m | fathom exact s | threads | nodes a texel | visible %% | GDAL s | GDAL sees, exact hides %% "
           "| GDAL hides, exact sees %% |\n|---|---|---|---|---|---|---|---|---|\n");
    bool ok = true;
    for (const char *p = sides; ok && *p;) {
        char *end;
        long n = strtol(p, &end, 10);
        if (end == p || (*end && *end != ',') || n < 16 || n > 16384) {
            ok = err_set(err, "--knob side: expected whole numbers from 16 to 16384, e.g. side=512,4096");
            break;
        }
        char path[sizeof dir + 32];
        snprintf(path, sizeof path, "%s/hills-%ld.tif", dir, n);
        ok = dem_write_hills(path, (int)n, err) && one_row(path, (int)n, 1.7, runs, err) &&
             one_row(path, (int)n, 100, runs, err);
        unlink(path);
        p = *end ? end + 1 : end;
    }
    rmdir(dir);
    return ok;
}
