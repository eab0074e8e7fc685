#include "data/geo/terrain_loader.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/geo/dem.h"
#include "data/geo/terrain_stream.h"

struct terrain_loader {
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t wake;
    bool stop, failed;
    err_t err;
    char path[PATH_MAX_LEN];
    terrain_grid grid;
    float ex, dx, dz;
    int cap;                /* tiles waiting to be read, and to be taken, at most */
    int *asked, asked_n;    /* waiting to be read, oldest first */
    terrain_loaded *ready;  /* read, waiting to be taken */
    int ready_n;
    unsigned char *state;   /* a tile: 0 not asked, 1 asked, read or ready */
};

/* The next tile to read (−1: stop). */
static int next_tile(terrain_loader *l)
{
    pthread_mutex_lock(&l->lock);
    while (!l->stop && (l->asked_n == 0 || l->ready_n == l->cap))
        pthread_cond_wait(&l->wake, &l->lock);
    int t = -1;
    if (!l->stop) {
        t = l->asked[0];
        memmove(l->asked, l->asked + 1, sizeof(int) * (size_t)--l->asked_n);
    }
    pthread_mutex_unlock(&l->lock);
    return t;
}

static void *run(void *arg)
{
    terrain_loader *l = arg;
    const terrain_grid *g = &l->grid;
    int w, h;
    dem_info info;
    err_t err = {0};
    struct dem_stream *s = dem_stream_open(l->path, &w, &h, &info, &err);
    size_t levels = terrain_tile_level_floats(g) + 1;
    for (int t; s && (t = next_tile(l)) >= 0;) {
        terrain_loaded r = {.tile = t};
        int x0, y0;
        terrain_tile_window(g, t % g->tiles_x, t / g->tiles_x, &x0, &y0, &r.w, &r.h);
        r.heights = malloc(sizeof(float) * (size_t)r.w * (size_t)r.h);
        r.levels = malloc(sizeof(float) * levels);
        unsigned long long before = dem_stream_bytes(s);
        bool ok = r.heights && r.levels && terrain_read_tile(s, g, t % g->tiles_x, t / g->tiles_x, l->ex, r.heights, &err);
        if (!ok) {
            if (!r.heights || !r.levels)
                err_set(&err, "reading '%s': out of memory for a tile", l->path);
            free(r.heights), free(r.levels);
            break;
        }
        terrain_tile_stats st;
        terrain_tile_build(g, t % g->tiles_x, t / g->tiles_x, r.heights, l->dx, l->dz, r.levels, &st);
        r.bytes = dem_stream_bytes(s) - before;
        pthread_mutex_lock(&l->lock);
        l->ready[l->ready_n++] = r; /* room: next_tile waits while ready is full */
        pthread_mutex_unlock(&l->lock);
    }
    pthread_mutex_lock(&l->lock);
    if (!l->stop) { /* it stopped on an error: said at the next take */
        l->failed = true;
        l->err = err;
    }
    pthread_mutex_unlock(&l->lock);
    dem_stream_close(s);
    return NULL;
}

terrain_loader *terrain_loader_start(const char *path, const terrain_grid *g, float ex, float dx, float dz, int queue,
                                     err_t *err)
{
    terrain_loader *l = util_calloc(1, sizeof *l, "the terrain's loader");
    snprintf(l->path, sizeof l->path, "%s", path);
    l->grid = *g, l->ex = ex, l->dx = dx, l->dz = dz, l->cap = queue;
    l->asked = util_alloc(sizeof(int) * (size_t)queue, "the terrain's loader");
    l->ready = util_alloc(sizeof *l->ready * (size_t)queue, "the terrain's loader");
    l->state = util_calloc((size_t)g->tiles_x * (size_t)g->tiles_y, 1, "the terrain's loader");
    pthread_mutex_init(&l->lock, NULL);
    pthread_cond_init(&l->wake, NULL);
    if (pthread_create(&l->thread, NULL, run, l) != 0) {
        pthread_mutex_destroy(&l->lock);
        pthread_cond_destroy(&l->wake);
        free(l->asked), free(l->ready), free(l->state), free(l);
        err_set(err, "cannot start the terrain's loader thread");
        return NULL;
    }
    return l;
}

void terrain_loader_ask(terrain_loader *l, int tile)
{
    pthread_mutex_lock(&l->lock);
    if (!l->state[tile] && l->asked_n < l->cap) {
        l->state[tile] = 1;
        l->asked[l->asked_n++] = tile;
        pthread_cond_signal(&l->wake);
    }
    pthread_mutex_unlock(&l->lock);
}

bool terrain_loader_take(terrain_loader *l, terrain_loaded *out)
{
    pthread_mutex_lock(&l->lock);
    bool got = l->ready_n > 0;
    if (got) {
        *out = l->ready[0];
        memmove(l->ready, l->ready + 1, sizeof *l->ready * (size_t)--l->ready_n);
        pthread_cond_signal(&l->wake); /* room for the next read */
    }
    pthread_mutex_unlock(&l->lock);
    return got;
}

bool terrain_loader_failed(terrain_loader *l, err_t *err)
{
    pthread_mutex_lock(&l->lock);
    bool failed = l->failed;
    if (failed)
        *err = l->err;
    pthread_mutex_unlock(&l->lock);
    return failed;
}

void terrain_loader_done(terrain_loader *l, terrain_loaded *t)
{
    pthread_mutex_lock(&l->lock);
    l->state[t->tile] = 0; /* it may be asked for again once evicted */
    pthread_mutex_unlock(&l->lock);
    free(t->heights), free(t->levels);
    t->heights = t->levels = NULL;
}

void terrain_loader_stop(terrain_loader *l)
{
    if (!l)
        return;
    pthread_mutex_lock(&l->lock);
    l->stop = true;
    pthread_cond_broadcast(&l->wake);
    pthread_mutex_unlock(&l->lock);
    pthread_join(l->thread, NULL);
    for (int i = 0; i < l->ready_n; i++)
        free(l->ready[i].heights), free(l->ready[i].levels);
    pthread_mutex_destroy(&l->lock);
    pthread_cond_destroy(&l->wake);
    free(l->asked), free(l->ready), free(l->state), free(l);
}
