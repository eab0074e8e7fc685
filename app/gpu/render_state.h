/* render_state — what the render module's files share (render.c: targets and samples;
 * render_output.c: display and readback): one renderer, one state. Internal to gpu/render*. GL. */
#ifndef FATHOM_RENDER_STATE_H
#define FATHOM_RENDER_STATE_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "gpu/render.h"
#include "view/camera.h"

enum { NUM_TARGETS = 5 }; /* radiance, normal and depth, steps and exit, radiance squared, albedo */

typedef struct render_state {
    GLuint display_prog;
    GLuint fbo, targets[NUM_TARGETS];
    GLuint out_fbo, out_tex; /* RGBA8 for sRGB readback */
    GLuint ref_fbo, ref_tex; /* a grabbed image for the difference view */
    int ref_samples;
    int width, height, samples;   /* the active image: all of the targets or, while flying, a corner */
    int alloc_width, alloc_height; /* the targets' size */
    int full_width, full_height, tile_x, tile_y; /* the image the target is a band of; its GL offset */
    GLuint prog; /* the current scene's program */
    /* adaptive sampling (render.c's masked_sample): samples only where mask_tex is set, the window's
     * edge mask (render_set_adaptive, shaders/edgemask.frag) or the standard error's (errormask.frag);
     * each pixel's alpha counts its own samples */
    bool adaptive;
    bool edge_aware; /* stretched images: depth-aware upsampling (display.frag) */
    GLuint mask_prog, error_prog, mask_fbo, mask_tex;
    int masked;            /* pixels the mask kept, of the last mask */
    bool converged;        /* the last error mask kept no pixel: the image is done */
    double pixel_samples;  /* samples taken by the image's pixels, all together */
    int band_done; /* rows of the current sample done by render_sample_band, from the top */
    int first_jitter; /* the Halton point of an image's first sample (0: the pixel centre) */
    GLuint preview_fbo, preview_tex; /* the last moving image, shown where a still one has no sample yet */
    GLuint stretch_fbo, stretch_tex; /* a moving image tone-mapped at its own size, before the stretch */
    int preview_w, preview_h;
    camera cam;
    double origin[3]; /* a deep zoom's: the world position the shader's coordinates are relative to */
    float heat_max;   /* the steps heat map's top (0: the scene's MAX_STEPS) */
    unsigned runtime_effects; /* effects switched on at run time (bits as in effect.h) */
    render_backend backend;   /* resolved by render_init: fragment or compute */
} render_state;

extern render_state render_shared;

#endif
