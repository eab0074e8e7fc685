/* cli_shot — the command line opened from a shot's description (cli.h: cli_apply_shot): its scene,
 * overrides and camera under the command line's own. */
#include "cli/cli.h"

#include <stdlib.h>
#include <string.h>

#include "data/media/image_io.h"
#include "scene/scene.h"
#include "view/shot.h"

_Static_assert((int)SHOT_SET_MAX <= (int)CLI_MAX_SETS, "a shot's overrides must fit the command line's");

bool cli_apply_shot_text(cli_options *o, const char *text, const char *source, shot_desc *d, err_t *err)
{
    if (!shot_parse(text, source, d, err))
        return false;
    if (d->scene_text) /* a user's own scene, carried whole: it reopens on any machine */
        scene_provide_text(d->scene, d->scene_text);
    strbuf notes = {0}; /* a formula changed or missing here: main prints them */
    bool resolved = shot_resolve_formulas(d, &notes, err);
    d->notes = notes.data;
    if (!resolved)
        return false;
    if (d->set_count + o->set_count > CLI_MAX_SETS)
        return err_set(err, "%s: its %d overrides and the command line's %d are more than %d", source, d->set_count,
                       o->set_count, CLI_MAX_SETS);
    const char *sets[CLI_MAX_SETS];
    int n = 0;
    for (int i = 0; i < d->set_count; i++)
        sets[n++] = d->sets[i];
    for (int i = 0; i < o->set_count; i++)
        sets[n++] = o->sets[i];
    memcpy(o->sets, sets, sizeof(sets[0]) * (size_t)n);
    o->set_count = n;
    o->scene = d->scene;
    if (!o->has_camera && !o->has_look_at && !o->has_fov)
        o->has_view = true, o->view = d->cam;
    if (!o->width)
        o->width = d->width, o->height = d->height;
    return true;
}

bool cli_apply_shot(cli_options *o, shot_desc *d, err_t *err)
{
    char *text;
    bool preset = shot_is_preset(o->scene);
    if (!util_file_exists(o->scene))
        return err_set(err, "%s '%s' not found: check the path", preset ? "preset" : "image", o->scene);
    if (preset ? !util_read_file(o->scene, &text, NULL, err) : !image_read_text(o->scene, SHOT_KEY, &text, err))
        return false;
    bool ok = cli_apply_shot_text(o, text, o->scene, d, err);
    free(text);
    return ok;
}
