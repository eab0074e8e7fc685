/* offline — a headless shot: EGL context, progressive samples with a progress bar, verified write.
 * Any size up to 16384² renders in bands of rows, each written as it is done (bounded memory).
 * .png: tone-mapped 8-bit sRGB. .exr: linear float RGBA plus the requested AOV channels
 * (Z = depth along the unit ray, +inf on a miss; N.X N.Y N.Z; steps; exit.X exit.Y exit.Z). */
#ifndef FATHOM_OFFLINE_H
#define FATHOM_OFFLINE_H

#include <stdbool.h>

#include "camera.h"
#include "scene.h"
#include "util.h"

typedef struct offline_desc {
    const scene *scene;
    camera cam;
    int width, height, spp;
    const char *output;
    unsigned aovs; /* cli.h aov_flag bits */
    const char *description; /* shot.h's text, stored in the file (NULL: none) */
    int strip_rows; /* rows a band (0: as many as fit 2 Mpixel); the image is rendered and written in bands */
    bool quiet;
} offline_desc;

/* Renders and writes d->output. Opens and closes its own headless context. */
bool offline_render(const offline_desc *d, err_t *err);

/* The same in the current GL context, after render_init and image_can_write (tests). */
bool offline_render_current(const offline_desc *d, err_t *err);

/* Writes the current render target to path (.png or .exr with aovs); used by offline and screenshots. */
bool offline_write(const char *path, int width, int height, unsigned aovs, const char *description, err_t *err);

#endif
