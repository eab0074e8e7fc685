#include "view/views.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

bool views_file(const char *scene_name, char *out, size_t n, err_t *err)
{
    const char *dir = getenv("FATHOM_VIEWS_DIR"), *xdg = getenv("XDG_CONFIG_HOME"), *home = getenv("HOME");
    int len;
    if (dir && *dir)
        len = snprintf(out, n, "%s/%s.json", dir, scene_name);
    else if (xdg && *xdg)
        len = snprintf(out, n, "%s/fathom/views/%s.json", xdg, scene_name);
    else if (home && *home)
        len = snprintf(out, n, "%s/.config/fathom/views/%s.json", home, scene_name);
    else
        return err_set(err, "no folder for saved views: set HOME, XDG_CONFIG_HOME or FATHOM_VIEWS_DIR");
    return (len > 0 && (size_t)len < n) || err_set(err, "the saved views' path is too long");
}

/* The file's views ({} when there is no file yet). */
static cJSON *read_views(const char *file, err_t *err)
{
    if (!util_file_exists(file))
        return cJSON_CreateObject();
    char *text;
    if (!util_read_file(file, &text, NULL, err))
        return NULL;
    cJSON *j = cJSON_Parse(text);
    free(text);
    if (!cJSON_IsObject(j)) {
        cJSON_Delete(j);
        err_set(err, "%s: not a views file (expected {\"NAME\": {...}, ...}); move it away", file);
        return NULL;
    }
    return j;
}

/* mkdir -p of file's folder. */
static bool make_folder(const char *file, err_t *err)
{
    char dir[PATH_MAX_LEN];
    if (!util_dirname(file, dir, sizeof dir))
        return err_set(err, "the saved views' path is too long");
    for (char *p = dir + 1;; p++) {
        char c = *p;
        if (c == '/' || c == '\0') {
            *p = '\0';
            if (mkdir(dir, 0755) != 0 && errno != EEXIST)
                return err_set(err, "cannot create '%s' for saved views: %s", dir, strerror(errno));
            *p = c;
        }
        if (c == '\0')
            return true;
    }
}

bool views_save(const char *file, const char *name, const char *shot_json, err_t *err)
{
    cJSON *views = read_views(file, err), *shot = cJSON_Parse(shot_json);
    bool ok = views && shot && make_folder(file, err);
    if (ok) {
        if (cJSON_GetObjectItemCaseSensitive(views, name)) /* in place: the file keeps its order */
            cJSON_ReplaceItemInObjectCaseSensitive(views, name, shot);
        else
            cJSON_AddItemToObject(views, name, shot);
        shot = NULL;
        char *text = cJSON_Print(views);
        strbuf line = {0};
        sb_printf(&line, "%s\n", text);
        ok = util_write_text_atomic(file, line.data, "the view", err);
        sb_free(&line);
        free(text);
    }
    cJSON_Delete(shot);
    cJSON_Delete(views);
    return ok;
}

bool views_load(const char *file, const char *name, char **shot_json, err_t *err)
{
    cJSON *views = read_views(file, err);
    if (!views)
        return false;
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(views, name);
    bool ok = v != NULL;
    if (ok) {
        *shot_json = cJSON_PrintUnformatted(v);
    } else {
        strbuf names = {0};
        for (const cJSON *it = views->child; it; it = it->next)
            sb_printf(&names, "%s%s", names.len ? ", " : "", it->string);
        err_set(err, "no saved view '%s' in %s (%s)", name, file, names.len ? names.data : "none saved yet: B in the window saves one");
        sb_free(&names);
    }
    cJSON_Delete(views);
    return ok;
}

bool views_flight_file(const char *scene_name, char *out, size_t n, err_t *err)
{
    char views[PATH_MAX_LEN];
    if (!views_file(scene_name, views, sizeof views, err))
        return false;
    size_t len = strlen(views);
    if (len < 5 || snprintf(out, n, "%.*s.flight.json", (int)(len - 5), views) >= (int)n)
        return err_set(err, "the flight file's name for '%s' is too long", scene_name);
    return make_folder(out, err);
}

int views_next_free(const char *file)
{
    err_t e;
    cJSON *views = read_views(file, &e);
    int free_slot = 0;
    for (int i = 1; views && i <= 9 && !free_slot; i++) {
        char name[2] = {(char)('0' + i), '\0'};
        if (!cJSON_GetObjectItemCaseSensitive(views, name))
            free_slot = i;
    }
    cJSON_Delete(views);
    return free_slot;
}
