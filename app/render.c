#include "render.h"

#include <assert.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "aov.h"
#include "shader.h"
#include "terrain.h"
#include "texture.h"

enum { MAX_PROGRAMS = 64, NUM_TARGETS = 3 };

typedef struct cached_program {
    program_kind kind;
    const char *frag;     /* sdf.frag (the image), probe.frag (map() at points), fogprobe.frag */
    char *preamble, *map; /* the key */
    GLuint prog;
} cached_program;

static struct {
    GLuint vao, display_prog;
    GLuint fbo, targets[NUM_TARGETS];
    GLuint out_fbo, out_tex; /* RGBA8 for sRGB readback */
    GLuint ref_fbo, ref_tex; /* a grabbed image for the difference view */
    int ref_samples;
    int width, height, samples;
    cached_program programs[MAX_PROGRAMS];
    int program_count;
    GLuint prog; /* current scene program */
    const scene *scene;
    GLuint textures[SCENE_MAX_TEXTURES], envmap;
    int texture_width[SCENE_MAX_TEXTURES]; /* heightmaps: texels across (relief step size) */
    GLuint height_tex, height_max_tex; /* terrain: heights, max pyramid */
    heightfield hf;
    int env_size;
    camera cam;
    unsigned runtime_effects; /* effects switched on at run time (bits as in variant.h) */
} state = {.runtime_effects = ~0u};

static char shader_root[PATH_MAX_LEN];

static GLuint build_display(err_t *err)
{
    return shader_build(shader_root, "fullscreen.vert", "display.frag", NULL, NULL, 0, err);
}

bool render_init(err_t *err)
{
    snprintf(shader_root, sizeof shader_root, "%s/shaders", util_data_dir());
    glGenVertexArrays(1, &state.vao); /* core profile draws nothing without a bound VAO */
    glBindVertexArray(state.vao);
    state.display_prog = build_display(err);
    return state.display_prog != 0;
}

static void free_targets(void)
{
    if (state.fbo) {
        glDeleteFramebuffers(1, &state.fbo);
        glDeleteTextures(NUM_TARGETS, state.targets);
        glDeleteFramebuffers(1, &state.out_fbo);
        glDeleteTextures(1, &state.out_tex);
        glDeleteFramebuffers(1, &state.ref_fbo);
        glDeleteTextures(1, &state.ref_tex);
        state.fbo = state.out_fbo = state.ref_fbo = state.ref_tex = 0;
        state.ref_samples = 0;
    }
}

static void free_scene_textures(void)
{
    if (state.height_tex) {
        glDeleteTextures(1, &state.height_tex);
        glDeleteTextures(1, &state.height_max_tex);
        state.height_tex = state.height_max_tex = 0;
        heightfield_free(&state.hf);
    }
    glDeleteTextures(SCENE_MAX_TEXTURES, state.textures);
    memset(state.textures, 0, sizeof state.textures);
    if (state.envmap)
        glDeleteTextures(1, &state.envmap);
    state.envmap = 0;
}

void render_set_runtime_effects(unsigned mask) { state.runtime_effects = mask; }

void render_shutdown(void)
{
    free_targets();
    free_scene_textures();
    for (int i = 0; i < state.program_count; i++) {
        glDeleteProgram(state.programs[i].prog);
        free(state.programs[i].preamble);
        free(state.programs[i].map);
    }
    glDeleteProgram(state.display_prog);
    glDeleteVertexArrays(1, &state.vao);
    memset(&state, 0, sizeof state);
    state.runtime_effects = ~0u;
}

void render_preamble(const scene *s, const char *extra_defines, strbuf *out)
{
    variant v = scene_variant(s);
    variant_preamble(&v, out);
    if (extra_defines)
        sb_append(out, extra_defines);
}

static GLuint build_scene_program(const char *frag, const char *preamble, const char *map, err_t *err)
{
    shader_virtual virt[] = {{"program.glsl", map}};
    return shader_build(shader_root, "fullscreen.vert", frag, preamble, virt, 1, err);
}

/* The cached program for (kind, fragment shader, preamble, map), compiled on first use. */
static GLuint get_program(const scene *s, const char *frag, const char *extra_defines, err_t *err)
{
    strbuf pre = {0};
    render_preamble(s, extra_defines, &pre);
    for (int i = 0; i < state.program_count; i++) {
        cached_program *c = &state.programs[i];
        if (c->kind == s->program && !strcmp(c->frag, frag) && !strcmp(c->preamble, pre.data) && !strcmp(c->map, s->map_glsl)) {
            sb_free(&pre);
            return c->prog;
        }
    }
    GLuint prog = build_scene_program(frag, pre.data, s->map_glsl, err);
    if (!prog) {
        sb_free(&pre);
        return 0;
    }
    if (state.program_count == MAX_PROGRAMS) { /* evict the oldest */
        glDeleteProgram(state.programs[0].prog);
        free(state.programs[0].preamble);
        free(state.programs[0].map);
        memmove(state.programs, state.programs + 1, sizeof state.programs[0] * (MAX_PROGRAMS - 1));
        state.program_count--;
    }
    state.programs[state.program_count++] = (cached_program){
        .kind = s->program, .frag = frag, .preamble = pre.data, .map = strdup(s->map_glsl), .prog = prog};
    return prog;
}

static GLuint float_texture(int w, int h, const float *data, int levels, float *const *mips)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (data)
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, w, h, 0, GL_RED, GL_FLOAT, data);
    for (int k = 0; k < levels; k++) {
        int lw = w >> k, lh = h >> k;
        glTexImage2D(GL_TEXTURE_2D, k, GL_R32F, lw > 0 ? lw : 1, lh > 0 ? lh : 1, 0, GL_RED, GL_FLOAT, mips[k]);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels > 0 ? levels - 1 : 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

/* Terrain: heights (exact texelFetch, bilinear done in the shader) and the max pyramid. */
static bool upload_terrain(const scene *s, err_t *err)
{
    heightfield_desc d = {.path = s->terrain.heightmap, .spacing = {s->terrain.spacing[0], s->terrain.spacing[1]},
                          .height_min = s->terrain.height_min, .height_max = s->terrain.height_max,
                          .exaggeration = s->terrain.exaggeration};
    if (!heightfield_load(&d, &state.hf, err))
        return false;
    state.height_tex = float_texture(state.hf.width, state.hf.height, state.hf.h, 0, NULL);
    state.height_max_tex = float_texture(state.hf.pw, state.hf.ph, NULL, state.hf.levels, state.hf.max);
    return true;
}

/* The noise terrain's parameters and its distance bound (shaders/terrain/noise.glsl). */
static void upload_noise_uniforms(GLuint prog, const scene *s)
{
    const struct scene_terrain *t = &s->terrain;
    const float QUINTIC_SLOPE = 30.0f / 16.0f, SQRT3 = 1.7320508f;
    float grad = 0, amp = 0.5f, freq = t->frequency;
    for (int o = 0; o < t->octaves; o++, amp *= 0.5f, freq *= 2.0f)
        grad += amp * freq * QUINTIC_SLOPE * SQRT3;
    glUseProgram(prog);
    glUniform4f(glGetUniformLocation(prog, "uNoise"), t->base, t->amplitude, t->frequency, (float)t->octaves);
    glUniform1f(glGetUniformLocation(prog, "uNoiseBound"), 1.0f / (1.0f + t->amplitude * grad));
    glUniform4f(glGetUniformLocation(prog, "uTerrainRange"), t->base, t->base + t->amplitude, 1.0f, 0.0f);
}

static void upload_layer_uniforms(GLuint prog, const scene *s)
{
    glUseProgram(prog);
    glUniform3f(glGetUniformLocation(prog, "uTerrainLayers"), s->terrain.sand_line, s->terrain.snow_line,
                s->terrain.grass_slope);
    static const char *const layers[4] = {"sand", "grass", "rock", "snow"};
    int idx[4];
    for (int l = 0; l < 4; l++) {
        idx[l] = -1;
        for (int m = 0; m < s->material_count; m++)
            if (!strcmp(s->materials[m].name, layers[l]))
                idx[l] = m;
    }
    if (idx[2] < 0) /* rock is the fallback layer: the first material */
        idx[2] = 0;
    for (int l = 0; l < 4; l++)
        idx[l] = idx[l] < 0 ? idx[2] : idx[l];
    glUniform4i(glGetUniformLocation(prog, "uLayerMaterial"), idx[0], idx[1], idx[2], idx[3]);
}

static void upload_terrain_uniforms(GLuint prog)
{
    const heightfield *hf = &state.hf;
    glUseProgram(prog);
    glUniform1i(glGetUniformLocation(prog, "uHeight"), SCENE_MAX_TEXTURES + 1);
    glUniform1i(glGetUniformLocation(prog, "uHeightMax"), SCENE_MAX_TEXTURES + 2);
    glUniform4f(glGetUniformLocation(prog, "uTerrainGrid"), hf->x0, hf->z0, hf->dx, hf->dz);
    glUniform4f(glGetUniformLocation(prog, "uTerrainRange"), hf->hmin, hf->hmax,
                1.0f / sqrtf(1.0f + hf->lipschitz * hf->lipschitz), (float)(hf->levels - 1));
    glUniform2i(glGetUniformLocation(prog, "uTerrainSize"), hf->width, hf->height);
}

/* Fractal parameters; a uniform the program does not use has location −1 and is ignored by GL. */
static void upload_fractal_uniforms(GLuint prog, const scene *s)
{
    const scene_fractal *f = &s->fractal;
    glUseProgram(prog);
    glUniform4f(glGetUniformLocation(prog, "uFractalA"), f->power, f->bailout, f->scale, f->min_radius);
    glUniform4f(glGetUniformLocation(prog, "uFractalB"), f->fixed_radius, f->fold_limit, f->bound_radius, f->size);
    glUniform3fv(glGetUniformLocation(prog, "uPalette"), 3, &f->palette[0][0]);
    glUniform4f(glGetUniformLocation(prog, "uGlow"), f->glow_color[0], f->glow_color[1], f->glow_color[2], f->glow);
}

static GLint loc(const char *name) { return glGetUniformLocation(state.prog, name); }

/* Scene constants: materials, lights, environment, fog, texture units. */
static void upload_scene_uniforms(void)
{
    const scene *s = state.scene;
    glUseProgram(state.prog);
    float base[SCENE_MAX_MATERIALS][4], params[SCENE_MAX_MATERIALS][4], absorb[SCENE_MAX_MATERIALS][4],
        emit[SCENE_MAX_MATERIALS][3];
    for (int i = 0; i < s->material_count; i++) {
        const scene_material *m = &s->materials[i];
        memcpy(base[i], m->base_color, sizeof m->base_color);
        base[i][3] = m->metallic;
        params[i][0] = m->roughness;
        params[i][1] = m->transmission;
        params[i][2] = m->ior;
        params[i][3] = (float)m->texture;
        memcpy(absorb[i], m->absorption, sizeof m->absorption);
        absorb[i][3] = m->uv_scale;
        memcpy(emit[i], m->emission, sizeof m->emission);
    }
    glUniform4fv(loc("uMatBase"), s->material_count, &base[0][0]);
    glUniform4fv(loc("uMatParams"), s->material_count, &params[0][0]);
    glUniform4fv(loc("uMatAbsorb"), s->material_count, &absorb[0][0]);
    glUniform3fv(loc("uMatEmission"), s->material_count, &emit[0][0]);
    float relief[SCENE_MAX_MATERIALS][4];
    for (int i = 0; i < s->material_count; i++) {
        const scene_material *m = &s->materials[i];
        relief[i][0] = (float)m->relief;
        relief[i][1] = m->relief_depth;
        relief[i][2] = m->relief >= 0 ? (float)state.texture_width[m->relief] : 1.0f;
        relief[i][3] = 0;
    }
    glUniform4fv(loc("uMatRelief"), s->material_count, &relief[0][0]);

    float lvec[SCENE_MAX_LIGHTS][4], lcol[SCENE_MAX_LIGHTS][4], lsoft[SCENE_MAX_LIGHTS];
    for (int i = 0; i < s->light_count; i++) {
        const scene_light *l = &s->lights[i];
        memcpy(lvec[i], l->vec, sizeof l->vec);
        lvec[i][3] = l->type == LIGHT_DIRECTIONAL ? 1.0f : 0.0f;
        for (int k = 0; k < 3; k++)
            lcol[i][k] = l->color[k] * l->intensity;
        lcol[i][3] = (float)l->shadow;
        lsoft[i] = l->softness;
    }
    if (s->light_count > 0) {
        glUniform4fv(loc("uLightVec"), s->light_count, &lvec[0][0]);
        glUniform4fv(loc("uLightColor"), s->light_count, &lcol[0][0]);
        glUniform1fv(loc("uLightSoftness"), s->light_count, lsoft);
    }
    float env[3];
    for (int k = 0; k < 3; k++)
        env[k] = s->env_color[k] * s->env_intensity;
    glUniform3fv(loc("uEnvColor"), 1, env);
    glUniform3fv(loc("uFogColor"), 1, s->fog_color);
    glUniform3f(loc("uFog"), s->fog_density, s->fog_falloff, s->fog_height);
    static const char *const tex_names[SCENE_MAX_TEXTURES] = {"uTex0", "uTex1", "uTex2", "uTex3"};
    for (int i = 0; i < SCENE_MAX_TEXTURES; i++)
        glUniform1i(loc(tex_names[i]), i);
    glUniform1i(loc("uEnvMap"), SCENE_MAX_TEXTURES);
    glUniform1f(loc("uEnvMaxLod"), state.env_size > 0 ? log2f((float)state.env_size) : 0.0f);
    upload_fractal_uniforms(state.prog, s);
    if (state.height_tex)
        upload_terrain_uniforms(state.prog);
    if (s->program == PROGRAM_NOISE)
        upload_noise_uniforms(state.prog, s);
    if (s->program == PROGRAM_TERRAIN || s->program == PROGRAM_NOISE)
        upload_layer_uniforms(state.prog, s);
}

bool render_set_scene(const scene *s, const char *extra_defines, err_t *err)
{
    GLuint prog = get_program(s, "sdf.frag", extra_defines, err);
    if (!prog)
        return false;

    free_scene_textures();
    for (int i = 0; i < s->texture_count; i++) {
        int w = 0;
        state.textures[i] = s->texture_linear[i] ? texture_load_height(s->textures[i], &w, err)
                                                 : texture_load_2d(s->textures[i], err);
        state.texture_width[i] = w;
        if (!state.textures[i])
            return false;
    }
    if (s->program == PROGRAM_TERRAIN && !upload_terrain(s, err))
        return false;
    state.env_size = 0;
    if (s->has_cubemap && (s->effects & (1u << EFFECT_ENVMAP))) {
        state.envmap = texture_load_cube(s->cubemap, &state.env_size, err);
        if (!state.envmap)
            return false;
    }
    state.prog = prog;
    state.scene = s;
    upload_scene_uniforms();
    return true;
}

void render_resize(int width, int height)
{
    assert(width > 0 && height > 0);
    if (state.fbo && width == state.width && height == state.height)
        return;
    free_targets();
    state.width = width;
    state.height = height;
    glGenFramebuffers(1, &state.fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, state.fbo);
    glGenTextures(NUM_TARGETS, state.targets);
    for (int i = 0; i < NUM_TARGETS; i++) {
        glBindTexture(GL_TEXTURE_2D, state.targets[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)i, GL_TEXTURE_2D, state.targets[i], 0);
    }
    assert(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    glGenFramebuffers(1, &state.out_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, state.out_fbo);
    glGenTextures(1, &state.out_tex);
    glBindTexture(GL_TEXTURE_2D, state.out_tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, state.out_tex, 0);
    assert(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    state.samples = 0;
}

void render_begin(const camera *c)
{
    state.cam = *c;
    state.samples = 0;
}

int render_samples(void) { return state.samples; }

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

void render_sample(void)
{
    assert(state.fbo && state.prog);
    glBindFramebuffer(GL_FRAMEBUFFER, state.fbo);
    glViewport(0, 0, state.width, state.height);
    static const GLenum all[NUM_TARGETS] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    static const GLenum colour_only[NUM_TARGETS] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE};
    bool first = state.samples == 0;
    glDrawBuffers(NUM_TARGETS, first ? all : colour_only);
    if (first) {
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    glEnablei(GL_BLEND, 0);
    glBlendFunc(GL_ONE, GL_ONE);
    glDisablei(GL_BLEND, 1);
    glDisablei(GL_BLEND, 2);

    glUseProgram(state.prog);
    camera_basis b = camera_get_basis(&state.cam);
    glUniform2f(loc("uResolution"), (float)state.width, (float)state.height);
    glUniform3fv(loc("uCamPos"), 1, state.cam.position);
    glUniform3fv(loc("uCamForward"), 1, b.forward);
    glUniform3fv(loc("uCamRight"), 1, b.right);
    glUniform3fv(loc("uCamUp"), 1, b.up);
    glUniform1f(loc("uTanHalfFov"), tanf(0.5f * state.cam.fov_y));
    glUniform1f(loc("uPixelAngle"), camera_pixel_angle(&state.cam, state.height));
    glUniform1ui(loc("uFxRuntime"), state.runtime_effects);
    bool jitter = (state.scene->effects & state.runtime_effects & (1u << EFFECT_AA)) && !first;
    glUniform2f(loc("uJitter"), jitter ? halton(state.samples, 2) - 0.5f : 0.0f,
                jitter ? halton(state.samples, 3) - 0.5f : 0.0f);
    for (int i = 0; i < SCENE_MAX_TEXTURES; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)i);
        glBindTexture(GL_TEXTURE_2D, state.textures[i]);
    }
    glActiveTexture(GL_TEXTURE0 + SCENE_MAX_TEXTURES);
    glBindTexture(GL_TEXTURE_CUBE_MAP, state.envmap);
    glActiveTexture(GL_TEXTURE0 + SCENE_MAX_TEXTURES + 1);
    glBindTexture(GL_TEXTURE_2D, state.height_tex);
    glActiveTexture(GL_TEXTURE0 + SCENE_MAX_TEXTURES + 2);
    glBindTexture(GL_TEXTURE_2D, state.height_max_tex);
    glActiveTexture(GL_TEXTURE0);

    glBindVertexArray(state.vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisablei(GL_BLEND, 0);
    state.samples++;
}

void render_grab_reference(void)
{
    if (!state.ref_tex) {
        glGenTextures(1, &state.ref_tex);
        glBindTexture(GL_TEXTURE_2D, state.ref_tex);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, state.width, state.height, 0, GL_RGBA, GL_FLOAT, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glGenFramebuffers(1, &state.ref_fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, state.ref_fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, state.ref_tex, 0);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, state.fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, state.ref_fbo);
    glDrawBuffers(1, (const GLenum[]){GL_COLOR_ATTACHMENT0});
    glBlitFramebuffer(0, 0, state.width, state.height, 0, 0, state.width, state.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    state.ref_samples = state.samples;
}

void render_display(GLuint fbo, int width, int height, float exposure, render_view view)
{
    GLuint p = state.display_prog;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, width, height);
    glUseProgram(p);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, state.targets[2]);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, state.targets[0]);
    glUniform1i(glGetUniformLocation(p, "uAccum"), 0);
    glUniform1i(glGetUniformLocation(p, "uAux"), 1);
    if (view == VIEW_DIFFERENCE && !state.ref_samples)
        view = VIEW_COLOR; /* nothing grabbed yet */
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, state.ref_tex);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(glGetUniformLocation(p, "uReference"), 2);
    glUniform1f(glGetUniformLocation(p, "uInvRefSamples"), state.ref_samples ? 1.0f / (float)state.ref_samples : 0.0f);
    glUniform1i(glGetUniformLocation(p, "uView"), (GLint)view);
    glUniform1f(glGetUniformLocation(p, "uMaxSteps"), state.scene ? (float)state.scene->quality.max_steps : 1.0f);
    glUniform1f(glGetUniformLocation(state.display_prog, "uInvSamples"),
                state.samples > 0 ? 1.0f / (float)state.samples : 0.0f);
    glUniform1f(glGetUniformLocation(state.display_prog, "uExposure"), exposure);
    glBindVertexArray(state.vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

/* GL rows run bottom to top; files run top to bottom. */
static void flip_rows(void *data, int height, size_t row_bytes)
{
    uint8_t *p = data, *tmp = malloc(row_bytes);
    assert(tmp);
    for (int y = 0; y < height / 2; y++) {
        uint8_t *a = p + (size_t)y * row_bytes, *b = p + (size_t)(height - 1 - y) * row_bytes;
        memcpy(tmp, a, row_bytes);
        memcpy(a, b, row_bytes);
        memcpy(b, tmp, row_bytes);
    }
    free(tmp);
}

static void read_target(GLuint fbo, GLenum attachment, GLenum type, void *out)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadBuffer(attachment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, state.width, state.height, GL_RGBA, type, out);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

void render_read_srgb8(uint8_t *rgba, float exposure)
{
    render_display(state.out_fbo, state.width, state.height, exposure, VIEW_COLOR);
    read_target(state.out_fbo, GL_COLOR_ATTACHMENT0, GL_UNSIGNED_BYTE, rgba);
    flip_rows(rgba, state.height, (size_t)state.width * 4);
}

void render_read_linear(float *rgba)
{
    read_target(state.fbo, GL_COLOR_ATTACHMENT0, GL_FLOAT, rgba);
    size_t n = (size_t)state.width * (size_t)state.height * 4;
    float inv = state.samples > 0 ? 1.0f / (float)state.samples : 0.0f;
    for (size_t i = 0; i < n; i++)
        rgba[i] *= inv;
    flip_rows(rgba, state.height, (size_t)state.width * 4 * sizeof(float));
}

void render_read_aovs(float *aov8)
{
    size_t n = (size_t)state.width * (size_t)state.height;
    float *a = malloc(sizeof(float) * 4 * n), *b = malloc(sizeof(float) * 4 * n);
    assert(a && b);
    read_target(state.fbo, GL_COLOR_ATTACHMENT1, GL_FLOAT, a);
    read_target(state.fbo, GL_COLOR_ATTACHMENT2, GL_FLOAT, b);
    for (size_t i = 0; i < n; i++) {
        memcpy(aov8 + i * AOV_FLOATS, a + i * 4, sizeof(float) * 4);
        memcpy(aov8 + i * AOV_FLOATS + 4, b + i * 4, sizeof(float) * 4);
        if (aov8[i * AOV_FLOATS + AOV_SLOT_DEPTH] < 0.0f) /* the shader marks a miss with depth −1 */
            aov8[i * AOV_FLOATS + AOV_SLOT_DEPTH] = INFINITY;
    }
    free(a);
    free(b);
    flip_rows(aov8, state.height, (size_t)state.width * AOV_FLOATS * sizeof(float));
}

bool render_reload(err_t *err)
{
    /* Build everything first: one failure keeps every old program. */
    GLuint fresh[MAX_PROGRAMS];
    GLuint display = build_display(err);
    if (!display)
        return false;
    for (int i = 0; i < state.program_count; i++) {
        cached_program *c = &state.programs[i];
        fresh[i] = build_scene_program(c->frag, c->preamble, c->map, err);
        if (!fresh[i]) {
            for (int k = 0; k < i; k++)
                glDeleteProgram(fresh[k]);
            glDeleteProgram(display);
            return false;
        }
    }
    glDeleteProgram(state.display_prog);
    state.display_prog = display;
    for (int i = 0; i < state.program_count; i++) {
        if (state.programs[i].prog == state.prog)
            state.prog = fresh[i];
        glDeleteProgram(state.programs[i].prog);
        state.programs[i].prog = fresh[i];
    }
    if (state.scene)
        upload_scene_uniforms();
    state.samples = 0;
    return true;
}

bool render_probe(const scene *s, const char *extra_defines, const float *points, int n, float *out, err_t *err)
{
    return render_probe_with(s, "probe.frag", extra_defines, points, n, out, err);
}

bool render_probe_with(const scene *s, const char *frag, const char *extra_defines, const float *points, int n,
                       float *out, err_t *err)
{
    assert(n > 0);
    GLuint prog = get_program(s, frag, extra_defines, err);
    if (!prog)
        return false;
    upload_fractal_uniforms(prog, s);
    glUniform3fv(glGetUniformLocation(prog, "uFogColor"), 1, s->fog_color);
    glUniform3f(glGetUniformLocation(prog, "uFog"), s->fog_density, s->fog_falloff, s->fog_height);
    if (state.height_tex && state.scene == s)
        upload_terrain_uniforms(prog);
    if (s->program == PROGRAM_NOISE)
        upload_noise_uniforms(prog, s);
    glActiveTexture(GL_TEXTURE0 + SCENE_MAX_TEXTURES + 1);
    glBindTexture(GL_TEXTURE_2D, state.height_tex);
    glActiveTexture(GL_TEXTURE0 + SCENE_MAX_TEXTURES + 2);
    glBindTexture(GL_TEXTURE_2D, state.height_max_tex);
    glActiveTexture(GL_TEXTURE0);
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    int w = n < max_side ? n : max_side, h = (n + w - 1) / w;
    float *px = calloc((size_t)w * (size_t)h * 4, sizeof(float));
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
    glBindVertexArray(state.vao);
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
    if (state.prog)
        glUseProgram(state.prog);
    return true;
}

bool render_ground_height(float x, float z, float *height)
{
    if (!state.height_tex)
        return false;
    *height = heightfield_at(&state.hf, x, z);
    return true;
}
