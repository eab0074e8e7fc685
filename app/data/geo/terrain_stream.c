#include "data/geo/terrain_stream.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "data/geo/dem.h"
#include "data/geo/terrain.h"

bool terrain_read_tile(struct dem_stream *s, const terrain_grid *g, int tx, int ty, float ex, float *out, err_t *err)
{
    int x0, y0, w, h;
    terrain_tile_window(g, tx, ty, &x0, &y0, &w, &h);
    if (!dem_stream_read(s, x0, y0, w, h, out, err))
        return false;
    for (size_t i = 0, n = (size_t)w * (size_t)h; i < n; i++) /* as heightfield_load: times ex, then NaN a hole */
        out[i] = isnan(out[i]) ? TERRAIN_HOLE : out[i] * ex;
    return true;
}

/* ---- the summary, built ------------------------------------------------------------------------- */

typedef struct job {
    const char *path;
    const terrain_grid *g;
    float dx, dz, ex;
    terrain_tile_stats *stats; /* one a tile */
    pthread_mutex_t lock;
    int next, done; /* the next tile to take; tiles finished */
    bool failed;
    err_t err;
    unsigned long long bytes;
} job;

static void *reader(void *arg)
{
    job *j = arg;
    const terrain_grid *g = j->g;
    int w, h, n = g->tiles_x * g->tiles_y;
    dem_info info;
    err_t err = {0};
    struct dem_stream *s = dem_stream_open(j->path, &w, &h, &info, &err);
    float *buf = s ? malloc(sizeof(float) * (size_t)g->slot_w * (size_t)g->slot_h) : NULL;
    bool ok = s && buf;
    if (s && !buf)
        err_set(&err, "summarising '%s': out of memory for a tile", j->path);
    bool show = isatty(2) && n > 64;
    for (;;) {
        pthread_mutex_lock(&j->lock);
        int t = ok && !j->failed ? j->next++ : n;
        pthread_mutex_unlock(&j->lock);
        if (t >= n)
            break;
        int tx = t % g->tiles_x, ty = t / g->tiles_x;
        if (!terrain_read_tile(s, g, tx, ty, j->ex, buf, &err)) {
            ok = false;
            break;
        }
        terrain_tile_build(g, tx, ty, buf, j->dx, j->dz, NULL, &j->stats[t]);
        pthread_mutex_lock(&j->lock);
        int done = ++j->done;
        pthread_mutex_unlock(&j->lock);
        if (show && done % 16 == 0)
            fprintf(stderr, "\rfathom: summarising %s: %3d %% of %d tiles", j->path, (int)(100.0 * done / n), n);
    }
    pthread_mutex_lock(&j->lock);
    if (!ok && !j->failed) {
        j->failed = true;
        j->err = err;
    }
    j->bytes += s ? dem_stream_bytes(s) : 0;
    pthread_mutex_unlock(&j->lock);
    free(buf);
    dem_stream_close(s);
    return NULL;
}

static int readers(void)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    const char *env = getenv("FATHOM_TERRAIN_THREADS");
    long want = env ? strtol(env, NULL, 10) : cores;
    if (want < 1)
        want = 1;
    return (int)(want < 16 ? want : 16);
}

static bool build(const char *path, const terrain_grid *g, float dx, float dz, float ex, terrain_summary *out, err_t *err)
{
    int n = g->tiles_x * g->tiles_y;
    job j = {.path = path, .g = g, .dx = dx, .dz = dz, .ex = ex};
    j.stats = malloc(sizeof *j.stats * (size_t)n);
    out->tile_max = malloc(sizeof(float) * (size_t)n);
    if (!j.stats || !out->tile_max) {
        free(j.stats);
        return err_set(err, "summarising '%s': out of memory for %d tiles", path, n);
    }
    pthread_mutex_init(&j.lock, NULL);
    int k = readers() < n ? readers() : n;
    pthread_t threads[16];
    int started = 0;
    for (; started < k; started++)
        if (pthread_create(&threads[started], NULL, reader, &j) != 0)
            break;
    if (started == 0)
        reader(&j);
    for (int i = 0; i < started; i++)
        pthread_join(threads[i], NULL);
    pthread_mutex_destroy(&j.lock);
    if (isatty(2) && n > 64)
        fprintf(stderr, "\n");
    if (j.failed) {
        *err = j.err;
        free(j.stats);
        free(out->tile_max);
        out->tile_max = NULL;
        return false;
    }
    out->hmin = INFINITY, out->hmax = -INFINITY;
    for (int t = 0; t < n; t++) {
        out->tile_max[t] = j.stats[t].max;
        out->hmin = fminf(out->hmin, j.stats[t].hmin);
        out->hmax = fmaxf(out->hmax, j.stats[t].hmax);
        out->lipschitz = fmaxf(out->lipschitz, j.stats[t].lipschitz);
        out->holes += j.stats[t].holes;
    }
    out->bytes = j.bytes;
    free(j.stats);
    return true;
}

/* ---- the summary, kept ---------------------------------------------------------------------------- */

typedef struct header {
    char magic[8];
    int32_t width, height, shift_x, shift_y, tiles_x, tiles_y;
    float hmin, hmax, lipschitz, pad;
    uint64_t holes, key_bytes;
} header;

static const char MAGIC[8] = "FTHMSUM1";

static uint64_t fnv1a(const char *s)
{
    uint64_t h = 1469598103934665603ull;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

/* <cache>/fathom/terrain/HASH.sum, its folders made; false (nothing kept) when there is no such folder. */
static bool cache_file(const char *key, char *out, size_t n)
{
    char dir[PATH_MAX_LEN];
    return util_cache_folder("terrain", NULL, dir, sizeof dir) &&
           snprintf(out, n, "%s/%016llx.sum", dir, (unsigned long long)fnv1a(key)) < (int)n;
}

static bool load(const char *file, const char *key, const terrain_grid *g, terrain_summary *out)
{
    FILE *f = fopen(file, "rb");
    if (!f)
        return false;
    header hd;
    size_t n = (size_t)g->tiles_x * (size_t)g->tiles_y, kl = strlen(key);
    char *k = NULL;
    bool ok = fread(&hd, sizeof hd, 1, f) == 1 && !memcmp(hd.magic, MAGIC, sizeof MAGIC) && hd.width == g->width &&
              hd.height == g->height && hd.shift_x == g->shift_x && hd.shift_y == g->shift_y &&
              hd.tiles_x == g->tiles_x && hd.tiles_y == g->tiles_y && hd.key_bytes == kl;
    ok = ok && (k = malloc(kl + 1)) && fread(k, 1, kl, f) == kl && !memcmp(k, key, kl);
    free(k);
    out->tile_max = ok ? malloc(sizeof(float) * n) : NULL;
    ok = ok && out->tile_max && fread(out->tile_max, sizeof(float), n, f) == n && fgetc(f) == EOF;
    fclose(f);
    if (!ok) {
        free(out->tile_max);
        out->tile_max = NULL;
        return false;
    }
    out->hmin = hd.hmin, out->hmax = hd.hmax, out->lipschitz = hd.lipschitz, out->holes = hd.holes;
    out->cached = true;
    return true;
}

/* Written whole beside its final name, then renamed: a reader never sees half of one. */
static void keep(const char *file, const char *key, const terrain_grid *g, const terrain_summary *s)
{
    char tmp[PATH_MAX_LEN + 32];
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", file, (long)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f)
        return;
    header hd = {.width = g->width, .height = g->height, .shift_x = g->shift_x, .shift_y = g->shift_y,
                 .tiles_x = g->tiles_x, .tiles_y = g->tiles_y, .hmin = s->hmin, .hmax = s->hmax,
                 .lipschitz = s->lipschitz, .holes = s->holes, .key_bytes = strlen(key)};
    memcpy(hd.magic, MAGIC, sizeof MAGIC);
    size_t n = (size_t)g->tiles_x * (size_t)g->tiles_y;
    bool ok = fwrite(&hd, sizeof hd, 1, f) == 1 && fwrite(key, 1, hd.key_bytes, f) == hd.key_bytes &&
              fwrite(s->tile_max, sizeof(float), n, f) == n;
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, file) != 0)
        unlink(tmp);
}

bool terrain_summary_get(const char *path, const terrain_grid *g, float dx, float dz, float ex, terrain_summary *out,
                         err_t *err)
{
    *out = (terrain_summary){0};
    double t0 = util_now();
    int w, h;
    dem_info info;
    struct dem_stream *s = dem_stream_open(path, &w, &h, &info, err);
    if (!s)
        return false;
    strbuf key = {0};
    dem_stream_identity(s, &key);
    dem_stream_close(s);
    sb_printf(&key, "|%dx%d tiles %d,%d|x%.9g|%.9g,%.9g", g->width, g->height, g->shift_x, g->shift_y, (double)ex,
              (double)dx, (double)dz);
    char file[PATH_MAX_LEN];
    bool have_file = cache_file(key.data, file, sizeof file);
    bool ok = (have_file && load(file, key.data, g, out)) || build(path, g, dx, dz, ex, out, err);
    if (ok && !out->cached && have_file)
        keep(file, key.data, g, out);
    sb_free(&key);
    out->seconds = util_now() - t0;
    return ok;
}

void terrain_summary_free(terrain_summary *s)
{
    free(s->tile_max);
    *s = (terrain_summary){0};
}
