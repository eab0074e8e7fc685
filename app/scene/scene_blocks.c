/* scene_blocks — the blocks every program reads: materials, lights, environment, fog,
 * quality and effects (the camera: scene_camera.c). Each checks its keys and ranges and names the key path in its errors. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "view/camera.h"
#include "scene/scene_parse.h"

/* ---- materials ---------------------------------------------------------------------------- */

static int add_texture(scene *s, const char *resolved, bool linear)
{
    for (int i = 0; i < s->texture_count; i++)
        if (!strcmp(s->textures[i], resolved) && s->texture_linear[i] == linear)
            return i;
    if (s->texture_count == SCENE_MAX_TEXTURES)
        return -1;
    strcpy(s->textures[s->texture_count], resolved);
    s->texture_linear[s->texture_count] = linear;
    return s->texture_count++;
}

static bool parse_material(scene_ctx *c, const cJSON *m, const char *path, scene_material *out)
{
    static const char *const keys[] = {"base_color", "metallic", "roughness", "transmission", "ior",
                                       "absorption", "emission", "texture", "uv_scale", "relief",
                                       "relief_depth", NULL};
    static const float white[3] = {1, 1, 1}, zero[3] = {0, 0, 0};
    if (!scene_check_keys(c, m, path, keys))
        return false;
    const char *tex = NULL, *relief = NULL;
    if (!scene_get_vec3(c, m, path, "base_color", white, 0, 1, out->base_color) ||
        !scene_get_num(c, m, path, "metallic", 0, 0, 1, &out->metallic) ||
        !scene_get_num(c, m, path, "roughness", 0.5f, 0, 1, &out->roughness) ||
        !scene_get_num(c, m, path, "transmission", 0, 0, 1, &out->transmission) ||
        !scene_get_num(c, m, path, "ior", 1.5f, 1, 4, &out->ior) ||
        !scene_get_vec3(c, m, path, "absorption", zero, 0, 1e4f, out->absorption) ||
        !scene_get_vec3(c, m, path, "emission", zero, 0, 1e6f, out->emission) ||
        !scene_get_num(c, m, path, "uv_scale", 1, 1e-7f, 1e4f, &out->uv_scale) ||
        !scene_get_str(c, m, path, "texture", NULL, &tex) || !scene_get_str(c, m, path, "relief", NULL, &relief) ||
        !scene_get_num(c, m, path, "relief_depth", 0.05f, 1e-5f, 1e3f, &out->relief_depth))
        return false;
    out->texture = -1;
    out->relief = -1;
    if (relief) {
        char p[512], resolved[PATH_MAX_LEN];
        scene_child_path(p, sizeof p, path, "relief");
        if (!scene_resolve_file(c, p, relief, resolved))
            return false;
        out->relief = add_texture(c->s, resolved, true);
        if (out->relief < 0)
            return scene_fail(c, p, "too many textures (at most %d)", SCENE_MAX_TEXTURES);
    }
    if (tex) {
        char p[512], resolved[PATH_MAX_LEN];
        scene_child_path(p, sizeof p, path, "texture");
        if (!scene_resolve_file(c, p, tex, resolved))
            return false;
        out->texture = add_texture(c->s, resolved, false);
        if (out->texture < 0)
            return scene_fail(c, p, "too many textures (at most %d)", SCENE_MAX_TEXTURES);
    }
    return true;
}

bool scene_parse_materials(scene_ctx *c, const cJSON *root)
{
    const cJSON *mats = cJSON_GetObjectItemCaseSensitive(root, "materials");
    if (!cJSON_IsObject(mats) || !mats->child)
        return scene_fail(c, "materials", "expected an object of named materials, e.g. {\"red\": {\"base_color\": [0.8, 0.1, 0.1]}}");
    for (const cJSON *m = mats->child; m; m = m->next) {
        char p[512];
        scene_child_path(p, sizeof p, "materials", m->string);
        if (c->s->material_count == SCENE_MAX_MATERIALS)
            return scene_fail(c, p, "too many materials (at most %d)", SCENE_MAX_MATERIALS);
        if (strlen(m->string) == 0 || strlen(m->string) >= SCENE_NAME_MAX)
            return scene_fail(c, p, "material names must have 1 to 63 characters");
        scene_material *out = &c->s->materials[c->s->material_count++];
        strcpy(out->name, m->string);
        if (!parse_material(c, m, p, out))
            return false;
    }
    return true;
}

int scene_find_material(const scene *s, const char *name)
{
    for (int i = 0; i < s->material_count; i++)
        if (!strcmp(s->materials[i].name, name))
            return i;
    return -1;
}

/* ---- droplets ---------------------------------------------------------------------------------- */

bool scene_parse_droplets(scene_ctx *c, const cJSON *root)
{
    scene *s = c->s;
    const cJSON *d = cJSON_GetObjectItemCaseSensitive(root, "droplets");
    if (!d)
        return true;
    static const char *const keys[] = {"file", "scale", "ior", "absorption", "roughness", "structure", NULL};
    static const char *const structures[] = {"grid", "bvh", NULL};
    /* pure water, per metre at 650, 550 and 450 nm (Pope & Fry, "Absorption spectrum (380–700 nm) of
     * pure water", Applied Optics 36(33), 1997) */
    static const float water[3] = {0.34f, 0.0565f, 0.0092f};
    const char *file = NULL;
    if (!cJSON_IsObject(d))
        return scene_fail(c, "droplets", "expected an object like {\"file\": \"spray.csv\"}");
    if (!scene_check_keys(c, d, "droplets", keys) || !scene_get_str(c, d, "droplets", "file", NULL, &file))
        return false;
    if (!file)
        return scene_fail(c, "droplets.file", "missing: name a CSV file of droplet centres and radii (ParaView's "
                                        "Points:0..2 with radius or diameter, or x,y,z,r)");
    s->has_droplets = true;
    int structure = 0;
    if (!scene_get_enum(c, d, "droplets", "structure", "droplet structure", structures, 0, &structure))
        return false;
    s->droplets.bvh = structure == 1;
    return scene_resolve_file(c, "droplets.file", file, s->droplets.file) &&
           scene_get_num(c, d, "droplets", "scale", 1, 1e-9f, 1e9f, &s->droplets.scale) &&
           scene_get_num(c, d, "droplets", "ior", 1.33f, 1.0001f, 4, &s->droplets.ior) &&
           scene_get_vec3(c, d, "droplets", "absorption", water, 0, 1e6f, s->droplets.absorption) &&
           scene_get_num(c, d, "droplets", "roughness", 0.08f, 0.01f, 1, &s->droplets.roughness);
}

/* ---- fog ------------------------------------------------------------------------------------ */

bool scene_parse_fog(scene_ctx *c, const cJSON *root)
{
    scene *s = c->s;
    const cJSON *fog = cJSON_GetObjectItemCaseSensitive(root, "fog");
    if (!fog)
        return true;
    static const char *const fkeys[] = {"color", "density", "falloff", "height", NULL};
    static const float fog_grey[3] = {0.6f, 0.65f, 0.7f};
    s->has_fog = true;
    return scene_check_keys(c, fog, "fog", fkeys) && scene_get_vec3(c, fog, "fog", "color", fog_grey, 0, 1e3f, s->fog_color) &&
           scene_get_num(c, fog, "fog", "density", 0.02f, 0, 1e3f, &s->fog_density) &&
           scene_get_num(c, fog, "fog", "falloff", 0, -1e3f, 1e3f, &s->fog_falloff) &&
           scene_get_num(c, fog, "fog", "height", 0, -1e7f, 1e7f, &s->fog_height);
}

/* ---- lights and environment ------------------------------------------------------------------- */

bool scene_parse_lights(scene_ctx *c, const cJSON *root)
{
    const cJSON *lights = cJSON_GetObjectItemCaseSensitive(root, "lights");
    if (!lights)
        return true;
    if (!cJSON_IsArray(lights))
        return scene_fail(c, "lights", "expected an array of lights");
    int i = 0;
    for (const cJSON *l = lights->child; l; l = l->next, i++) {
        char p[64];
        snprintf(p, sizeof p, "lights.%d", i);
        if (c->s->light_count == SCENE_MAX_LIGHTS)
            return scene_fail(c, p, "too many lights (at most %d)", SCENE_MAX_LIGHTS);
        static const char *const keys[] = {"type", "position", "direction", "color", "intensity", "shadow",
                                           "softness", NULL};
        if (!scene_check_keys(c, l, p, keys))
            return false;
        scene_light *out = &c->s->lights[c->s->light_count++];
        static const float white[3] = {1, 1, 1}, up[3] = {0, 1, 0}, zero[3] = {0, 0, 0};
        /* in the order of light_type and shadow_mode (scene.h) */
        static const char *const TYPES[] = {"point", "directional", NULL}, *const SHADOWS[] = {"none", "hard", "soft", NULL};
        int type, shadow;
        if (!scene_get_enum(c, l, p, "type", "light type", TYPES, LIGHT_POINT, &type) ||
            !scene_get_enum(c, l, p, "shadow", "shadow", SHADOWS, SHADOW_HARD, &shadow) ||
            !scene_get_vec3(c, l, p, "color", white, 0, 1e3f, out->color) ||
            !scene_get_num(c, l, p, "intensity", 1, 0, 1e7f, &out->intensity) ||
            !scene_get_num(c, l, p, "softness", 16, 1, 1024, &out->softness))
            return false;
        out->type = (light_type)type;
        out->shadow = (shadow_mode)shadow;
        if (c->params)
            params_label(c->params, p, TYPES[type]);
        /* a point light has a position, a directional light a direction: the other key is a mistake */
        const char *own = type == LIGHT_POINT ? "position" : "direction", *other = type == LIGHT_POINT ? "direction" : "position";
        if (cJSON_GetObjectItemCaseSensitive(l, other)) {
            char kp[96];
            scene_child_path(kp, sizeof kp, p, other);
            return scene_fail(c, kp, "a %s light has a \"%s\", not a %s", TYPES[type], own, other);
        }
        if (!scene_get_vec3(c, l, p, own, type == LIGHT_POINT ? zero : up, -1e6f, 1e6f, out->vec))
            return false;
        if (type == LIGHT_DIRECTIONAL) { /* unit, toward the light */
            float len = sqrtf(out->vec[0] * out->vec[0] + out->vec[1] * out->vec[1] + out->vec[2] * out->vec[2]);
            if (len < 1e-6f)
                return scene_fail(c, p, "direction must not be zero");
            for (int k = 0; k < 3; k++)
                out->vec[k] /= len;
        }
    }
    return true;
}

bool scene_parse_environment(scene_ctx *c, const cJSON *root)
{
    scene *s = c->s;
    static const float grey[3] = {0.5f, 0.6f, 0.7f};
    const cJSON *env = cJSON_GetObjectItemCaseSensitive(root, "environment");
    if (!env) {
        memcpy(s->env_color, grey, sizeof grey);
        s->env_intensity = 1;
        return true;
    }
    static const char *const keys[] = {"color", "intensity", "cubemap", "sky", NULL};
    static const char *const SKIES[] = {"color", "physical", NULL};
    int sky;
    if (!scene_check_keys(c, env, "environment", keys) ||
        !scene_get_vec3(c, env, "environment", "color", grey, 0, 1e3f, s->env_color) ||
        !scene_get_num(c, env, "environment", "intensity", 1, 0, 1e6f, &s->env_intensity) ||
        !scene_get_enum(c, env, "environment", "sky", "sky", SKIES, 0, &sky))
        return false;
    s->has_sky = sky == 1; /* the colour (or cube map) stays what reflections see when the sky is off */
    const cJSON *cube = cJSON_GetObjectItemCaseSensitive(env, "cubemap");
    if (!cube)
        return true;
    if (!cJSON_IsArray(cube) || cJSON_GetArraySize(cube) != 6)
        return scene_fail(c, "environment.cubemap", "expected six image paths in the order +X, -X, +Y, -Y, +Z, -Z");
    int i = 0;
    for (const cJSON *f = cube->child; f; f = f->next, i++) {
        char p[64];
        snprintf(p, sizeof p, "environment.cubemap.%d", i);
        if (!cJSON_IsString(f))
            return scene_fail(c, p, "expected an image path in quotes");
        if (!scene_resolve_file(c, p, f->valuestring, s->cubemap[i]))
            return false;
    }
    s->has_cubemap = true;
    return true;
}

/* The "quality" block: "preset" picks the starting values, then every knob of QUALITY_KNOBS may be set. */
bool scene_parse_quality(scene_ctx *c, const cJSON *root)
{
    scene *s = c->s;
    const cJSON *q = cJSON_GetObjectItemCaseSensitive(root, "quality");
    s->preset = PRESET_INTERACTIVE;
    if (!q) {
        s->quality = preset_quality(s->preset);
        return true;
    }
    const char *keys[KNOB_COUNT + 2] = {"preset"};
    for (int k = 0; k < KNOB_COUNT; k++)
        keys[k + 1] = knob_get_def((knob_id)k)->name;
    keys[KNOB_COUNT + 1] = NULL;
    if (!scene_check_keys(c, q, "quality", keys))
        return false;
    const char *name = NULL;
    if (!scene_get_str(c, q, "quality", "preset", "interactive", &name))
        return false;
    if (!preset_from_name(name, &s->preset)) {
        strbuf known = {0};
        for (int p = 0; p < PRESET_COUNT; p++)
            sb_printf(&known, "%s%s", p ? ", " : "", preset_name((quality_preset)p));
        bool r = scene_fail(c, "quality.preset", "unknown preset '%s' (known: %s)", name, known.data);
        sb_free(&known);
        return r;
    }
    s->quality = preset_quality(s->preset);
    for (int k = 0; k < KNOB_COUNT; k++) {
        const knob_def *d = knob_get_def((knob_id)k);
        float v;
        if (!scene_get_num(c, q, "quality", d->name, (float)knob_value(&s->quality, (knob_id)k), (float)d->min,
                     (float)d->max, &v))
            return false;
        if (d->type == KNOB_INT && v != floorf(v)) {
            char p[KEY_PATH_MAX];
            scene_child_path(p, sizeof p, "quality", d->name);
            return scene_fail(c, p, "expected a whole number");
        }
        knob_set_value(&s->quality, (knob_id)k, v);
    }
    return true;
}

bool scene_parse_effects(scene_ctx *c, const cJSON *root)
{
    const cJSON *fx = cJSON_GetObjectItemCaseSensitive(root, "effects");
    if (!fx)
        return true;
    if (!cJSON_IsObject(fx))
        return scene_fail(c, "effects", "expected an object like {\"fog\": \"off\"}");
    for (const cJSON *it = fx->child; it; it = it->next) {
        char p[128];
        scene_child_path(p, sizeof p, "effects", it->string);
        effect e;
        if (!effect_from_name(it->string, &e)) {
            strbuf list = {0};
            for (int i = 0; i < EFFECT_COUNT; i++)
                sb_printf(&list, "%s%s", i ? ", " : "", effect_name((effect)i));
            bool r = scene_fail(c, p, "unknown effect '%s' (known: %s)", it->string, list.data);
            sb_free(&list);
            return r;
        }
        /* in the order of effect_mode (scene.h) */
        static const char *const MODES[] = {"auto", "on", "off", NULL};
        int mode;
        if (!scene_get_enum(c, fx, "effects", it->string, "mode", MODES, EFFECT_AUTO, &mode))
            return false;
        c->s->effect_modes[e] = (effect_mode)mode;
    }
    return true;
}
