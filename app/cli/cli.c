/* realpath() is XSI */
#define _XOPEN_SOURCE 700
#include "cli/cli.h"

#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "view/camera.h"
#include "view/path.h"
#include "scene/quality.h"
#include "scene/scene.h"
#include "scene/formula/frag.h"
#include "data/media/image_io.h"
#include "data/media/video.h"

enum { MAX_IMAGE_SIDE = 16384, MAX_SPP = 1 << 16, DEFAULT_RUNS = 5, MAX_RUNS = 1000 };
static const float MAX_FOV_DEG = 179.0f; /* vertical field of view; 180 degrees has no perspective */

static const char USAGE[] =
    "usage: fathom [options]\n"
    "       fathom bench [--scene S] [--size WxH] [--runs N] [--knob NAME=v1,v2,...]... [--truth model|path]\n"
    "                    [--quick|--full] [--out DIR] [--name N]\n"
    "       fathom render --path FLIGHT.json [--frames A-B] [--fps N] --output DIR/frame_%04d.png [options]\n"
    "       fathom render --path FLIGHT.json [--fps N] [--video LIST] --output flight.mp4 [options]\n"
    "       fathom stitch --output POSTER.png POSTER.tile-*.png\n"
    "       fathom check-formula NAME|FILE [--set fractal.KEY=VALUE]... [--quick]\n"
    "  Opens the explorer window, or renders an offline shot with --output (no display needed).\n"
    "  bench: headless; for fixed views, sweeps each accuracy knob on its own (default: all that\n"
    "  apply), the presets and every effect; time = median of N [5] images after warm-up (wall clock\n"
    "  around glFinish); error against a reference render. --out writes CSVs, plots (one panel a knob;\n"
    "  an overview of the presets and the Pareto front), a summary and an HTML report [240x135: 3-5 min\n"
    "  on 2 CPU cores];\n"
    "  the knob CSV grows row by row, so a run stopped half-way keeps the rows it finished.\n"
    "  --quick: 160x90, 3 runs, 3 values a knob (a first look in a minute or two); --full: 640x360,\n"
    "  9 runs (--size, --runs and --knob still win).\n"
    "  bench --truth path: the error against the path tracer (quality.integrator=1, 256 spp) instead\n"
    "  of the reference preset, and the model's approximations (AO, soft shadows, fog) swept too;\n"
    "  with --out, difference images of the presets and approximations against it (in the report).\n"
    "  bench --frame-times: only each preset's frame time (one sample per pixel), median of N.\n"
    "  bench --interactive [--fps N]: a scripted 100-frame flight as the window flies it (lower\n"
    "  internal resolution for N fps [30]): frame times, internal size, error, time to converge [1280x720].\n"
    "  bench --terrain-scale [--knob side=N1,N2,...]: generated DEMs from 256² to 32768²: load time, peak\n"
    "  memory, frame time and height samples per pixel, maxmip and linear [640x360].\n"
    "  bench --terrain-stream [--knob side=N1,N2,...]: DEMs past memory (VRT mosaics of a generated\n"
    "  4096² tile, 4096² to 65536²) streamed from disk: open, first image, shot, warm frames against\n"
    "  in core, peak memory, bytes read [640x360].\n"
    "  bench --final-frame: the final preset's whole shot as a process, every pixel sampled against\n"
    "  adaptive sampling (quality.tolerance) in turn: time, samples a pixel, difference [1920x1080].\n"
    "  bench --viewshed [--knob side=N1,N2,...]: the exact viewshed on generated DEMs [512² to 4096²]\n"
    "  against GDAL's: times and where GDAL's answer differs.\n"
    "  render --path: the frames of a camera path (keyframe file: docs/flights.md) at N frames a second\n"
    "  [30], each written atomically to the pattern's file; frames already on disk are skipped (resume).\n"
    "  --tile I/N renders tile I of N (horizontal strips) of the --output image to OUTPUT.tile-I-of-N.EXT;\n"
    "  stitch joins the N tiles into the whole image, bit for bit as if rendered at once.\n"
    "  check-formula: NaN/Inf over random points, the distance estimate against the distance to the\n"
    "  surface along random rays, then rays around the worst (the worst overshoot and the step factor\n"
    "  that avoids it), and that the set stays inside its bounding sphere: at the defaults, then with\n"
    "  each parameter at the ends of its range (the worst set named); --quick: the defaults only.\n"
    "\n"
    ;
/* the options (ISO C bounds one string literal at 4095 characters) */
static const char USAGE_OPTIONS[] =
    "  --scene NAME|FILE     scene to load: a name from scenes/ (csg), a scene file path, or a PNG/EXR\n"
    "                        or .fathom preset fathom wrote (reopens its scene, overrides and view), or a\n"
    "                        Fragmentarium DE fragment (.frag, unmodified: at its default preset) [csg]\n"
    "  --dem FILE            open any DEM GDAL reads (GeoTIFF, .hgt, .asc, netCDF, VRT, ...) with a\n"
    "                        camera framed from its extent (the dem scene, with terrain.heightmap=FILE)\n"
    "  --formula NAME|FILE   a fractal formula: a shipped or user name, your own .glsl file or a .frag\n"
    "                        fragment (the fractal scene framed from its bound, or --scene's)\n"
    "  --help-formula NAME   the formula's parameters: type, default, range, meaning\n"
    "  --list-formulas       list the formulas (shipped, then ~/.config/fathom/formulas/)\n"
    "  --output FILE         render headless to FILE (.png 8-bit sRGB, .exr linear float) and exit\n"
    "  --size WxH            image or window size in pixels [1280x720]\n"
    "  --spp N               samples per pixel (progressive, jittered: anti-aliasing) [preset]\n"
    "  --strip-rows N        offline: render in bands of N rows (bounded memory at any size;\n"
    "                        at most 16 Mpixel a band) [2 Mpixel]\n"
    "  --quality Q           draft | interactive | final | reference [the scene's]\n"
    "  --camera X,Y,Z        camera position\n"
    "  --look-at X,Y,Z       point the camera looks at\n"
    "  --fov DEG             vertical field of view in degrees (0 < DEG < 179)\n"
    "  --view NAME           start from a view saved with B in the window (1-9), with its overrides;\n"
    "                        for a fragment, one of its presets (--help-formula lists them)\n"
    "  --set KEY=VALUE       override any scene parameter, e.g. --set materials.glass.ior=1.33,\n"
    "                        --set effects.fog=off, --set lights.0.intensity=40 (repeatable)\n"
    "  --aov LIST            extra EXR channels: depth,normal,steps,exit,variance,samples,position,albedo\n"
    "                        (needs .exr output; the camera goes in as worldToCamera and worldToNDC)\n"
    "  --frames N            window mode: render N frames, then exit (and say what they cost); with\n"
    "                        --path: frames A-B or N\n"
    "  --panel               window: start with the parameter panel open (F1 toggles it)\n"
    "  --path FILE           a camera path (keyframes) to render frame by frame (with --output PATTERN),\n"
    "                        or to a video (--output NAME.mp4, .webm or .mkv; frames in NAME.mp4.frames/)\n"
    "                        (a .frag: its KeyFrame presets, over 10 s; --scene the same fragment)\n"
    "  --video LIST          the video's codec=h264|av1|vp9, crf=N (quality: lower is better) and\n"
    "                        pix_fmt=yuv420p|yuv444p [h264 (webm: vp9), crf 18 (vp9: 6, av1: 3), yuv420p]\n"
    "  --tile I/N            render only tile I of N of the --output image (for posters and farms)\n"
    "  --fps N               window: frame rate to hold while moving (lower internal resolution) [30];\n"
    "                        with --path: frames per second of the flight [30]\n"
    "  --print-variant       print the effects and #defines the scene compiles, then exit\n"
    "  --list-scenes         list the shipped scenes, each with its title\n"
    "  --backend B           auto | fragment | compute: how samples run (compute needs GL 4.3 and\n"
    "                        reaches all of a datacenter GPU); FATHOM_BACKEND=B too [auto: compute\n"
    "                        on a GPU, fragment on llvmpipe]\n"
    "  --quiet               no progress bar\n"
    "  --help, --version\n"
    "\n"
    "Window keys: WASD move, mouse look, Space/C up/down, Shift faster, scroll speed, F1 or Tab the\n"
    "parameter panel, F2 the full HUD, O orbit, T walk, 1-9 scenes, Ctrl+Z undo, Ctrl+S save a preset,\n"
    "R reload shaders, P or F12 screenshot, N keyframe (Shift+N clears, L plays the flight), J a\n"
    "fragment's next preset (Shift+J the previous), Esc quit.\n";

const char *cli_usage(void)
{
    static char text[sizeof USAGE + sizeof USAGE_OPTIONS + 4096];
    if (!text[0])
        snprintf(text, sizeof text, "%s%s%s\n%s", USAGE, cli_mesh_usage(), cli_gis_usage(), USAGE_OPTIONS);
    return text;
}

static bool parse_int(const char *s, long lo, long hi, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end != '\0' || v < lo || v > hi)
        return false;
    *out = (int)v;
    return true;
}

static bool parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end != '\0' || !isfinite(v))
        return false;
    *out = v;
    return true;
}

static bool parse_float(const char *s, float *out)
{
    double v;
    if (!parse_double(s, &v) || !(fabs(v) <= FLT_MAX))
        return false;
    *out = (float)v;
    return true;
}

bool cli_parse_size(const char *s, int *w, int *h)
{
    const char *x = strchr(s, 'x');
    if (!x || x == s || (size_t)(x - s) >= 16)
        return false;
    char left[16];
    memcpy(left, s, (size_t)(x - s));
    left[x - s] = '\0';
    return parse_int(left, 1, MAX_IMAGE_SIDE, w) && parse_int(x + 1, 1, MAX_IMAGE_SIDE, h);
}

bool cli_parse_vec3(const char *s, double v[3])
{
    char buf[128];
    if (strlen(s) >= sizeof buf)
        return false;
    strcpy(buf, s);
    char *parts[3], *p = buf;
    for (int i = 0; i < 3; i++) {
        parts[i] = p;
        char *comma = strchr(p, ',');
        if (i < 2) {
            if (!comma)
                return false;
            *comma = '\0';
            p = comma + 1;
        } else if (comma) {
            return false;
        }
    }
    for (int i = 0; i < 3; i++)
        if (!parse_double(parts[i], &v[i]) || fabs(v[i]) > CAMERA_MAX_COORD)
            return false;
    return true;
}

static bool parse_aovs(const char *s, unsigned *mask)
{
    static const struct { const char *name; aov_flag flag; } names[] = {
        {"depth", AOV_DEPTH}, {"normal", AOV_NORMAL}, {"steps", AOV_STEPS}, {"exit", AOV_EXIT},
        {"variance", AOV_VARIANCE}, {"samples", AOV_SAMPLES}, {"position", AOV_POSITION},
        {"albedo", AOV_ALBEDO}};
    *mask = 0;
    const char *p = s;
    while (*p) {
        size_t n = strcspn(p, ",");
        bool found = false;
        for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
            if (strlen(names[i].name) == n && strncmp(p, names[i].name, n) == 0) {
                *mask |= names[i].flag;
                found = true;
            }
        if (!found)
            return false;
        p += n;
        if (*p == ',')
            p++;
    }
    return *mask != 0;
}

/* --formula NAME|FILE: the override fractal.formula=… (a file by its absolute path, so shots made with
 * it reopen from any folder). Without --scene the fractal scene frames it ("camera": "auto"). */
static bool set_formula(const char *val, cli_options *o, err_t *err)
{
    if (o->formula || o->dem)
        return err_set(err, "--formula: give it once, and not with --dem");
    if (!*val)
        return err_set(err, "bad --formula '': a formula's name (fathom --list-formulas) or a .glsl file");
    if (o->set_count == CLI_MAX_SETS)
        return err_set(err, "too many --set options (at most %d)", CLI_MAX_SETS);
    char abs[PATH_MAX];
    bool file = strchr(val, '/') || strstr(val, ".glsl") || strstr(val, ".frag");
    if (file && !realpath(val, abs))
        return err_set(err, "--formula: file '%s' not found (a path from the folder you are in)", val);
    if (snprintf(o->formula_set, sizeof o->formula_set, "fractal.formula=%s", file ? abs : val) >=
        (int)sizeof o->formula_set)
        return err_set(err, "bad --formula: the path is longer than %d characters", PATH_MAX_LEN - 1);
    o->formula = val;
    o->sets[o->set_count++] = o->formula_set;
    return true;
}

/* Options that take a value, first half: what to render and where (*handled: it was one of them). */
static bool set_output_option(const char *name, const char *val, cli_options *o, err_t *err, bool *handled)
{
    *handled = true;
    if (!strcmp(name, "--scene")) {
        if (frag_is_fragment(val)) /* a Fragmentarium fragment is a formula of the fractal scene */
            return set_formula(val, o, err);
        if (o->dem)
            return err_set(err, "--scene and --dem both name what to render: give one");
        o->scene = val;
        o->scene_given = true;
    } else if (!strcmp(name, "--dem")) {
        if (o->scene_given || o->dem || o->formula)
            return err_set(err, "--dem opens a DEM in the dem scene: give it once, without --scene or --formula");
        if (!*val)
            return err_set(err, "bad --dem '': the path of an elevation file (GeoTIFF, .hgt, .asc, netCDF, ...)");
        if (o->set_count == CLI_MAX_SETS)
            return err_set(err, "too many --set options (at most %d)", CLI_MAX_SETS);
        if (snprintf(o->dem_set, sizeof o->dem_set, "terrain.heightmap=%s", val) >= (int)sizeof o->dem_set)
            return err_set(err, "bad --dem: the path is longer than %d characters", PATH_MAX_LEN - 1);
        o->dem = val;
        o->scene = "dem";
        o->sets[o->set_count++] = o->dem_set;
    } else if (!strcmp(name, "--formula")) {
        return set_formula(val, o, err);
    } else if (!strcmp(name, "--help-formula")) {
        o->help_formula = val;
    } else if (!strcmp(name, "--output")) {
        o->output = val;
    } else if (!strcmp(name, "--size")) {
        if (!cli_parse_size(val, &o->width, &o->height))
            return err_set(err, "bad --size '%s': expected WxH with 1 <= W,H <= %d, e.g. 1920x1080", val,
                           MAX_IMAGE_SIDE);
    } else if (!strcmp(name, "--spp")) {
        if (!parse_int(val, 1, MAX_SPP, &o->spp))
            return err_set(err, "bad --spp '%s': expected a whole number from 1 to %d", val, MAX_SPP);
    } else if (!strcmp(name, "--strip-rows")) {
        if (!parse_int(val, 1, MAX_IMAGE_SIDE, &o->strip_rows))
            return err_set(err, "bad --strip-rows '%s': expected a whole number from 1 to %d", val, MAX_IMAGE_SIDE);
    } else if (!strcmp(name, "--runs")) {
        if (!parse_int(val, 1, MAX_RUNS, &o->runs))
            return err_set(err, "bad --runs '%s': expected a whole number from 1 to %d", val, MAX_RUNS);
        o->runs_given = true;
    } else if (!strcmp(name, "--out")) {
        o->out = val;
    } else if (!strcmp(name, "--name")) {
        if (!*val || strchr(val, '/'))
            return err_set(err, "bad --name '%s': a file name prefix, without '/'", val);
        o->name = val;
    } else if (!strcmp(name, "--knob")) {
        if (!strchr(val, '=') || val[0] == '=')
            return err_set(err, "bad --knob '%s': expected NAME=v1,v2,..., e.g. --knob max_steps=32,64,128", val);
        if (o->knob_count == CLI_MAX_SETS)
            return err_set(err, "too many --knob options (at most %d)", CLI_MAX_SETS);
        o->knobs[o->knob_count++] = val;
    } else if (!strcmp(name, "--view")) {
        if (!*val || strchr(val, '/'))
            return err_set(err, "bad --view '%s': the name of a saved view (B in the window saves views 1 to 9)", val);
        o->view_name = val;
    } else if (!strcmp(name, "--fps")) {
        if (!parse_int(val, 1, 1000, &o->fps))
            return err_set(err, "bad --fps '%s': expected a whole number from 1 to 1000", val);
    } else if (!strcmp(name, "--frames")) {
        o->has_frames = true;
        o->frames_arg = val; /* a count for the window, a range for --path: decided once all are read */
    } else if (!strcmp(name, "--video")) {
        o->video = val; /* checked with --output (its container) once all are read */
    } else if (!strcmp(name, "--path")) {
        o->path = val;
    } else if (!strcmp(name, "--tile")) {
        int i = 0, n = 0, used = 0;
        if (sscanf(val, "%d/%d%n", &i, &n, &used) != 2 || val[used] || n < 1 || n > 4096 || i < 1 || i > n)
            return err_set(err, "bad --tile '%s': expected I/N with 1 <= I <= N <= 4096, e.g. --tile 3/16", val);
        o->tile_index = i;
        o->tile_count = n;
    } else {
        *handled = false;
    }
    return true;
}

/* --quality Q is sugar for --set quality.preset=Q, checked here so a typo is a command-line error. */
static bool add_quality(const char *val, cli_options *o, err_t *err)
{
    quality_preset p;
    if (!preset_from_name(val, &p)) {
        strbuf known = {0};
        for (int i = 0; i < PRESET_COUNT; i++)
            sb_printf(&known, "%s%s", i ? ", " : "", preset_name((quality_preset)i));
        err_set(err, "bad --quality '%s': use one of %s", val, known.data);
        sb_free(&known);
        return false;
    }
    if (o->set_count == CLI_MAX_SETS)
        return err_set(err, "too many --set/--quality options (at most %d)", CLI_MAX_SETS);
    /* one buffer per override slot: a later --quality adds, never rewrites */
    char *buf = o->preset_sets[o->set_count];
    snprintf(buf, sizeof o->preset_sets[0], "quality.preset=%s", preset_name(p));
    o->sets[o->set_count++] = buf;
    return true;
}

/* Options that take a value, second half: the view, the scene's parameters and how it is rendered. */
static bool set_view_option(const char *name, const char *val, cli_options *o, err_t *err)
{
    if (!strcmp(name, "--fov")) {
        if (!parse_float(val, &o->fov_deg) || o->fov_deg <= 0.0f || o->fov_deg >= MAX_FOV_DEG)
            return err_set(err, "bad --fov '%s': expected degrees, 0 < fov < %g", val, (double)MAX_FOV_DEG);
        o->has_fov = true;
    } else if (!strcmp(name, "--camera")) {
        if (!cli_parse_vec3(val, o->camera))
            return err_set(err, "bad --camera '%s': expected X,Y,Z within ±%g m, e.g. 0,1.5,6", val, CAMERA_MAX_COORD);
        o->has_camera = true;
    } else if (!strcmp(name, "--look-at")) {
        if (!cli_parse_vec3(val, o->look_at))
            return err_set(err, "bad --look-at '%s': expected X,Y,Z within ±%g m, e.g. 0,0.5,0", val, CAMERA_MAX_COORD);
        o->has_look_at = true;
    } else if (!strcmp(name, "--quality")) {
        return add_quality(val, o, err);
    } else if (!strcmp(name, "--set")) {
        if (!strchr(val, '=') || val[0] == '=')
            return err_set(err, "bad --set '%s': expected KEY=VALUE, e.g. --set camera.fov=40", val);
        if (o->set_count == CLI_MAX_SETS)
            return err_set(err, "too many --set options (at most %d)", CLI_MAX_SETS);
        o->sets[o->set_count++] = val;
    } else if (!strcmp(name, "--aov")) {
        if (!parse_aovs(val, &o->aovs))
            return err_set(err, "bad --aov '%s': expected a comma list of depth, normal, steps, exit, variance, samples, position, albedo", val);
    } else if (!strcmp(name, "--truth")) {
        if (strcmp(val, "model") && strcmp(val, "path"))
            return err_set(err, "bad --truth '%s': use model (the reference preset) or path (the path tracer)", val);
        o->path_truth = !strcmp(val, "path");
    } else if (!strcmp(name, "--backend")) {
        if (strcmp(val, "auto") && strcmp(val, "fragment") && strcmp(val, "compute"))
            return err_set(err, "bad --backend '%s': use auto, fragment or compute", val);
        o->backend = val;
    } else {
        return err_set(err, "unknown option '%s' (see fathom --help)", name);
    }
    return true;
}

/* Flags without a value. False: a is not one of them. */
static bool set_flag(const char *a, cli_options *o)
{
    static const struct { const char *name; size_t offset; } FLAGS[] = {
        {"--help", offsetof(cli_options, help)},           {"-h", offsetof(cli_options, help)},
        {"--version", offsetof(cli_options, version)},     {"--print-variant", offsetof(cli_options, print_variant)},
        {"--list-scenes", offsetof(cli_options, list_scenes)}, {"--quiet", offsetof(cli_options, quiet)},
        {"--list-formulas", offsetof(cli_options, list_formulas)},
        {"--frame-times", offsetof(cli_options, frame_times)},
        {"--quick", offsetof(cli_options, quick)},         {"--full", offsetof(cli_options, full)},
        {"--interactive", offsetof(cli_options, interactive)},
        {"--terrain-scale", offsetof(cli_options, terrain_scale)},
        {"--terrain-stream", offsetof(cli_options, terrain_stream)},
        {"--final-frame", offsetof(cli_options, final_frame)}, {"--viewshed", offsetof(cli_options, viewshed)},
        {"--panel", offsetof(cli_options, panel)},
        {"--one-shell", offsetof(cli_options, one_shell)},
    };
    for (size_t i = 0; i < sizeof FLAGS / sizeof FLAGS[0]; i++)
        if (!strcmp(a, FLAGS[i].name)) {
            *(bool *)((char *)o + FLAGS[i].offset) = true;
            return true;
        }
    return false;
}

/* A video output: a flight's, with --video's options good for its container. */
static bool check_video(const cli_options *o, err_t *err)
{
    video_options vo;
    bool video = o->output && video_is_file(o->output);
    if ((o->video || video) && !(o->path && video))
        return err_set(err, "a video is a flight's: give --path FLIGHT.json and --output NAME.mp4 (or .webm, .mkv)%s",
                       o->video ? " with --video" : "");
    return !o->video || video_options_parse(o->video, o->output, &vo, err);
}

/* Options that only make sense together. */
static bool check_combinations(const cli_options *o, err_t *err)
{
    if (o->mesh || !cli_mesh_check(o, err)) /* fathom mesh: its own rules (cli_mesh.c) */
        return o->mesh && cli_mesh_check(o, err);
    if (o->stitch && (!o->output || o->input_count == 0))
        return err_set(err, "stitch needs --output POSTER and the tile files, e.g. fathom stitch --output "
                            "poster.png poster.tile-*.png");
    if (o->tile_count && (!o->output || o->path || o->bench || o->stitch))
        return err_set(err, "--tile renders one tile of an offline shot: give --output (and no --path)");
    if (o->tile_count && o->tile_count > (o->height ? o->height : FATHOM_DEFAULT_HEIGHT) / 2)
        return err_set(err, "--tile %d/%d: at most %d tiles for an image %d rows tall (2 rows a tile at least)",
                       o->tile_index, o->tile_count, (o->height ? o->height : FATHOM_DEFAULT_HEIGHT) / 2, o->height ? o->height : FATHOM_DEFAULT_HEIGHT);
    if (o->path && (o->bench || !o->output))
        return err_set(err, "--path renders a flight's frames: give --output with a %%d for the frame number, e.g. "
                            "--output out/frame_%%04d.png");
    if (o->render_word && !o->output && !o->print_variant)
        return err_set(err, "fathom render needs --output: a file for a shot, or a pattern with %%d and --path for a "
                            "flight (fathom --help)");
    if (o->path && (o->has_camera || o->has_look_at || o->has_fov || o->has_view))
        return err_set(err, "--path gives the camera for every frame: drop --camera, --look-at, --fov and --view");
    if (o->path && !video_is_file(o->output)) {
        char name[PATH_MAX_LEN];
        if (!path_frame_name(o->output, 0, name, sizeof name, err))
            return false;
    }
    if (o->bench && (o->output || o->aovs || o->frames || o->print_variant))
        return err_set(err, "fathom bench takes --scene, --size, --runs, --knob, --truth, --quick, --full, --out, --name, --set and --quiet only");
    if (!o->bench && (o->out || o->name || o->knob_count || o->frame_times || o->runs_given || o->path_truth ||
                      (o->quick && !o->check_formula) || o->full))
        return err_set(err, "--runs, --knob, --out, --name, --truth, --quick and --full belong to fathom bench "
                            "(check-formula takes --quick too)");
    if (o->quick && o->full)
        return err_set(err, "bench --quick and --full: pick one (a short run or a long one)");
    if (o->aovs && !o->output)
        return err_set(err, "--aov needs an offline shot: add --output FILE.exr");
    if (o->fps && ((o->output && !o->path) || (o->bench && !o->interactive)))
        return err_set(err, "--fps is the window's (and bench --interactive's): it does not apply here");
    if (o->check_formula && (o->output || o->aovs || o->path || o->tile_count || o->spp || o->width || o->frames))
        return err_set(err, "fathom check-formula prints a report: --output, --aov, --path, --tile, --spp, --size and "
                            "--frames do not apply (it takes NAME|FILE, --scene, --set and --quick)");
    if ((o->bench || (!o->output && !o->stitch && !o->check_formula && !o->help_formula)) && o->width &&
        (long)o->width * o->height > CLI_MAX_TARGET_PIXELS)
        return err_set(err, "--size %dx%d: the window and the bench hold the whole image in %d-byte-a-pixel targets, "
                            "at most %ld pixels (a 2 GB texture); offline shots render in strips and take up to %dx%d",
                       o->width, o->height, CLI_TARGET_BYTES_PER_PIXEL, (long)CLI_MAX_TARGET_PIXELS, MAX_IMAGE_SIDE,
                       MAX_IMAGE_SIDE);
    if (o->panel && (o->output || o->bench || o->path || o->check_formula))
        return err_set(err, "--panel is the window's: it does not apply here");
    if (o->interactive && !o->bench)
        return err_set(err, "--interactive belongs to fathom bench");
    if ((o->terrain_scale || o->terrain_stream || o->final_frame || o->viewshed) && !o->bench)
        return err_set(err, "%s belongs to fathom bench",
                       o->final_frame ? "--final-frame" : o->viewshed ? "--viewshed"
                       : o->terrain_stream ? "--terrain-stream" : "--terrain-scale");
    if (o->has_frames && o->output && !o->path)
        return err_set(err, "--frames counts the window's frames (or a flight's, with --path): an offline shot "
                            "(--output without --path) is one image");
    if (o->strip_rows && !o->output)
        return err_set(err, "--strip-rows needs an offline shot: add --output FILE");
    if (o->has_camera && o->has_look_at && camera_degenerate(o->camera, o->look_at))
        return err_set(err, "--camera and --look-at are the same point: the camera needs a direction to look in");
    if (!check_video(o, err))
        return false;
    if (o->output && !video_is_file(o->output)) {
        const char *dot = strrchr(o->output, '.');
        bool png = dot && !strcasecmp(dot, ".png"), exr = dot && !strcasecmp(dot, ".exr");
        if (!png && !exr)
            return err_set(err, "bad --output '%s': the file name must end in .png or .exr (a flight's: or .mp4, "
                                ".webm, .mkv)", o->output);
        if (o->aovs && !exr)
            return err_set(err, "--aov channels need an EXR file: use --output %.*s.exr",
                           (int)(dot ? dot - o->output : (long)strlen(o->output)), o->output);
    }
    return true;
}

bool cli_parse(int argc, char **argv, cli_options *o, err_t *err)
{
    *o = (cli_options){.scene = "csg", .runs = DEFAULT_RUNS};
    int first = 1;
    if (argc > 1 && !strcmp(argv[1], "bench")) {
        o->bench = true;
        first = 2;
    } else if (argc > 1 && !strcmp(argv[1], "render")) { /* the offline word: --output says the same */
        o->render_word = true;
        first = 2;
    } else if (argc > 1 && !strcmp(argv[1], "mesh")) {
        o->mesh = true;
        first = 2;
    } else if (argc > 1 && !strcmp(argv[1], "stitch")) {
        o->stitch = true;
        first = 2;
    } else if (argc > 1 && !strcmp(argv[1], "check-formula")) { /* then the formula, then options */
        o->check_formula = true;
        if (argc < 3 || !strncmp(argv[2], "--", 2))
            return err_set(err, "fathom check-formula needs a formula: a name (fathom --list-formulas) or a .glsl file");
        if (!set_formula(argv[2], o, err))
            return false;
        first = 3;
    }
    unsigned long seen = 0; /* the options with a value given so far, a bit each (WITH_VALUE's order) */
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        if (set_flag(a, o))
            continue;
        if (o->stitch && strncmp(a, "--", 2) != 0) { /* stitch: the tile files */
            if (o->input_count == (int)(sizeof o->inputs / sizeof o->inputs[0]))
                return err_set(err, "stitch: too many files (at most %d)", (int)(sizeof o->inputs / sizeof o->inputs[0]));
            o->inputs[o->input_count++] = a;
            continue;
        }
        /* flags with a value: "--flag value" or "--flag=value" */
        const char *eq = strchr(a, '=');
        char name[32];
        const char *val;
        if (strncmp(a, "--", 2) == 0 && eq && (size_t)(eq - a) < sizeof name) {
            memcpy(name, a, (size_t)(eq - a));
            name[eq - a] = '\0';
            val = eq + 1;
        } else {
            if (strlen(a) >= sizeof name)
                return err_set(err, "unknown option '%s' (see fathom --help)", a);
            strcpy(name, a);
            val = (i + 1 < argc) ? argv[++i] : NULL;
        }
        static const char *const WITH_VALUE[] = {"--scene", "--dem", "--formula", "--help-formula", "--output", "--size", "--spp", "--quality",
                                                 "--camera", "--look-at", "--fov", "--set", "--aov", "--frames",
                                                 "--runs", "--out", "--knob", "--name", "--strip-rows", "--fps", "--view", "--backend", "--truth",
                                                 "--path", "--tile", "--video",
                                                 "--resolution", "--box", "--triangles", "--tolerance", "--print-size", "--base"};
        static const char *const REPEATABLE[] = {"--set", "--knob"};
        size_t k = 0;
        while (k < sizeof WITH_VALUE / sizeof WITH_VALUE[0] && strcmp(name, WITH_VALUE[k]))
            k++;
        if (k == sizeof WITH_VALUE / sizeof WITH_VALUE[0])
            return err_set(err, "unknown option '%s' (see fathom --help)", name);
        if (!val)
            return err_set(err, "option %s needs a value (see fathom --help)", name);
        if ((seen >> k & 1) && strcmp(name, REPEATABLE[0]) && strcmp(name, REPEATABLE[1]))
            return err_set(err, "%s is given twice (the second time '%s'): give it once", name, val);
        seen |= 1ul << k;
        bool handled;
        if (!set_output_option(name, val, o, err, &handled) || (!handled && !cli_mesh_option(name, val, o, err, &handled)))
            return false;
        if (!handled && !set_view_option(name, val, o, err))
            return false;
    }
    if (o->has_frames && o->path && !path_parse_frames(o->frames_arg, &o->frame_first, &o->frame_last, err))
        return false;
    if (o->has_frames && !o->path && !parse_int(o->frames_arg, 1, 1 << 30, &o->frames))
        return err_set(err, "bad --frames '%s': expected a whole number >= 1 (a range A-B needs --path)", o->frames_arg);
    if (o->formula && !o->scene_given)
        o->scene = "fractal"; /* framed from the formula's bound */
    if ((o->quick || o->full) && !o->runs_given)
        o->runs = o->quick ? 3 : 9;
    return check_combinations(o, err);
}
