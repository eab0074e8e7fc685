/* uniforms — named shader uniforms as plain data, so the pure side can say what a program reads and
 * the GL side (render_scene.c) can upload it. A sink receives (name, type, components, count, data);
 * helpers below keep call sites short. Names are the GLSL names ("uTerrainSpacing"). */
#ifndef FATHOM_UNIFORMS_H
#define FATHOM_UNIFORMS_H

typedef enum uniform_type { UNIFORM_FLOAT, UNIFORM_INT } uniform_type;

typedef struct uniform_sink {
    /* comps: 1–4 (float, vec2 … vec4 / int, ivec2 …); count: array length; data: count·comps values */
    void (*set)(void *user, const char *name, uniform_type type, int comps, int count, const void *data);
    void *user;
} uniform_sink;

static inline void uniform_f(const uniform_sink *u, const char *name, float v)
{
    u->set(u->user, name, UNIFORM_FLOAT, 1, 1, &v);
}
static inline void uniform_i(const uniform_sink *u, const char *name, int v)
{
    u->set(u->user, name, UNIFORM_INT, 1, 1, &v);
}
static inline void uniform_fv(const uniform_sink *u, const char *name, int comps, int count, const float *v)
{
    u->set(u->user, name, UNIFORM_FLOAT, comps, count, v);
}
static inline void uniform_iv(const uniform_sink *u, const char *name, int comps, int count, const int *v)
{
    u->set(u->user, name, UNIFORM_INT, comps, count, v);
}

#endif
