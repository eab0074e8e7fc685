/* realpath() is XSI */
#define _XOPEN_SOURCE 700
#include "view/shot.h"

#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "data/media/image_io.h"

/* A shipped scene's name ("mandelbulb" for <data>/scenes/fractals/mandelbulb.json's folder set), or
 * false for a file of the user's. */
static bool shipped_name(const char *abs, char *name, size_t n)
{
    char data[PATH_MAX];
    if (!realpath(util_data_dir(), data))
        return false;
    size_t len = strlen(data);
    if (strncmp(abs, data, len) || strncmp(abs + len, "/scenes/", 8))
        return false;
    const char *base = strrchr(abs, '/') + 1, *dot = strrchr(base, '.');
    if (!dot || strcmp(dot, ".json"))
        return false;
    snprintf(name, n, "%.*s", (int)(dot - base), base);
    return true;
}

/* FNV-1a, 64 bits, of text: 16 hex digits into out[17] */
static void text_hash(const char *text, char out[17])
{
    unsigned long long h = 14695981039346656037ull;
    for (const unsigned char *c = (const unsigned char *)text; *c; c++)
        h = (h ^ *c) * 1099511628211ull;
    snprintf(out, 17, "%016llx", h);
}

/* The path of a formula file as formula.h's `file` names it: shipped ones live under <data>/shaders */
static bool formula_path(const char *file, char *path, size_t n)
{
    if (file[0] == '/')
        return snprintf(path, n, "%s", file) < (int)n;
    return snprintf(path, n, "%s/shaders/%s", util_data_dir(), file) < (int)n;
}

static void describe_formulas(cJSON *j, const char *const files[SHOT_FORMULA_MAX])
{
    static const char *const KEYS[SHOT_FORMULA_MAX] = {"fractal.formula", "fractal.hybrid.formula"};
    cJSON *arr = NULL;
    for (int i = 0; files && i < SHOT_FORMULA_MAX; i++) {
        char path[PATH_MAX_LEN], hash[17], *text = NULL;
        err_t e;
        if (!files[i] || !formula_path(files[i], path, sizeof path) ||
            !util_read_file_max(path, UTIL_SOURCE_FILE_MAX, &text, NULL, &e))
            continue;
        arr = arr ? arr : cJSON_AddArrayToObject(j, "formulas");
        cJSON *f = cJSON_CreateObject();
        text_hash(text, hash);
        cJSON_AddStringToObject(f, "key", KEYS[i]);
        cJSON_AddStringToObject(f, "file", files[i]);
        cJSON_AddStringToObject(f, "hash", hash);
        if (files[i][0] == '/') /* a user's own: carried whole */
            cJSON_AddStringToObject(f, "text", text);
        cJSON_AddItemToArray(arr, f);
        free(text);
    }
}

void shot_describe(const char *scene_path, const char *const *sets, int set_count, const camera *cam, int width,
                   int height, strbuf *out)
{
    shot_describe_fractal(scene_path, sets, set_count, NULL, cam, width, height, out);
}

void shot_describe_fractal(const char *scene_path, const char *const *sets, int set_count,
                           const char *const formula_files[SHOT_FORMULA_MAX], const camera *cam, int width, int height,
                           strbuf *out)
{
    char abs[PATH_MAX], name[PATH_MAX];
    cJSON *j = cJSON_CreateObject();
    bool resolved = realpath(scene_path, abs) != NULL;
    if (resolved && shipped_name(abs, name, sizeof name)) {
        cJSON_AddStringToObject(j, "scene", name);
    } else {
        char *text = NULL;
        err_t e;
        cJSON_AddStringToObject(j, "scene", resolved ? abs : scene_path);
        if (util_read_file(resolved ? abs : scene_path, &text, NULL, &e)) /* else it stays a path */
            cJSON_AddStringToObject(j, "scene_text", text);
        free(text);
    }
    cJSON *arr = cJSON_AddArrayToObject(j, "sets");
    for (int i = 0; i < set_count; i++)
        cJSON_AddItemToArray(arr, cJSON_CreateString(sets[i]));
    describe_formulas(j, formula_files);
    cJSON *c = cJSON_AddObjectToObject(j, "camera");
    /* %.9g keeps every float exactly, %.17g every double (the position: a deep zoom's digits) */
    char num[64];
    cJSON *pos = cJSON_AddArrayToObject(c, "position");
    for (int i = 0; i < 3; i++) {
        snprintf(num, sizeof num, "%.17g", cam->position[i]);
        cJSON_AddItemToArray(pos, cJSON_CreateRaw(num));
    }
    snprintf(num, sizeof num, "%.9g", (double)cam->yaw);
    cJSON_AddRawToObject(c, "yaw", num);
    snprintf(num, sizeof num, "%.9g", (double)cam->pitch);
    cJSON_AddRawToObject(c, "pitch", num);
    snprintf(num, sizeof num, "%.9g", (double)cam->roll);
    cJSON_AddRawToObject(c, "roll", num);
    snprintf(num, sizeof num, "%.9g", (double)cam->fov_y);
    cJSON_AddRawToObject(c, "fov_y", num);
    cJSON *size = cJSON_AddArrayToObject(j, "size");
    cJSON_AddItemToArray(size, cJSON_CreateNumber(width));
    cJSON_AddItemToArray(size, cJSON_CreateNumber(height));
    char *text = cJSON_PrintUnformatted(j);
    sb_append(out, text);
    free(text);
    cJSON_Delete(j);
}

void shot_note_renderer(const char *text, const char *renderer, strbuf *out)
{
    cJSON *j = cJSON_Parse(text);
    if (!cJSON_IsObject(j)) {
        sb_append(out, text);
        cJSON_Delete(j);
        return;
    }
    cJSON_DeleteItemFromObjectCaseSensitive(j, "renderer");
    cJSON_AddStringToObject(j, "renderer", renderer);
    char *t = cJSON_PrintUnformatted(j);
    sb_append(out, t);
    free(t);
    cJSON_Delete(j);
}

static bool number_d(const cJSON *v, double lo, double hi, double *out)
{
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble) || v->valuedouble < lo || v->valuedouble > hi)
        return false;
    *out = v->valuedouble;
    return true;
}

static bool number(const cJSON *v, double lo, double hi, float *out)
{
    double d;
    if (!number_d(v, lo, hi, &d))
        return false;
    *out = (float)d;
    return true;
}

/* The "formulas" array (absent: none); false when any entry is malformed */
static bool parse_formulas(const cJSON *arr, shot_desc *d)
{
    if (!arr)
        return true;
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) > SHOT_FORMULA_MAX)
        return false;
    for (const cJSON *f = arr->child; f; f = f->next) {
        const cJSON *key = cJSON_GetObjectItemCaseSensitive(f, "key"), *file = cJSON_GetObjectItemCaseSensitive(f, "file");
        const cJSON *hash = cJSON_GetObjectItemCaseSensitive(f, "hash"), *text = cJSON_GetObjectItemCaseSensitive(f, "text");
        if (!cJSON_IsString(key) || (strcmp(key->valuestring, "fractal.formula") &&
                                     strcmp(key->valuestring, "fractal.hybrid.formula")) ||
            !cJSON_IsString(file) || !file->valuestring[0] || strlen(file->valuestring) >= PATH_MAX_LEN ||
            !cJSON_IsString(hash) || strlen(hash->valuestring) != 16 ||
            strspn(hash->valuestring, "0123456789abcdef") != 16 ||
            (text && (!cJSON_IsString(text) || strlen(text->valuestring) > SHOT_FORMULA_TEXT_MAX)))
            return false;
        shot_formula *g = &d->formulas[d->formula_count++];
        snprintf(g->key, sizeof g->key, "%s", key->valuestring);
        snprintf(g->file, sizeof g->file, "%s", file->valuestring);
        snprintf(g->hash, sizeof g->hash, "%s", hash->valuestring);
        g->text = text ? util_strdup(text->valuestring) : NULL;
    }
    return true;
}

bool shot_parse(const char *text, const char *source, shot_desc *d, err_t *err)
{
    *d = (shot_desc){0};
    cJSON *j = cJSON_Parse(text);
    const cJSON *scene = cJSON_GetObjectItemCaseSensitive(j, "scene"), *sets = cJSON_GetObjectItemCaseSensitive(j, "sets");
    const cJSON *scene_text = cJSON_GetObjectItemCaseSensitive(j, "scene_text");
    const cJSON *cam = cJSON_GetObjectItemCaseSensitive(j, "camera"), *size = cJSON_GetObjectItemCaseSensitive(j, "size");
    const cJSON *pos = cJSON_GetObjectItemCaseSensitive(cam, "position");
    float w = 0, h = 0;
    bool ok = cJSON_IsString(scene) && strlen(scene->valuestring) < sizeof d->scene && cJSON_IsArray(sets) &&
              (!scene_text || cJSON_IsString(scene_text)) &&
              cJSON_GetArraySize(sets) <= SHOT_SET_MAX && cJSON_IsArray(pos) && cJSON_GetArraySize(pos) == 3 &&
              number(cJSON_GetObjectItemCaseSensitive(cam, "yaw"), -10, 10, &d->cam.yaw) &&
              number(cJSON_GetObjectItemCaseSensitive(cam, "pitch"), -1.5707964, 1.5707964, &d->cam.pitch) &&
              (!cJSON_GetObjectItemCaseSensitive(cam, "roll") || /* shots before roll have none */
               number(cJSON_GetObjectItemCaseSensitive(cam, "roll"), -10, 10, &d->cam.roll)) &&
              number(cJSON_GetObjectItemCaseSensitive(cam, "fov_y"), 1e-3, 3.1, &d->cam.fov_y) &&
              cJSON_IsArray(size) && number(cJSON_GetArrayItem(size, 0), 1, 16384, &w) &&
              number(cJSON_GetArrayItem(size, 1), 1, 16384, &h);
    for (int i = 0; ok && i < 3; i++)
        ok = number_d(cJSON_GetArrayItem(pos, i), -CAMERA_MAX_COORD, CAMERA_MAX_COORD, &d->cam.position[i]);
    if (ok) {
        snprintf(d->scene, sizeof d->scene, "%s", scene->valuestring);
        d->scene_text = scene_text ? util_strdup(scene_text->valuestring) : NULL;
        for (const cJSON *s = sets->child; ok && s; s = s->next) {
            ok = cJSON_IsString(s) && strchr(s->valuestring, '=') && strlen(s->valuestring) < sizeof d->sets[0];
            if (ok)
                snprintf(d->sets[d->set_count++], sizeof d->sets[0], "%s", s->valuestring);
        }
        d->width = (int)w, d->height = (int)h;
        ok = ok && parse_formulas(cJSON_GetObjectItemCaseSensitive(j, "formulas"), d);
    }
    cJSON_Delete(j);
    if (!ok) {
        shot_free(d);
        return err_set(err, "%s: its fathom shot description is damaged; render the scene again", source);
    }
    return true;
}

void shot_free(shot_desc *d)
{
    free(d->scene_text);
    d->scene_text = NULL;
    for (int i = 0; i < d->formula_count; i++) {
        free(d->formulas[i].text);
        d->formulas[i].text = NULL;
    }
    d->formula_count = 0;
    free(d->notes);
    d->notes = NULL;
}

/* <cache>/fathom/formulas/HASH/NAME.glsl (a fragment's: NAME.frag) for a carried text: the folders made
 * (only this user may write them), NAME the original's base name made safe */
static bool cache_path(const shot_formula *f, const char *hash, char *out, size_t n, err_t *err)
{
    const char *base = strrchr(f->file, '/');
    char dir[PATH_MAX_LEN], name[64];
    base = base ? base + 1 : f->file;
    size_t k = 0;
    for (const char *c = base; *c && *c != '.' && k + 1 < sizeof name - 5; c++)
        name[k++] = (isalnum((unsigned char)*c) || *c == '_' || *c == '-') ? *c : '_';
    size_t fl = strlen(f->file);
    bool fragment = fl > 5 && !strcmp(f->file + fl - 5, ".frag"); /* read as a fragment again (scene/formula/frag.h) */
    snprintf(name + k, sizeof name - k, "%s%s", k ? "" : "formula", fragment ? ".frag" : ".glsl");
    if (!util_cache_folder("formulas", hash, dir, sizeof dir))
        return errno == ENAMETOOLONG ? err_set(err, "cannot keep the shot's formula: the cache path is too long")
                                     : err_set(err, "cannot keep the shot's formula in '%s': %s", dir, strerror(errno));
    if (snprintf(out, n, "%s/%s", dir, name) >= (int)n)
        return err_set(err, "cannot keep the shot's formula: the cache path is too long");
    return true;
}

bool shot_resolve_formulas(shot_desc *d, strbuf *notes, err_t *err)
{
    for (int i = 0; i < d->formula_count; i++) {
        shot_formula *f = &d->formulas[i];
        char path[PATH_MAX_LEN], now[17] = "", carried[17], cached[PATH_MAX_LEN], *text = NULL;
        err_t e;
        bool here = formula_path(f->file, path, sizeof path) &&
                    util_read_file_max(path, UTIL_SOURCE_FILE_MAX, &text, NULL, &e);
        if (here)
            text_hash(text, now);
        free(text);
        if (here && !strcmp(now, f->hash))
            continue; /* the same text as when the shot was made */
        if (!f->text) { /* shipped (or an old shot): nothing carried to draw it with */
            sb_printf(notes, "note: formula %s %s since this shot was made: the image may differ\n", f->file,
                      here ? "changed" : "is missing");
            continue;
        }
        text_hash(f->text, carried);
        if (strcmp(carried, f->hash))
            return err_set(err, "the shot's formula %s does not match its own hash: the shot is damaged", f->file);
        if (!cache_path(f, carried, cached, sizeof cached, err) ||
            !util_write_text_atomic(cached, f->text, "the shot's formula", err))
            return false;
        if (d->set_count == SHOT_SET_MAX)
            return err_set(err, "the shot has too many overrides to add its formula's (%d)", SHOT_SET_MAX);
        if (snprintf(d->sets[d->set_count], sizeof d->sets[0], "%s=%s", f->key, cached) >= (int)sizeof d->sets[0])
            return err_set(err, "cannot name the shot's formula by '%s': the path is too long", cached);
        d->set_count++;
        sb_printf(notes, "note: formula %s %s: drawn with the text the shot carries (%s)\n", f->file,
                  here ? "changed since this shot was made" : "is not on this machine", cached);
    }
    return true;
}

bool shot_is_preset(const char *name)
{
    const char *dot = strrchr(name, '.');
    return dot && !strcmp(dot, SHOT_PRESET_EXT);
}

bool shot_is_image(const char *name)
{
    const char *dot = strrchr(name, '.');
    return dot && (!strcasecmp(dot, ".png") || !strcasecmp(dot, ".exr"));
}
