/* render_probe — a probe shader (probe.frag: map() at points; fogprobe.frag: fog optical depth) run
 * over a texture of points: the shader's own numbers, for tests and the window's flying speed. */
#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "render.h"
#include "render_parts.h"

bool render_probe(const scene *s, const char *extra_defines, const float *points, int n, float *out, err_t *err)
{
    return render_probe_with(s, "probe.frag", extra_defines, points, n, out, err);
}

bool render_probe_with(const scene *s, const char *frag, const char *extra_defines, const float *points, int n,
                       float *out, err_t *err)
{
    assert(n > 0);
    GLuint prog = programs_get(s, frag, extra_defines, err);
    if (!prog)
        return false;
    scene_gpu_uniforms(prog, s);
    scene_gpu_bind_textures();
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    int w = n < max_side ? n : max_side, h = (n + w - 1) / w;
    float *px = util_calloc((size_t)w * (size_t)h * 4, sizeof(float), "probe points");
    for (int i = 0; i < n; i++)
        memcpy(px + (size_t)i * 4, points + (size_t)i * 3, sizeof(float) * 3);
    GLuint tex[2], fbo;
    glGenTextures(2, tex);
    for (int i = 0; i < 2; i++) { /* without mipmaps, the default filter leaves a texture incomplete */
        glBindTexture(GL_TEXTURE_2D, tex[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, i == 0 ? px : NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex[1], 0);
    glDrawBuffers(1, (const GLenum[]){GL_COLOR_ATTACHMENT0});
    glViewport(0, 0, w, h);
    glUseProgram(prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex[0]);
    glUniform1i(glGetUniformLocation(prog, "uPoints"), 0);
    glBindVertexArray(render_vao());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, px);
    for (int i = 0; i < n; i++) {
        out[2 * i] = px[(size_t)i * 4];
        out[2 * i + 1] = px[(size_t)i * 4 + 1];
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(2, tex);
    free(px);
    return true;
}
