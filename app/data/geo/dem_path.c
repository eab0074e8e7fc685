/* dem_is_image, in the binary and in fathom_dem.so alike: a path's kind needs no GDAL (data/lazy/lazy.h). */
#include "data/geo/dem.h"

#include <string.h>
#include <strings.h>

bool dem_is_image(const char *path)
{
    static const char *const images[] = {".png", ".jpg", ".jpeg", ".exr", ".hdr", ".pfm"};
    const char *dot = strrchr(path, '.');
    for (size_t i = 0; dot && i < sizeof images / sizeof *images; i++)
        if (!strcasecmp(dot, images[i]))
            return true;
    return false;
}
