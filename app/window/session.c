/* session — the scene the window shows and its edits (session.h). */
#include "window/session.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/render.h"
#include "view/shot.h"

void session_init(session *s, const cli_options *opt)
{
    memset(s, 0, sizeof *s);
    s->opt = opt;
    for (int i = 0; i < opt->set_count && i < CLI_MAX_SETS; i++)
        snprintf(s->base[i], OVERRIDE_LEN, "%s", opt->sets[i]);
    s->base_count = opt->set_count < CLI_MAX_SETS ? opt->set_count : CLI_MAX_SETS;
}

void session_free(session *s)
{
    dem_geo_close(s->geo);
    params_free(&s->params);
    if (s->have_scene)
        scene_free(&s->scene);
    s->have_scene = false;
    s->geo = NULL;
}

/* The overrides the scene loads with: the base ones, then the edits. */
static int current_sets(const session *s, const char **sets)
{
    int n = 0;
    for (int i = 0; i < s->base_count; i++)
        sets[n++] = s->base[i];
    int m;
    overrides_list(&s->edits, sets + n, &m);
    return n + m;
}

bool session_load(session *s, const char *name, bool *new_file, err_t *err)
{
    const char *sets[CLI_MAX_SETS + OVERRIDES_MAX];
    int n = current_sets(s, sets);
    scene next;
    param_list params = {0};
    *new_file = false;
    if (!scene_load_params(name, sets, n, &next, &params, err)) {
        params_free(&params);
        return false;
    }
    if (s->opt->spp)
        next.quality.spp = s->opt->spp;
    next.fractal.deep_now = next.fractal.deep_now || (s->have_scene && s->scene.fractal.deep_now && next.fractal.deep_ok &&
                                                      next.fractal.precision == PRECISION_AUTO);
    bool same_file = s->have_scene && !strcmp(s->scene.path, next.path);
    if (!render_set_scene(&next, NULL, err)) { /* the renderer copies what it needs */
        scene_free(&next);
        params_free(&params);
        if (s->have_scene) {
            err_t ignore;
            render_set_scene(&s->scene, NULL, &ignore); /* back to the last good scene */
        }
        return false;
    }
    if (s->have_scene)
        scene_free(&s->scene);
    params_free(&s->params);
    s->scene = next;
    s->params = params;
    s->have_scene = true;
    *new_file = !same_file;
    if (strcmp(s->geo_path, s->scene.terrain.heightmap)) { /* a DEM's place on the Earth, for the cursor */
        dem_geo_close(s->geo);
        s->geo = s->scene.terrain.heightmap[0] ? dem_geo_open(s->scene.terrain.heightmap) : NULL;
        snprintf(s->geo_path, sizeof s->geo_path, "%s", s->scene.terrain.heightmap);
    }
    return true;
}

bool session_edit(session *s, const char *kv, err_t *err)
{
    overrides keep = s->edits;
    bool new_file;
    if (!overrides_set(&s->edits, kv))
        return err_set(err, "'%.200s' is not key=value (or too many edits)", kv);
    if (!session_load(s, s->scene.path, &new_file, err)) {
        s->edits = keep;
        return false;
    }
    return true;
}

bool session_switch(session *s, const char *name, bool *new_file, err_t *err)
{
    s->base_count = 0; /* the command line's and a view's overrides belong to their own scene */
    overrides_clear(&s->edits);
    return session_load(s, name, new_file, err);
}

void session_describe(const session *s, const camera *cam, int w, int h, strbuf *out)
{
    const char *sets[CLI_MAX_SETS + OVERRIDES_MAX];
    int n = current_sets(s, sets);
    const char *formulas[SHOT_FORMULA_MAX];
    scene_formula_files(&s->scene, formulas);
    shot_describe_fractal(s->scene.path, sets, n, formulas, cam, w, h, out);
}

bool session_open_shot(session *s, const char *text, const char *source, camera *cam, bool *new_file, err_t *err)
{
    shot_desc d;
    if (!shot_parse(text, source, &d, err))
        return false;
    if (d.scene_text)
        scene_provide_text(d.scene, d.scene_text);
    strbuf notes = {0};
    if (!shot_resolve_formulas(&d, &notes, err)) {
        sb_free(&notes);
        shot_free(&d);
        return false;
    }
    if (notes.data) /* its formulas: changed since, or carried (view/shot.h) */
        fputs(notes.data, stderr);
    sb_free(&notes);
    char keep_base[CLI_MAX_SETS][OVERRIDE_LEN];
    int keep_count = s->base_count;
    overrides keep_edits = s->edits;
    memcpy(keep_base, s->base, sizeof keep_base);
    for (int i = 0; i < d.set_count && i < CLI_MAX_SETS; i++)
        snprintf(s->base[i], OVERRIDE_LEN, "%s", d.sets[i]);
    s->base_count = d.set_count < CLI_MAX_SETS ? d.set_count : CLI_MAX_SETS;
    overrides_clear(&s->edits);
    bool ok = session_load(s, d.scene, new_file, err);
    if (ok) {
        *cam = d.cam;
    } else { /* what was in force stays */
        memcpy(s->base, keep_base, sizeof keep_base);
        s->base_count = keep_count;
        s->edits = keep_edits;
    }
    shot_free(&d);
    return ok;
}
