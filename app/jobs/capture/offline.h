/* offline — a headless shot: EGL context, progressive samples with a progress bar, verified write.
 * Any size up to 16384² renders in bands of rows, each written as it is done (bounded memory).
 * .png: tone-mapped 8-bit sRGB. .exr: linear float RGBA plus the requested AOV channels
 * (Z = depth along the unit ray, +inf on a miss; N.X N.Y N.Z; steps; exit.X exit.Y exit.Z). */
#ifndef FATHOM_OFFLINE_H
#define FATHOM_OFFLINE_H

#include <stdbool.h>

#include "cli/cli.h"
#include "view/camera.h"
#include "scene/scene.h"
#include "util.h"

/* Zero means default (offline_desc_defaults): size GPU_DEFAULT_WIDTH x GPU_DEFAULT_HEIGHT, the
 * scene's spp, bands of at most 2 Mpixel, the whole image. */
typedef struct offline_desc {
    const scene *scene;
    camera cam;
    int width, height, spp;
    const char *output;
    unsigned aovs; /* cli.h aov_flag bits */
    const char *description; /* shot.h's text, stored in the file (NULL: none) */
    int strip_rows; /* rows a band (0: as many as fit 2 Mpixel); the image is rendered and written in bands */
    int tile_index, tile_count; /* tile I of N (1 = top) of the width × height image; count 0: all of it */
    bool quiet;
} offline_desc;

/* Tiles: a poster too big for one machine or one job, cut into N horizontal strips (tile 1 at the top).
 * Strips are cut from the bottom in even row counts, like bands, so a tile's pixels equal the same
 * rows of the whole image bit for bit; the top tile takes the remainder. Each tile file records where
 * it sits (TILE_KEY: "index count width height top aovs") and the whole shot's description. */
#define TILE_KEY "fathom_tile"
enum { TILE_MAX = 4096 };
void offline_tile_rows(int height, int index, int count, int *top, int *rows);
/* "poster.png", 3, 16 -> "poster.tile-03-of-16.png" */
bool offline_tile_name(const char *output, int index, int count, char *out, size_t n, err_t *err);
/* A tile file's record (TILE_KEY text), parsed and checked against what fathom writes: counts and sizes
 * in range, AOV bits fathom knows (a PNG tile carries none), nothing after them. False: damaged. */
typedef struct tile_record {
    int index, count, width, height, top;
    unsigned aovs;
} tile_record;
bool offline_tile_record(const char *text, bool png, tile_record *r);
/* Writes output from the n tile files (any order), checking they are one complete set. */
bool offline_stitch(const char *output, const char *const *tiles, int n, bool quiet, err_t *err);

/* d with its zero fields given their defaults. */
offline_desc offline_desc_defaults(const offline_desc *d);

/* One shot as `base` asks it (size, AOVs, bands, quiet; zero: the defaults; spp from s) of s from cam
 * into output, with the description the file keeps (scene, the overrides `sets` it was loaded with,
 * camera, size): the single shot and every frame of a flight are set up here. Free *description. */
offline_desc offline_shot(offline_desc base, const scene *s, camera cam, const char *output, const char *const *sets,
                          int nsets, strbuf *description);

/* Renders and writes d->output. Opens and closes its own headless context. */
bool offline_render(const offline_desc *d, err_t *err);

/* The same in the current GL context, after render_init and image_can_write (tests). */
bool offline_render_current(const offline_desc *d, err_t *err);

/* Writes the current render target to path (.png or .exr with aovs); used by offline and screenshots. */
bool offline_write(const char *path, int width, int height, unsigned aovs, const char *description, err_t *err);

#endif
