#include "scene/scene.h"

#include "view/camera.h"

#include <assert.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/droplets/droplets.h"
#include "scene/scene_parse.h"

/* A block that holds another program's shape is a mistake, not something to ignore. */
static bool check_shape_blocks(scene_ctx *c, const cJSON *root, const program_def *p)
{
    for (int k = 0; k < PROGRAM_COUNT; k++) {
        const char *block = program_get((program_kind)k)->block;
        if (!strcmp(block, p->block) || !cJSON_GetObjectItemCaseSensitive(root, block))
            continue;
        strbuf readers = {0};
        for (int r = 0; r < PROGRAM_COUNT; r++)
            if (!strcmp(program_get((program_kind)r)->block, block))
                sb_printf(&readers, "%s%s", readers.len ? ", " : "", program_name((program_kind)r));
        bool ok = scene_fail(c, block, "a %s scene has no \"%s\" block (its shape is the \"%s\" block; only %s read \"%s\")",
                             p->name, block, p->block, readers.data, block);
        sb_free(&readers);
        return ok;
    }
    return true;
}

/* An effect is compiled in when the scene's content calls for it ("auto"), then "on"/"off" force it. */
static unsigned derive_effects(const scene *s)
{
    bool shadows = false, soft = false, mirror = false, glass = false, relief = false;
    for (int i = 0; i < s->light_count; i++) {
        shadows |= s->lights[i].shadow != SHADOW_NONE;
        soft |= s->lights[i].shadow == SHADOW_SOFT;
    }
    for (int i = 0; i < s->material_count; i++) {
        const scene_material *m = &s->materials[i];
        glass |= m->transmission > 0;
        relief |= m->relief >= 0;
        mirror |= m->transmission == 0 && m->roughness <= MIRROR_ROUGHNESS;
    }
    bool want[EFFECT_COUNT] = {
        [EFFECT_SHADOWS] = shadows,
        [EFFECT_SOFT_SHADOWS] = soft,
        [EFFECT_AO] = s->env_intensity > 0 && s->quality.ao_samples > 0,
        [EFFECT_REFLECTIONS] = mirror && s->quality.bounces > 0,
        [EFFECT_REFRACTION] = (glass && s->quality.bounces > 0) || s->terrain.has_water, /* water spends no bounce */
        [EFFECT_FOG] = s->has_fog,
        [EFFECT_ENVMAP] = s->has_cubemap,
        [EFFECT_TEXTURES] = s->texture_count > 0 && !(s->texture_count == 1 && s->texture_linear[0]),
        [EFFECT_AA] = s->quality.spp > 1,
        [EFFECT_GLOW] = s->fractal.glow > 0,
        [EFFECT_RELIEF] = relief,
        [EFFECT_DROPLETS] = s->has_droplets,
        [EFFECT_SKY] = s->has_sky,
        [EFFECT_WATER] = s->terrain.has_water,
    };
    unsigned fx = 0;
    for (int e = 0; e < EFFECT_COUNT; e++) {
        bool on = s->effect_modes[e] == EFFECT_ON || (s->effect_modes[e] == EFFECT_AUTO && want[e]);
        fx |= (unsigned)on << e;
    }
    /* penumbrae are a kind of shadow: without shadow rays there is nothing to soften */
    if (!(fx & (1u << EFFECT_SHADOWS)))
        fx &= ~(1u << EFFECT_SOFT_SHADOWS);
    /* droplets come from a file: a scene without one has none to draw */
    if (!s->has_droplets)
        fx &= ~(1u << EFFECT_DROPLETS);
    /* water lies on a DEM: a scene without one (or without a level) has none to draw */
    if (!s->terrain.has_water)
        fx &= ~(1u << EFFECT_WATER);
    /* terrain programs run the lab's search themselves, over their own surface: no relief there */
    if (program_get(s->program)->family == FAMILY_TERRAIN)
        fx &= ~(1u << EFFECT_RELIEF);
    return fx;
}


/* The top level: which program, then the blocks every program reads, then the program's own. */
static bool parse_root(scene_ctx *c, cJSON *root)
{
    scene *s = c->s;
    /* the blocks every program reads, then each program's own shape block (PROGRAM_LIST) */
    const char *keys[16 + PROGRAM_COUNT] = {"title", "program", "camera", "environment", "lights", "fog",
                                            "materials", "quality", "effects", "droplets", "sun"};
    int n = 11;
    for (int k = 0; k < PROGRAM_COUNT; k++) {
        int i = 0;
        while (i < n && strcmp(keys[i], program_get((program_kind)k)->block))
            i++;
        if (i == n)
            keys[n++] = program_get((program_kind)k)->block;
    }
    keys[n] = NULL;
    if (!scene_check_keys(c, root, "", keys))
        return false;
    const char *title = NULL, *prog = NULL;
    if (!scene_get_str(c, root, "", "title", "", &title) || !scene_get_str(c, root, "", "program", NULL, &prog))
        return false;
    snprintf(s->title, sizeof s->title, "%s", title);
    if (!prog)
        return scene_fail(c, "program", "missing: say which program draws the scene, e.g. \"program\": \"csg\"");
    formula named; /* "program": "mandelbulb": the fractal program with that formula */
    err_t ignore;
    if (program_from_name(prog, &s->program)) {
        c->formula = NULL;
    } else if (!strchr(prog, '/') && !strstr(prog, ".glsl") && formula_load(prog, NULL, &named, &ignore)) {
        s->program = PROGRAM_FRACTAL;
        c->formula = prog;
    } else {
        strbuf known = {0}, formulas = {0};
        program_names(&known);
        formula_list(&formulas);
        for (char *q = formulas.data; q && *q; q++)
            if (*q == '\n')
                *q = q[1] ? ' ' : '\0';
        bool r = scene_fail(c, "program", "unknown program '%s' (programs: %s; or a formula's name: %s)", prog, known.data,
                      formulas.data ? formulas.data : "none");
        sb_free(&known);
        sb_free(&formulas);
        return r;
    }
    const program_def *p = program_get(s->program);
    if (!check_shape_blocks(c, root, p))
        return false;
    if (!scene_parse_camera(c, root) || !scene_parse_fog(c, root) || !scene_parse_environment(c, root) || !scene_parse_lights(c, root) ||
        !scene_parse_sun(c, root) ||
        !scene_parse_quality(c, root) || !scene_parse_effects(c, root) || !scene_parse_droplets(c, root))
        return false;
    /* fractals colour their own surface: their "materials" are optional */
    bool materials = p->family != FAMILY_FRACTAL || cJSON_GetObjectItemCaseSensitive(root, "materials");
    if ((materials && !scene_parse_materials(c, root)) || !p->parse(c, root))
        return false;
    if (p->map_file)
        sb_printf(&c->code, "#include \"%s\"\n", p->map_file);
    s->effects = derive_effects(s);
    return true;
}

/* ---- entry points ------------------------------------------------------------------------------ */

static void line_col(const char *text, const char *at, int *line, int *col)
{
    *line = 1;
    *col = 1;
    for (const char *p = text; p < at && *p; p++) {
        if (*p == '\n') {
            (*line)++;
            *col = 1;
        } else {
            (*col)++;
        }
    }
}

/* JSON allows a key twice in an object and cJSON keeps both, reading the first: a second value would
 * go unchecked and unused. Refused, with the key's path. */
static bool check_duplicates(scene_ctx *c, const cJSON *node, const char *path)
{
    int index = 0;
    for (const cJSON *it = node->child; it; it = it->next, index++) {
        char p[KEY_PATH_MAX];
        if (cJSON_IsObject(node)) {
            scene_child_path(p, sizeof p, path, it->string);
            for (const cJSON *before = node->child; before != it; before = before->next)
                if (!strcmp(before->string, it->string))
                    return scene_fail(c, p, "the key '%s' appears twice in the same object; keep one", it->string);
        } else {
            char idx[16];
            snprintf(idx, sizeof idx, "%d", index);
            scene_child_path(p, sizeof p, path, idx);
        }
        if ((cJSON_IsObject(it) || cJSON_IsArray(it)) && !check_duplicates(c, it, p))
            return false;
    }
    return true;
}

/* Deepest nesting of [ and { outside strings, and where it first passes `limit`. */
static int nesting(const char *text, int limit, const char **at)
{
    int depth = 0, deepest = 0;
    bool in_string = false;
    for (const char *p = text; *p; p++) {
        if (in_string) {
            if (*p == '\\' && p[1])
                p++;
            else if (*p == '"')
                in_string = false;
        } else if (*p == '"') {
            in_string = true;
        } else if (*p == '[' || *p == '{') {
            if (++depth > deepest && (deepest = depth) == limit + 1)
                *at = p;
        } else if (*p == ']' || *p == '}') {
            depth--;
        }
    }
    return deepest;
}

/* The scene with overrides failed (err says why): the file is parsed alone, only now, to tell whose
 * mistake it is. The file's own error is reported as the file's; else the override that breaks it
 * alone is named (a --set or --dem), or "the overrides" when only together they do. */
static bool load_text(const char *text, const char *path, const char *const *sets, int set_count, scene *s,
                      bool blame, param_list *params, err_t *err);

static void blame_override(const char *text, const char *path, const char *const *sets, int set_count, err_t *err)
{
    scene alone;
    err_t other;
    if (!load_text(text, path, NULL, 0, &alone, false, NULL, &other)) {
        *err = other;
        return;
    }
    scene_free(&alone);
    const char *culprit = NULL;
    /* the one without which the rest load (a fragment's preset comes as overrides too: the user's
     * --set among them is named, not a preset line that only fails without the fragment), else the
     * first that fails alone */
    const char **rest = util_alloc(sizeof *rest * (size_t)(set_count > 1 ? set_count - 1 : 1), "the overrides");
    for (int i = 0; i < set_count && !culprit; i++) {
        int n = 0;
        for (int k = 0; k < set_count; k++)
            if (k != i)
                rest[n++] = sets[k];
        if (load_text(text, path, rest, n, &alone, false, NULL, &other))
            scene_free(&alone), culprit = sets[i];
    }
    free(rest);
    for (int i = 0; i < set_count && !culprit; i++) {
        if (load_text(text, path, &sets[i], 1, &alone, false, NULL, &other))
            scene_free(&alone);
        else
            culprit = sets[i];
    }
    char suffix[160];
    if (culprit)
        snprintf(suffix, sizeof suffix, " (from the override %.120s)", culprit);
    else
        snprintf(suffix, sizeof suffix, " (from the overrides together)");
    size_t len = strlen(err->msg), add = strlen(suffix);
    if (len + add < sizeof err->msg)
        memcpy(err->msg + len, suffix, add + 1);
}

bool scene_load_text(const char *text, const char *path, const char *const *sets, int set_count, scene *s,
                     err_t *err)
{
    return load_text(text, path, sets, set_count, s, true, NULL, err);
}


bool scene_knob_applies(const scene *s, knob_id k)
{
    switch (knob_get_def(k)->scope) {
    case SCOPE_ANY: return true;
    case SCOPE_SHADOWS: return s->effects & (1u << EFFECT_SHADOWS);
    case SCOPE_AO: return s->effects & (1u << EFFECT_AO);
    case SCOPE_BOUNCES: return s->effects & ((1u << EFFECT_REFLECTIONS) | (1u << EFFECT_REFRACTION));
    case SCOPE_TEXTURES: return s->effects & (1u << EFFECT_TEXTURES);
    case SCOPE_REFINES: /* common/march.glsl refines; fractals define their surface by the footprint */
        return !program_is_fractal(s->program) && !s->terrain.heightmap[0];
    case SCOPE_SEARCH: /* the lab's search runs: linear terrain, or relief materials */
        return (s->terrain.heightmap[0] && !s->terrain.maxmip) || (s->effects & (1u << EFFECT_RELIEF));
    case SCOPE_DROPLETS: return s->effects & (1u << EFFECT_DROPLETS);
    case SCOPE_EXACT: return program_get(s->program)->family == FAMILY_CSG;
    case SCOPE_ENVMAP: return s->has_cubemap && (s->effects & (1u << EFFECT_ENVMAP));
    }
    return false;
}

/* What the parser does not read key by key: every quality knob (with its help, whether the file sets
 * it or not) and the preset; and the formulas' descriptions for their parameters. */
static void finish_params(const scene *s, param_list *l)
{
    for (int k = 0; k < KNOB_COUNT; k++) {
        const knob_def *d = knob_get_def((knob_id)k);
        if (!scene_knob_applies(s, (knob_id)k)) { /* nothing about what the scene does not use */
            for (int i = 0; i < l->count;) /* the rest keep the order the parser met them in */
                if (!strncmp(l->items[i].key, "quality.", 8) && !strcmp(l->items[i].key + 8, d->name))
                    memmove(&l->items[i], &l->items[i + 1], sizeof *l->items * (size_t)(--l->count - i));
                else
                    i++;
            continue;
        }
        scene_param p = {.type = d->type == KNOB_INT ? PARAM_INT : PARAM_FLOAT, .lo = d->min, .hi = d->max,
                         .value = {knob_value(&s->quality, (knob_id)k)}};
        snprintf(p.key, sizeof p.key, "quality.%s", d->name);
        snprintf(p.help, sizeof p.help, "%s", d->help);
        params_add(l, &p);
    }
    scene_param preset = {.type = PARAM_ENUM, .hi = PRESET_COUNT - 1, .value = {s->preset}, .key = "quality.preset"};
    size_t at = 0;
    for (int i = 0; i < PRESET_COUNT; i++, preset.name_count++) {
        const char *name = preset_name((quality_preset)i);
        memcpy(preset.names + at, name, strlen(name) + 1);
        at += strlen(name) + 1;
    }
    snprintf(preset.help, sizeof preset.help, "sets every knob to the preset's value (then the file's own knobs)");
    params_add(l, &preset);
    for (int e = 0; e < EFFECT_COUNT; e++) { /* every effect: compiled in when the content needs it, or forced */
        scene_param fx = {.type = PARAM_ENUM, .hi = 2, .value = {s->effect_modes[e]}, .name_count = 3};
        memcpy(fx.names, "auto\0on\0off", sizeof "auto\0on\0off");
        snprintf(fx.key, sizeof fx.key, "effects.%s", effect_name((effect)e));
        snprintf(fx.help, sizeof fx.help, "auto: compiled in when the scene needs it (now %s); on, off: forced",
                 s->effects & (1u << e) ? "in" : "out");
        params_add(l, &fx);
    }
    for (int i = 0; i < l->count; i++) {
        scene_param *p = &l->items[i];
        bool hybrid = !strncmp(p->key, "fractal.hybrid.", 15);
        const formula *f = hybrid ? &s->fractal.hybrid : &s->fractal.formula;
        const formula_param *q = !strncmp(p->key, "fractal.", 8) ? formula_find(f, p->key + (hybrid ? 15 : 8)) : NULL;
        if (q && program_is_fractal(s->program))
            snprintf(p->help, sizeof p->help, "%s", q->description), snprintf(p->group, sizeof p->group, "%s", q->group);
    }
}

bool scene_load_params(const char *name_or_path, const char *const *sets, int set_count, scene *s,
                       param_list *params, err_t *err)
{
    char path[PATH_MAX_LEN];
    char *text;
    if (!scene_locate(name_or_path, path, sizeof path, err) || !scene_read_text(path, &text, err))
        return false;
    bool ok = load_text(text, path, sets, set_count, s, true, params, err);
    free(text);
    return ok;
}

static bool load_text(const char *text, const char *path, const char *const *sets, int set_count, scene *s,
                      bool blame, param_list *params, err_t *err)
{
    *s = (scene){0};
    snprintf(s->path, sizeof s->path, "%s", path);
    util_dirname(path, s->dir, sizeof s->dir);
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(s->name, sizeof s->name, "%.*s", (int)strcspn(base, "."), base);

    const char *end = NULL;
    if (nesting(text, CJSON_NESTING_LIMIT, &end) > CJSON_NESTING_LIMIT) {
        int line, col;
        line_col(text, end, &line, &col);
        return err_set(err, "%s:%d:%d: brackets nested deeper than %d levels; no scene needs that many", path, line,
                       col, CJSON_NESTING_LIMIT);
    }
    cJSON *root = cJSON_ParseWithOpts(text, &end, true);
    if (!root) {
        int line, col;
        line_col(text, end ? end : text, &line, &col);
        return err_set(err, "%s:%d:%d: malformed JSON near here (check commas, quotes and brackets)", path, line, col);
    }
    scene_ctx c = {.file = path, .err = err, .s = s, .params = params};
    bool ok = check_duplicates(&c, root, "");
    for (int i = 0; ok && i < set_count; i++)
        ok = scene_apply_set(root, sets[i], err); /* its errors name the override already */
    if (ok) {
        ok = parse_root(&c, root) &&
             (!s->cam_auto || program_get(s->program)->frame(s, err)) && scene_apply_sun(s, err) &&
             scene_apply_sky(s, err);
        if (!ok && set_count > 0 && blame)
            blame_override(text, path, sets, set_count, err);
    }
    cJSON_Delete(root);
    if (ok) {
        s->map_glsl = c.code.data;
        if (params)
            finish_params(s, params);
    } else {
        sb_free(&c.code);
        scene_free(s);
    }
    return ok;
}

/* Scene texts a shot or preset carried (scene_provide_text), by the path the scene had. */
bool scene_load(const char *name_or_path, const char *const *sets, int set_count, scene *s, err_t *err)
{
    char path[PATH_MAX_LEN];
    char *text;
    if (!scene_locate(name_or_path, path, sizeof path, err) || !scene_read_text(path, &text, err))
        return false;
    bool ok = scene_load_text(text, path, sets, set_count, s, err);
    free(text);
    return ok;
}

void scene_free(scene *s)
{
    free(s->map_glsl);
    free(s->csg_list);
    free(s->csg_nodes);
    s->map_glsl = NULL;
    s->csg_list = s->csg_nodes = NULL;
}

bool scene_needs_double(const scene *s, double distance, const camera *c, int height, bool now)
{
    const scene_fractal *f = &s->fractal;
    if (s->program != PROGRAM_FRACTAL || !f->deep_ok || f->precision == PRECISION_FLOAT)
        return false;
    if (f->precision == PRECISION_DOUBLE)
        return true;
    double threshold = (double)s->quality.hit_k * distance * (double)camera_pixel_angle(c, height);
    double resolution = (double)PRECISION_REL * (camera_norm(c->position) + distance);
    return threshold < DEEP_MARGIN * (now ? 2.0 : 1.0) * resolution;
}

void scene_preamble(const scene *s, strbuf *out)
{
    const program_def *p = program_get(s->program);
    sb_printf(out, "#define PROGRAM_%s 1\n", p->name);
    effect_preamble(s->effects, out);
    quality q = s->quality; /* a formula's estimate is trusted to its @step (not a Julia set's or hybrid's) */
    if (program_is_fractal(s->program) && !s->fractal.julia && !s->fractal.has_hybrid && s->fractal.step > 0)
        q.step_factor = fminf(q.step_factor, s->fractal.step);
    quality_preamble(&q, out);
    sb_printf(out, "#define NUM_LIGHTS %d\n#define NUM_MATERIALS %d\n#define MIRROR_ROUGHNESS %.9g\n"
                   "#define PRECISION_REL %.9g\n",
              s->light_count, s->material_count, (double)MIRROR_ROUGHNESS, (double)PRECISION_REL);
    if (s->has_droplets)
        sb_printf(out, "#define DROPLET_BVH %d\n", s->droplets.bvh);
    if (p->defines)
        p->defines(s, out);
}

/* Materials (shaders/common/material.glsl, relief.glsl). */
static void material_uniforms(const scene *s, const uniform_sink *u)
{
    enum { N = SCENE_MAX_MATERIALS };
    float base[N][3], metallic[N], rough[N], trans[N], ior[N], absorb[N][3], uv[N], emit[N][3], depth[N];
    int tex[N], relief[N];
    for (int i = 0; i < s->material_count; i++) {
        const scene_material *m = &s->materials[i];
        memcpy(base[i], m->base_color, sizeof base[i]);
        memcpy(absorb[i], m->absorption, sizeof absorb[i]);
        memcpy(emit[i], m->emission, sizeof emit[i]);
        metallic[i] = m->metallic;
        rough[i] = m->roughness;
        trans[i] = m->transmission;
        ior[i] = m->ior;
        uv[i] = m->uv_scale;
        tex[i] = m->texture;
        relief[i] = m->relief;
        depth[i] = m->relief_depth;
    }
    int n = s->material_count;
    uniform_fv(u, "uMatBaseColor", 3, n, &base[0][0]);
    uniform_fv(u, "uMatMetallic", 1, n, metallic);
    uniform_fv(u, "uMatRoughness", 1, n, rough);
    uniform_fv(u, "uMatTransmission", 1, n, trans);
    uniform_fv(u, "uMatIor", 1, n, ior);
    uniform_fv(u, "uMatAbsorption", 3, n, &absorb[0][0]);
    uniform_fv(u, "uMatEmission", 3, n, &emit[0][0]);
    uniform_fv(u, "uMatUvScale", 1, n, uv);
    uniform_iv(u, "uMatTexture", 1, n, tex);
    uniform_iv(u, "uMatRelief", 1, n, relief);
    uniform_fv(u, "uMatReliefDepth", 1, n, depth);
}

/* Lights (shaders/common/lights.glsl). */
static void light_uniforms(const scene *s, const uniform_sink *u)
{
    enum { N = SCENE_MAX_LIGHTS };
    float vec[N][3], col[N][3], soft[N];
    int directional[N], shadow[N];
    for (int i = 0; i < s->light_count; i++) {
        const scene_light *l = &s->lights[i];
        memcpy(vec[i], l->vec, sizeof vec[i]);
        for (int k = 0; k < 3; k++)
            col[i][k] = l->color[k] * l->intensity;
        directional[i] = l->type == LIGHT_DIRECTIONAL;
        shadow[i] = (int)l->shadow;
        soft[i] = l->softness;
    }
    if (s->light_count == 0) /* GLSL has no arrays of size 0: the program declares none */
        return;
    uniform_fv(u, "uLightVec", 3, s->light_count, &vec[0][0]);
    uniform_fv(u, "uLightColor", 3, s->light_count, &col[0][0]);
    uniform_iv(u, "uLightDirectional", 1, s->light_count, directional);
    uniform_iv(u, "uLightShadow", 1, s->light_count, shadow);
    uniform_fv(u, "uLightSoftness", 1, s->light_count, soft);
}

void scene_formula_files(const scene *s, const char *files[2])
{
    bool fractal = program_is_fractal(s->program);
    files[0] = fractal ? s->fractal.formula.file : NULL;
    files[1] = fractal && s->fractal.has_hybrid ? s->fractal.hybrid.file : NULL;
}

void scene_uniforms(const scene *s, const uniform_sink *u)
{
    material_uniforms(s, u);
    light_uniforms(s, u);
    uniform_i(u, "uLoopProbe", 2); /* the sentinel loop that tells a cut invocation: common/budget.glsl */
    float env[3];
    for (int k = 0; k < 3; k++)
        env[k] = s->env_color[k] * s->env_intensity;
    uniform_fv(u, "uEnvColor", 3, 1, env);
    uniform_fv(u, "uFogColor", 3, 1, s->fog_color);
    uniform_f(u, "uFogDensity", s->fog_density);
    uniform_f(u, "uFogFalloff", s->fog_falloff);
    uniform_f(u, "uFogHeight", s->fog_height);
    if (s->effects & (1u << EFFECT_SKY)) { /* shaders/common/sky.glsl */
        uniform_fv(u, "uSkySun", 3, 1, s->sky.sun);
        uniform_fv(u, "uSkyIrradiance", 3, 1, s->sky.irradiance);
        uniform_fv(u, "uSkyMs", 3, SKY_MS_N, &s->sky.ms[0][0]);
        uniform_f(u, "uSkyScale", s->sky.scale);
    }
    if (s->has_droplets) { /* shaders/common/droplets.glsl; the grid's uniforms come with its buffers */
        uniform_f(u, "uDropletIor", s->droplets.ior);
        uniform_fv(u, "uDropletAbsorption", 3, 1, s->droplets.absorption);
        uniform_f(u, "uDropletRoughness", s->droplets.roughness);
        droplet_lod_table lod;
        droplets_lod_table(s->droplets.ior, &lod);
        uniform_fv(u, "uDropletLodWeight", 1, DROPLET_LOD_NODES, lod.weight);
        uniform_fv(u, "uDropletLodCosT", 1, DROPLET_LOD_NODES, lod.cos_t);
        uniform_f(u, "uDropletReflect", lod.reflect);
    }
    const program_def *p = program_get(s->program);
    if (p->uniforms)
        p->uniforms(s, u);
}

camera_lens scene_lens(const scene *s)
{
    camera_lens l = s->cam_lens;
    if (!(l.focus > 0))
        l.focus = (float)camera_distance(s->cam_position, s->cam_look_at);
    if (!(l.eye_separation > 0))
        l.eye_separation = l.focus / 30.0f;
    return l;
}

camera scene_camera(const scene *s, const double eye[3], const double at[3], float fov_deg)
{
    camera c = camera_look_at_up(eye, at, s->cam_up, glm_rad(fov_deg));
    c.roll = remainderf(c.roll + glm_rad(s->cam_roll_deg), 2.0f * GLM_PIf);
    c.lens = s->cam_lens;
    if (!(c.lens.focus > 0))
        c.lens.focus = (float)camera_distance(eye, at);
    if (!(c.lens.eye_separation > 0))
        c.lens.eye_separation = c.lens.focus / 30.0f;
    return c;
}
