#include "terrain.h"

#include <assert.h>
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_io.h"

static int next_pow2(int v)
{
    int p = 1;
    while (p < v)
        p *= 2;
    return p;
}

static void build(heightfield *hf)
{
    int W = hf->width, H = hf->height;
    hf->x0 = -0.5f * (float)W * hf->dx;
    hf->z0 = -0.5f * (float)H * hf->dz;
    hf->hmin = INFINITY;
    hf->hmax = -INFINITY;
    for (int i = 0; i < W * H; i++) {
        hf->hmin = fminf(hf->hmin, hf->h[i]);
        hf->hmax = fmaxf(hf->hmax, hf->h[i]);
    }
    /* steepest bilinear cell: its gradient is bounded by its largest x and z edge differences */
    float L = 0;
    for (int j = 0; j + 1 < H; j++)
        for (int i = 0; i + 1 < W; i++) {
            const float *r0 = hf->h + j * W + i, *r1 = r0 + W;
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
    hf->max = util_calloc((size_t)hf->levels, sizeof *hf->max, "the heightfield pyramid");
    hf->max[0] = util_alloc(sizeof(float) * (size_t)hf->pw * (size_t)hf->ph, "the heightfield pyramid");
    for (int j = 0; j < hf->ph; j++)
        for (int i = 0; i < hf->pw; i++) {
            float m = -INFINITY;
            if (i < cw && j < ch) {
                int i1 = i + 1 < W ? i + 1 : i, j1 = j + 1 < H ? j + 1 : j;
                m = fmaxf(fmaxf(hf->h[j * W + i], hf->h[j * W + i1]), fmaxf(hf->h[j1 * W + i], hf->h[j1 * W + i1]));
            }
            hf->max[0][j * hf->pw + i] = m;
        }
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
                            m = fmaxf(m, hf->max[k - 1][y * pw + x]);
                    }
                hf->max[k][j * w + i] = m;
            }
    }
}

void heightfield_from(const float *heights, int w, int h, float dx, float dz, heightfield *hf)
{
    *hf = (heightfield){.width = w, .height = h, .dx = dx, .dz = dz};
    hf->h = util_alloc(sizeof(float) * (size_t)w * (size_t)h, "the heightfield");
    memcpy(hf->h, heights, sizeof(float) * (size_t)w * (size_t)h);
    build(hf);
}

bool terrain_spacing_ok(double metres) { return isfinite(metres) && metres > 0 && metres <= TERRAIN_SPACING_MAX; }

/* NAME.json beside NAME.png: spacing and the height range of an integer image. Only the values the
 * scene left unset are taken, and each is checked like the scene's own. */
static bool read_sidecar(const char *path, float spacing[2], float *lo, float *hi, err_t *err)
{
    char side[PATH_MAX_LEN];
    const char *dot = strrchr(path, '.');
    snprintf(side, sizeof side, "%.*s.json", (int)(dot ? dot - path : (long)strlen(path)), path);
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

/* NaN and infinite heights cannot be drawn (the terrain issue turns them into nodata holes): refused,
 * counted, with the first one's texel so the user can find it. */
static bool check_finite(const char *path, const float *heights, int w, int h, err_t *err)
{
    size_t bad = 0, first = 0;
    for (size_t i = 0, n = (size_t)w * (size_t)h; i < n; i++)
        if (!isfinite(heights[i]) && bad++ == 0)
            first = i;
    if (bad == 0)
        return true;
    return err_set(err, "heightmap '%s': %zu of %zu heights are NaN or infinite (the first at column %zu, row %zu); "
                        "replace them with real heights", path, bad, (size_t)w * (size_t)h, first % (size_t)w,
                   first / (size_t)w);
}

bool heightfield_load(const heightfield_desc *d, heightfield *hf, err_t *err)
{
    float spacing[2] = {d->spacing[0], d->spacing[1]}, lo = d->height_min, hi = d->height_max;
    if (!read_sidecar(d->path, spacing, &lo, &hi, err))
        return false;
    if (!(spacing[0] > 0 && spacing[1] > 0))
        return err_set(err, "heightmap '%s': no spacing (set terrain.spacing=[dx,dz] in metres per texel)", d->path);
    int w, h, c;
    float *px;
    if (!image_read_f32(d->path, 1, IMAGE_MAX_SIDE, &w, &h, &c, &px, err))
        return false;
    if (w < 2 || h < 2) {
        free(px);
        return err_set(err, "heightmap '%s' is %dx%d: it needs at least 2x2 texels", d->path, w, h);
    }
    /* OpenImageIO reads integer images normalised to 0..1; float images keep their values */
    const char *dot = strrchr(d->path, '.');
    bool is_float = dot && (!strcmp(dot, ".exr") || !strcmp(dot, ".hdr") || !strcmp(dot, ".pfm"));
    if (!is_float && lo == 0 && hi == 0) {
        free(px);
        return err_set(err, "heightmap '%s' is an integer image: set terrain.height_min and terrain.height_max "
                            "(metres for black and white)", d->path);
    }
    float *heights = malloc(sizeof(float) * (size_t)w * (size_t)h);
    if (!heights) {
        free(px);
        return err_set(err, "heightmap '%s' (%dx%d): out of memory", d->path, w, h);
    }
    float ex = d->exaggeration > 0 ? d->exaggeration : 1.0f;
    for (size_t i = 0, n = (size_t)w * (size_t)h; i < n; i++) {
        float v = px[i * (size_t)c];
        heights[i] = (is_float ? v : lo + v * (hi - lo)) * ex;
    }
    free(px);
    bool ok = check_finite(d->path, heights, w, h, err);
    if (ok)
        heightfield_from(heights, w, h, spacing[0], spacing[1], hf);
    free(heights);
    return ok;
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

float heightfield_at(const heightfield *hf, float x, float z)
{
    float u = (x - hf->x0) / hf->dx - 0.5f, v = (z - hf->z0) / hf->dz - 0.5f;
    u = fminf(fmaxf(u, 0.0f), (float)(hf->width - 1));
    v = fminf(fmaxf(v, 0.0f), (float)(hf->height - 1));
    int i = (int)fminf(floorf(u), (float)(hf->width - 2)), j = (int)fminf(floorf(v), (float)(hf->height - 2));
    float a = u - (float)i, b = v - (float)j;
    const float *r0 = hf->h + j * hf->width + i, *r1 = r0 + hf->width;
    return (1 - b) * ((1 - a) * r0[0] + a * r0[1]) + b * ((1 - a) * r1[0] + a * r1[1]);
}
