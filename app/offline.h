/* offline — a headless shot: EGL context, progressive samples with a progress bar, atomic write.
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
    bool quiet;
} offline_desc;

/* Renders and writes d->output. Opens and closes its own headless context. */
bool offline_render(const offline_desc *d, err_t *err);

/* Writes the current render target to path (.png or .exr with aovs); used by offline and screenshots. */
bool offline_write(const char *path, int width, int height, unsigned aovs, err_t *err);

#endif
