/* render_probe — probe shaders run over a texture of points (render_probe.h). */
#include "gpu/render_probe.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/gpu.h"
#include "gpu/render.h"
#include "gpu/render_programs.h"
#include "gpu/shader.h"
#include "gpu/render_scene.h"
#include "gpu/res_heightfield.h"

bool render_probe(const scene *s, const char *extra_defines, const float *points, int n, float *out, err_t *err)
{
    return render_probe_with(s, "probe.frag", extra_defines, points, n, out, err);
}

/* in: n points of 3 floats (and with in2, n more of 3); out: n results of out_comps floats. */
static bool probe_run(const scene *s, const char *frag, const char *extra_defines, const float *in, int in_stride,
                      int n, float *out, int out_comps, err_t *err)
{
    assert(n > 0);
    GLuint prog = render_programs_get(s, frag, extra_defines, err);
    if (!prog)
        return false;
    render_scene_uniforms(prog, s);
    render_origin_uniforms(prog);
    render_scene_bind();
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    int w = n < max_side ? n : max_side, h = (n + w - 1) / w;
    int inputs = in_stride / 3;
    float *px = util_calloc((size_t)w * (size_t)h * 4, sizeof(float), "probe points");
    GLuint tex[3], fbo;
    glGenTextures(3, tex);
    for (int i = 0; i < 3; i++) { /* inputs, then the result; without mipmaps, the default filter leaves a texture incomplete */
        bool input = i < inputs;
        if (input)
            for (int k = 0; k < n; k++)
                memcpy(px + (size_t)k * 4, in + (size_t)k * (size_t)in_stride + 3 * (size_t)i, sizeof(float) * 3);
        glBindTexture(GL_TEXTURE_2D, tex[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, input ? px : NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex[2], 0);
    glDrawBuffers(1, (const GLenum[]){GL_COLOR_ATTACHMENT0});
    glViewport(0, 0, w, h);
    glUseProgram(prog);
    static const char *const names[2] = {"uPoints", "uDirs"};
    for (int i = 0; i < inputs; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, tex[i]);
        glUniform1i(glGetUniformLocation(prog, names[i]), i);
    }
    glBindVertexArray(render_programs_vao());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, px);
    for (int i = 0; i < n; i++)
        memcpy(out + (size_t)i * (size_t)out_comps, px + (size_t)i * 4, sizeof(float) * (size_t)out_comps);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(3, tex);
    glActiveTexture(GL_TEXTURE0);
    free(px);
    return true;
}

bool render_probe_with(const scene *s, const char *frag, const char *extra_defines, const float *points, int n,
                       float *out, err_t *err)
{
    return probe_run(s, frag, extra_defines, points, 3, n, out, 2, err);
}

bool render_probe_loops(const scene *s, const float *points, int n, int *loops, err_t *err)
{
    int limit = render_programs_loop_limit();
    if (limit == 0)
        return err_set(err, "this driver (%s) has no loop limiter to measure loops against", gpu_describe());
    char define[48];
    snprintf(define, sizeof define, "#define PROBE_LOOPS %d\n", limit);
    float *out = util_alloc(sizeof(float) * 4 * (size_t)n, "loop probes");
    bool ok = probe_run(s, "probe.frag", define, points, 3, n, out, 4, err);
    for (int i = 0; ok && i < n; i++)
        loops[i] = limit - (int)out[4 * i + 2];
    free(out);
    return ok;
}

bool render_probe_rays(const scene *s, const char *frag, const char *extra_defines, const float *rays, int n,
                       float *out, err_t *err)
{
    return probe_run(s, frag, extra_defines, rays, 6, n, out, 4, err);
}

bool render_ground_height(float x, float z, float *height)
{
    const heightfield *hf = res_heightfield_loaded(NULL, NULL);
    const scene *s = render_scene_current();
    if (!hf || !s)
        return false;
    /* the terrain's map() at height 0 is −h · (its slope bound): probed on the GPU, the heights' home */
    float p[3] = {x, 0.0f, z}, out[2];
    err_t e;
    if (!render_probe(s, NULL, p, 1, out, &e))
        return false;
    float h = -out[0] * sqrtf(1.0f + hf->lipschitz * hf->lipschitz);
    if (!isfinite(h) || TERRAIN_IS_HOLE(h)) /* over a nodata hole: no ground */
        return false;
    *height = h;
    return true;
}

bool render_fit_precision(scene *s, const camera *c, int height, err_t *err)
{
    if (s->program != PROGRAM_FRACTAL || !s->fractal.deep_ok || s->fractal.precision != PRECISION_AUTO)
        return true;
    bool deep = s->fractal.deep_now;
    double origin[3] = {0, 0, 0};
    float p[3], d[2];
    for (int i = 0; i < 3; i++) {
        origin[i] = deep ? c->position[i] : 0.0;
        p[i] = (float)(c->position[i] - origin[i]);
    }
    render_set_origin(origin);
    if (!render_probe(s, NULL, p, 1, d, err))
        return false;
    bool want = scene_needs_double(s, fabs((double)d[0]), c, height, deep);
    if (want == deep)
        return true;
    if (want && !render_has_fp64())
        return err_set(err, "this view needs double precision (a deep zoom), which this OpenGL (%s) lacks "
                            "(GL_ARB_gpu_shader_fp64): the image stops resolving detail here", gpu_describe());
    s->fractal.deep_now = want;
    return render_set_scene(s, NULL, err);
}

static GLuint float_texture(const float *rgba, int w, int h)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, rgba);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

bool render_probe_error_mask(const float *sum, const float *squares, int w, int h, float tolerance, uint8_t *mask,
                             err_t *err)
{
    GLuint prog = shader_build(render_programs_shader_root(), "fullscreen.vert", "errormask.frag", NULL, NULL, 0, err);
    if (!prog)
        return false;
    GLuint tex[3] = {float_texture(sum, w, h), float_texture(squares, w, h), 0}, fbo;
    glGenTextures(1, &tex[2]);
    glBindTexture(GL_TEXTURE_2D, tex[2]);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, w, h, 0, GL_RED, GL_UNSIGNED_BYTE, NULL);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex[2], 0);
    render_mask_draw(prog, tex[0], tex[1], w, h, tolerance, false);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RED, GL_UNSIGNED_BYTE, mask);
    for (int i = 0; i < w * h; i++)
        mask[i] = mask[i] > 127;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(3, tex);
    glDeleteProgram(prog);
    return true;
}
