/* scene_terrain — the terrain programs' "terrain" block (noise and heightmap), their framing from a DEM's
 * extent and their #defines and uniforms (scene.h, program.h's table); the fractal and torus blocks are
 * in scene_programs.c. */
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "scene/scene_parse.h"
#include "data/geo/terrain.h"
#include "data/geo/viewshed.h"

/* ---- terrains: the "terrain" block ------------------------------------------------------------ */

bool scene_noise_parse(scene_ctx *c, const cJSON *root)
{
    struct scene_terrain *t = &c->s->terrain;
    const cJSON *tb = cJSON_GetObjectItemCaseSensitive(root, "terrain");
    static const char *const keys[] = {"base", "amplitude", "frequency", "octaves", "sand_line", "snow_line",
                                       "grass_slope", NULL};
    const cJSON *empty = cJSON_CreateObject(), *use = tb ? tb : empty;
    bool ok = (!tb || scene_check_keys(c, tb, "terrain", keys)) &&
              scene_get_num(c, use, "terrain", "base", 0, -1e6f, 1e6f, &t->base) &&
              scene_get_num(c, use, "terrain", "amplitude", 40, 0, 1e6f, &t->amplitude) &&
              scene_get_num(c, use, "terrain", "frequency", 0.01f, 1e-7f, 1e3f, &t->frequency) &&
              scene_get_int(c, use, "terrain", "octaves", 6, 1, 12, &t->octaves) &&
              scene_get_num(c, use, "terrain", "sand_line", -1e9f, -1e9f, 1e9f, &t->sand_line) &&
              scene_get_num(c, use, "terrain", "snow_line", 1e9f, -1e9f, 1e9f, &t->snow_line) &&
              scene_get_num(c, use, "terrain", "grass_slope", 0.8f, 0, 1, &t->grass_slope);
    cJSON_Delete((cJSON *)empty);
    return ok;
}

static bool spacing_ok(const cJSON *v) { return cJSON_IsNumber(v) && terrain_spacing_ok(v->valuedouble); }

/* "imagery": a file, or an array of files and {"file": F, "opacity": A} layers, drawn in order. */
static bool parse_imagery(scene_ctx *c, const cJSON *tb)
{
    struct scene_terrain *t = &c->s->terrain;
    const cJSON *im = cJSON_GetObjectItemCaseSensitive(tb, "imagery");
    if (!im)
        return true;
    const cJSON *first = cJSON_IsArray(im) ? im->child : im;
    if (!first && cJSON_IsArray(im))
        return true; /* [] drapes nothing */
    static const char *const keys[] = {"file", "opacity", NULL};
    int i = 0;
    for (const cJSON *l = first; l; l = cJSON_IsArray(im) ? l->next : NULL, i++) {
        char p[64];
        snprintf(p, sizeof p, cJSON_IsArray(im) ? "terrain.imagery.%d" : "terrain.imagery", i);
        if (i == SCENE_MAX_IMAGERY)
            return scene_fail(c, p, "too many imagery layers (at most %d)", SCENE_MAX_IMAGERY);
        const char *file = cJSON_IsString(l) ? l->valuestring : NULL;
        float opacity = 1;
        if (cJSON_IsObject(l) && (!scene_check_keys(c, l, p, keys) || !scene_get_str(c, l, p, "file", NULL, &file) ||
                                  !scene_get_num(c, l, p, "opacity", 1, 0, 1, &opacity)))
            return false;
        if (!file)
            return scene_fail(c, p, "expected an imagery file (any raster GDAL reads, georeferenced) or {\"file\": F, "
                                    "\"opacity\": 0.7}");
        if (!scene_resolve_file(c, p, file, t->imagery[i]))
            return false;
        t->imagery_opacity[i] = opacity;
        t->imagery_count = i + 1;
    }
    return true;
}

/* "vectors": a file, or an array of files and {"file": F, "color": [r, g, b], "width": M, "opacity": A}. */
static bool parse_vectors(scene_ctx *c, const cJSON *tb)
{
    struct scene_terrain *t = &c->s->terrain;
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(tb, "vectors");
    if (!v)
        return true;
    static const char *const keys[] = {"file", "color", "width", "opacity", NULL};
    static const float red[3] = {1.0f, 0.25f, 0.1f};
    int i = 0;
    for (const cJSON *l = cJSON_IsArray(v) ? v->child : v; l; l = cJSON_IsArray(v) ? l->next : NULL, i++) {
        char p[64];
        snprintf(p, sizeof p, cJSON_IsArray(v) ? "terrain.vectors.%d" : "terrain.vectors", i);
        if (i == SCENE_MAX_IMAGERY)
            return scene_fail(c, p, "too many vector layers (at most %d)", SCENE_MAX_IMAGERY);
        const char *file = cJSON_IsString(l) ? l->valuestring : NULL;
        float *col = t->vector_color[i];
        memcpy(col, red, sizeof red);
        col[3] = 1;
        t->vector_width[i] = 0;
        if (cJSON_IsObject(l) &&
            (!scene_check_keys(c, l, p, keys) || !scene_get_str(c, l, p, "file", NULL, &file) ||
             !scene_get_vec3(c, l, p, "color", red, 0, 1, col) || !scene_get_num(c, l, p, "width", 0, 0, 1e5f, &t->vector_width[i]) ||
             !scene_get_num(c, l, p, "opacity", 1, 0, 1, &col[3])))
            return false;
        if (!file)
            return scene_fail(c, p, "expected a vector file (GPX, KML, GeoJSON, GeoPackage, Shapefile) or {\"file\": F, "
                                    "\"color\": [1, 0.2, 0.1], \"width\": 30}");
        if (!scene_resolve_file(c, p, file, t->vectors[i]))
            return false;
        t->vector_count = i + 1;
    }
    return true;
}

/* "water": a level; its look is the material "water", clear water unless the scene defines it (pure water's
 * absorption at 650, 550 and 450 nm, Pope & Fry 1997, "Absorption spectrum (380–700 nm) of pure water";
 * the refractive index 1.333). */
static bool parse_water(scene_ctx *c, const cJSON *tb)
{
    struct scene_terrain *t = &c->s->terrain;
    const cJSON *w = cJSON_GetObjectItemCaseSensitive(tb, "water");
    t->has_water = w != NULL;
    t->water_mode = WATER_NONE;
    if (!w)
        return true;
    if (cJSON_IsString(w) && !strcmp(w->valuestring, "fill")) {
        t->water_mode = WATER_FILL;
    } else if (cJSON_IsString(w)) {
        const char *base = strrchr(w->valuestring, '/') ? strrchr(w->valuestring, '/') + 1 : w->valuestring;
        if (!strcasecmp(base, "nan") || !strcasecmp(base, "inf") || !strcasecmp(base, "-inf") || !strcasecmp(base, "infinity"))
            return scene_fail(c, "terrain.water", "'%s' is no level: give a height in metres from -100000 to 100000, "
                                                  "\"fill\" or a raster file", base);
        if (!scene_resolve_file(c, "terrain.water", w->valuestring, t->water_raster))
            return false;
        t->water_mode = WATER_RASTER;
    } else if (cJSON_IsNumber(w)) {
        if (!scene_get_num(c, tb, "terrain", "water", 0, -1e5f, 1e5f, &t->water_level))
            return false;
        t->water_mode = WATER_LEVEL;
    } else {
        return scene_fail(c, "terrain.water", "expected a level in metres, \"fill\" (the lakes the DEM implies) or a "
                                              "raster of water-surface heights on the DEM's grid");
    }
    if (t->water_mode != WATER_LEVEL && !t->maxmip)
        return scene_fail(c, "terrain.water", "lakes and rasters of water are drawn by terrain.method \"maxmip\" (the "
                                              "exact walk); this scene's is \"linear\"");
    t->water_material = scene_find_material(c->s, "water");
    if (t->water_material >= 0)
        return true;
    if (c->s->material_count + (c->s->material_count == 0 ? 2 : 1) > SCENE_MAX_MATERIALS)
        return scene_fail(c, "terrain.water", "no room for the water's material (at most %d materials): define one "
                                              "named \"water\" in place of another", SCENE_MAX_MATERIALS);
    if (c->s->material_count == 0) /* the ground is material 0 (its layers' colours): water is another */
        c->s->materials[c->s->material_count++] = (scene_material){
            .name = "ground", .base_color = {0.6f, 0.6f, 0.6f}, .roughness = 0.9f, .ior = 1.5f, .texture = -1,
            .uv_scale = 1, .relief = -1, .relief_depth = 0.05f};
    t->water_material = c->s->material_count++;
    c->s->materials[t->water_material] = (scene_material){
        .name = "water", .base_color = {0.02f, 0.05f, 0.06f}, .roughness = 0, .transmission = 1, .ior = 1.333f,
        .absorption = {0.340f, 0.0565f, 0.0092f}, .texture = -1, .uv_scale = 1, .relief = -1, .relief_depth = 0.05f};
    return true;
}

bool scene_heightmap_parse(scene_ctx *c, const cJSON *root)
{
    struct scene_terrain *t = &c->s->terrain;
    const cJSON *tb = cJSON_GetObjectItemCaseSensitive(root, "terrain");
    static const char *const keys[] = {"heightmap", "spacing", "height_min", "height_max", "exaggeration", "method",
                                       "sand_line", "snow_line", "grass_slope", "nodata", "normals", "colors", "imagery",
                                       "vectors", "cache_mb", "water", "curvature", NULL};
    if (!tb)
        return scene_fail(c, "terrain", "a terrain scene needs a \"terrain\" block with a \"heightmap\"");
    if (!scene_check_keys(c, tb, "terrain", keys))
        return false;
    const char *hm = NULL;
    static const float zero2[3] = {0, 0, 0};
    float sp[3];
    if (!scene_get_str(c, tb, "terrain", "heightmap", NULL, &hm))
        return false;
    if (!hm)
        return scene_fail(c, "terrain.heightmap", "missing: a heightmap image (16-bit PNG, EXR, TIFF…)");
    if (!scene_resolve_file(c, "terrain.heightmap", hm, t->heightmap))
        return false;
    const cJSON *spacing = cJSON_GetObjectItemCaseSensitive(tb, "spacing");
    if (spacing) {
        if (!cJSON_IsArray(spacing) || cJSON_GetArraySize(spacing) != 2 || !spacing_ok(spacing->child) ||
            !spacing_ok(spacing->child->next))
            return scene_fail(c, "terrain.spacing", "expected [dx, dz]: metres per texel, both from %g to %g",
                        (double)TERRAIN_SPACING_MIN, (double)TERRAIN_SPACING_MAX);
        sp[0] = (float)spacing->child->valuedouble;
        sp[1] = (float)spacing->child->next->valuedouble;
    } else {
        memcpy(sp, zero2, sizeof sp);
    }
    t->spacing[0] = sp[0];
    t->spacing[1] = sp[1];
    t->exaggeration_set = cJSON_HasObjectItem(tb, "exaggeration"); /* 1 is true scale, not "not set" */
    if (!scene_get_num(c, tb, "terrain", "height_min", 0, -1e5f, 1e5f, &t->height_min) ||
        !scene_get_num(c, tb, "terrain", "height_max", 0, -1e5f, 1e5f, &t->height_max) ||
        !scene_get_num(c, tb, "terrain", "exaggeration", 1, 0.01f, 100, &t->exaggeration) ||
        !scene_get_num(c, tb, "terrain", "sand_line", -1e9f, -1e9f, 1e9f, &t->sand_line) ||
        !scene_get_num(c, tb, "terrain", "snow_line", 1e9f, -1e9f, 1e9f, &t->snow_line) ||
        !scene_get_num(c, tb, "terrain", "grass_slope", 0.8f, 0, 1, &t->grass_slope) ||
        !scene_get_int(c, tb, "terrain", "cache_mb", 0, 0, 999999, &t->cache_mb))
        return false;
    if (t->height_min > t->height_max)
        return scene_fail(c, "terrain.height_max", "%g is below height_min %g: height_min is the height of black, "
                    "height_max of white", (double)t->height_max, (double)t->height_min);
    static const char *const METHODS[] = {"linear", "maxmip", NULL};
    int m;
    if (!scene_get_enum(c, tb, "terrain", "method", "method", METHODS, 1, &m))
        return false;
    t->maxmip = m == 1;
    static const char *const NODATA[] = {"hole", "fill", NULL}, *const NORMALS[] = {"smooth", "patch", NULL};
    if (!scene_get_enum(c, tb, "terrain", "nodata", "nodata handling", NODATA, 0, &m))
        return false;
    t->fill_nodata = m == 1;
    if (!scene_get_enum(c, tb, "terrain", "normals", "normals", NORMALS, 0, &m))
        return false;
    t->patch_normals = m == 1;
    static const char *const COLORS[] = {"layers", "elevation", NULL};
    if (!scene_get_enum(c, tb, "terrain", "colors", "terrain colouring", COLORS, 0, &m))
        return false;
    t->elevation_ramp = m == 1;
    const cJSON *curve = cJSON_GetObjectItemCaseSensitive(tb, "curvature");
    if (curve && !cJSON_IsBool(curve))
        return scene_fail(c, "terrain.curvature", "expected true (the DEM drawn on the Earth's curvature) or false");
    t->curvature = cJSON_IsTrue(curve);
    return parse_imagery(c, tb) && parse_vectors(c, tb) && parse_water(c, tb);
}


/* "camera": "auto": a view across the DEM from above its southern edge, and what follows from its
 * size: the far distance, haze over its width, sand and snow by the height range, textures that
 * repeat every 24 texels. A DEM whose relief is under RELIEF_SHOWN of its width (a continent, at true
 * scale a flat plate) is exaggerated up to that, at most ×20, unless the scene sets
 * terrain.exaggeration (the Himalaya's 5 arc-minute grid: ×9.6, where ×4.8 read as a green plain). */
static const double SNOW_ALTITUDE = 2500.0; /* metres: below it a DEM framed by "auto" gets no snow */
static const double RELIEF_SHOWN = 0.04;    /* of the DEM's width: a flatter one is exaggerated to it */

bool scene_terrain_frame(scene *s, err_t *err)
{
    struct scene_terrain *t = &s->terrain;
    heightfield_desc d = {.path = t->heightmap, .spacing = {t->spacing[0], t->spacing[1]}, .height_min = t->height_min,
                          .height_max = t->height_max, .exaggeration = t->exaggeration};
    double size[2], range[2], spacing[2];
    if (!heightfield_probe(&d, size, range, spacing, err))
        return false;
    double R = fmax(size[0], size[1]), relief = fmax(range[1] - range[0], 1e-3 * R);
    if (!t->exaggeration_set && relief < RELIEF_SHOWN * R) { /* continental DEMs look flat at true scale */
        double ex = fmin(RELIEF_SHOWN * R / relief, 20);
        t->exaggeration = (float)ex;
        range[0] *= ex, range[1] *= ex, relief *= ex;
    }
    /* over the southern edge, looking north across the middle: the near half fills the view */
    double at[3] = {0, range[0] + 0.3 * relief, -0.1 * size[1]};
    double eye[3] = {-0.1 * size[0], range[1] + 0.12 * R, 0.5 * size[1] + 0.05 * R};
    memcpy(s->cam_position, eye, sizeof eye);
    memcpy(s->cam_look_at, at, sizeof at);
    s->cam_fov_deg = 50;
    s->quality.max_dist = (float)fmin(4 * R + range[1], 1e7);
    s->fog_density = (float)(0.35 / R); /* about a third of the light lost across the DEM, low down */
    s->fog_falloff = (float)(2.0 / relief);
    s->fog_height = (float)range[0];
    t->sand_line = (float)(range[0] + 0.03 * relief);
    /* snow on the DEM's highest ground, but only where it is high on the Earth too: a lowland's top is
     * not snowed over (the exaggerated heights: SNOW_ALTITUDE times the exaggeration) */
    t->snow_line = (float)fmax(range[0] + 0.85 * relief, SNOW_ALTITUDE * t->exaggeration);
    for (int i = 0; i < s->material_count; i++)
        if (s->materials[i].texture >= 0)
            s->materials[i].uv_scale = (float)(1.0 / (24.0 * fmin(spacing[0], spacing[1])));
    return true;
}

void scene_heightmap_defines(const scene *s, strbuf *out)
{
    sb_printf(out, "#define TERRAIN_MAXMIP %d\n", s->terrain.maxmip);
    if (s->terrain.patch_normals)
        sb_printf(out, "#define TERRAIN_PATCH_NORMALS 1\n");
    if (s->terrain.imagery_count || s->terrain.vector_count) /* only a scene with a drape samples it */
        sb_printf(out, "#define TERRAIN_IMAGERY 1\n");
    if (s->terrain.water_mode == WATER_FILL || s->terrain.water_mode == WATER_RASTER) /* a water level a texel */
        sb_printf(out, "#define TERRAIN_WATER_GRID 1\n");
    if (s->terrain.curvature)
        sb_printf(out, "#define TERRAIN_CURVATURE 1\n");
}

/* The layered albedo (shaders/terrain/layers.glsl): which material each layer uses, and where. */
void scene_layer_uniforms(const scene *s, const uniform_sink *u)
{
    uniform_i(u, "uElevationRamp", s->terrain.elevation_ramp);
    uniform_f(u, "uExaggeration", s->terrain.exaggeration > 0 ? s->terrain.exaggeration : 1.0f);
    uniform_f(u, "uSandLine", s->terrain.sand_line);
    uniform_f(u, "uSnowLine", s->terrain.snow_line);
    uniform_f(u, "uGrassSlope", s->terrain.grass_slope);
    if (s->terrain.curvature) /* the drop (1 − k) d² / 2R, exaggerated with the heights (the viewshed's k, R) */
        uniform_f(u, "uCurvature", (float)((s->terrain.exaggeration > 0 ? s->terrain.exaggeration : 1.0) *
                                           (1.0 - VIEWSHED_REFRACTION) / (2.0 * VIEWSHED_EARTH_RADIUS)));
    if (s->effects & (1u << EFFECT_WATER)) { /* terrain/terrain.glsl: the water's surface, in world heights */
        uniform_i(u, "uWaterMaterial", s->terrain.water_material);
        if (s->terrain.water_mode == WATER_LEVEL)
            uniform_f(u, "uWaterLevel", s->terrain.water_level * (s->terrain.exaggeration > 0 ? s->terrain.exaggeration : 1.0f));
    }
    static const char *const layers[4] = {"sand", "grass", "rock", "snow"};
    static const char *const names[4] = {"uLayerSand", "uLayerGrass", "uLayerRock", "uLayerSnow"};
    enum { ROCK = 2 };
    int idx[4];
    for (int l = 0; l < 4; l++)
        idx[l] = scene_find_material(s, layers[l]);
    if (idx[ROCK] < 0) /* rock is the fallback layer: the first material */
        idx[ROCK] = 0;
    for (int l = 0; l < 4; l++)
        uniform_i(u, names[l], idx[l] < 0 ? idx[ROCK] : idx[l]);
}

/* The noise terrain's parameters and its distance bound (shaders/terrain/noise.glsl). */
void scene_noise_uniforms(const scene *s, const uniform_sink *u)
{
    const struct scene_terrain *t = &s->terrain;
    const float QUINTIC_SLOPE = 30.0f / 16.0f; /* per unit on each axis: the quintic's steepest */
    uniform_f(u, "uNoiseSlope", QUINTIC_SLOPE);
    uniform_f(u, "uNoiseBase", t->base);
    uniform_f(u, "uNoiseAmplitude", t->amplitude);
    uniform_f(u, "uNoiseFrequency", t->frequency);
    uniform_i(u, "uNoiseOctaves", t->octaves);
    uniform_f(u, "uTerrainHeightMin", t->base);
    uniform_f(u, "uTerrainHeightMax", t->base + t->amplitude);
    scene_layer_uniforms(s, u);
}
