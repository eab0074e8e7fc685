/* scene_files — where scenes come from (scene.h): a shipped name (scenes/, then scenes/fractals/), a
 * path, or the text a shot carried for a path; and the list of the shipped ones. */
#include "scene/scene.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_parse.h"

/* Shipped scenes by name: scenes/ first (the window's keys 1-9 take them in order), then each fractal
 * formula's own view in scenes/fractals/. */
static const char *const SCENE_FOLDER[] = {"scenes", "scenes/fractals"};
enum { SCENE_FOLDERS = sizeof SCENE_FOLDER / sizeof SCENE_FOLDER[0] };

enum { PROVIDED_MAX = 8 };
static struct {
    char path[PROVIDED_MAX][PATH_MAX_LEN];
    char *text[PROVIDED_MAX];
    int count;
} provided;

static const char *provided_text(const char *path)
{
    for (int i = 0; i < provided.count; i++)
        if (!strcmp(provided.path[i], path))
            return provided.text[i];
    return NULL;
}

void scene_provide_text(const char *path, const char *text)
{
    for (int i = 0; i < provided.count; i++)
        if (!strcmp(provided.path[i], path)) {
            free(provided.text[i]);
            provided.text[i] = util_strdup(text);
            return;
        }
    if (provided.count == PROVIDED_MAX) { /* the oldest goes */
        free(provided.text[0]);
        memmove(&provided.path[0], &provided.path[1], sizeof provided.path[0] * (PROVIDED_MAX - 1));
        memmove(&provided.text[0], &provided.text[1], sizeof provided.text[0] * (PROVIDED_MAX - 1));
        provided.count--;
    }
    snprintf(provided.path[provided.count], PATH_MAX_LEN, "%s", path);
    provided.text[provided.count++] = util_strdup(text);
}

bool scene_locate(const char *name_or_path, char *out, size_t n, err_t *err)
{
    if (strchr(name_or_path, '/') || strstr(name_or_path, ".json")) {
        if (!util_file_exists(name_or_path) && !provided_text(name_or_path))
            return err_set(err, "scene file '%s' not found: check the path, or pass a name from --list-scenes",
                           name_or_path);
        snprintf(out, n, "%s", name_or_path);
        return true;
    }
    bool found = false;
    for (int i = 0; i < SCENE_FOLDERS && !found; i++) {
        snprintf(out, n, "%s/%s/%s.json", util_data_dir(), SCENE_FOLDER[i], name_or_path);
        found = util_file_exists(out);
    }
    if (!found) {
        strbuf names = {0};
        scene_list(&names, false);
        for (char *p = names.data; p && *p; p++)
            if (*p == '\n')
                *p = p[1] ? ' ' : '\0';
        err_set(err, "unknown scene '%s' (known: %s); pass a name or a path to a .json scene file", name_or_path,
                names.data ? names.data : "none");
        sb_free(&names);
        return false;
    }
    return true;
}

bool scene_read_text(const char *path, char **text, err_t *err)
{
    const char *carried = provided_text(path);
    if (carried) {
        *text = util_strdup(carried);
        return true;
    }
    return util_read_file(path, text, NULL, err);
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* The scenes of one folder, sorted, one a line. */
/* The scene's title, read from its file ("" when it has none or does not parse). */
static void title_of(const char *path, char *out, size_t n)
{
    char *text;
    err_t e;
    out[0] = '\0';
    if (!util_read_file(path, &text, NULL, &e))
        return;
    cJSON *root = cJSON_Parse(text);
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(root, "title");
    if (cJSON_IsString(t))
        snprintf(out, n, "%s", t->valuestring);
    cJSON_Delete(root);
    free(text);
}

static void list_folder(const char *dir, bool titles, strbuf *out)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    char *names[256];
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) && n < 256;) {
        size_t len = strlen(e->d_name);
        if (len > 5 && !strcmp(e->d_name + len - 5, ".json"))
            names[n++] = strndup(e->d_name, len - 5);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], cmp_str);
    for (int i = 0; i < n; i++) {
        char path[PATH_MAX_LEN + 300], title[256];
        snprintf(path, sizeof path, "%s/%s.json", dir, names[i]);
        if (titles)
            title_of(path, title, sizeof title);
        sb_printf(out, titles && title[0] ? "%-22s %s\n" : "%s\n", names[i], titles ? title : "");
        free(names[i]);
    }
}

void scene_list(strbuf *out, bool titles)
{
    for (int i = 0; i < SCENE_FOLDERS; i++) {
        char dir[PATH_MAX_LEN];
        snprintf(dir, sizeof dir, "%s/%s", util_data_dir(), SCENE_FOLDER[i]);
        list_folder(dir, titles, out);
    }
}

