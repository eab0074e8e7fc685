/* scene_text — scene files written and loaded by the scene tests (scene_text.h). */
#include "scene_text.h"

bool scene_text_load(const char *text, const char *const *sets, int n, scene *s, err_t *e)
{
    return scene_load_text(text, "/tmp/test.json", sets, n, s, e);
}

void scene_text_error(const char *text, const char *const *sets, int n, const char *needle)
{
    scene s;
    err_t e = {{0}};
    assert_false(scene_text_load(text, sets, n, &s, &e));
    if (!strstr(e.msg, needle))
        fail_msg("error '%s' does not mention '%s'", e.msg, needle);
}

int scene_text_count(const char *hay, const char *needle)
{
    int n = 0;
    for (const char *p = strstr(hay, needle); p; p = strstr(p + 1, needle))
        n++;
    return n;
}
