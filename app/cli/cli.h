/* cli — the command line, parsed into an options struct. No GL. cli_parse reads no file (it only
 * resolves --formula FILE to an absolute path, realpath); cli_apply_shot reads the shot it opens.
 *
 *   fathom [options]              explorer window (or an offline shot with --output)
 *   fathom bench [options]        what accuracy costs: knob sweeps, presets, effects (time and error)
 *   fathom render --path F ...    a flight: the frames of a camera path (app/view/path.h) to numbered files
 *   fathom stitch --output F T... tiles rendered with --tile I/N, joined into the whole image
 *   fathom check-formula NAME     a fractal formula's distance estimate checked (jobs/check/check.h)
 *   fathom mesh --output F ...    the scene's surface as a mesh file (jobs/mesh/mesh_job.h)
 *   fathom --help                 usage
 *
 * Angles are degrees on the command line (radians inside the code); sizes are pixels.
 */
#ifndef FATHOM_CLI_H
#define FATHOM_CLI_H

#include <stdbool.h>

#include "view/camera.h"
#include "view/shot.h"
#include "util.h"

enum { CLI_MAX_SETS = 192 };
/* The render targets hold 16 bytes a pixel (RGBA32F), and llvmpipe refuses a texture over 2 GB (an
 * assert fired at 11586x11586): the window and the bench, which hold the whole image, take at most this
 * many pixels; offline shots render in strips. */
enum { CLI_TARGET_BYTES_PER_PIXEL = 16, CLI_MAX_TARGET_PIXELS = 0x7fffffff / CLI_TARGET_BYTES_PER_PIXEL };

typedef enum aov_flag {
    AOV_DEPTH = 1u << 0,  /* distance along the normalized ray to the first hit, +inf on a miss */
    AOV_NORMAL = 1u << 1, /* world-space unit normal at the first hit, 0 on a miss */
    AOV_STEPS = 1u << 2,  /* march steps of the primary ray */
    AOV_EXIT = 1u << 3,   /* direction in which the main path left the scene (debug for refraction) */
    AOV_VARIANCE = 1u << 4, /* per channel, the variance of the pixel's mean over its samples */
    AOV_SAMPLES = 1u << 5,  /* how many samples the pixel took */
    AOV_POSITION = 1u << 6, /* world position of the first hit (P.X, P.Y, P.Z), 0 on a miss */
    AOV_ALBEDO = 1u << 7,   /* the first hit's material colour (albedo.R/G/B), 0 on a miss */
    AOV_ALL = AOV_DEPTH | AOV_NORMAL | AOV_STEPS | AOV_EXIT | AOV_VARIANCE | AOV_SAMPLES | AOV_POSITION | AOV_ALBEDO,
} aov_flag;

typedef struct cli_options {
    const char *scene;  /* scene name (scenes/NAME.json) or a path to a scene file */
    bool scene_given;   /* --scene was on the command line */
    const char *dem;    /* --dem FILE: the dem scene with terrain.heightmap=FILE */
    char dem_set[PATH_MAX_LEN + 32];
    const char *formula; /* --formula NAME|FILE: fractal.formula=NAME (a file made absolute), the fractal scene */
    char formula_set[PATH_MAX_LEN + 32];
    const char *help_formula; /* --help-formula NAME|FILE */
    const char *output; /* NULL: window; else offline shot to .png or .exr */
    int width, height;  /* 0: default */
    int spp;            /* 0: the quality preset's */
    int strip_rows;     /* offline: rows rendered and written at a time; 0: as many as fit 2 Mpixel */
    int frames;         /* window: exit after N frames; 0: run until closed */
    const char *path;   /* --path FILE: render a flight's frames (flight.h) */
    bool has_frames;    /* --frames given (with --path: the range) */
    const char *frames_arg;
    int frame_first, frame_last; /* --path: frames to render (inclusive); without --frames, all */
    int tile_index, tile_count; /* --tile I/N: render tile I (1 = top) of N; count 0: the whole image */
    bool stitch;                /* `fathom stitch`: join the tile files in inputs into --output */
    bool render_word;           /* `fathom render ...`: an offline shot or flight, never the window */
    const char *inputs[4096];
    int input_count;
    const char *video;  /* --video: a flight video's encoding (data/media/video.h), or NULL */
    int fps;            /* window: frame rate to hold while moving; 0: the default (30) */
    const char *backend; /* --backend auto|fragment|compute (NULL: FATHOM_BACKEND, else auto) */
    bool has_camera, has_look_at, has_fov;
    bool has_view;      /* --scene SHOT.png or --view NAME: the shot's exact camera (shot.h) */
    const char *view_name; /* --view NAME: a saved view of the scene (views.h) */
    camera view;
    double camera[3], look_at[3];
    float fov_deg;
    const char *sets[CLI_MAX_SETS]; /* "key=value" scene overrides, in order */
    char preset_sets[CLI_MAX_SETS][48]; /* storage for the overrides --quality writes (slot = its index) */
    int set_count;
    unsigned aovs; /* aov_flag bits */
    bool print_variant, list_scenes, list_formulas, help, version, quiet;
    bool panel; /* window: start with the parameter panel open */
    bool bench;        /* `fathom bench ...` */
    bool check_formula; /* `fathom check-formula NAME|FILE ...` (jobs/check/check.h) */
    int runs;          /* bench: timed images per setting (median reported) */
    bool runs_given;   /* --runs was on the command line */
    const char *out;   /* bench: folder for CSV, plot and summary (NULL: print only) */
    const char *name;  /* bench: file name prefix in that folder (NULL: the scene's name) */
    bool frame_times;  /* bench: only the presets' frame times (1 sample per pixel), no error */
    bool path_truth;   /* bench --truth path: errors against the path tracer, not the reference preset */
    bool quick, full;  /* bench: a short run (160x90, 3 runs, 3 values a knob) or a long one (640x360, 9 runs) */
    bool interactive;  /* bench: a scripted flight as the window flies it */
    bool terrain_scale; /* bench: generated DEMs from 256² up: load time, memory, frame time */
    bool terrain_stream; /* bench: VRT mosaics past memory, streamed: open, first image, shot, memory */
    bool final_frame;   /* bench: the final preset's whole shot, every pixel against adaptive */
    bool viewshed;      /* bench --viewshed: the exact viewshed's cost against GDAL's */
    const char *knobs[CLI_MAX_SETS]; /* bench: "NAME=v1,v2,..." sweeps (none: every knob, default values) */
    int knob_count;
    bool mesh;            /* `fathom mesh ...` (jobs/mesh/mesh_job.h) */
    int mesh_resolution;  /* --resolution N (0: the default) */
    bool has_box;         /* --box: the box meshed */
    double box[6];
    long mesh_triangles;  /* --triangles N: simplify toward N (0: keep all) */
    double mesh_tolerance; /* --tolerance V: in voxels (0: the default) */
    bool one_shell;       /* --one-shell */
    double print_mm;      /* --print-size MM */
    double mesh_base;     /* --base M */
} cli_options;

/* Parses argv into *o (zeroed first). False with one line in err on bad input. */
bool cli_parse(int argc, char **argv, cli_options *o, err_t *err);

/* Parses "WxH" with 1 <= W,H <= 16384. */
bool cli_parse_size(const char *s, int *w, int *h);

/* Parses "X,Y,Z" (finite floats). */
bool cli_parse_vec3(const char *s, double v[3]); /* double: a deep zoom's camera needs the digits */

const char *cli_usage(void);

/* cli_mesh.c: `fathom mesh`'s options (handled false: not one of them), their combinations, usage. */
bool cli_mesh_option(const char *name, const char *val, cli_options *o, err_t *err, bool *handled);
bool cli_mesh_check(const cli_options *o, err_t *err);
const char *cli_mesh_usage(void);
/* cli_gis.c: `fathom viewshed` and `fathom track`'s usage (their options: cli_gis.h). */
const char *cli_gis_usage(void);

/* --scene IMAGE: reads the image's shot and rewrites o to reopen it. The image's overrides come first
 * and the command line's after them (so they win); its camera and size are used unless the command
 * line gives its own. */
bool cli_apply_shot(cli_options *o, shot_desc *d, err_t *err);
/* The same from a shot text already read (a saved view: views.h). */
bool cli_apply_shot_text(cli_options *o, const char *text, const char *source, shot_desc *d, err_t *err);

#endif
