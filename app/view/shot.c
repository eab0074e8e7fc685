/* realpath() is XSI */
#define _XOPEN_SOURCE 700
#include "view/shot.h"

#include <cjson/cJSON.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/image_io.h"

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

void shot_describe(const char *scene_path, const char *const *sets, int set_count, const camera *cam, int width,
                   int height, strbuf *out)
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
              number(cJSON_GetObjectItemCaseSensitive(cam, "pitch"), -CAMERA_MAX_PITCH, CAMERA_MAX_PITCH, &d->cam.pitch) &&
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
}

bool shot_is_preset(const char *name)
{
    const char *dot = strrchr(name, '.');
    return dot && !strcmp(dot, SHOT_PRESET_EXT);
}

bool shot_is_image(const char *name)
{
    const char *dot = strrchr(name, '.');
    return dot && (!strcmp(dot, ".png") || !strcmp(dot, ".exr"));
}
