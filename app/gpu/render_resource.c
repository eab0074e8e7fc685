/* render_resource — helpers the resource kinds share (render_resource.h). */
#include "gpu/render_resource.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

bool render_resource_fault(const char *name, err_t *err)
{
    const char *fault = getenv("FATHOM_RESOURCE_FAULT");
    if (!fault || strcmp(fault, name))
        return false;
    err_set(err, "%s: a failure injected halfway (FATHOM_RESOURCE_FAULT)", name);
    return true;
}

void render_file_key(const char *path, char *key, size_t n)
{
    struct stat st = {0};
    stat(path, &st);
    size_t len = strlen(key);
    snprintf(key + len, n - len, "%s|%lld|%lld.%09ld;", path, (long long)st.st_size, (long long)st.st_mtim.tv_sec,
             st.st_mtim.tv_nsec);
}
