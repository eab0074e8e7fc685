/* render_output — the render module's display and readback (render.h): the tone-mapped display pass
 * and its views (steps heat map, difference to a grabbed reference), reading images, AOVs and single
 * pixels back, and counting what the image left unresolved. */
#include "gpu/render.h"

#include <assert.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "view/aov.h"
#include "gpu/render_programs.h"
#include "gpu/render_scene.h"
#include "gpu/render_state.h"
#include "gpu/texture.h"
#include "scene/program.h"

static render_state *const state = &render_shared;

void render_grab_reference(void)
{
    if (!state->ref_tex) {
        glGenTextures(1, &state->ref_tex);
        glBindTexture(GL_TEXTURE_2D, state->ref_tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, state->alloc_width, state->alloc_height, 0, GL_RGBA, GL_FLOAT, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glGenFramebuffers(1, &state->ref_fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, state->ref_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, state->ref_tex, 0);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, state->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, state->ref_fbo);
    glDrawBuffers(1, (const GLenum[]){GL_COLOR_ATTACHMENT0});
    glBlitFramebuffer(0, 0, state->width, state->height, 0, 0, state->width, state->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    state->ref_samples = state->samples;
}

static void display_pass(GLuint fbo, int width, int height, float exposure, render_view view);

/* A stretched colour image (a moving frame): tone-mapped at its own size, then stretched by the
 * blitter's bilinear filter, so the full-screen pass runs over the small image's pixels, not the
 * window's (at 1280x720 on llvmpipe the pass took 26 ms of each moving frame). The filtering is then
 * in display colour rather than linear: moving frames only. */
void render_display(GLuint fbo, int width, int height, float exposure, render_view view)
{
    bool stretched = state->width != width || state->height != height;
    if (!(view == VIEW_COLOR && stretched && !state->edge_aware && state->stretch_fbo)) {
        display_pass(fbo, width, height, exposure, view);
        return;
    }
    display_pass(state->stretch_fbo, state->width, state->height, exposure, view);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, state->stretch_fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glBlitFramebuffer(0, 0, state->width, state->height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
}

/* A fragment's own look's post (fractal.look = fragment, display.frag): its ToneMapping, Exposure, Gamma,
 * Brightness, Contrast and Saturation, in that order, into post; false when the scene's look is fathom's. */
static bool fragment_post(const scene *s, float post[6])
{
    static const char *const KEYS[6] = {"ToneMapping", "Exposure", "Gamma", "Brightness", "Contrast", "Saturation"};
    static const float DEFAULTS[6] = {4, 1, 2, 1, 1, 1}; /* Fragmentarium's 3D include's */
    if (!s || !program_is_fractal(s->program) || s->fractal.look != LOOK_FRAGMENT)
        return false;
    const formula *f = &s->fractal.formula;
    for (int k = 0; k < 6; k++) {
        post[k] = DEFAULTS[k];
        for (int i = 0; i < f->param_count; i++)
            if (!strcmp(f->params[i].key, KEYS[k]))
                post[k] = s->fractal.values[i][0];
    }
    return true;
}

static void display_pass(GLuint fbo, int width, int height, float exposure, render_view view)
{
    GLuint p = state->display_prog;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, width, height);
    glUseProgram(p);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, state->targets[2]);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, state->targets[0]);
    glUniform1i(glGetUniformLocation(p, "uAccum"), 0);
    glUniform1i(glGetUniformLocation(p, "uAux"), 1);
    if (view == VIEW_DIFFERENCE && !state->ref_samples)
        view = VIEW_COLOR; /* nothing grabbed yet */
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, state->ref_tex);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, state->targets[1]);
    glActiveTexture(GL_TEXTURE4);
    glBindTexture(GL_TEXTURE_2D, state->preview_tex);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(glGetUniformLocation(p, "uPreview"), 4);
    glUniform2f(glGetUniformLocation(p, "uPreviewSize"), (float)state->preview_w, (float)state->preview_h);
    glUniform1i(glGetUniformLocation(p, "uReference"), 2);
    glUniform1i(glGetUniformLocation(p, "uNormalDepth"), 3);
    glUniform1i(glGetUniformLocation(p, "uEdgeAware"), state->edge_aware ? 1 : 0);
    glUniform1f(glGetUniformLocation(p, "uInvRefSamples"), state->ref_samples ? 1.0f / (float)state->ref_samples : 0.0f);
    glUniform1i(glGetUniformLocation(p, "uView"), (GLint)view);
    float top = state->heat_max > 0 ? state->heat_max
                : render_scene_current() ? (float)render_scene_current()->quality.max_steps : 1.0f;
    glUniform1f(glGetUniformLocation(p, "uMaxSteps"), top);
    glUniform1f(glGetUniformLocation(state->display_prog, "uExposure"), exposure);
    float post[6]; /* ToneMapping, Exposure, Gamma, Brightness, Contrast, Saturation */
    bool own = fragment_post(render_scene_current(), post);
    glUniform1i(glGetUniformLocation(p, "uPost"), own);
    if (own) {
        glUniform1i(glGetUniformLocation(p, "uPostTone"), (GLint)post[0]);
        glUniform4f(glGetUniformLocation(p, "uPostGEBC"), fmaxf(post[2], 1e-3f), post[1], post[3], post[4]);
        glUniform1f(glGetUniformLocation(p, "uPostSaturation"), post[5]);
    }
    glUniform2f(glGetUniformLocation(p, "uSrcSize"), (float)state->width, (float)state->height);
    glUniform2f(glGetUniformLocation(p, "uDstSize"), (float)width, (float)height);
    glBindVertexArray(render_programs_vao());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

static void read_rect(GLuint fbo, GLenum attachment, GLenum type, int w, int h, void *out)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadBuffer(attachment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, type, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

static void read_target(GLuint fbo, GLenum attachment, GLenum type, void *out)
{
    read_rect(fbo, attachment, type, state->width, state->height, out);
}

void render_read_stretched_srgb8(uint8_t *rgba, int width, int height, float exposure)
{
    assert(width <= state->alloc_width && height <= state->alloc_height);
    render_display(state->out_fbo, width, height, exposure, VIEW_COLOR);
    read_rect(state->out_fbo, GL_COLOR_ATTACHMENT0, GL_UNSIGNED_BYTE, width, height, rgba);
    texture_flip_rows(rgba, height, (size_t)width * 4);
}

void render_read_srgb8(uint8_t *rgba, float exposure)
{
    render_read_stretched_srgb8(rgba, state->width, state->height, exposure);
}

void render_read_linear(float *rgba)
{
    read_target(state->fbo, GL_COLOR_ATTACHMENT0, GL_FLOAT, rgba);
    size_t n = (size_t)state->width * (size_t)state->height;
    for (size_t i = 0; i < n; i++) { /* alpha counts the pixel's own samples (adaptive sampling) */
        float inv = rgba[i * 4 + 3] > 0.0f ? 1.0f / rgba[i * 4 + 3] : 0.0f;
        for (int c = 0; c < 4; c++)
            rgba[i * 4 + (size_t)c] *= inv;
    }
    texture_flip_rows(rgba, state->height, (size_t)state->width * 4 * sizeof(float));
}

/* The position AOV (GL rows, bottom up, before the flip): the pixel's ray (the lens's or eye's centre:
 * camera_ray_from) in the whole image, in double, to the depth. */
static void aov_positions(float *aov8)
{
    for (int y = 0; y < state->height; y++)
        for (int x = 0; x < state->width; x++) {
            float *o = aov8 + ((size_t)y * (size_t)state->width + (size_t)x) * AOV_FLOATS;
            double origin[3];
            vec3 d;
            bool sees = camera_ray_from(&state->cam, state->full_width, state->full_height, (float)(x + state->tile_x),
                                        (float)(y + state->tile_y), origin, d);
            float t = o[AOV_SLOT_DEPTH];
            for (int i = 0; i < 3; i++)
                o[AOV_SLOT_POSITION + i] = sees && isfinite(t) ? (float)(origin[i] + (double)d[i] * (double)t) : 0.0f;
        }
}

void render_read_aovs(float *aov8)
{
    size_t n = (size_t)state->width * (size_t)state->height;
    float *t[NUM_TARGETS];
    for (int k = 0; k < NUM_TARGETS; k++) {
        t[k] = util_alloc(sizeof(float) * 4 * n, "the AOV readback");
        read_target(state->fbo, GL_COLOR_ATTACHMENT0 + (GLenum)k, GL_FLOAT, t[k]);
    }
    for (size_t i = 0; i < n; i++) {
        float *o = aov8 + i * AOV_FLOATS;
        memcpy(o, t[1] + i * 4, sizeof(float) * 4);
        memcpy(o + 4, t[2] + i * 4, sizeof(float) * 4);
        memcpy(o + AOV_SLOT_ALBEDO, t[4] + i * 4, sizeof(float) * 3);
        if (o[AOV_SLOT_DEPTH] < 0.0f) /* the shader marks a miss with depth −1 */
            o[AOV_SLOT_DEPTH] = INFINITY;
        /* the variance of the mean from the sums of x and x² over n samples (in double: the two sums
         * are close, and float would cancel): (Σx² − (Σx)²/n) / (n (n − 1)) */
        double samples = t[0][i * 4 + 3];
        o[AOV_SLOT_SAMPLES] = (float)samples;
        for (int c = 0; c < 3; c++) {
            double sum = t[0][i * 4 + (size_t)c], sq = t[3][i * 4 + (size_t)c];
            double var = samples >= 2 ? (sq - sum * sum / samples) / (samples * (samples - 1)) : -1.0;
            o[AOV_SLOT_VARIANCE + c] = (float)(samples >= 2 && var < 0 ? 0 : var); /* rounding */
        }
    }
    for (int k = 0; k < NUM_TARGETS; k++)
        free(t[k]);
    aov_positions(aov8);
    texture_flip_rows(aov8, state->height, (size_t)state->width * AOV_FLOATS * sizeof(float));
}

long render_unresolved_pixels(long *loops)
{
    size_t n = (size_t)state->width * (size_t)state->height;
    float *steps = util_alloc(sizeof(float) * n, "the steps readback");
    glBindFramebuffer(GL_READ_FRAMEBUFFER, state->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT2); /* AOV_SLOT_STEPS is its red channel */
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, state->width, state->height, GL_RED, GL_FLOAT, steps);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    long count = 0;
    for (size_t i = 0; i < n; i++) {
        count += steps[i] < 0.0f;
        if (loops)
            *loops += steps[i] < 0.0f && steps[i] != floorf(steps[i]); /* −(steps + ½): aov.h */
    }
    free(steps);
    return count;
}

void render_set_heat_max(float steps) { state->heat_max = steps; }

float render_heat_max(void)
{
    const scene *s = render_scene_current();
    return state->heat_max > 0 ? state->heat_max : s ? (float)s->quality.max_steps : 1.0f;
}

bool render_read_pixel(int x, int y_from_top, float out[AOV_FLOATS])
{
    if (!state->fbo || x < 0 || y_from_top < 0 || x >= state->width || y_from_top >= state->height || state->samples == 0)
        return false;
    int y = state->height - 1 - y_from_top;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, state->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(x, y, 1, 1, GL_RGBA, GL_FLOAT, out);
    glReadBuffer(GL_COLOR_ATTACHMENT2);
    glReadPixels(x, y, 1, 1, GL_RGBA, GL_FLOAT, out + 4);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (int i = 8; i < AOV_FLOATS; i++) /* the variance and sample count: not read for a cursor */
        out[i] = 0.0f;
    if (out[AOV_SLOT_DEPTH] < 0.0f)
        out[AOV_SLOT_DEPTH] = INFINITY;
    return true;
}

double render_reference_rmse(void)
{
    if (!state->ref_samples || !state->samples)
        return -1.0;
    size_t n = (size_t)state->width * (size_t)state->height;
    float *now = util_alloc(sizeof(float) * 4 * n, "the reference comparison");
    float *ref = util_alloc(sizeof(float) * 4 * n, "the reference comparison");
    read_target(state->fbo, GL_COLOR_ATTACHMENT0, GL_FLOAT, now);
    read_target(state->ref_fbo, GL_COLOR_ATTACHMENT0, GL_FLOAT, ref);
    double sum = 0;
    for (size_t i = 0; i < n; i++) { /* each pixel's mean: alpha counts its samples */
        float a = now[4 * i + 3] > 0 ? 1.0f / now[4 * i + 3] : 0.0f, b = ref[4 * i + 3] > 0 ? 1.0f / ref[4 * i + 3] : 0.0f;
        for (int c = 0; c < 3; c++) {
            double d = (double)(now[4 * i + (size_t)c] * a - ref[4 * i + (size_t)c] * b);
            sum += d * d;
        }
    }
    free(now);
    free(ref);
    return sqrt(sum / (3.0 * (double)n));
}

