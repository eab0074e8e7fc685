/* scene_set — --set overrides: "a.b.0.c=value" edits the parsed JSON tree before it is read, so an
 * override meets exactly the checks the file does. Values parse as JSON ("1,2,3" as a vector), else
 * as a string. */
#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "scene_parse.h"

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

bool scene_apply_set(cJSON *root, const char *kv, err_t *err)
{
    const char *eq = strchr(kv, '=');
    assert(eq);
    char key[256];
    if ((size_t)(eq - kv) >= sizeof key)
        return err_set(err, "--set %s: key too long", kv);
    memcpy(key, kv, (size_t)(eq - kv));
    key[eq - kv] = '\0';
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
                return cJSON_ReplaceItemInArray(node, (int)idx, parse_value(eq + 1)) ||
                       err_set(err, "--set %s: cannot replace", kv);
            node = cJSON_GetArrayItem(node, (int)idx);
        } else if (cJSON_IsObject(node)) {
            cJSON *next = cJSON_GetObjectItemCaseSensitive(node, seg);
            if (last) {
                if (next)
                    cJSON_ReplaceItemInObjectCaseSensitive(node, seg, parse_value(eq + 1));
                else
                    cJSON_AddItemToObject(node, seg, parse_value(eq + 1));
                return true;
            }
            if (!next)
                next = cJSON_AddObjectToObject(node, seg);
            node = next;
        } else {
            return err_set(err, "--set %s: '%s' is inside a value that is neither an object nor an array", kv, seg);
        }
    }
    return err_set(err, "--set %s: empty key", kv);
}

