/* scene_camera — the scene file's camera block (scene_parse.h): where it stands and looks, or "auto"
 * (framed by the program's own hook: program.h), and its lens. Above the programs' block parsers,
 * which never call it (tests/tree/calls.sh). */
#include <math.h>
#include <string.h>

#include "scene/program.h"
#include "scene/scene_parse.h"
#include "view/camera.h"

static bool scene_parse_lens(scene_ctx *c, const cJSON *cam);

bool scene_parse_camera(scene_ctx *c, const cJSON *root)
{
    scene *s = c->s;
    const program_def *p = program_get(s->program);
    const cJSON *cam = cJSON_GetObjectItemCaseSensitive(root, "camera");
    static const double cam_pos[3] = {0, 1, 5}, cam_at[3] = {0, 0, 0};
    if (cJSON_IsString(cam)) { /* "auto": framed from the terrain's extent once it is known (scene.c) */
        if (strcmp(cam->valuestring, "auto") || !p->frame)
            return scene_fail(c, "camera", "expected an object with position and look_at%s%s%s",
                              p->frame ? ", or \"auto\" (framed from " : "", p->frame ? p->frame_from : "",
                              p->frame ? ")" : "");
        s->cam_auto = true;
        cam = NULL;
    }
    if (cam) {
        static const char *const ckeys[] = {"position", "look_at", "fov", "adaptive_speed", "up", "roll", "projection",
                                            "aperture", "focus", "stereo", "eye_separation", "auto", NULL};
        if (!scene_check_keys(c, cam, "camera", ckeys))
            return false;
        const cJSON *framed = cJSON_GetObjectItemCaseSensitive(cam, "auto"); /* "auto" with a lens */
        if (framed && (!cJSON_IsBool(framed) || (cJSON_IsTrue(framed) && !p->frame)))
            return scene_fail(c, "camera.auto", "expected true or false%s%s%s", p->frame ? " (true: framed from " : "",
                              p->frame ? p->frame_from : "", p->frame ? ")" : ": this program frames nothing itself");
        s->cam_auto |= cJSON_IsTrue(framed);
        const cJSON *adaptive = cJSON_GetObjectItemCaseSensitive(cam, "adaptive_speed");
        if (adaptive && !cJSON_IsBool(adaptive))
            return scene_fail(c, "camera.adaptive_speed", "expected true or false");
        s->adaptive_speed = adaptive ? cJSON_IsTrue(adaptive) : p->adaptive;
    } else {
        s->adaptive_speed = p->adaptive;
    }
    if (!scene_get_dvec3(c, cam, "camera", "position", cam_pos, -CAMERA_MAX_COORD, CAMERA_MAX_COORD, s->cam_position) ||
        !scene_get_dvec3(c, cam, "camera", "look_at", cam_at, -CAMERA_MAX_COORD, CAMERA_MAX_COORD, s->cam_look_at) ||
        !scene_get_num(c, cam, "camera", "fov", 50, 1, 170, &s->cam_fov_deg))
        return false;
    if (camera_degenerate(s->cam_position, s->cam_look_at))
        return scene_fail(c, "camera.look_at", "is the camera's position: the camera needs a point to look at");
    return scene_parse_lens(c, cam);
}

/* The camera's up, roll and lens (view/camera.h); focus and eye separation 0 are "not set": the look-at
 * distance and a thirtieth of the focus (scene_lens). */
static bool scene_parse_lens(scene_ctx *c, const cJSON *cam)
{
    scene *s = c->s;
    static const double y_up[3] = {0, 1, 0};
    int projection = 0, stereo = 0;
    if (!scene_get_dvec3(c, cam, "camera", "up", y_up, -1e6, 1e6, s->cam_up) ||
        !scene_get_num(c, cam, "camera", "roll", 0, -180, 180, &s->cam_roll_deg) ||
        !scene_get_enum(c, cam, "camera", "projection", "projection", CAMERA_PROJECTIONS, 0, &projection) ||
        !scene_get_num(c, cam, "camera", "aperture", 0, 0, 1e6f, &s->cam_lens.aperture) ||
        !scene_get_num(c, cam, "camera", "focus", 0, 0, 1e9f, &s->cam_lens.focus) ||
        !scene_get_enum(c, cam, "camera", "stereo", "stereo", CAMERA_STEREOS, 0, &stereo) ||
        !scene_get_num(c, cam, "camera", "eye_separation", 0, 0, 1e6f, &s->cam_lens.eye_separation))
        return false;
    s->cam_lens.projection = (camera_projection)projection;
    s->cam_lens.stereo = (camera_stereo)stereo;
    double d[3] = {s->cam_look_at[0] - s->cam_position[0], s->cam_look_at[1] - s->cam_position[1],
                   s->cam_look_at[2] - s->cam_position[2]};
    double n = camera_norm(s->cam_up), cx = d[1] * s->cam_up[2] - d[2] * s->cam_up[1],
           cy = d[2] * s->cam_up[0] - d[0] * s->cam_up[2], cz = d[0] * s->cam_up[1] - d[1] * s->cam_up[0];
    if (!(n > 0) || !(sqrt(cx * cx + cy * cy + cz * cz) > 1e-6 * n * camera_norm(d)))
        return scene_fail(c, "camera.up", "is zero or along the view: give the direction the image's top should face, "
                                          "e.g. [0, 1, 0]");
    return true;
}
