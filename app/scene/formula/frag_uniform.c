/* frag_uniform — a fragment's annotated uniforms as formula parameters (frag.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "scene/formula/frag_internal.h"

static const struct { const char *glsl; formula_type type; } TYPES[] = {
    {"float", FORMULA_FLOAT}, {"int", FORMULA_INT}, {"bool", FORMULA_BOOL},
    {"vec2", FORMULA_VEC2},   {"vec3", FORMULA_VEC3}, {"vec4", FORMULA_VEC4},
};

/* The three values of slider[LO, DEFAULT, HI] (each a number or, for a vector, a tuple): the range is
 * the smallest that holds every component's ends and the default (Fragmentarium keeps one range a
 * component; 3D.frag's Up is slider[(0,0,0),(0,1,0),(0,0,0)]). */
static bool slider(const char **p, formula_param *q)
{
    int comps = formula_components(q->type);
    float lo[4], hi[4];
    if (!frag_numbers(p, lo, comps) || *(*p)++ != ',' || !frag_numbers(p, q->def, comps) || *(*p)++ != ',' ||
        !frag_numbers(p, hi, comps))
        return false;
    q->lo = INFINITY, q->hi = -INFINITY;
    for (int i = 0; i < comps; i++)
        q->lo = fminf(q->lo, fminf(fminf(lo[i], hi[i]), q->def[i])),
        q->hi = fmaxf(q->hi, fmaxf(fmaxf(lo[i], hi[i]), q->def[i]));
    if (q->type == FORMULA_INT && (q->def[0] != floorf(q->def[0]) || q->lo != floorf(q->lo) || q->hi != floorf(q->hi)))
        return false;
    return q->lo < q->hi || q->type != FORMULA_FLOAT;
}

/* color[R,G,B] (a vec3) or color[LO,DEFAULT,HI,R,G,B] (a vec4: RGB, and the intensity in w). */
static bool color(const char **p, formula_param *q)
{
    float v[6];
    if (q->type == FORMULA_VEC3) {
        q->type = FORMULA_COLOR, q->lo = 0, q->hi = 1;
        return frag_numbers(p, q->def, 3);
    }
    if (q->type != FORMULA_VEC4 || !frag_numbers(p, v, 6))
        return false;
    q->type = FORMULA_COLOR4;
    q->def[0] = v[3], q->def[1] = v[4], q->def[2] = v[5], q->def[3] = v[1];
    q->lo = fminf(v[0], v[1]), q->hi = fmaxf(v[2], v[1]);
    return true;
}

/* The annotation after "uniform T NAME;": into q, and whether it is Locked. */
static bool annotation(const char *a, formula_param *q, const char **why)
{
    const char *p = frag_skip(a);
    size_t w = strspn(p, "abcdefghijklmnopqrstuvwxyz");
    const char *open = frag_skip(p + w);
    if (*open != '[')
        return *why = "expected slider[...], checkbox[...] or color[...] after the uniform", false;
    const char *args = open + 1;
    bool ok;
    if (w == 6 && !strncmp(p, "slider", 6)) {
        ok = q->type != FORMULA_BOOL && slider(&args, q);
        *why = "expected slider[LO,DEFAULT,HI] (a vector's as (x,y,..) tuples) with LO < HI";
    } else if (w == 8 && !strncmp(p, "checkbox", 8)) {
        const char *v = frag_skip(args);
        ok = q->type == FORMULA_BOOL && (!strncmp(v, "true", 4) || !strncmp(v, "false", 5));
        q->def[0] = ok && v[0] == 't', q->lo = 0, q->hi = 1;
        args = frag_skip(v + (v[0] == 't' ? 4 : 5));
        *why = "expected checkbox[true] or checkbox[false] on a bool";
    } else if (w == 5 && !strncmp(p, "color", 5)) {
        ok = color(&args, q);
        *why = "expected color[R,G,B] on a vec3 or color[LO,DEFAULT,HI,R,G,B] on a vec4";
    } else if (w == 4 && !strncmp(p, "file", 4)) {
        return *why = "file[...] names a texture: it goes on a sampler2D or a samplerCube", false;
    } else {
        return *why = "unknown annotation (known: slider, checkbox, color)", false;
    }
    if (!ok || *frag_skip(args) != ']')
        return false;
    const char *rest = frag_skip(frag_skip(args) + 1);
    q->locked = !strncmp(rest, "Locked", 6);
    return true;
}

/* The unannotated uniforms a fragment may declare for the host to set: `time` is a parameter (a
 * flight's set track animates it); the rest keep GLSL's zero. */
static bool host_uniform(frag_ctx *x, const char *type, const char *name, formula_param *q)
{
    (void)x;
    if (strcmp(type, "float") || strcmp(name, "time"))
        return false;
    *q = (formula_param){.type = FORMULA_FLOAT, .lo = 0, .hi = 1e5f};
    snprintf(q->description, sizeof q->description, "Fragmentarium's time in seconds (a flight's set track animates it)");
    return true;
}

/* Adds q (named NAME) to the formula: an int named Iterations is the fractal block's iterations. */
static bool add_param(frag_ctx *x, formula_param *q, const char *name, bool *iterations, const char **why)
{
    formula *f = x->f;
    *iterations = q->type == FORMULA_INT && !strcmp(name, "Iterations") && !q->locked;
    if (*iterations) {
        f->iterations_lo = (int)fmaxf(1, q->lo), f->iterations_hi = (int)fminf(1000, fmaxf(q->hi, 1));
        f->iterations = (int)fminf(fmaxf(q->def[0], (float)f->iterations_lo), (float)f->iterations_hi);
        return true;
    }
    _Static_assert(FORMULA_MAX_PARAMS == 160, "the message below names the limit");
    static const char *const reserved[] = {FORMULA_COMMON_KEYS};
    for (size_t i = 0; i < sizeof reserved / sizeof *reserved; i++)
        if (!strcmp(reserved[i], name))
            return *why = "the name of a key of every fractal block: fathom cannot take it", false;
    for (int i = 0; i < f->param_count; i++)
        if (!strcmp(f->params[i].key, name))
            return *why = "declared twice", false;
    if (f->param_count == FORMULA_MAX_PARAMS)
        return *why = "more parameters than fathom's limit of 160", false;
    snprintf(q->key, sizeof q->key, "%s", name);
    snprintf(q->uniform, sizeof q->uniform, "%s", name);
    snprintf(q->group, sizeof q->group, "%s", x->group);
    if (!q->description[0])
        snprintf(q->description, sizeof q->description, "%s", x->comment[0] ? x->comment : name);
    f->params[f->param_count++] = *q;
    return true;
}

/* The image formats a fragment's texture may be (read through OpenImageIO: data/media/image_io.h). */
static bool image_file(const char *path)
{
    static const char *const EXT[] = {".png", ".jpg", ".jpeg", ".hdr", ".exr", ".tga", ".bmp", ".tif", ".tiff"};
    const char *dot = strrchr(path, '.');
    for (size_t i = 0; dot && i < sizeof EXT / sizeof *EXT; i++)
        if (!strcasecmp(dot, EXT[i]))
            return true;
    return false;
}

/* "uniform sampler2D NAME; file[PATH]" (or samplerCube): the texture, found as an include is found. */
static bool texture_uniform(frag_ctx *x, const char *type, const char *name, const char *a, strbuf *out,
                            const char **why)
{
    formula *f = x->f;
    char rel[PATH_MAX_LEN];
    const char *open = strncmp(a, "file", 4) ? NULL : frag_skip(a + 4);
    const char *close = open && *open == '[' ? strchr(open, ']') : NULL;
    if (!close)
        return *why = "expected file[IMAGE] after the sampler", false;
    snprintf(rel, sizeof rel, "%.*s", (int)(close - open - 1), frag_skip(open + 1));
    for (char *e = rel + strlen(rel); e > rel && (e[-1] == ' ' || e[-1] == '\t'); e--)
        e[-1] = '\0';
    if (f->frag_texture_count == FRAG_TEXTURES_MAX)
        return *why = "more textures than fathom's limit of 4", false;
    if (!image_file(rel))
        return *why = "not an image file (.png, .jpg, .hdr, .exr, .tga, .bmp, .tif)", false;
    frag_texture *t = &f->frag_textures[f->frag_texture_count];
    if (!frag_find_file(x, rel, x->root, t->path, sizeof t->path, why)) {
        if (!strcmp(*why, "no such file"))
            *why = "no such file in the fragment's folder or its collection's Include folder";
        return false;
    }
    snprintf(t->name, sizeof t->name, "%s", name);
    t->cube = !strcmp(type, "samplerCube");
    f->frag_texture_count++;
    sb_printf(out, "uniform %s %s;\n", type, name);
    return true;
}

void frag_texparameter(frag_ctx *x, const char *args)
{
    formula *f = x->f;
    char w[3][FRAG_TEXPARAM_MAX];
    if (f->frag_texparam_count < FRAG_TEXPARAMS_MAX && sscanf(args, " %39s %39s %39s", w[0], w[1], w[2]) == 3)
        memcpy(f->frag_texparams[f->frag_texparam_count++], w, sizeof w);
}

bool frag_uniform(frag_ctx *x, const char *line, const char *code, const char *shown, int n, strbuf *out)
{
    char type[16], name[FORMULA_KEY_MAX];
    int end = 0;
    if (sscanf(code, "uniform %15s %47[A-Za-z0-9_] ;%n", type, name, &end) != 2 || end == 0) {
        sb_printf(out, "%s\n", line); /* not one uniform with a name: GLSL's to judge */
        return true;
    }
    static const char *const CAMERA[][3] = {/* 3D.frag's camera, which the host sets: fathom's camera */
        {"vec3", "Eye", "uCamPos"}, {"vec3", "Target", "(uCamPos + uCamForward * uFocus)"}, {"vec3", "Up", "uCamUp"},
        {"float", "FOV", "uTanHalfFov"}};
    for (size_t i = 0; i < sizeof CAMERA / sizeof *CAMERA; i++)
        if (!strcmp(type, CAMERA[i][0]) && !strcmp(name, CAMERA[i][1])) {
            sb_printf(out, "#define %s %s\n", name, CAMERA[i][2]);
            frag_add_name(&x->macros, name, strlen(name));
            return true;
        }
    formula_param q = {0};
    const char *why = "";
    bool typed = false;
    for (size_t i = 0; i < sizeof TYPES / sizeof *TYPES; i++)
        if (!strcmp(type, TYPES[i].glsl))
            q.type = TYPES[i].type, typed = true;
    const char *a = frag_skip(code + end);
    if (!*a || *a == ';') { /* no annotation */
        if (!strcmp(type, "vec2") && !strcmp(name, "pixelSize")) { /* 3D.frag's: the host's (frag/raytracer.frag) */
            sb_printf(out, "\n");
            return true;
        }
        if (!typed || !host_uniform(x, type, name, &q)) {
            sb_printf(out, "%s\n", line);
            return true;
        }
    } else if (!typed && (!strcmp(type, "sampler2D") || !strcmp(type, "samplerCube"))) {
        return texture_uniform(x, type, name, a, out, &why) ||
               err_set(x->err, "%s:%d: texture '%s': %s%s", shown, n, name, why, x->chain);
    } else if (!typed) {
        return err_set(x->err, "%s:%d: '%s %s': a parameter is a float, int, bool, vec2, vec3 or vec4%s", shown, n,
                       type, name, x->chain);
    } else if (!annotation(a, &q, &why)) {
        return err_set(x->err, "%s:%d: '%s': %s%s", shown, n, name, why, x->chain);
    }
    bool iterations;
    if (!add_param(x, &q, name, &iterations, &why))
        return err_set(x->err, "%s:%d: parameter '%s': %s%s", shown, n, name, why, x->chain);
    if (iterations) /* a loop bound the compiler sees, as every formula's (fractal/iterate.glsl) */
        sb_printf(out, "const int Iterations = FRACTAL_ITERATIONS;\n");
    else if (q.locked) /* its value is a #define of the preamble (scene_fractal_defines) */
        sb_printf(out, "const %s %s = FRAG_LOCKED_%s;\n", type, name, name);
    else
        sb_printf(out, "uniform %s %s;\n", type, name);
    return true;
}

void frag_widen_to_presets(const char *text, formula *f)
{
    char line[256]; /* a preset line (frag_presets.c reads them as long) */
    bool in = false;
    for (const char *p = text; frag_next_line(&p, line, sizeof line);) {
        const char *c = frag_skip(line), *eq = strchr(c, '=');
        in = in ? strncmp(c, "#endpreset", 10) != 0 : !strncmp(c, "#preset", 7);
        if (!in || !eq)
            continue;
        int k = (int)(eq - c);
        while (k > 0 && (c[k - 1] == ' ' || c[k - 1] == '\t'))
            k--;
        for (int i = 0; i < f->param_count; i++) {
            formula_param *q = &f->params[i];
            double v[4];
            int n = (int)strlen(q->key) == k && !strncmp(q->key, c, (size_t)k) && q->type != FORMULA_BOOL &&
                            q->type != FORMULA_COLOR
                        ? frag_values(frag_skip(eq + 1), v, 4)
                        : 0;
            for (int j = q->type == FORMULA_COLOR4 ? 3 : 0; j < n && j < formula_components(q->type); j++)
                q->lo = fminf(q->lo, (float)v[j]), q->hi = fmaxf(q->hi, (float)v[j]);
        }
    }
}
