/* render_resource — helpers the resource kinds share (render_resource.h). */
#include "gpu/render_resource.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

void render_file_key(const char *path, char *key, size_t n)
{
    struct stat st = {0};
    stat(path, &st);
    size_t len = strlen(key);
    snprintf(key + len, n - len, "%s|%lld|%lld.%09ld;", path, (long long)st.st_size, (long long)st.st_mtim.tv_sec,
             st.st_mtim.tv_nsec);
}
