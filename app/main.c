/* fathom — a terrain and fractal ray-marching explorer.
 * main: parse the command line, load the scene, then open the window or render offline.
 * Exit codes: 0 done, 1 failed (bad data or environment), 2 bad command line. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jobs/bench.h"
#include "jobs/flight.h"
#include "cli.h"
#include "window/explore.h"
#include "data/image_io.h"
#include "jobs/offline.h"
#include "gpu/render.h"
#include "scene/scene.h"
#include "view/shot.h"
#include "view/views.h"

enum { EXIT_USAGE = 2, DEFAULT_WIDTH = 1280, DEFAULT_HEIGHT = 720 };

static void print_variant(const scene *s)
{
    printf("scene %s (%s): program %s, quality %s\n", s->name, s->path, program_name(s->program),
           preset_name(s->preset));
    printf("effects compiled in:");
    for (int e = 0; e < EFFECT_COUNT; e++)
        if (s->effects & (1u << e))
            printf(" %s", effect_name((effect)e));
    printf("\nleft out:");
    for (int e = 0; e < EFFECT_COUNT; e++)
        if (!(s->effects & (1u << e)))
            printf(" %s", effect_name((effect)e));
    printf("\n");
    strbuf pre = {0};
    render_preamble(s, NULL, &pre);
    fputs(pre.data, stdout);
    sb_free(&pre);
}

/* --view NAME: the saved view of the scene named on the command line. */
static bool apply_view(cli_options *o, shot_desc *shot, err_t *err)
{
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

int main(int argc, char **argv)
{
    image_io_install_signal_cleanup();
    cli_options opt;
    err_t err;
    if (!cli_parse(argc, argv, &opt, &err)) {
        fprintf(stderr, "fathom: %s\n", err.msg);
        return EXIT_USAGE;
    }
    if (opt.dem && !util_file_exists(opt.dem)) {
        fprintf(stderr, "fathom: --dem: file '%s' not found (a path from the folder you are in)\n", opt.dem);
        return 1;
    }
    static shot_desc shot; /* --scene SHOT.png: opt points into it */
    if (opt.scene && shot_is_image(opt.scene) && !cli_apply_shot(&opt, &shot, &err)) {
        fprintf(stderr, "fathom: %s\n", err.msg);
        return 1;
    }
    static shot_desc view; /* --view NAME: likewise */
    if (opt.view_name && !apply_view(&opt, &view, &err)) {
        fprintf(stderr, "fathom: %s\n", err.msg);
        return 1;
    }
    if (opt.help) {
        strbuf knobs = {0};
        quality_describe(&knobs);
        printf("%s\nQuality knobs (--set quality.NAME=VALUE) [draft/interactive/final/reference]:\n%s", cli_usage(),
               knobs.data);
        sb_free(&knobs);
        return 0;
    }
    if (opt.version) {
        printf("fathom 0.1\n");
        return 0;
    }
    if (opt.list_scenes) {
        strbuf names = {0};
        scene_list(&names);
        fputs(names.data ? names.data : "", stdout);
        sb_free(&names);
        return 0;
    }
    if (opt.stitch) {
        bool ok = offline_stitch(opt.output, opt.inputs, opt.input_count, opt.quiet, &err);
        if (!ok)
            fprintf(stderr, "fathom: %s\n", err.msg);
        return ok ? 0 : 1;
    }
    if (opt.path) {
        bool ok = flight_render(&opt, &err);
        if (!ok)
            fprintf(stderr, "fathom: %s\n", err.msg);
        return ok ? 0 : 1;
    }
    if (opt.bench) {
        bool ok = bench_run(&opt, &err);
        if (!ok)
            fprintf(stderr, "fathom: %s\n", err.msg);
        return ok ? 0 : 1;
    }
    if (!opt.output && !opt.print_variant) {
        bool ok = explore_run(&opt, &err);
        if (!ok)
            fprintf(stderr, "fathom: %s\n", err.msg);
        return ok ? 0 : 1;
    }

    scene s;
    if (!scene_load(opt.scene, opt.sets, opt.set_count, &s, &err)) {
        fprintf(stderr, "fathom: %s\n", err.msg);
        return 1;
    }
    if (opt.spp)
        s.quality.spp = opt.spp;
    int rc = 0;
    if (opt.print_variant) {
        print_variant(&s);
    } else {
        float fov = opt.has_fov ? opt.fov_deg : s.cam_fov_deg;
        const float *eye = opt.has_camera ? opt.camera : s.cam_position;
        const float *at = opt.has_look_at ? opt.look_at : s.cam_look_at;
        if (!opt.has_view && camera_degenerate(eye, at)) {
            fprintf(stderr, "fathom: the camera (%g, %g, %g) is at its look-at point: pass --look-at (or "
                            "--camera) elsewhere\n", (double)eye[0], (double)eye[1], (double)eye[2]);
            scene_free(&s);
            return 1;
        }
        offline_desc d = {
            .scene = &s,
            .cam = opt.has_view ? opt.view : camera_look_at_deg(eye, at, fov),
            .width = opt.width ? opt.width : DEFAULT_WIDTH,
            .height = opt.height ? opt.height : DEFAULT_HEIGHT,
            .spp = s.quality.spp,
            .output = opt.output,
            .aovs = opt.aovs,
            .strip_rows = opt.strip_rows,
            .quiet = opt.quiet,
        };
        /* the shot remembers the overrides, --spp as the one it stands for */
        const char *sets[CLI_MAX_SETS + 1];
        char spp[48];
        memcpy(sets, opt.sets, sizeof(sets[0]) * (size_t)opt.set_count);
        int nsets = opt.set_count;
        if (opt.spp) {
            snprintf(spp, sizeof spp, "quality.spp=%d", opt.spp);
            sets[nsets++] = spp;
        }
        strbuf description = {0};
        shot_describe(s.path, sets, nsets, &d.cam, d.width, d.height, &description);
        d.description = description.data;
        char tile[PATH_MAX_LEN];
        bool ok = true;
        if (opt.tile_count) { /* tile I of N goes to OUTPUT.tile-I-of-N.EXT */
            d.tile_index = opt.tile_index;
            d.tile_count = opt.tile_count;
            ok = offline_tile_name(opt.output, opt.tile_index, opt.tile_count, tile, sizeof tile, &err);
            d.output = tile;
        }
        ok = ok && offline_render(&d, &err);
        sb_free(&description);
        if (!ok) {
            fprintf(stderr, "fathom: %s\n", err.msg);
            rc = 1;
        }
    }
    scene_free(&s);
    return rc;
}
