/* lazy — modules loaded on first use (lazy.h). */
#include "data/lazy.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

typedef struct module {
    const char *file, *what; /* the module's file name; what it brings, for messages */
    bool tried;
    void *handle;
    err_t why; /* why it could not be loaded */
} module;

static module modules[LAZY_COUNT] = {
    [LAZY_IMAGE] = {.file = "fathom_image.so", .what = "which reads and writes images through OpenImageIO"},
    [LAZY_DEM] = {.file = "fathom_dem.so", .what = "which reads DEMs through GDAL"},
};

/* Beside the binary (a build folder), one folder up (the tests' binaries in build/tests), or the
 * installed <prefix>/lib/fathom. The first file that exists is loaded. */
static void load(module *m)
{
    m->tried = true;
    char exe[PATH_MAX_LEN], dir[PATH_MAX_LEN], path[PATH_MAX_LEN + 64];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) {
        err_set(&m->why, "cannot find the running binary (/proc/self/exe) to load %s beside it", m->file);
        return;
    }
    exe[n] = '\0';
    util_dirname(exe, dir, sizeof dir);
    static const char *const places[] = {"", "/..", "/../lib/fathom"};
    for (size_t i = 0; i < sizeof places / sizeof places[0]; i++) {
        snprintf(path, sizeof path, "%s%s/%s", dir, places[i], m->file);
        if (access(path, F_OK) != 0)
            continue;
        m->handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
        if (!m->handle)
            err_set(&m->why, "cannot load %s, %s: %s", path, m->what, dlerror());
        return;
    }
    err_set(&m->why, "%s, %s, is not beside %s nor in ../lib/fathom: reinstall fathom (cmake --install BUILD)",
            m->file, m->what, exe);
}

void *lazy_symbol(lazy_module id, const char *name, err_t *err)
{
    module *m = &modules[id];
    if (!m->tried)
        load(m);
    void *sym = m->handle ? dlsym(m->handle, name) : NULL;
    if (!sym && m->handle)
        err_set(&m->why, "%s lacks %s: it is not this fathom's; reinstall fathom", m->file, name);
    if (!sym && err)
        *err = m->why;
    return sym;
}

bool lazy_loaded(lazy_module id) { return modules[id].handle != NULL; }
