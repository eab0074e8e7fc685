/* fathom — a terrain and fractal ray-marching explorer.
 * main: parse the command line, load the scene, then open the window or render offline.
 * Exit codes: 0 done, 1 failed (bad data or environment), 2 bad command line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <string.h>

#include "jobs/bench/bench.h"
#include "jobs/check/check.h"
#include "jobs/capture/flight.h"
#include "jobs/mesh/mesh_job.h"
#include "jobs/gis/gis_job.h"
#include "cli/cli.h"
#include "window/explore.h"
#include "data/media/image_io.h"
#include "jobs/capture/offline.h"
#include "gpu/render.h"
#include "scene/scene.h"
#include "scene/formula/frag.h"
#include "view/shot.h"
#include "view/views.h"

enum { EXIT_USAGE = 2 };

static void print_variant(const scene *s)
{
    printf("scene %s (%s): program %s", s->name, s->path, program_name(s->program));
    const scene_fractal *f = &s->fractal;
    if (program_is_fractal(s->program))
        printf(" (formula %s%s%s%s%s)", f->formula.name, f->has_hybrid ? " + " : "", f->has_hybrid ? f->hybrid.name : "",
               f->has_hybrid ? " hybrid" : "", f->julia ? ", Julia set" : "");
    printf(", quality %s\n", preset_name(s->preset));
    printf("effects compiled in:");
    for (int e = 0; e < EFFECT_COUNT; e++)
        if (s->effects & (1u << e))
            printf(" %s", effect_name((effect)e));
    printf("\nleft out:");
    for (int e = 0; e < EFFECT_COUNT; e++)
        if (!(s->effects & (1u << e)))
            printf(" %s", effect_name((effect)e));
    printf("\n");
    if (s->sun.on) {
        const float *v = s->lights[s->sun.light].vec;
        printf("sun: %s %05.2f h (UTC%+g) at latitude %.4f, longitude %.4f: azimuth %.2f° from true north, %.2f° from the grid's north "
               "(true north %+.2f° from it), elevation %.2f°; light %d toward (%.4f, %.4f, %.4f) (+X east, +Y up, −Z "
               "grid north)\n",
               s->sun.date, (double)s->sun.hour, (double)s->sun.utc_offset, s->sun.latitude, s->sun.longitude,
               s->sun.azimuth, fmod(s->sun.azimuth + s->sun.convergence + 360, 360), s->sun.convergence,
               s->sun.elevation, s->sun.light, (double)v[0], (double)v[1], (double)v[2]);
    }
    strbuf pre = {0};
    render_preamble(s, NULL, &pre);
    fputs(pre.data, stdout);
    sb_free(&pre);
}

/* A fragment's preset (--view NAME, else where FragM starts: its default preset or the sliders' defaults)
 * as the starting view: its camera unless the command line gives one, its parameters under the command
 * line's --set. */
static bool apply_preset(cli_options *o, shot_desc *shot, err_t *err)
{
    const char *path = o->formula_set + strlen("fractal.formula=");
    strbuf text = {0};
    char *ignored = NULL;
    bool ok = frag_preset_shot(path, o->view_name, &text, &ignored, err) &&
              cli_apply_shot_text(o, text.data, path, shot, err);
    if (ok && ignored && !o->quiet)
        fprintf(stderr, "fathom: note: the preset's %s are settings of Fragmentarium's host or renderer that fathom "
                        "does not draw (docs/guide/fragments.md)\n", ignored);
    free(ignored);
    sb_free(&text);
    return ok;
}

/* --view NAME: the saved view of the scene named on the command line. */
static bool apply_view(cli_options *o, shot_desc *shot, err_t *err)
{
    if (o->formula && frag_is_fragment(o->formula))
        return apply_preset(o, shot, err);
    char path[PATH_MAX_LEN], file[PATH_MAX_LEN], *text;
    if (!scene_locate(o->scene, path, sizeof path, err))
        return false;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    char name[SCENE_NAME_MAX];
    snprintf(name, sizeof name, "%.*s", (int)strcspn(base, "."), base);
    if (!views_file(name, file, sizeof file, err) || !views_load(file, o->view_name, &text, err))
        return false;
    bool ok = cli_apply_shot_text(o, text, file, shot, err);
    free(text);
    return ok;
}

/* Prints err as fathom's one line; the exit code for ok. */
static int finish(bool ok, const err_t *err)
{
    if (!ok)
        fprintf(stderr, "fathom: %s\n", err->msg);
    return ok ? 0 : 1;
}

/* --help, --version, --list-scenes: true when one of them was asked (and answered). */
static bool answer_query(const cli_options *opt)
{
    if (opt->help) {
        strbuf knobs = {0};
        quality_describe(&knobs);
        printf("%s\nQuality knobs (--set quality.NAME=VALUE) [draft/interactive/final/reference]:\n%s", cli_usage(),
               knobs.data);
        sb_free(&knobs);
    } else if (opt->version) {
        printf("fathom %s\n", FATHOM_VERSION);
    } else if (opt->list_scenes || opt->list_formulas) {
        strbuf names = {0};
        if (opt->list_scenes)
            scene_list(&names, true);
        else
            formula_list(&names);
        fputs(names.data ? names.data : "", stdout);
        sb_free(&names);
    }
    return opt->help || opt->version || opt->list_scenes || opt->list_formulas;
}

/* --help-formula NAME|FILE */
static bool help_formula(const char *name, err_t *err)
{
    formula f;
    if (!formula_load(name, NULL, &f, err))
        return false;
    strbuf text = {0};
    formula_describe(&f, &text);
    char names[FRAG_PRESET_MAX][FRAG_PRESET_NAME_MAX];
    int n = f.fragment ? frag_presets(f.file, names, FRAG_PRESET_MAX, err) : 0;
    for (int i = 0; i < n; i++) /* a fragment's presets: --view NAME */
        sb_printf(&text, "%s\"%s\"%s", i ? ", " : "  presets (--view NAME): ", names[i], i + 1 == n ? "\n" : "");
    fputs(text.data, stdout);
    sb_free(&text);
    return n >= 0;
}

/* The kind of offline shot the command line asks for: size, AOVs, bands, quiet. */
static offline_desc shot_of(const cli_options *opt)
{
    return (offline_desc){.width = opt->width, .height = opt->height, .aovs = opt->aovs, .strip_rows = opt->strip_rows,
                          .quiet = opt->quiet};
}

/* The jobs' own descriptions of what the command line asks (jobs never see cli_options). */
static flight_desc flight_of(const cli_options *o)
{
    return (flight_desc){.path = o->path, .output = o->output, .video = o->video, .scene = o->scene, .sets = o->sets,
                         .set_count = o->set_count, .spp = o->spp, .fps = o->fps, .has_frames = o->has_frames,
                         .frame_first = o->frame_first, .frame_last = o->frame_last, .shot = shot_of(o)};
}

static bench_desc bench_of(const cli_options *o)
{
    return (bench_desc){.scene = o->scene, .sets = o->sets, .set_count = o->set_count, .width = o->width,
                        .height = o->height, .runs = o->runs, .knobs = o->knobs, .knob_count = o->knob_count,
                        .out = o->out, .name = o->name, .quick = o->quick, .full = o->full, .quiet = o->quiet,
                        .path_truth = o->path_truth, .frame_times = o->frame_times, .interactive = o->interactive,
                        .terrain_scale = o->terrain_scale, .terrain_stream = o->terrain_stream, .final_frame = o->final_frame,
                        .viewshed = o->viewshed, .fps = o->fps};
}

static mesh_desc mesh_of(const cli_options *o)
{
    return (mesh_desc){.scene = o->scene, .sets = o->sets, .set_count = o->set_count, .output = o->output,
                       .resolution = o->mesh_resolution, .has_box = o->has_box, .box = {o->box[0], o->box[1], o->box[2],
                       o->box[3], o->box[4], o->box[5]}, .triangles = (size_t)o->mesh_triangles,
                       .tolerance = o->mesh_tolerance, .one_shell = o->one_shell, .print_mm = o->print_mm,
                       .base = o->mesh_base, .quiet = o->quiet};
}

/* One offline shot (or one tile of it) of s as the command line asks. */
static bool render_shot(const cli_options *opt, const scene *s, err_t *err)
{
    float fov = opt->has_fov ? opt->fov_deg : s->cam_fov_deg;
    const double *eye = opt->has_camera ? opt->camera : s->cam_position;
    const double *at = opt->has_look_at ? opt->look_at : s->cam_look_at;
    if (!opt->has_view && camera_degenerate(eye, at))
        return err_set(err, "the camera (%g, %g, %g) is at its look-at point: pass --look-at (or --camera) elsewhere",
                       (double)eye[0], (double)eye[1], (double)eye[2]);
    /* the shot remembers the overrides, --spp as the one it stands for */
    const char *sets[CLI_MAX_SETS + 1];
    char spp[48];
    memcpy(sets, opt->sets, sizeof(sets[0]) * (size_t)opt->set_count);
    int nsets = opt->set_count;
    if (opt->spp) {
        snprintf(spp, sizeof spp, "quality.spp=%d", opt->spp);
        sets[nsets++] = spp;
    }
    strbuf description = {0};
    camera cam = opt->has_view ? opt->view : scene_camera(s, eye, at, fov);
    if (opt->has_view) /* a view or a shot keeps its pose; the lens is the scene's with the overrides */
        cam.lens = scene_lens(s);
    offline_desc d = offline_shot(shot_of(opt), s, cam, opt->output, sets, nsets, &description);
    char tile[PATH_MAX_LEN];
    bool ok = true;
    if (opt->tile_count) { /* tile I of N goes to OUTPUT.tile-I-of-N.EXT */
        d.tile_index = opt->tile_index;
        d.tile_count = opt->tile_count;
        ok = offline_tile_name(opt->output, opt->tile_index, opt->tile_count, tile, sizeof tile, err);
        d.output = tile;
    }
    ok = ok && offline_render(&d, err);
    sb_free(&description);
    return ok;
}

int main(int argc, char **argv)
{
    util_guard_terminal();
    image_io_install_signal_cleanup();
    cli_options opt;
    err_t err;
    gis_options gis;
    if (!cli_gis_parse(argc, argv, &gis, &err)) {
        fprintf(stderr, "fathom: %s\n", err.msg);
        return EXIT_USAGE;
    }
    if (gis.command != GIS_NONE)
        return finish(gis.command == GIS_VIEWSHED ? gis_viewshed_run(&gis, &err)
                      : gis.command == GIS_WATER  ? gis_water_run(&gis, &err)
                                                  : gis_track_run(&gis, &err), &err);
    if (!cli_parse(argc, argv, &opt, &err)) {
        fprintf(stderr, "fathom: %s\n", err.msg);
        return EXIT_USAGE;
    }
    render_backend backend;
    if (opt.backend && render_parse_backend(opt.backend, &backend))
        render_request_backend(backend);
    struct stat st;
    if (opt.dem && !stat(opt.dem, &st) && S_ISDIR(st.st_mode))
        return finish(err_set(&err, "--dem '%s' is a folder: give the elevation file in it (a GeoTIFF, .hgt, .asc, ...)",
                              opt.dem), &err);
    if (opt.dem && !util_file_exists(opt.dem))
        return finish(err_set(&err, "--dem: file '%s' not found (a path from the folder you are in)", opt.dem), &err);
    static shot_desc shot; /* --scene SHOT.png: opt points into it */
    if (opt.scene && (shot_is_image(opt.scene) || shot_is_preset(opt.scene)) && !cli_apply_shot(&opt, &shot, &err))
        return finish(false, &err);
    if (shot.notes) /* its formulas: changed since, or carried (view/shot.h) */
        fputs(shot.notes, stderr);
    static shot_desc view; /* --view NAME (a fragment: its preset, named or not): likewise */
    if ((opt.view_name || (opt.formula && frag_is_fragment(opt.formula) && !opt.help_formula)) &&
        !apply_view(&opt, &view, &err))
        return finish(false, &err);
    if (answer_query(&opt))
        return 0;
    if (opt.help_formula)
        return finish(help_formula(opt.help_formula, &err), &err);
    if (opt.stitch)
        return finish(offline_stitch(opt.output, opt.inputs, opt.input_count, opt.quiet, &err), &err);
    if (opt.path) {
        flight_desc f = flight_of(&opt);
        return finish(flight_render(&f, &err), &err);
    }
    if (opt.mesh) {
        mesh_desc m = mesh_of(&opt);
        return finish(mesh_job_run(&m, &err), &err);
    }
    if (opt.bench) {
        bench_desc b = bench_of(&opt);
        return finish(bench_run(&b, &err), &err);
    }
    if (opt.check_formula)
        return finish(check_formula_run(&(check_desc){.scene = opt.scene, .sets = opt.sets, .set_count = opt.set_count,
                                                         .defaults_only = opt.quick}, &err),
                      &err);
    if (!opt.output && !opt.print_variant)
        return finish(explore_run(&opt, &err), &err);
    scene s;
    if (!scene_load(opt.scene, opt.sets, opt.set_count, &s, &err))
        return finish(false, &err);
    if (opt.spp)
        s.quality.spp = opt.spp;
    bool ok = true;
    if (opt.print_variant)
        print_variant(&s);
    else
        ok = render_shot(&opt, &s, &err);
    scene_free(&s);
    return finish(ok, &err);
}
