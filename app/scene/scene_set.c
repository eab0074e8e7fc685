/* scene_set — --set overrides: "a.b.0.c=value" edits the parsed JSON tree before it is read, so an
 * override meets exactly the checks the file does. Values parse as JSON ("1,2,3" as a vector), else
 * as a string. File paths given this way are relative to the current folder. */
#include <assert.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/scene_parse.h"

static cJSON *parse_value(const char *v)
{
    cJSON *j = cJSON_ParseWithOpts(v, NULL, true); /* all of it: "1,2,3" must not parse as 1 */
    if (j)
        return j;
    if (strchr(v, ',')) { /* "1,2,3" is a vector */
        strbuf b = {0};
        sb_printf(&b, "[%s]", v);
        j = cJSON_ParseWithOpts(b.data, NULL, true);
        sb_free(&b);
        if (j)
            return j;
    }
    return cJSON_CreateString(v);
}

/* Keys that name files. In the scene file they are relative to the file's folder; on the command line
 * the user means the folder they are in, so --set makes a relative path absolute from there. */
static bool file_key(const char *key)
{
    const char *last = strrchr(key, '.');
    last = last ? last + 1 : key;
    if (!strncmp(key, "materials.", 10))
        return !strcmp(last, "texture") || !strcmp(last, "relief");
    return !strcmp(key, "terrain.heightmap") || !strcmp(key, "terrain.imagery") || !strcmp(key, "terrain.vectors") || !strcmp(key, "droplets.file") || !strncmp(key, "environment.cubemap", 19);
}

static void from_cwd(cJSON *v)
{
    if (cJSON_IsArray(v)) {
        for (cJSON *e = v->child; e; e = e->next)
            from_cwd(e);
        return;
    }
    if (cJSON_IsObject(v)) { /* a layer's object form: {"file": "route.gpx", "width": 30} */
        from_cwd(cJSON_GetObjectItemCaseSensitive(v, "file"));
        return;
    }
    char cwd[PATH_MAX_LEN], abs[PATH_MAX_LEN];
    if (!cJSON_IsString(v) || v->valuestring[0] == '/' || !getcwd(cwd, sizeof cwd) ||
        !util_join(cwd, v->valuestring, abs, sizeof abs))
        return;
    cJSON_SetValuestring(v, abs);
}

static cJSON *override_value(const char *key, const char *v)
{
    cJSON *j = parse_value(v);
    /* terrain.water: a file unless it is a level or "fill" */
    if (file_key(key) || (!strcmp(key, "terrain.water") && cJSON_IsString(j) && strcmp(j->valuestring, "fill")))
        from_cwd(j);
    return j;
}

/* --set materials.NAME.KEY=… where the scene has no material NAME: refused with the names it has. */
static bool unknown_material(const cJSON *materials, const char *kv, const char *name, err_t *err)
{
    strbuf names = {0};
    for (const cJSON *m = materials->child; m; m = m->next)
        sb_printf(&names, "%s%s", names.data ? ", " : "", m->string);
    err_set(err, "--set %s: the scene has no material '%s' (its materials: %s)", kv, name, names.data ? names.data : "none");
    sb_free(&names);
    return false;
}

bool scene_apply_set(cJSON *root, const char *kv, err_t *err)
{
    const char *eq = strchr(kv, '=');
    assert(eq);
    char key[256];
    if ((size_t)(eq - kv) >= sizeof key)
        return err_set(err, "--set %s: key too long", kv);
    memcpy(key, kv, (size_t)(eq - kv));
    key[eq - kv] = '\0';
    char full[256];
    memcpy(full, key, sizeof full); /* strtok_r below cuts key */
    cJSON *node = root;
    char *save = NULL;
    for (char *seg = strtok_r(key, ".", &save); seg; seg = strtok_r(NULL, ".", &save)) {
        bool last = (save == NULL || *save == '\0');
        if (cJSON_IsArray(node)) {
            char *end;
            long idx = strtol(seg, &end, 10);
            if (*end || idx < 0 || idx >= cJSON_GetArraySize(node))
                return err_set(err, "--set %s: '%s' is not an index of that array (it has %d items)", kv, seg,
                               cJSON_GetArraySize(node));
            if (last)
                return cJSON_ReplaceItemInArray(node, (int)idx, override_value(full, eq + 1)) ||
                       err_set(err, "--set %s: cannot replace", kv);
            node = cJSON_GetArrayItem(node, (int)idx);
        } else if (cJSON_IsObject(node)) {
            cJSON *next = cJSON_GetObjectItemCaseSensitive(node, seg);
            if (last) {
                if (next)
                    cJSON_ReplaceItemInObjectCaseSensitive(node, seg, override_value(full, eq + 1));
                else
                    cJSON_AddItemToObject(node, seg, override_value(full, eq + 1));
                return true;
            }
            if (!next && node == cJSON_GetObjectItemCaseSensitive(root, "materials"))
                return unknown_material(node, kv, seg, err); /* a typo would make a new, unused material */
            if (!next)
                next = cJSON_AddObjectToObject(node, seg);
            node = next;
        } else {
            return err_set(err, "--set %s: '%s' is inside a value that is neither an object nor an array", kv, seg);
        }
    }
    return err_set(err, "--set %s: empty key", kv);
}

