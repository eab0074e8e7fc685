/* render — targets, backends and samples (render.h). The rest of the module:
 *   render_output.c    display and readback
 *   render_programs.c  the program cache and the full-screen VAO
 *   render_scene.c     the current scene and its GPU resources, one file a kind (render_resource.h) */
#include "gpu/render.h"

#include <assert.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "view/aov.h"
#include "gpu/render_programs.h"
#include "gpu/render_resource.h"
#include "gpu/render_scene.h"
#include "gpu/res_droplets.h"
#include "gpu/res_heightfield.h"
#include "gpu/gpu.h"
#include "gpu/render_state.h"
#include "gpu/shader.h"

render_state render_shared = {.runtime_effects = ~0u};
static render_state *const state = &render_shared;

static render_backend requested = BACKEND_AUTO; /* render_request_backend */
static bool requested_set;

/* One compute dispatch covers at most this many pixels: a 4K frame's sample is 8 dispatches, each a
 * few ms on a big GPU, so no dispatch nears a desktop driver's watchdog, and the driver can start on
 * one while the next is queued. Samples of a window's bands are smaller still. */
enum { COMPUTE_TILE_PIXELS = 1 << 20 };
static int compute_tile_pixels = COMPUTE_TILE_PIXELS;

void render_set_compute_tile(int pixels) { compute_tile_pixels = pixels > 0 ? pixels : COMPUTE_TILE_PIXELS; }

static const char *const backend_names[] = {"auto", "fragment", "compute"};

bool render_parse_backend(const char *name, render_backend *out)
{
    for (int i = 0; i < 3; i++)
        if (name && !strcmp(name, backend_names[i])) {
            *out = (render_backend)i;
            return true;
        }
    return false;
}

const char *render_backend_name(render_backend b) { return backend_names[b]; }

void render_request_backend(render_backend b)
{
    requested = b;
    requested_set = true;
}

render_backend render_backend_used(void) { return state->backend; }

bool render_has_compute(void)
{
    return epoxy_gl_version() >= 43 || epoxy_has_gl_extension("GL_ARB_compute_shader");
}

bool render_auto_is_compute(void)
{
    /* A software rasteriser runs fragments in 4x4 blocks that suit its SIMD better than compute
     * invocations: on llvmpipe the fragment path is 1.1-1.9x faster (docs/gpu/README.md). A hardware
     * GPU takes compute: an H100 runs fragment shaders on 2 of its TPCs and compute on all of them. */
    const char *r = (const char *)glGetString(GL_RENDERER);
    bool software = r && (strstr(r, "llvmpipe") || strstr(r, "softpipe") || strstr(r, "swrast"));
    return render_has_compute() && !software;
}

bool render_switch_backend(render_backend b, err_t *err)
{
    if (b == BACKEND_COMPUTE && !render_has_compute())
        return err_set(err, "the compute backend needs OpenGL 4.3 compute shaders, which this OpenGL (%s) lacks: "
                            "use --backend fragment", gpu_describe());
    state->backend = b == BACKEND_AUTO ? (render_auto_is_compute() ? BACKEND_COMPUTE : BACKEND_FRAGMENT) : b;
    state->samples = 0;
    state->band_done = 0;
    return true;
}

/* The backend to use: the request (--backend), else FATHOM_BACKEND, else auto. */
static bool resolve_backend(err_t *err)
{
    render_backend b = requested;
    const char *env = getenv("FATHOM_BACKEND");
    if (!requested_set && env && *env && !render_parse_backend(env, &b))
        return err_set(err, "FATHOM_BACKEND='%s' is not a backend: use auto, fragment or compute, or unset it", env);
    return render_switch_backend(b, err);
}


static GLuint build_display(err_t *err)
{
    return shader_build(render_programs_shader_root(), "fullscreen.vert", "display.frag", NULL, NULL, 0, err);
}

static GLuint build_mask(err_t *err)
{
    return shader_build(render_programs_shader_root(), "fullscreen.vert", "edgemask.frag", NULL, NULL, 0, err);
}

static GLuint build_error_mask(err_t *err)
{
    return shader_build(render_programs_shader_root(), "fullscreen.vert", "errormask.frag", NULL, NULL, 0, err);
}

bool render_init(err_t *err)
{
    if (!resolve_backend(err))
        return false;
    render_programs_init();
    state->display_prog = build_display(err);
    state->mask_prog = state->display_prog ? build_mask(err) : 0;
    state->error_prog = state->mask_prog ? build_error_mask(err) : 0;
    return state->display_prog != 0 && state->mask_prog != 0 && state->error_prog != 0;
}

static void free_targets(void)
{
    if (state->fbo) {
        glDeleteFramebuffers(1, &state->fbo);
        glDeleteTextures(NUM_TARGETS, state->targets);
        glDeleteFramebuffers(1, &state->out_fbo);
        glDeleteTextures(1, &state->out_tex);
        glDeleteFramebuffers(1, &state->ref_fbo);
        glDeleteTextures(1, &state->ref_tex);
        glDeleteFramebuffers(1, &state->mask_fbo);
        glDeleteTextures(1, &state->mask_tex);
        glDeleteFramebuffers(1, &state->preview_fbo);
        glDeleteTextures(1, &state->preview_tex);
        glDeleteFramebuffers(1, &state->stretch_fbo);
        glDeleteTextures(1, &state->stretch_tex);
        state->stretch_fbo = state->stretch_tex = 0;
        state->preview_fbo = state->preview_tex = 0;
        state->preview_w = state->preview_h = 0;
        state->fbo = state->out_fbo = state->ref_fbo = state->ref_tex = state->mask_fbo = state->mask_tex = 0;
        state->ref_samples = 0;
    }
}

void render_set_runtime_effects(unsigned mask) { state->runtime_effects = mask; }

void render_shutdown(void)
{
    free_targets();
    render_scene_shutdown();
    glDeleteProgram(state->display_prog);
    glDeleteProgram(state->mask_prog);
    glDeleteProgram(state->error_prog);
    render_programs_shutdown();
    memset(state, 0, sizeof *state);
    state->runtime_effects = ~0u;
}

void render_preamble(const scene *s, const char *extra_defines, strbuf *out)
{
    scene_preamble(s, out);
    if (extra_defines)
        sb_append(out, extra_defines);
}

bool render_set_scene(const scene *s, const char *extra_defines, err_t *err)
{
    strbuf defines = {0}; /* the caller's, and what the scene's resources need (a streamed terrain's feedback) */
    sb_append(&defines, extra_defines ? extra_defines : "");
    res_heightfield_defines(s, &defines);
    GLuint prog = render_programs_get(s, state->backend == BACKEND_COMPUTE ? "sdf.comp" : "sdf.frag", defines.data, err);
    sb_free(&defines);
    if (!prog || !render_scene_set(s, err))
        return false;
    state->prog = prog;
    render_scene_uniforms(prog, s);
    return true;
}

/* A framebuffer with one NEAREST-filtered colour texture. */
static void single_target(GLenum internal, GLenum format, GLenum type, int w, int h, GLuint *fbo, GLuint *tex)
{
    glGenFramebuffers(1, fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
    glGenTextures(1, tex);
    glBindTexture(GL_TEXTURE_2D, *tex);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, type, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *tex, 0);
    assert(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
}

void render_resize(int width, int height)
{
    assert(width > 0 && height > 0);
    if (state->fbo && width == state->alloc_width && height == state->alloc_height) {
        render_set_active(width, height);
        return;
    }
    free_targets();
    state->width = state->alloc_width = width;
    state->height = state->alloc_height = height;
    render_set_window(width, height, 0, 0);
    glGenFramebuffers(1, &state->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, state->fbo);
    glGenTextures(NUM_TARGETS, state->targets);
    for (int i = 0; i < NUM_TARGETS; i++) {
        glBindTexture(GL_TEXTURE_2D, state->targets[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)i, GL_TEXTURE_2D, state->targets[i], 0);
    }
    assert(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    single_target(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, width, height, &state->out_fbo, &state->out_tex);
    single_target(GL_R8, GL_RED, GL_UNSIGNED_BYTE, width, height, &state->mask_fbo, &state->mask_tex);
    single_target(GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height, &state->preview_fbo, &state->preview_tex);
    single_target(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, width, height, &state->stretch_fbo, &state->stretch_tex);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    state->samples = 0;
    state->band_done = 0;
}

void render_set_active(int width, int height)
{
    assert(width > 0 && height > 0 && width <= state->alloc_width && height <= state->alloc_height);
    if (width != state->width || height != state->height) {
        state->samples = 0;
        state->band_done = 0;
    }
    state->width = width;
    state->height = height;
    render_set_window(width, height, 0, 0);
}

void render_active_size(int *width, int *height)
{
    *width = state->width;
    *height = state->height;
}

void render_set_window(int full_width, int full_height, int left, int top)
{
    state->full_width = full_width;
    state->full_height = full_height;
    state->tile_x = left;
    state->tile_y = full_height - top - state->height; /* GL counts rows from the bottom */
}

void render_begin(const camera *c)
{
    state->cam = *c;
    state->samples = 0;
    state->band_done = 0;
    const scene *s = render_scene_current();
    bool deep = s && s->fractal.deep_now;
    for (int i = 0; i < 3; i++)
        state->origin[i] = deep ? c->position[i] : 0.0;
}

void render_origin(double origin[3]) { memcpy(origin, state->origin, sizeof state->origin); }

void render_set_origin(const double origin[3]) { memcpy(state->origin, origin, sizeof state->origin); }

void render_origin_uniforms(GLuint prog)
{
    /* the eye and the pixel's angle: what a probe's map() sees of the view (the noise terrain's
     * filtering depends on them), as the image's does */
    float eye[3];
    for (int i = 0; i < 3; i++)
        eye[i] = (float)(state->cam.position[i] - state->origin[i]);
    glUniform3fv(glGetUniformLocation(prog, "uCamPos"), 1, eye);
    if (state->full_height > 0)
        glUniform1f(glGetUniformLocation(prog, "uPixelAngle"), camera_pixel_angle(&state->cam, state->full_height));
    glUniform1f(glGetUniformLocation(prog, "uFootprintT0"), camera_footprint_t0(&state->cam));
    GLint o = glGetUniformLocation(prog, "uOrigin");
    if (o < 0) /* a float program: its positions are world positions */
        return;
    glUniform3d(o, state->origin[0], state->origin[1], state->origin[2]);
    glUniform3f(glGetUniformLocation(prog, "uOriginApprox"), (float)state->origin[0], (float)state->origin[1],
                (float)state->origin[2]);
    glUniform1f(glGetUniformLocation(prog, "uOriginFloor"), (float)camera_resolution(state->origin, true));
}

bool render_has_fp64(void)
{
    return epoxy_gl_version() >= 40 || epoxy_has_gl_extension("GL_ARB_gpu_shader_fp64");
}

int render_samples(void) { return state->samples; }

void render_set_adaptive(bool on) { state->adaptive = on; }

void render_set_first_jitter(int k) { state->first_jitter = k; }

void render_set_edge_aware(bool on) { state->edge_aware = on; }

int render_adaptive_pixels(void) { return state->masked; }

/* Whether s's pixels may stop early by their standard error: a tolerance, and not the path tracer (the
 * unbiased truth, whose two samples may agree by chance). */
static bool stops_by_error(const scene *s) { return s->quality.tolerance > 0 && !s->quality.integrator; }

int render_adaptive_margin(const scene *s, int spp)
{
    int m = stops_by_error(s) && spp > RENDER_ADAPTIVE_MIN ? spp - RENDER_ADAPTIVE_MIN : 0;
    return (m + 1) & ~1;
}

double render_mean_samples(void)
{
    double n = (double)state->width * state->height;
    return n > 0 ? state->pixel_samples / n : 0.0;
}

/* Pixels the mask in mask_tex keeps (a small readback, once a sample: the HUD, the bench and the
 * early stop read it). */
static int count_mask(void)
{
    size_t n = (size_t)state->width * (size_t)state->height;
    uint8_t *m = malloc(n);
    int kept = (int)n; /* unknown: as if every pixel went on */
    if (m) {
        kept = 0;
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, state->width, state->height, GL_RED, GL_UNSIGNED_BYTE, m);
        for (size_t i = 0; i < n; i++)
            kept += m[i] > 127;
        free(m);
    }
    return kept;
}

/* A mask into mask_tex: the edge mask from the first sample (shaders/edgemask.frag), or the pixels
 * whose standard error is still above the tolerance (shaders/errormask.frag). */
void render_mask_draw(unsigned prog, unsigned accum, unsigned second, int w, int h, float tolerance, bool edges)
{
    glViewport(0, 0, w, h);
    glUseProgram(prog);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, second);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, accum);
    glUniform1i(glGetUniformLocation(prog, "uAccum"), 0);
    glUniform1i(glGetUniformLocation(prog, edges ? "uNormalDepth" : "uSquares"), 1);
    glUniform1f(glGetUniformLocation(prog, "uExposure"), 1.0f);
    glUniform1f(glGetUniformLocation(prog, "uTolerance"), tolerance);
    glUniform1f(glGetUniformLocation(prog, "uEdgeStep"), RENDER_EDGE_STEP * tolerance);
    glUniform2i(glGetUniformLocation(prog, "uSize"), w, h);
    glBindVertexArray(render_programs_vao());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

static void build_mask_tex(bool edges, float tolerance)
{
    glBindFramebuffer(GL_FRAMEBUFFER, state->mask_fbo);
    render_mask_draw(edges ? state->mask_prog : state->error_prog, state->targets[0], state->targets[edges ? 1 : 3],
                     state->width, state->height, tolerance, edges);
    state->masked = count_mask();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

/* Whether this sample goes only to the pixels mask_tex keeps, building the mask where a sample
 * starts. Shading is deterministic but for the sub-pixel position, a lens's point and the path
 * tracer's random numbers: in the window (render_set_adaptive) the samples after the first and before
 * RENDER_ADAPTIVE_MIN go only to edges while there is no lens or path tracer; from sample
 * RENDER_ADAPTIVE_MIN on, only pixels the error mask keeps take more (shaders/errormask.frag: a standard
 * error above the tolerance in the 3x3 block, a pass-by, an edge not yet placed; every image; bands
 * and tiles carry margin rows for the block: render_adaptive_margin). Once no
 * pixel is left, the image has converged and further samples cost nothing. */
static bool masked_sample(void)
{
    const scene *s = render_scene_current();
    if (state->samples == 0)
        return false;
    if (state->samples < RENDER_ADAPTIVE_MIN) {
        if (!state->adaptive || !stops_by_error(s) || state->cam.lens.aperture > 0)
            return false;
        if (state->samples == 1 && state->band_done == 0)
            build_mask_tex(true, 0.0f);
        return true;
    }
    if (!stops_by_error(s))
        return false;
    if (state->band_done == 0 && !state->converged) {
        build_mask_tex(false, s->quality.tolerance);
        state->converged = state->masked == 0;
    }
    return true;
}

/* Halton (2, 3) points, centred: low-discrepancy sub-pixel offsets. Sample 0 is the pixel centre. */
static float halton(int i, int base)
{
    float f = 1.0f, r = 0.0f;
    for (; i > 0; i /= base) {
        f /= (float)base;
        r += f * (float)(i % base);
    }
    return r;
}

static GLint loc(const char *name) { return glGetUniformLocation(state->prog, name); }

/* The projection, stereo and thin lens (view/camera.h): sample k's lens point is Halton (5, 7) point
 * k + 1 (the shader shifts it per pixel). */
static void lens_uniforms(int k)
{
    const camera_lens *l = &state->cam.lens;
    glUniform1i(loc("uProjection"), (int)l->projection);
    glUniform1i(loc("uStereo"), (int)l->stereo);
    glUniform1f(loc("uEyeSeparation"), l->stereo ? l->eye_separation : 0.0f);
    glUniform1f(loc("uFocus"), camera_focus(&state->cam));
    glUniform1f(loc("uLensRadius"), l->aperture);
    glUniform2f(loc("uLensSample"), halton(k + 1, 5), halton(k + 1, 7));
}

/* The fragment path: a full-screen triangle over rows [y0, y1), target 0 blended additively. */
static void draw_rows(int y0, int y1, bool first)
{
    static const GLenum all[NUM_TARGETS] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                            GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
    static const GLenum sums_only[NUM_TARGETS] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE, GL_COLOR_ATTACHMENT3, GL_NONE};
    glDrawBuffers(NUM_TARGETS, first ? all : sums_only);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, y0, state->width, y1 - y0);
    glEnablei(GL_BLEND, 0); /* the sums: radiance and its square */
    glEnablei(GL_BLEND, 3);
    glBlendFunc(GL_ONE, GL_ONE);
    glDisablei(GL_BLEND, 1);
    glDisablei(GL_BLEND, 2);
    glBindVertexArray(render_programs_vao());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisablei(GL_BLEND, 0);
    glDisablei(GL_BLEND, 3);
    glDisable(GL_SCISSOR_TEST);
}

/* The compute path: rows [y0, y1) in dispatches of at most COMPUTE_TILE_PIXELS, the targets bound as
 * images (sdf.comp adds to target 0 itself). */
static void dispatch_rows(int y0, int y1, bool first)
{
    for (int i = 0; i < NUM_TARGETS; i++)
        glBindImageTexture((GLuint)i, state->targets[i], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glUniform1i(loc("uAccum"), 0);
    glUniform1i(loc("uNormalDepth"), 1);
    glUniform1i(loc("uAux"), 2);
    glUniform1i(loc("uSquares"), 3);
    glUniform1i(loc("uAlbedo"), 4);
    glUniform1i(loc("uFirstSample"), first ? 1 : 0);
    GLint group[3]; /* sdf.comp's local size */
    glGetProgramiv(state->prog, GL_COMPUTE_WORK_GROUP_SIZE, group);
    int rows = compute_tile_pixels / state->width;
    rows = rows < group[1] ? group[1] : rows / group[1] * group[1];
    for (int y = y0; y < y1; y += rows) {
        int h = y1 - y < rows ? y1 - y : rows;
        glUniform4i(loc("uRect"), 0, y, state->width, h);
        glDispatchCompute((GLuint)((state->width + group[0] - 1) / group[0]), (GLuint)((h + group[1] - 1) / group[1]), 1);
        if (y + rows < y1)
            glFlush(); /* the GPU starts on this tile while the next is queued */
    }
    /* the targets are read next as textures (display, edge mask), by blits and by glReadPixels */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

/* Rows [y0, y1) of the current sample (GL rows, bottom up). */
static void sample_rows(int y0, int y1)
{
    assert(state->fbo && state->prog);
    if (state->samples == 0 && state->band_done == 0) {
        state->converged = false;
        state->pixel_samples = 0;
    }
    bool adaptive = masked_sample();
    int rows = y1 - y0, n = state->width * rows;
    state->pixel_samples += adaptive ? (double)state->masked * rows / state->height : (double)n;
    if (adaptive && state->converged)
        return; /* no pixel takes this sample */
    glBindFramebuffer(GL_FRAMEBUFFER, state->fbo);
    glViewport(0, 0, state->width, state->height);
    bool first = state->samples == 0;
    if (first && state->band_done == 0) {
        static const GLenum all[NUM_TARGETS] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                                GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
        glDrawBuffers(NUM_TARGETS, all);
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT);
    }

    glUseProgram(state->prog);
    camera_basis b = camera_get_basis(&state->cam);
    glUniform2f(loc("uResolution"), (float)state->full_width, (float)state->full_height);
    glUniform2f(loc("uTileOffset"), (float)state->tile_x, (float)state->tile_y);
    render_origin_uniforms(state->prog); /* uCamPos relative to the origin: 0 in a deep zoom */
    glUniform3fv(loc("uCamForward"), 1, b.forward);
    glUniform3fv(loc("uCamRight"), 1, b.right);
    glUniform3fv(loc("uCamUp"), 1, b.up);
    glUniform1f(loc("uTanHalfFov"), tanf(0.5f * state->cam.fov_y));
    lens_uniforms(state->samples);
    glUniform1ui(loc("uFxRuntime"), state->runtime_effects);
    glUniform1i(loc("uSampleIndex"), state->samples); /* the path tracer's random numbers */
    glUniform1i(loc("uAdaptive"), adaptive ? 1 : 0);
    glUniform1i(loc("uEdgeMask"), render_scene_units_end());
    int k = first ? state->first_jitter : state->samples; /* Halton point k; 0 is the pixel centre */
    bool jitter = (render_scene_current()->effects & state->runtime_effects & (1u << EFFECT_AA)) && k > 0;
    glUniform2f(loc("uJitter"), jitter ? halton(k, 2) - 0.5f : 0.0f, jitter ? halton(k, 3) - 0.5f : 0.0f);
    render_scene_bind();
    glActiveTexture(GL_TEXTURE0 + (GLenum)render_scene_units_end());
    glBindTexture(GL_TEXTURE_2D, state->mask_tex);
    glActiveTexture(GL_TEXTURE0);
    if (state->backend == BACKEND_COMPUTE)
        dispatch_rows(y0, y1, first);
    else
        draw_rows(y0, y1, first);
}

void render_sample(void)
{
    sample_rows(0, state->height - state->band_done);
    state->samples++;
    state->band_done = 0;
}

int render_band_rows(void) { return state->band_done; }

bool render_sample_band(int rows)
{
    rows = rows < 1 ? 1 : rows;
    int top = state->height - state->band_done, bottom = top - rows > 0 ? top - rows : 0;
    sample_rows(bottom, top);
    state->band_done += top - bottom;
    if (state->band_done < state->height)
        return false;
    state->samples++;
    state->band_done = 0;
    return true;
}

void render_keep_preview(void)
{
    if (!state->samples)
        return;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, state->fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, state->preview_fbo);
    glBlitFramebuffer(0, 0, state->width, state->height, 0, 0, state->width, state->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    state->preview_w = state->width;
    state->preview_h = state->height;
}

bool render_reload(err_t *err)
{
    /* Build everything first: one failure keeps every old program. */
    GLuint display = build_display(err), mask = display ? build_mask(err) : 0;
    GLuint error = mask ? build_error_mask(err) : 0;
    if (!display || !mask || !error || !render_programs_reload(&state->prog, err)) {
        glDeleteProgram(display);
        glDeleteProgram(mask);
        glDeleteProgram(error);
        return false;
    }
    glDeleteProgram(state->display_prog);
    glDeleteProgram(state->mask_prog);
    glDeleteProgram(state->error_prog);
    state->display_prog = display;
    state->mask_prog = mask;
    state->error_prog = error;
    if (render_scene_current())
        render_scene_uniforms(state->prog, render_scene_current());
    state->samples = 0;
    state->band_done = 0;
    return true;
}

void render_release_scene(void) { render_scene_release(); }

bool render_terrain_tiles(int *tiles_x, int *tiles_y) { return res_heightfield_loaded(tiles_x, tiles_y) != NULL; }

const struct droplets *render_droplets(double *read_s, double *grid_s) { return res_droplets_loaded(read_s, grid_s); }
