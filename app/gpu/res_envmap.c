/* res_envmap — the environment cube map (six files), kept while they are unchanged, and the
 * distribution the path tracer draws sky directions from (shaders/common/pathtrace.glsl, envSample):
 * the cube cut into ENV_CELLS² cells a face, each cell as likely as the light it sends, its mean
 * luminance (the mip level of that size) times its solid angle. Stored as a cumulative table of
 * 6 · ENV_CELLS² + 1 floats in a texture buffer, cells in the order face, row (t), column (s). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/render_resource.h"
#include "gpu/texture.h"

enum { ENV_CELLS = 32 }; /* cells across a face (fewer when the face is smaller) */

static struct {
    GLuint tex;
    char key[6 * (PATH_MAX_LEN + 64)];
    int size;          /* texels across a face */
    int cells;         /* cells across a face in the distribution; 0: none (a black sky) */
    GLuint cdf_buf, cdf_tex;
} state;

static void release(void)
{
    glDeleteTextures(1, &state.tex); /* a 0 name is ignored */
    glDeleteTextures(1, &state.cdf_tex);
    glDeleteBuffers(1, &state.cdf_buf);
    memset(&state, 0, sizeof state);
}

static int held(void) { return (state.tex != 0) + (state.cdf_tex != 0) + (state.cdf_buf != 0); }

/* The solid angle of the rectangle [x0, x1] × [y0, y1] on the plane at distance 1 from the eye: the
 * corners of F(x, y) = atan(x y / √(1 + x² + y²)), the solid angle of [0, x] × [0, y]. */
static double rect_solid_angle(double x0, double x1, double y0, double y1)
{
    double F[2][2];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double x = i ? x1 : x0, y = j ? y1 : y0;
            F[i][j] = atan2(x * y, sqrt(1 + x * x + y * y));
        }
    return F[1][1] - F[0][1] - F[1][0] + F[0][0];
}

static double srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* A cell's weight: its luminance, or a share of its brightest neighbour's on the same face when that
 * is more. Filtering spreads a texel half a texel into its neighbours (linear, seamless), so the light
 * of a bright cell spills into the next cell's edge: about a quarter of its radiance over half a
 * texel of a cell `texels` wide, the share below. Without it the spill is found only by the path's
 * own samples (6 % of a small square's light, measured: test_pathtrace's sky patch). */
static double cell_weight(const double *lum, int n, int i, int j, int texels)
{
    double spill = 0;
    for (int dj = -1; dj <= 1; dj++)
        for (int di = -1; di <= 1; di++) {
            int x = i + di, y = j + dj;
            if (x >= 0 && y >= 0 && x < n && y < n)
                spill = fmax(spill, lum[y * n + x]);
        }
    return fmax(lum[j * n + i], spill * 0.25 / texels);
}

/* The cumulative table from the cube map's level of n × n texels a face (linear RGB). */
static bool make_distribution(int n, err_t *err)
{
    int level = 0;
    for (int s = state.size; s > n; s /= 2)
        level++;
    size_t cells = 6 * (size_t)n * (size_t)n;
    float *rgba = util_alloc(sizeof(float) * 4 * (size_t)n * (size_t)n, "the sky's distribution");
    double *lum = util_alloc(sizeof(double) * (size_t)n * (size_t)n, "the sky's distribution");
    float *cdf = util_alloc(sizeof(float) * (cells + 1), "the sky's distribution");
    double total = 0;
    cdf[0] = 0;
    glBindTexture(GL_TEXTURE_CUBE_MAP, state.tex);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    for (int f = 0; f < 6; f++) {
        /* the sRGB texture (texture_load_cube) reads back as it is stored, encoded: measured on llvmpipe
         * (a driver that decoded it would make the sampling less apt, never biased) */
        glGetTexImage(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, level, GL_RGBA, GL_FLOAT, rgba);
        for (size_t k = 0; k < (size_t)n * (size_t)n; k++)
            lum[k] = fmax(0.2126 * srgb_to_linear(rgba[4 * k]) + 0.7152 * srgb_to_linear(rgba[4 * k + 1]) +
                              0.0722 * srgb_to_linear(rgba[4 * k + 2]),
                          0);
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double omega = rect_solid_angle(2.0 * i / n - 1, 2.0 * (i + 1) / n - 1, 2.0 * j / n - 1,
                                                2.0 * (j + 1) / n - 1);
                total += cell_weight(lum, n, i, j, state.size / n) * omega;
                cdf[((size_t)f * (size_t)n + (size_t)j) * (size_t)n + (size_t)i + 1] = (float)total;
            }
    }
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    free(rgba);
    free(lum);
    bool ok = true;
    if (total > 0) {
        for (size_t k = 1; k <= cells; k++)
            cdf[k] = (float)(cdf[k] / total);
        cdf[cells] = 1.0f;
        ok = texture_buffer(GL_R32F, cdf, sizeof(float) * (cells + 1), &state.cdf_buf, &state.cdf_tex);
        if (!ok)
            err_set(err, "the cube map's sky distribution: the GPU is out of memory");
    }
    state.cells = total > 0 && ok ? n : 0;
    free(cdf);
    return ok;
}

static bool set(const scene *s, err_t *err)
{
    if (!s->has_cubemap || !(s->effects & (1u << EFFECT_ENVMAP))) {
        release();
        return true;
    }
    char key[sizeof state.key] = "";
    for (int f = 0; f < 6; f++)
        render_file_key(s->cubemap[f], key, sizeof key);
    if (state.tex && !strcmp(key, state.key))
        return true;
    release();
    state.tex = texture_load_cube(s->cubemap, &state.size, err);
    if (!state.tex)
        return false;
    if (render_resource_fault(res_envmap.name, err) || !make_distribution(state.size < ENV_CELLS ? state.size : ENV_CELLS, err)) {
        release();
        return false;
    }
    snprintf(state.key, sizeof state.key, "%s", key);
    return true;
}

/* The units, the mip count that rough reflections blur over, and the sky's distribution. */
static void uniforms(const scene *s, const uniform_sink *u, int unit)
{
    (void)s;
    uniform_i(u, "uEnvMap", unit);
    uniform_i(u, "uEnvCdf", unit + 1); /* the path tracer's sky distribution */
    uniform_f(u, "uEnvMaxLod", state.size > 0 ? log2f((float)state.size) : 0.0f);
    uniform_i(u, "uEnvCells", state.cells);
}

static void bind(int unit)
{
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_CUBE_MAP, state.tex);
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit + 1);
    glBindTexture(GL_TEXTURE_BUFFER, state.cdf_tex);
}

const render_resource res_envmap = {"cube map", set, 2, uniforms, bind, release, held};
