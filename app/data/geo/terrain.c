#include "data/geo/terrain.h"

#include <assert.h>
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "data/geo/dem.h"
#include "data/media/image_io.h"

static int next_pow2(int v)
{
    int p = 1;
    while (p < v)
        p *= 2;
    return p;
}

float heightfield_cell_max(const heightfield *hf, int i, int j)
{
    int W = hf->width, H = hf->height;
    if (i < 0 || j < 0 || i >= (W > 1 ? W - 1 : 1) || j >= (H > 1 ? H - 1 : 1))
        return -INFINITY; /* padding */
    int i1 = i + 1 < W ? i + 1 : i, j1 = j + 1 < H ? j + 1 : j;
    const float *r0 = hf->h + (size_t)j * (size_t)W, *r1 = hf->h + (size_t)j1 * (size_t)W;
    float lo = fminf(fminf(r0[i], r0[i1]), fminf(r1[i], r1[i1]));
    /* a cell with a hole at a corner has no surface: never entered */
    return TERRAIN_IS_HOLE(lo) ? -INFINITY : fmaxf(fmaxf(r0[i], r0[i1]), fmaxf(r1[i], r1[i1]));
}

static void build(heightfield *hf)
{
    int W = hf->width, H = hf->height;
    hf->x0 = -0.5f * (float)W * hf->dx;
    hf->z0 = -0.5f * (float)H * hf->dz;
    hf->hmin = INFINITY;
    hf->hmax = -INFINITY;
    hf->holes = 0;
    for (size_t i = 0, n = (size_t)W * (size_t)H; i < n; i++) {
        if (isnan(hf->h[i])) {
            hf->h[i] = TERRAIN_HOLE;
            hf->holes++;
            continue;
        }
        hf->hmin = fminf(hf->hmin, hf->h[i]);
        hf->hmax = fmaxf(hf->hmax, hf->h[i]);
    }
    if (hf->holes == (size_t)W * (size_t)H) /* only tests get here: heightfield_load refuses it */
        hf->hmin = hf->hmax = 0;
    /* steepest bilinear cell: its gradient is bounded by its largest x and z edge differences */
    float L = 0;
    for (int j = 0; j + 1 < H; j++)
        for (int i = 0; i + 1 < W; i++) {
            const float *r0 = hf->h + (size_t)j * (size_t)W + (size_t)i, *r1 = r0 + W;
            if (TERRAIN_IS_HOLE(fminf(fminf(r0[0], r0[1]), fminf(r1[0], r1[1]))))
                continue;
            float gx = fmaxf(fabsf(r0[1] - r0[0]), fabsf(r1[1] - r1[0])) / hf->dx;
            float gz = fmaxf(fabsf(r1[0] - r0[0]), fabsf(r1[1] - r0[1])) / hf->dz;
            L = fmaxf(L, sqrtf(gx * gx + gz * gz));
        }
    hf->lipschitz = L;
    int cw = W > 1 ? W - 1 : 1, ch = H > 1 ? H - 1 : 1;
    hf->pw = next_pow2(cw);
    hf->ph = next_pow2(ch);
    hf->levels = 1;
    for (int s = hf->pw > hf->ph ? hf->pw : hf->ph; s > 1; s /= 2)
        hf->levels++;
    /* level 0 (one node per cell) is never stored: the walk intersects a cell's patch instead of
     * reading its maximum (terrain.glsl), so level 1 is computed from the cells directly */
    hf->max = util_calloc((size_t)hf->levels, sizeof *hf->max, "the heightfield pyramid");
    for (int k = 1; k < hf->levels; k++) {
        /* the level below's size, at least 1 on each side: on a long grid the short side reaches 1
         * first (without the floor, its size shifted to 0, every upper level read nothing and became
         * −inf, and rays skipped the whole terrain) */
        int pw = hf->pw >> (k - 1), ph = hf->ph >> (k - 1);
        pw = pw > 0 ? pw : 1;
        ph = ph > 0 ? ph : 1;
        int w = pw > 1 ? pw / 2 : 1, h = ph > 1 ? ph / 2 : 1;
        hf->max[k] = util_alloc(sizeof(float) * (size_t)w * (size_t)h, "the heightfield pyramid");
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                float m = -INFINITY;
                for (int b = 0; b < 2; b++)
                    for (int a = 0; a < 2; a++) {
                        int x = 2 * i + a, y = 2 * j + b;
                        if (x < pw && y < ph)
                            m = fmaxf(m, k == 1 ? heightfield_cell_max(hf, x, y)
                                                : hf->max[k - 1][(size_t)y * (size_t)pw + (size_t)x]);
                    }
                hf->max[k][(size_t)j * (size_t)w + (size_t)i] = m;
            }
    }
}

/* Takes `heights` (malloc'd) as its own: a big DEM is never copied. */
static void heightfield_adopt(float *heights, int w, int h, float dx, float dz, heightfield *hf)
{
    *hf = (heightfield){.width = w, .height = h, .dx = dx, .dz = dz, .h = heights};
    build(hf);
}

void heightfield_from(const float *heights, int w, int h, float dx, float dz, heightfield *hf)
{
    float *copy = util_alloc(sizeof(float) * (size_t)w * (size_t)h, "the heightfield");
    memcpy(copy, heights, sizeof(float) * (size_t)w * (size_t)h);
    heightfield_adopt(copy, w, h, dx, dz, hf);
}

bool terrain_spacing_ok(double metres)
{
    return isfinite(metres) && metres >= TERRAIN_SPACING_MIN && metres <= TERRAIN_SPACING_MAX;
}

/* NAME.json beside NAME.png: spacing and the height range of an integer image. Only the values the
 * scene left unset are taken, and each is checked like the scene's own. */
void terrain_sidecar_path(const char *path, char *out, size_t n)
{
    const char *dot = strrchr(path, '.');
    snprintf(out, n, "%.*s.json", (int)(dot ? dot - path : (long)strlen(path)), path);
}

static bool read_sidecar(const char *path, float spacing[2], float *lo, float *hi, err_t *err)
{
    char side[PATH_MAX_LEN];
    terrain_sidecar_path(path, side, sizeof side);
    if (!util_file_exists(side))
        return true;
    char *text;
    if (!util_read_file(side, &text, NULL, err))
        return false;
    cJSON *j = cJSON_Parse(text);
    free(text);
    if (!j)
        return err_set(err, "%s: malformed JSON", side);
    bool ok = true;
    const cJSON *s = cJSON_GetObjectItemCaseSensitive(j, "spacing");
    if (s && spacing[0] == 0) {
        const cJSON *a = cJSON_GetArrayItem(s, 0), *b = cJSON_GetArrayItem(s, 1);
        ok = cJSON_IsArray(s) && cJSON_GetArraySize(s) == 2 && cJSON_IsNumber(a) && cJSON_IsNumber(b) &&
             terrain_spacing_ok(a->valuedouble) && terrain_spacing_ok(b->valuedouble);
        if (!ok)
            err_set(err, "%s: spacing: expected [dx, dz], metres per texel, both above 0 and at most %g", side,
                    TERRAIN_SPACING_MAX);
        else
            spacing[0] = (float)a->valuedouble, spacing[1] = (float)b->valuedouble;
    }
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(j, "height_min"), *b = cJSON_GetObjectItemCaseSensitive(j, "height_max");
    if (ok && (a || b) && *lo == 0 && *hi == 0) {
        ok = cJSON_IsNumber(a) && cJSON_IsNumber(b) && isfinite(a->valuedouble) && isfinite(b->valuedouble) &&
             fabs(a->valuedouble) <= 1e5 && fabs(b->valuedouble) <= 1e5 && a->valuedouble <= b->valuedouble;
        if (!ok)
            err_set(err, "%s: height_min, height_max: expected two numbers from -1e5 to 1e5, height_min at most "
                         "height_max", side);
        else
            *lo = (float)a->valuedouble, *hi = (float)b->valuedouble;
    }
    cJSON_Delete(j);
    return ok;
}

/* An image through image_io: integer images are normalised to 0..1 and mapped to [lo, hi]; float
 * images (EXR, HDR, PFM) hold metres. NaN and infinite values become holes. */
static bool read_image(const heightfield_desc *d, float lo, float hi, int *w, int *h, float **heights, strbuf *about,
                       err_t *err)
{
    int c;
    float *px;
    if (!image_read_f32(d->path, 1, TERRAIN_MAX_SIDE, w, h, &c, &px, err))
        return false;
    const char *dot = strrchr(d->path, '.');
    bool is_float = dot && (!strcasecmp(dot, ".exr") || !strcasecmp(dot, ".hdr") || !strcasecmp(dot, ".pfm"));
    if (!is_float && lo == 0 && hi == 0) {
        free(px);
        return err_set(err, "heightmap '%s' is an integer image: set terrain.height_min and terrain.height_max "
                            "(metres for black and white)", d->path);
    }
    size_t n = (size_t)*w * (size_t)*h;
    float *v = malloc(sizeof(float) * n);
    if (!v) {
        free(px);
        return err_set(err, "heightmap '%s' (%dx%d): out of memory", d->path, *w, *h);
    }
    for (size_t i = 0; i < n; i++) {
        float x = px[i * (size_t)c];
        v[i] = isfinite(x) ? (is_float ? x : lo + x * (hi - lo)) : NAN;
    }
    free(px);
    *heights = v;
    sb_printf(about, "%s: %dx%d %s image", d->path, *w, *h, is_float ? "float" : "integer");
    return true;
}

static bool no_crs(const char *path, const dem_info *info, err_t *err)
{
    return err_set(err, "DEM '%s' has a pixel size (%g x %g) but no CRS, so its unit is unknown: set "
                        "terrain.spacing=[dx,dz] in metres, or give the file a CRS (a .prj beside it)",
                   path, info->pixel[0], info->pixel[1]);
}

static bool bad_spacing(const char *path, const double spacing[2], err_t *err)
{
    return err_set(err, "DEM '%s': its georeferencing gives %g x %g m per texel, outside %g to %g: fix its "
                        "geotransform or set terrain.spacing=[dx,dz]", path, spacing[0], spacing[1],
                   TERRAIN_SPACING_MIN, TERRAIN_SPACING_MAX);
}

/* Heights beyond ±TERRAIN_HEIGHT_MAX (a band's scale or offset gone wrong) are refused, not drawn. */
static bool heights_in_range(const char *path, double lo, double hi, err_t *err)
{
    if (fabs(lo) <= TERRAIN_HEIGHT_MAX && fabs(hi) <= TERRAIN_HEIGHT_MAX)
        return true;
    return err_set(err, "heightmap '%s' has heights from %g to %g m, beyond ±%g m: check the band's scale and offset "
                        "(gdalinfo) or the height range", path, lo, hi, TERRAIN_HEIGHT_MAX);
}

/* What a DEM's georeferencing says (the about line) and the spacing it gives when the scene gives none. */
static bool dem_spacing(const heightfield_desc *d, const dem_info *info, int w, int h, float spacing[2], strbuf *about,
                        err_t *err)
{
    sb_printf(about, "%s: %dx%d %s", d->path, w, h, info->type);
    if (info->georeferenced) {
        sb_printf(about, ", %s", info->crs);
        if (info->geographic)
            sb_printf(about, " (geographic: %.1f x %.1f m per texel at %.2f°%c)", info->spacing[0], info->spacing[1],
                      fabs(info->latitude), info->latitude >= 0 ? 'N' : 'S');
        else
            sb_printf(about, " (%.1f x %.1f m per texel)", info->spacing[0], info->spacing[1]);
    }
    if (spacing[0] == 0 && info->georeferenced) {
        if (!terrain_spacing_ok(info->spacing[0]) || !terrain_spacing_ok(info->spacing[1]))
            return bad_spacing(d->path, info->spacing, err);
        spacing[0] = (float)info->spacing[0];
        spacing[1] = (float)info->spacing[1];
    } else if (spacing[0] != 0 && info->georeferenced) {
        sb_printf(about, ", spacing from the scene");
    } else if (spacing[0] == 0 && info->pixel[0] > 0) {
        return no_crs(d->path, info, err);
    }
    return true;
}

static bool heights_are_metres(const heightfield_desc *d, float lo, float hi, err_t *err)
{
    return (lo == 0 && hi == 0) ||
           err_set(err, "heightmap '%s' is a DEM whose values are heights already: remove terrain.height_min and "
                        "terrain.height_max (they map an 8/16-bit image's grey levels)", d->path);
}

/* A DEM through GDAL: metres, and the spacing from its georeferencing when the scene gives none. */
static bool read_dem(const heightfield_desc *d, float spacing[2], float lo, float hi, int *w, int *h, float **heights,
                     strbuf *about, err_t *err)
{
    if (!heights_are_metres(d, lo, hi, err))
        return false;
    dem_info info;
    if (!dem_read(d->path, TERRAIN_MAX_SIDE, w, h, heights, &info, err))
        return false;
    if (!dem_spacing(d, &info, *w, *h, spacing, about, err)) {
        free(*heights);
        *heights = NULL;
        return false;
    }
    return true;
}

bool heightfield_open_stream(const heightfield_desc *d, heightfield *hf, dem_stream **out, err_t *err)
{
    *out = NULL;
    *hf = (heightfield){0};
    float spacing[2] = {d->spacing[0], d->spacing[1]}, lo = d->height_min, hi = d->height_max;
    if (!read_sidecar(d->path, spacing, &lo, &hi, err) || !heights_are_metres(d, lo, hi, err))
        return false;
    if (d->fill_nodata)
        return err_set(err, "heightmap '%s' is streamed from disk (it is larger than terrain.cache_mb), and filling "
                            "nodata needs the whole DEM at once: fill it first (gdal_fillnodata.py) or raise "
                            "terrain.cache_mb", d->path);
    int w, h;
    dem_info info;
    dem_stream *s = dem_stream_open(d->path, &w, &h, &info, err);
    if (!s)
        return false;
    strbuf about = {0};
    bool ok = dem_spacing(d, &info, w, h, spacing, &about, err);
    if (ok && !(spacing[0] > 0 && spacing[1] > 0))
        ok = err_set(err, "heightmap '%s': no spacing (set terrain.spacing=[dx,dz] in metres per texel, or give the "
                          "DEM a CRS)", d->path);
    if (ok && (w < 2 || h < 2))
        ok = err_set(err, "heightmap '%s' is %dx%d: it needs at least 2x2 texels", d->path, w, h);
    if (ok) {
        *hf = (heightfield){.width = w, .height = h, .dx = spacing[0], .dz = spacing[1]};
        hf->x0 = -0.5f * (float)w * hf->dx;
        hf->z0 = -0.5f * (float)h * hf->dz;
        snprintf(hf->about, sizeof hf->about, "%s", about.data);
        *out = s;
    } else {
        dem_stream_close(s);
    }
    sb_free(&about);
    return ok;
}

bool heightfield_stream_check(const heightfield_desc *d, const heightfield *hf, err_t *err)
{
    if (hf->holes == (size_t)hf->width * (size_t)hf->height)
        return err_set(err, "heightmap '%s' has no heights: all %zu texels are nodata or NaN", d->path, hf->holes);
    return heights_in_range(d->path, hf->hmin, hf->hmax, err);
}

bool heightfield_load(const heightfield_desc *d, heightfield *hf, err_t *err)
{
    float spacing[2] = {d->spacing[0], d->spacing[1]}, lo = d->height_min, hi = d->height_max;
    if (!read_sidecar(d->path, spacing, &lo, &hi, err))
        return false;
    int w, h;
    float *heights;
    strbuf about = {0};
    bool image = dem_is_image(d->path);
    if (!(image ? read_image(d, lo, hi, &w, &h, &heights, &about, err)
                : read_dem(d, spacing, lo, hi, &w, &h, &heights, &about, err))) {
        sb_free(&about);
        return false;
    }
    bool ok = false;
    size_t n = (size_t)w * (size_t)h, holes = 0;
    float ex = d->exaggeration > 0 ? d->exaggeration : 1.0f;
    double lo_h = INFINITY, hi_h = -INFINITY; /* in double: a height times the exaggeration may pass a float */
    for (size_t i = 0; i < n; i++) {
        holes += isnan(heights[i]) ? 1 : 0;
        if (!isnan(heights[i]))
            lo_h = fmin(lo_h, (double)heights[i] * ex), hi_h = fmax(hi_h, (double)heights[i] * ex);
    }
    if (holes < n && !heights_in_range(d->path, lo_h, hi_h, err))
        ;
    else if (!(spacing[0] > 0 && spacing[1] > 0))
        err_set(err, "heightmap '%s': no spacing (set terrain.spacing=[dx,dz] in metres per texel%s)", d->path,
                image ? "" : ", or give the DEM a CRS");
    else if (w < 2 || h < 2)
        err_set(err, "heightmap '%s' is %dx%d: it needs at least 2x2 texels", d->path, w, h);
    else if (holes == n)
        err_set(err, "heightmap '%s' has no heights: all %zu texels are nodata or NaN", d->path, n);
    else if (holes && d->fill_nodata && !dem_fill_holes(heights, w, h, err))
        ;
    else
        ok = true;
    if (ok) {
        for (size_t i = 0; i < n; i++)
            heights[i] *= ex;
        heightfield_adopt(heights, w, h, spacing[0], spacing[1], hf);
        heights = NULL;
        if (holes)
            sb_printf(&about, ", %zu nodata texels %s", holes, d->fill_nodata ? "filled" : "left as holes");
        snprintf(hf->about, sizeof hf->about, "%s", about.data ? about.data : d->path);
    }
    free(heights);
    sb_free(&about);
    return ok;
}

bool heightfield_probe(const heightfield_desc *d, double size[2], double range[2], double spacing_out[2], err_t *err)
{
    float spacing[2] = {d->spacing[0], d->spacing[1]}, lo = d->height_min, hi = d->height_max;
    if (!read_sidecar(d->path, spacing, &lo, &hi, err))
        return false;
    float ex = d->exaggeration > 0 ? d->exaggeration : 1.0f;
    int w, h;
    if (dem_is_image(d->path)) { /* small enough to read: the exact range */
        heightfield hf;
        if (!heightfield_load(d, &hf, err))
            return false;
        w = hf.width, h = hf.height;
        spacing[0] = hf.dx, spacing[1] = hf.dz;
        range[0] = hf.hmin, range[1] = hf.hmax;
        heightfield_free(&hf);
    } else {
        dem_info info;
        if (!dem_probe(d->path, &w, &h, range, &info, err))
            return false;
        if (spacing[0] == 0 && !info.georeferenced && info.pixel[0] > 0)
            return no_crs(d->path, &info, err);
        if (spacing[0] == 0 && !info.georeferenced)
            return err_set(err, "heightmap '%s': no spacing (set terrain.spacing=[dx,dz] in metres per texel, or "
                                "give the DEM a CRS)", d->path);
        if (spacing[0] == 0 && (!terrain_spacing_ok(info.spacing[0]) || !terrain_spacing_ok(info.spacing[1])))
            return bad_spacing(d->path, info.spacing, err);
        if (spacing[0] == 0)
            spacing[0] = (float)info.spacing[0], spacing[1] = (float)info.spacing[1];
        range[0] *= ex, range[1] *= ex;
        if (!heights_in_range(d->path, range[0], range[1], err))
            return false;
    }
    spacing_out[0] = spacing[0], spacing_out[1] = spacing[1];
    size[0] = (double)w * spacing[0];
    size[1] = (double)h * spacing[1];
    return true;
}

void heightfield_drop_pyramid(heightfield *hf)
{
    if (hf->max)
        for (int k = 0; k < hf->levels; k++) {
            free(hf->max[k]);
            hf->max[k] = NULL;
        }
}

void heightfield_free(heightfield *hf)
{
    if (hf->max)
        for (int k = 0; k < hf->levels; k++)
            free(hf->max[k]);
    free(hf->max);
    free(hf->h);
    *hf = (heightfield){0};
}
