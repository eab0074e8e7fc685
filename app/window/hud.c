#include "window/hud.h"

#include <epoxy/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/shader.h"
#include <stb_easy_font.h>

enum { MAX_QUADS = 4096, VERTEX_BYTES = 16 /* stb_easy_font: x, y, z floats + 4 colour bytes */ };
static const float PAD = 4.0f;

static struct {
    GLuint prog, vao, vbo, ebo;
    char *verts;
} state;

bool hud_init(err_t *err)
{
    char root[PATH_MAX_LEN];
    snprintf(root, sizeof root, "%s/shaders", util_data_dir());
    state.prog = shader_build(root, "hud.vert", "hud.frag", NULL, NULL, 0, err);
    if (!state.prog)
        return false;
    state.verts = util_alloc((size_t)MAX_QUADS * 4 * VERTEX_BYTES, "the HUD");
    /* Quads → two triangles each, through a fixed index buffer. */
    GLuint *idx = util_alloc(sizeof(GLuint) * MAX_QUADS * 6, "the HUD");
    for (GLuint q = 0; q < MAX_QUADS; q++) {
        GLuint b = q * 4, *o = idx + q * 6;
        o[0] = b, o[1] = b + 1, o[2] = b + 2, o[3] = b, o[4] = b + 2, o[5] = b + 3;
    }
    glGenVertexArrays(1, &state.vao);
    glBindVertexArray(state.vao);
    glGenBuffers(1, &state.vbo);
    glBindBuffer(GL_ARRAY_BUFFER, state.vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)MAX_QUADS * 4 * VERTEX_BYTES, NULL, GL_STREAM_DRAW);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, VERTEX_BYTES, (void *)0);
    glEnableVertexAttribArray(0);
    glGenBuffers(1, &state.ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, state.ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof(GLuint) * MAX_QUADS * 6), idx, GL_STATIC_DRAW);
    free(idx);
    glBindVertexArray(0);
    return true;
}

void hud_shutdown(void)
{
    glDeleteProgram(state.prog);
    glDeleteBuffers(1, &state.vbo);
    glDeleteBuffers(1, &state.ebo);
    glDeleteVertexArrays(1, &state.vao);
    free(state.verts);
    memset(&state, 0, sizeof state);
}

static void draw_quads(int n, const float rgba[4])
{
    glUniform4fv(glGetUniformLocation(state.prog, "uColor"), 1, rgba);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)n * 4 * VERTEX_BYTES, state.verts);
    glDrawElements(GL_TRIANGLES, n * 6, GL_UNSIGNED_INT, NULL);
}

void hud_draw(const char *text, float x, float y, int width, int height, float scale)
{
    if (!state.prog || !text || !*text)
        return;
    char *copy = util_strdup(text);
    int quads = stb_easy_font_print(PAD, PAD, copy, NULL, state.verts, MAX_QUADS * 4 * VERTEX_BYTES);
    float w = (float)stb_easy_font_width(copy) + 2 * PAD, h = (float)stb_easy_font_height(copy) + 2 * PAD;
    free(copy);
    if (y < 0)
        y += (float)height - h * scale;
    for (int i = 0; i < quads * 4; i++) { /* scale about the origin, then move to (x, y) */
        float *v = (float *)(state.verts + i * VERTEX_BYTES);
        v[0] = v[0] * scale + x;
        v[1] = v[1] * scale + y;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(state.prog);
    glUniform2f(glGetUniformLocation(state.prog, "uViewport"), (float)width, (float)height);
    glBindVertexArray(state.vao);
    glBindBuffer(GL_ARRAY_BUFFER, state.vbo);

    /* the panel first, reusing the text buffer's head for its one quad */
    char *text_verts = util_alloc((size_t)quads * 4 * VERTEX_BYTES, "the HUD");
    memcpy(text_verts, state.verts, (size_t)quads * 4 * VERTEX_BYTES);
    float x1 = x + w * scale, y1 = y + h * scale;
    float panel[4][4] = {{x, y, 0, 0}, {x1, y, 0, 0}, {x1, y1, 0, 0}, {x, y1, 0, 0}};
    memcpy(state.verts, panel, sizeof panel);
    static const float panel_rgba[4] = {0.0f, 0.0f, 0.0f, 0.55f}, text_rgba[4] = {1.0f, 1.0f, 0.85f, 1.0f};
    draw_quads(1, panel_rgba);
    memcpy(state.verts, text_verts, (size_t)quads * 4 * VERTEX_BYTES);
    free(text_verts);
    draw_quads(quads, text_rgba);
    glDisable(GL_BLEND);
}
