/* scene_programs — the program rows of PROGRAM_LIST (app/scene/program.h): each program's block parser,
 * what it adds to the #define preamble, and its named uniforms (the fractal shaders read them under the
 * names written here): the fractal and torus blocks; the terrain block is scene_terrain.c's. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/formula/frag.h"
#include "scene/scene_parse.h"

/* ---- fractals: the "fractal" block ------------------------------------------------------------ */

/* The palette's three colours as parameters, elements of one array (an edit sets the whole palette:
 * a file without one has no array to index). */
static void record_palette(scene_ctx *c, float pal[3][3])
{
    for (int i = 0; i < 3; i++) {
        char key[8];
        snprintf(key, sizeof key, "%d", i);
        scene_param *p = scene_record_param(c, "fractal.palette", key, PARAM_COLOR,
                                      (const double[3]){pal[i][0], pal[i][1], pal[i][2]}, 0, 1);
        if (p)
            p->array_len = 3, p->array_index = i;
    }
}

static bool get_palette(scene_ctx *c, const cJSON *f, float out[3][3])
{
    static const float def[3][3] = {{0.95f, 0.55f, 0.25f}, {0.25f, 0.45f, 0.75f}, {0.92f, 0.9f, 0.85f}};
    memcpy(out, def, sizeof def);
    const cJSON *pal = cJSON_GetObjectItemCaseSensitive(f, "palette");
    if (!pal) {
        record_palette(c, out);
        return true;
    }
    if (!cJSON_IsArray(pal) || cJSON_GetArraySize(pal) != 3)
        return scene_fail(c, "fractal.palette", "expected three colours [[r,g,b], [r,g,b], [r,g,b]] (near, middle, far)");
    int i = 0;
    for (const cJSON *col = pal->child; col; col = col->next, i++) {
        if (!cJSON_IsArray(col) || cJSON_GetArraySize(col) != 3)
            return scene_fail(c, "fractal.palette", "colour %d: expected [r, g, b]", i);
        for (int k = 0; k < 3; k++) {
            const cJSON *v = cJSON_GetArrayItem(col, k);
            if (!cJSON_IsNumber(v) || v->valuedouble < 0 || v->valuedouble > 1)
                return scene_fail(c, "fractal.palette", "colour %d: expected numbers from 0 to 1", i);
            out[i][k] = (float)v->valuedouble;
        }
    }
    record_palette(c, out);
    return true;
}

static const float WARM[3] = {1.0f, 0.6f, 0.3f};
enum { BLOCK_KEYS_MAX = FORMULA_MAX_PARAMS + 32 }; /* the parameters, the common keys (16) and NULL */
static const float BOUND_MIN = 1e-3f, BOUND_MAX = 1e6f;

/* Keys every fractal reads: the palette, the glow and the hit rule (a fragment's default: its renderer's,
 * Fragmentarium's, with the renderer's Detail and MaxDistance). */
static bool fractal_common(scene_ctx *c, const cJSON *use, scene_fractal *fr)
{
    static const char *const RULES[] = {"footprint", "fragment", NULL}, *const LOOKS[] = {"fathom", "fragment", NULL};
    const formula *f = &fr->formula;
    int rule = HIT_RULE_FOOTPRINT, look = LOOK_FATHOM;
    bool ok = get_palette(c, use, fr->palette) && scene_get_num(c, use, "fractal", "glow", 0, 0, 100, &fr->glow) &&
              scene_get_vec3(c, use, "fractal", "glow_color", WARM, 0, 100, fr->glow_color) &&
              scene_get_num(c, use, "fractal", "hit_distance", 0, 0, 1, &fr->hit_distance) &&
              scene_get_enum(c, use, "fractal", "hit_rule", "hit rule", RULES,
                             f->fragment ? HIT_RULE_FRAGMENT : HIT_RULE_FOOTPRINT, &rule) &&
              scene_get_num(c, use, "fractal", "detail", f->fragment ? f->frag_detail : -2.3f, -7, 0, &fr->detail) &&
              scene_get_num(c, use, "fractal", "max_distance", f->fragment ? f->frag_max_distance : 100000, 1e-3f,
                            1e6f, &fr->max_distance) &&
              scene_get_enum(c, use, "fractal", "look", "look", LOOKS, f->frag_light != FRAG_LIGHT_NONE ? LOOK_FRAGMENT : LOOK_FATHOM,
                             &look);
    fr->hit_rule = (fractal_hit_rule)rule;
    fr->look = (fractal_look)look;
    if (ok && fr->look == LOOK_FRAGMENT && !f->fragment)
        ok = scene_fail(c, "fractal.look", "fragment is a Fragmentarium fragment's own renderer: %s is none (take fathom)",
                        f->name);
    return ok;
}

/* Fractals are drawn with material 0; a scene may omit "materials". */
static void default_material(scene *s)
{
    if (s->material_count == 0) {
        s->material_count = 1;
        s->materials[0] = (scene_material){.name = "surface", .base_color = {1, 1, 1}, .roughness = 0.5f,
                                           .ior = 1.5f, .texture = -1, .uv_scale = 1, .relief = -1};
    }
}

/* The message a formula call left in c->err, under the key path `path`. */
static bool fail_formula(scene_ctx *c, const char *path)
{
    err_t why = *c->err;
    return scene_fail(c, path, "%s", why.msg);
}

/* One declared parameter from the block at `path` (its default when absent), checked against its
 * declaration. */
static bool get_param(scene_ctx *c, const cJSON *use, const char *path, const formula_param *q, float v[4])
{
    char key[128];
    scene_child_path(key, sizeof key, path, q->key);
    switch (q->type) {
    case FORMULA_INT: {
        int i;
        if (!scene_get_int(c, use, path, q->key, (int)q->def[0], (int)q->lo, (int)q->hi, &i))
            return false;
        v[0] = (float)i;
        break;
    }
    case FORMULA_BOOL: {
        const cJSON *b = cJSON_GetObjectItemCaseSensitive(use, q->key);
        if (b && !cJSON_IsBool(b) && !(cJSON_IsNumber(b) && (b->valuedouble == 0 || b->valuedouble == 1)))
            return scene_fail(c, key, "expected true or false");
        v[0] = !b ? q->def[0] : cJSON_IsBool(b) ? (float)cJSON_IsTrue(b) : (float)b->valuedouble;
        scene_record_param(c, path, q->key, PARAM_BOOL, (const double[1]){v[0]}, 0, 1);
        break;
    }
    case FORMULA_VEC3:
    case FORMULA_COLOR:
    case FORMULA_VEC2:
    case FORMULA_VEC4:
    case FORMULA_COLOR4:
        return scene_get_vecn(c, use, path, q->key, formula_components(q->type), q->def, q->lo, q->hi,
                              q->type == FORMULA_COLOR || q->type == FORMULA_COLOR4, v);
    default:
        if (!scene_get_num(c, use, path, q->key, q->def[0], q->lo, q->hi, v))
            return false;
    }
    if (q->has_gap && v[0] > q->gap_lo && v[0] < q->gap_hi)
        return scene_fail(c, key, "%g is between %g and %g, where the formula has no set: take a value outside",
                    (double)v[0], (double)q->gap_lo, (double)q->gap_hi);
    return true;
}

/* Evaluates a formula's expression over its parameters' values. */
static bool eval(scene_ctx *c, const char *path, const formula *f, float (*values)[4], int iterations,
                 const char *expr, double *out)
{
    return formula_eval(f, expr, (const float(*)[4])values, iterations, out, c->err) || fail_formula(c, path);
}

/* The formula's @require lines over the values read. */
static bool check_requires(scene_ctx *c, const char *path, const formula *f, float (*values)[4], int iterations)
{
    for (int i = 0; i < f->require_count; i++) {
        const formula_require *r = &f->requires[i];
        double a, b;
        if (!eval(c, path, f, values, iterations, r->lhs, &a) || !eval(c, path, f, values, iterations, r->rhs, &b))
            return false;
        if (r->less ? !(a < b) : !(a > b))
            return scene_fail(c, path, "%s (formula %s: %s %c %s)", r->message, f->name, r->lhs, r->less ? '<' : '>', r->rhs);
    }
    return true;
}

/* A formula's parameters from the block at `path`, with the block's own keys (`common`, NULL-ended)
 * allowed beside them; then its requirements. */
static bool formula_block(scene_ctx *c, const cJSON *use, const char *path, const char *const *common,
                          const formula *f, float (*values)[4], int iterations)
{
    const char *keys[BLOCK_KEYS_MAX];
    int n = 0;
    while (common[n] && n < BLOCK_KEYS_MAX - FORMULA_MAX_PARAMS - 1)
        keys[n] = common[n], n++;
    for (int i = 0; i < f->param_count; i++)
        keys[n++] = f->params[i].key;
    keys[n] = NULL;
    if (!scene_check_keys(c, use, path, keys))
        return false;
    for (int i = 0; i < f->param_count; i++)
        if (!get_param(c, use, path, &f->params[i], values[i]))
            return false;
    return check_requires(c, path, f, values, iterations);
}

/* Whether the formula's double-precision path takes these values (@deep whole KEY...). */
static bool deep_ok(const formula *f, float (*values)[4])
{
    if (!f->deep)
        return false;
    for (int i = 0; i < f->param_count; i++)
        if (strstr(f->deep_whole, f->params[i].key) && values[i][0] != floorf(values[i][0]))
            return false;
    return true;
}

/* "hybrid": {"formula": NAME, "steps": N, its parameters...}: a second step formula whose N steps
 * follow the first one's `steps` in each cycle. */
static bool hybrid_block(scene_ctx *c, const cJSON *block, scene_fractal *fr)
{
    const cJSON *h = cJSON_GetObjectItemCaseSensitive(block, "hybrid");
    if (!h)
        return true;
    const char *name = NULL;
    if (!cJSON_IsObject(h))
        return scene_fail(c, "fractal.hybrid", "expected an object like {\"formula\": \"mandelbulb\", \"steps\": 1}");
    if (!fr->formula.step_formula)
        return scene_fail(c, "fractal.hybrid", "formula %s has its own estimate (no @de): only step formulas take part in "
                    "hybrids", fr->formula.name);
    if (!scene_get_str(c, h, "fractal.hybrid", "formula", NULL, &name))
        return false;
    if (!name)
        return scene_fail(c, "fractal.hybrid.formula", "missing: name the step formula whose steps alternate with %s's",
                    fr->formula.name);
    if (!formula_load(name, c->s->dir, &fr->hybrid, c->err))
        return fail_formula(c, "fractal.hybrid.formula");
    if (!fr->hybrid.step_formula)
        return scene_fail(c, "fractal.hybrid.formula", "%s has its own estimate (no @de): only step formulas take part in "
                    "hybrids", fr->hybrid.name);
    if (!strcmp(fr->hybrid.file, fr->formula.file))
        return scene_fail(c, "fractal.hybrid.formula", "%s with itself is %s with more iterations: name another", name, name);
    static const char *const common[] = {"formula", "steps", NULL};
    fr->has_hybrid = true;
    return scene_get_int(c, h, "fractal.hybrid", "steps", 1, 1, 16, &fr->steps[1]) &&
           formula_block(c, h, "fractal.hybrid", common, &fr->hybrid, fr->hybrid_values, fr->iterations);
}

/* A step formula's loop: the escape radius (a hybrid's: the larger, at most HYBRID_LOG_ESCAPE when
 * one of them grows like a power, whose next step would leave the float range) and Julia mode. */
static const float HYBRID_LOG_ESCAPE = 64.0f;
static bool step_loop(scene_ctx *c, const cJSON *use, scene_fractal *fr)
{
    static const float JULIA_C[3] = {-0.6f, 0.4f, 0.2f};
    const cJSON *julia = cJSON_GetObjectItemCaseSensitive(use, "julia");
    if (julia && !cJSON_IsBool(julia))
        return scene_fail(c, "fractal.julia", "expected true or false");
    fr->julia = cJSON_IsTrue(julia);
    if (fr->formula.step_formula)
        scene_record_param(c, "fractal", "julia", PARAM_BOOL, (const double[1]){fr->julia}, 0, 1);
    if (!fr->formula.step_formula) {
        if (fr->julia || cJSON_GetObjectItemCaseSensitive(use, "julia_c") || cJSON_GetObjectItemCaseSensitive(use, "steps"))
            return scene_fail(c, "fractal", "julia, julia_c and steps belong to step formulas (@de); %s has its own estimate",
                        fr->formula.name);
        return true;
    }
    double a, b = 0;
    if (!scene_get_vec3(c, use, "fractal", "julia_c", JULIA_C, -4, 4, fr->julia_c) ||
        !scene_get_int(c, use, "fractal", "steps", 1, 1, 16, &fr->steps[0]) ||
        !eval(c, "fractal", &fr->formula, fr->values, fr->iterations, fr->formula.escape, &a) ||
        (fr->has_hybrid && !eval(c, "fractal.hybrid", &fr->hybrid, fr->hybrid_values, fr->iterations, fr->hybrid.escape, &b)))
        return false;
    bool log_de = fr->formula.de_log || (fr->has_hybrid && fr->hybrid.de_log);
    double escape = fmax(a, b);
    if (fr->has_hybrid && log_de)
        escape = fmin(escape, HYBRID_LOG_ESCAPE);
    if (!(escape > 1 && escape < 1e18))
        return scene_fail(c, "fractal", "the escape radius %g (formula %s's @escape) is not above 1", escape, fr->formula.name);
    fr->escape = (float)escape;
    return true;
}

/* The orbit trap's range and the bounding sphere (the larger of a hybrid's two unless the scene sets it). */
static bool trap_and_bound(scene_ctx *c, const cJSON *use, scene_fractal *fr)
{
    const formula *f = &fr->formula;
    double lo, hi, bound, other = 0;
    if (!eval(c, "fractal", f, fr->values, fr->iterations, f->trap[0], &lo) ||
        !eval(c, "fractal", f, fr->values, fr->iterations, f->trap[1], &hi) ||
        !eval(c, "fractal", f, fr->values, fr->iterations, f->bound, &bound) ||
        (fr->has_hybrid && !eval(c, "fractal.hybrid", &fr->hybrid, fr->hybrid_values, fr->iterations, fr->hybrid.bound, &other)))
        return false;
    if (!(hi > lo))
        return scene_fail(c, "fractal", "formula %s's @trap %s %s gives %g to %g: the second must be larger", f->name, f->trap[0],
                    f->trap[1], lo, hi);
    fr->trap[0] = (float)lo, fr->trap[1] = (float)hi;
    double loops, hybrid_loops = 0;
    if (!eval(c, "fractal", f, fr->values, fr->iterations, f->loops, &loops) ||
        (fr->has_hybrid &&
         !eval(c, "fractal.hybrid", &fr->hybrid, fr->hybrid_values, fr->iterations, fr->hybrid.loops, &hybrid_loops)))
        return false;
    loops = fmax(loops, hybrid_loops);
    if (!(loops >= 1 && loops <= FORMULA_LOOPS_MAX))
        return scene_fail(c, "fractal", "formula %s's @loops %s gives %g: expected 1 to %d loop iterations an estimate",
                    f->name, f->loops, loops, FORMULA_LOOPS_MAX);
    fr->loops = (int)ceil(loops);
    double step = 1;
    if (f->step[0] && !eval(c, "fractal", f, fr->values, fr->iterations, f->step, &step))
        return false;
    if (!(step > 0 && step <= 1))
        return scene_fail(c, "fractal", "formula %s's @step %s gives %g: expected above 0 and at most 1", f->name, f->step, step);
    fr->step = (float)step;
    bound = fmax(bound, other);
    return scene_get_num(c, use, "fractal", "bound_radius", (float)fmin(fmax(bound, BOUND_MIN), BOUND_MAX), BOUND_MIN,
                   BOUND_MAX, &fr->bound_radius);
}

/* "precision": "auto" (double once the view needs it and the formula allows it), "float", "double". */
static bool precision(scene_ctx *c, const cJSON *use, scene_fractal *fr)
{
    static const char *const names[] = {"auto", "float", "double", NULL};
    int p = 0;
    if (!scene_get_enum(c, use, "fractal", "precision", "precision", names, 0, &p))
        return false;
    fr->precision = (fractal_precision)p;
    fr->deep_ok = deep_ok(&fr->formula, fr->values) && (!fr->has_hybrid || deep_ok(&fr->hybrid, fr->hybrid_values)) &&
                  !c->s->has_droplets;
    if (fr->precision == PRECISION_DOUBLE && !fr->deep_ok)
        return scene_fail(c, "fractal.precision", "double needs a formula written for it (@deep)%s%s: %s cannot",
                    fr->formula.deep_whole[0] ? " with whole " : "", fr->formula.deep_whole,
                    fr->has_hybrid && fr->formula.deep ? fr->hybrid.name : fr->formula.name);
    fr->deep_now = fr->precision == PRECISION_DOUBLE;
    return true;
}

/* The program.glsl of a formula: the shared code, the formula (a step formula's step renamed, as a
 * hybrid's two are, and the second one's uniforms renamed too: HYBRID_PREFIX), the step loop, map(). */
static void fractal_code(scene_ctx *c, const scene_fractal *fr)
{
    strbuf *o = &c->code;
    sb_append(o, "#include \"fractal/common.glsl\"\n");
    if (fr->formula.fragment) {
        /* a fragment is plain GLSL: fathom's precision names are not its words (a local named real) */
        const char *f = fr->formula.file;
        sb_printf(o, "#undef real\n#undef real3\n#undef real4\n#undef realMat3\n#include \"%s:prelude\"\n"
                     "#include \"%s\"\n#define real float\n#define real3 vec3\n#define real4 vec4\n"
                     "#define realMat3 mat3\n#define FORMULA_EXACT 1\n#include \"frag/glue.glsl\"\n"
                     "#include \"%s:postlude\"\n// translation %016llx\n", f, f, f, frag_digest(f));
    } else if (!fr->formula.step_formula) {
        sb_printf(o, "#include \"%s\"\n", fr->formula.file);
    } else {
        sb_printf(o, "#define formulaStep formulaStepA\n#include \"%s\"\n#undef formulaStep\n", fr->formula.file);
        if (fr->has_hybrid) {
            sb_append(o, "#define FORMULA_HYBRID 1\n#define formulaStep formulaStepB\n");
            for (int i = 0; i < fr->hybrid.param_count; i++)
                sb_printf(o, "#define %s " HYBRID_PREFIX "%s\n", fr->hybrid.params[i].uniform, fr->hybrid.params[i].uniform);
            sb_printf(o, "#include \"%s\"\n#undef formulaStep\n", fr->hybrid.file);
            for (int i = 0; i < fr->hybrid.param_count; i++)
                sb_printf(o, "#undef %s\n", fr->hybrid.params[i].uniform);
        }
        bool log_de = fr->formula.de_log || (fr->has_hybrid && fr->hybrid.de_log);
        sb_printf(o, "#define FORMULA_DE_LOG %d\n#include \"fractal/iterate.glsl\"\n", log_de);
    }
    sb_append(o, "#include \"fractal/map.glsl\"\n");
}

/* The fractal block: "formula" (or the program's name when it names one), the block's own keys and
 * the formula's declared parameters (formula.h); a hybrid's second formula; map() is made of them. */
bool scene_fractal_parse(scene_ctx *c, const cJSON *root)
{
    scene_fractal *fr = &c->s->fractal;
    const cJSON *block = cJSON_GetObjectItemCaseSensitive(root, "fractal");
    cJSON *empty = cJSON_CreateObject();
    const cJSON *use = block ? block : empty;
    const char *name = c->formula;
    static const char *const common[] = {FORMULA_COMMON_KEYS, NULL};
    bool ok = cJSON_IsObject(use) || scene_fail(c, "fractal", "expected an object {...}");
    ok = ok && scene_get_str(c, use, "fractal", "formula", c->formula, &name);
    if (ok && !name)
        ok = scene_fail(c, "fractal.formula", "missing: name a formula (fathom --list-formulas), e.g. \"formula\": \"mandelbulb\"");
    ok = ok && (formula_load(name, c->s->dir, &fr->formula, c->err) || fail_formula(c, "fractal.formula"));
    const formula *f = &fr->formula;
    fr->steps[0] = fr->steps[1] = 1;
    /* in the panel's order: the formula's own parameters first, then the colours */
    ok = ok &&
         scene_get_int(c, use, "fractal", "iterations", f->iterations, f->iterations_lo, f->iterations_hi, &fr->iterations) &&
         formula_block(c, use, "fractal", common, f, fr->values, fr->iterations) && hybrid_block(c, use, fr) &&
         step_loop(c, use, fr) && trap_and_bound(c, use, fr) && precision(c, use, fr) && fractal_common(c, use, fr);
    cJSON_Delete(empty);
    if (ok) {
        default_material(c->s);
        fractal_code(c, fr);
    }
    return ok;
}

bool scene_fractal_frame(scene *s, err_t *err)
{
    (void)err;
    const float R = s->fractal.bound_radius, DIR[3] = {0.55f, 0.42f, 0.72f}; /* a unit three-quarter view */
    for (int i = 0; i < 3; i++)
        s->cam_position[i] = 2.4 * R * DIR[i], s->cam_look_at[i] = 0;
    s->cam_fov_deg = 45;
    s->quality.max_dist = fmaxf(s->quality.max_dist, 6 * R);
    return true;
}

void scene_fractal_defines(const scene *s, strbuf *out)
{
    sb_printf(out, "#define FRACTAL_ITERATIONS %d\n", s->fractal.iterations);
    const formula *f = &s->fractal.formula;
    for (int i = 0; i < f->param_count; i++) /* a fragment's Locked parameters: compile-time constants */
        if (f->params[i].locked) {
            char v[160];
            frag_literal(&f->params[i], s->fractal.values[i], v, sizeof v);
            sb_printf(out, "#define FRAG_LOCKED_%s %s\n", f->params[i].uniform, v);
        }
    if (s->fractal.hit_distance > 0) /* an absolute hit distance: common/march.glsl */
        sb_printf(out, "#define HIT_DISTANCE %.9g\n", (double)s->fractal.hit_distance);
    else if (s->fractal.hit_rule == HIT_RULE_FRAGMENT) /* Fragmentarium's rule (uHitRelative): common/march.glsl */
        sb_append(out, "#define HIT_RELATIVE 1\n");
    if (s->fractal.look == LOOK_FRAGMENT) /* the fragment's own renderer: frag/look.glsl */
        sb_printf(out, "#define FRAG_LOOK 1\n%s%s%s", f->frag_syntopia ? "#define FRAG_SHADOW_CAMERA_LIGHT 1\n" : "",
                  f->frag_light >= FRAG_LIGHT_PHONG ? "#define FRAG_LIGHT_PHONG 1\n" : "",
                  f->frag_light == FRAG_LIGHT_PHONG_SHADOWS ? "#define FRAG_LIGHT_PHONG_SHADOWS 1\n" : "");
    if (s->fractal.deep_now) /* a deep zoom: common/uniforms.glsl, fractal/common.glsl */
        sb_append(out, "#extension GL_ARB_gpu_shader_fp64 : require\n#define PRECISION_DOUBLE 1\n");
}

/* The block's own uniforms (shaders/fractal/common.glsl and iterate.glsl, the glow in sdf_main.glsl), then
 * each declared parameter under its uniform's name (a hybrid's second formula's with HYBRID_PREFIX). */
static void param_uniforms(const formula *f, const float *values, const char *prefix, const uniform_sink *u)
{
    for (int i = 0; i < f->param_count; i++) {
        const formula_param *q = &f->params[i];
        char name[FORMULA_KEY_MAX + 16];
        snprintf(name, sizeof name, "%s%s", prefix, q->uniform);
        if (q->locked) /* a compile-time constant: scene_fractal_defines */
            continue;
        if (q->type == FORMULA_INT || q->type == FORMULA_BOOL)
            uniform_i(u, name, (int)values[4 * i]);
        else
            uniform_fv(u, name, formula_components(q->type), 1, values + 4 * i);
    }
}

void scene_fractal_uniforms(const scene *s, const uniform_sink *u)
{
    const scene_fractal *f = &s->fractal;
    uniform_f(u, "uBoundRadius", f->bound_radius);
    uniform_f(u, "uHitRelative", powf(10, f->detail)); /* common/march.glsl: Fragmentarium's rule */
    uniform_f(u, "uFragMaxDistance", f->max_distance);
    uniform_i(u, "uFormulaLoops", f->loops);
    /* a step formula's loop spends its share each iteration: 1 unless @loops says its step loops too */
    uniform_i(u, "uFormulaStepLoops", f->loops > f->iterations + 1 ? (f->loops - 1 + f->iterations - 1) / f->iterations : 1);
    uniform_fv(u, "uPalette", 3, 3, &f->palette[0][0]);
    uniform_fv(u, "uTrapRange", 2, 1, f->trap);
    uniform_fv(u, "uGlowColor", 3, 1, f->glow_color);
    uniform_f(u, "uGlowStrength", f->glow);
    uniform_f(u, "uEscape", f->escape);
    uniform_i(u, "uJulia", f->julia);
    uniform_fv(u, "uJuliaC", 3, 1, f->julia_c);
    uniform_i(u, "uStepsA", f->steps[0]);
    uniform_i(u, "uStepsB", f->steps[1]);
    param_uniforms(&f->formula, &f->values[0][0], "", u);
    if (f->has_hybrid)
        param_uniforms(&f->hybrid, &f->hybrid_values[0][0], HYBRID_PREFIX, u);
}

/* ---- torus: one primitive, the smallest program (shaders/shapes/torus.glsl) ----------------------- */

bool scene_torus_parse(scene_ctx *c, const cJSON *root)
{
    struct scene_torus *t = &c->s->torus;
    const cJSON *tb = cJSON_GetObjectItemCaseSensitive(root, "torus");
    static const char *const keys[] = {"major", "minor", "material", NULL};
    const char *material;
    if (!tb)
        return scene_fail(c, "torus", "missing: the torus program draws the \"torus\" block, e.g. "
                                      "{\"major\": 1, \"minor\": 0.25, \"material\": \"gold\"}");
    if (!scene_check_keys(c, tb, "torus", keys) || !scene_get_num(c, tb, "torus", "major", 1, 1e-3f, 1e3f, &t->major) ||
        !scene_get_num(c, tb, "torus", "minor", 0.25f, 1e-4f, 1e3f, &t->minor) ||
        !scene_get_str(c, tb, "torus", "material", NULL, &material))
        return false;
    if (t->minor > t->major)
        return scene_fail(c, "torus.minor", "is larger than torus.major: the tube would cross the axis");
    t->material = material ? scene_find_material(c->s, material) : 0; /* none named: the first */
    return t->material >= 0 || scene_fail(c, "torus.material", "unknown material '%s'", material);
}

void scene_torus_uniforms(const scene *s, const uniform_sink *u)
{
    uniform_f(u, "uTorusMajor", s->torus.major);
    uniform_f(u, "uTorusMinor", s->torus.minor);
    uniform_i(u, "uTorusMaterial", s->torus.material);
}
