/* frag_files — the files a fragment names (includes, textures), found inside its folders only (frag_internal.h). */
/* realpath() is XSI */
#define _XOPEN_SOURCE 700
#include <ctype.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "scene/formula/frag_internal.h"

bool frag_find_file(const frag_ctx *x, const char *rel, const char *home, char *path, size_t n, const char **why)
{
    if (rel[0] == '/' || !rel[0])
        return *why = "an absolute path", false;
    for (const char *c = rel; *c; c++)
        if (!isalnum((unsigned char)*c) && !strchr("_-. /", *c))
            return *why = "a character other than letters, digits, '_', '-', '.', ' ' and '/'", false;
    for (const char *c = rel; c; c = strchr(c, '/'), c = c ? c + 1 : NULL)
        if (!strncmp(c, "..", 2) && (c[2] == '/' || c[2] == '\0'))
            return *why = "a '..' part", false;
    const char *dirs[2] = {home, x->include_dir[0] ? x->include_dir : NULL}, *roots[2] = {x->root, x->include_dir};
    for (int i = 0; i < 2; i++) {
        char joined[PATH_MAX_LEN], real[PATH_MAX];
        if (!dirs[i] || !util_join(dirs[i], rel, joined, sizeof joined) || !realpath(joined, real))
            continue;
        size_t r = strlen(roots[i]);
        if (strncmp(real, roots[i], r) || real[r] != '/' || strlen(real) >= n)
            return *why = "it leads out of the fragment's folder", false;
        memcpy(path, real, strlen(real) + 1);
        return true;
    }
    return *why = "no such file", false;
}
