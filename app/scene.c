#include "scene.h"

#include <assert.h>
#include <cjson/cJSON.h>
#include <dirent.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEG2RAD 0.017453292519943295

/* Context for messages: every error names the file and the key path. */
typedef struct ctx {
    const char *file;
    err_t *err;
    scene *s;
    strbuf code;
    int next_var;
} ctx;

static bool fail(ctx *c, const char *path, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static bool fail(ctx *c, const char *path, const char *fmt, ...)
{
    char what[1024];
    va_list ap;
    va_start(ap, fmt);
    if (vsnprintf(what, sizeof what, fmt, ap) >= (int)sizeof what)
        what[sizeof what - 1] = '\0';
    va_end(ap);
    return err_set(c->err, "%s: %s: %s", c->file, path[0] ? path : "(top level)", what);
}

/* Key paths only appear in messages: a long one is cut, which is fine there. */
static void child_path(char *out, size_t n, const char *parent, const char *key)
{
    if (snprintf(out, n, "%s%s%s", parent, parent[0] ? "." : "", key) >= (int)n)
        out[n - 1] = '\0';
}

/* Every object is checked against the keys it may hold, so a typo is an error, not a silent default. */
static bool check_keys(ctx *c, const cJSON *obj, const char *path, const char *const *allowed)
{
    if (!cJSON_IsObject(obj))
        return fail(c, path, "expected an object {...}");
    for (const cJSON *it = obj->child; it; it = it->next) {
        bool ok = false;
        for (const char *const *k = allowed; *k; k++)
            ok |= !strcmp(it->string, *k);
        if (!ok) {
            char p[512];
            child_path(p, sizeof p, path, it->string);
            strbuf list = {0};
            for (const char *const *k = allowed; *k; k++)
                sb_printf(&list, "%s%s", k == allowed ? "" : ", ", *k);
            bool r = fail(c, p, "unknown key '%s' (allowed here: %s)", it->string, list.data);
            sb_free(&list);
            return r;
        }
    }
    return true;
}

static bool get_num(ctx *c, const cJSON *obj, const char *path, const char *key, float def, float lo,
                    float hi, float *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    child_path(p, sizeof p, path, key);
    if (!v) {
        *out = def;
        return true;
    }
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble) || v->valuedouble < lo || v->valuedouble > hi) {
        char range[128];
        snprintf(range, sizeof range, "%g to %g", (double)lo, (double)hi);
        return fail(c, p, "expected a number from %s", range);
    }
    *out = (float)v->valuedouble;
    return true;
}

static bool get_int(ctx *c, const cJSON *obj, const char *path, const char *key, int def, int lo, int hi,
                    int *out)
{
    float f;
    if (!get_num(c, obj, path, key, (float)def, (float)lo, (float)hi, &f))
        return false;
    if (f != floorf(f)) {
        char p[512];
        child_path(p, sizeof p, path, key);
        return fail(c, p, "expected a whole number");
    }
    *out = (int)f;
    return true;
}

static bool get_vec3(ctx *c, const cJSON *obj, const char *path, const char *key, const float def[3],
                     float lo, float hi, float out[3])
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[512];
    child_path(p, sizeof p, path, key);
    if (!v) {
        memcpy(out, def, sizeof(float) * 3);
        return true;
    }
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 3)
        return fail(c, p, "expected three numbers [x, y, z]");
    for (int i = 0; i < 3; i++) {
        const cJSON *e = cJSON_GetArrayItem(v, i);
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble) || e->valuedouble < lo || e->valuedouble > hi) {
            char range[128];
            snprintf(range, sizeof range, "%g to %g", (double)lo, (double)hi);
            return fail(c, p, "expected three numbers, each from %s", range);
        }
        out[i] = (float)e->valuedouble;
    }
    return true;
}

static bool get_str(ctx *c, const cJSON *obj, const char *path, const char *key, const char *def,
                    const char **out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) {
        *out = def;
        return true;
    }
    if (!cJSON_IsString(v)) {
        char p[512];
        child_path(p, sizeof p, path, key);
        return fail(c, p, "expected a string in quotes");
    }
    *out = v->valuestring;
    return true;
}

static bool resolve_file(ctx *c, const char *path, const char *rel, char *out)
{
    if (!util_join(c->s->dir, rel, out, PATH_MAX_LEN))
        return fail(c, path, "path '%s' is too long", rel);
    if (!util_file_exists(out))
        return fail(c, path, "file '%s' not found (paths are relative to the scene file's folder)", out);
    return true;
}

/* ---- materials ---------------------------------------------------------------------------- */

static int add_texture(scene *s, const char *resolved, bool linear)
{
    for (int i = 0; i < s->texture_count; i++)
        if (!strcmp(s->textures[i], resolved) && s->texture_linear[i] == linear)
            return i;
    if (s->texture_count == SCENE_MAX_TEXTURES)
        return -1;
    strcpy(s->textures[s->texture_count], resolved);
    s->texture_linear[s->texture_count] = linear;
    return s->texture_count++;
}

static bool parse_material(ctx *c, const cJSON *m, const char *path, scene_material *out)
{
    static const char *const keys[] = {"base_color", "metallic", "roughness", "transmission", "ior",
                                       "absorption", "emission", "texture", "uv_scale", "relief",
                                       "relief_depth", NULL};
    static const float white[3] = {1, 1, 1}, zero[3] = {0, 0, 0};
    if (!check_keys(c, m, path, keys))
        return false;
    const char *tex = NULL, *relief = NULL;
    if (!get_vec3(c, m, path, "base_color", white, 0, 1, out->base_color) ||
        !get_num(c, m, path, "metallic", 0, 0, 1, &out->metallic) ||
        !get_num(c, m, path, "roughness", 0.5f, 0, 1, &out->roughness) ||
        !get_num(c, m, path, "transmission", 0, 0, 1, &out->transmission) ||
        !get_num(c, m, path, "ior", 1.5f, 1, 4, &out->ior) ||
        !get_vec3(c, m, path, "absorption", zero, 0, 1e4f, out->absorption) ||
        !get_vec3(c, m, path, "emission", zero, 0, 1e6f, out->emission) ||
        !get_num(c, m, path, "uv_scale", 1, 1e-7f, 1e4f, &out->uv_scale) ||
        !get_str(c, m, path, "texture", NULL, &tex) || !get_str(c, m, path, "relief", NULL, &relief) ||
        !get_num(c, m, path, "relief_depth", 0.05f, 1e-5f, 1e3f, &out->relief_depth))
        return false;
    out->texture = -1;
    out->relief = -1;
    if (relief) {
        char p[512], resolved[PATH_MAX_LEN];
        child_path(p, sizeof p, path, "relief");
        if (!resolve_file(c, p, relief, resolved))
            return false;
        out->relief = add_texture(c->s, resolved, true);
        if (out->relief < 0)
            return fail(c, p, "too many textures (at most %d)", SCENE_MAX_TEXTURES);
    }
    if (tex) {
        char p[512], resolved[PATH_MAX_LEN];
        child_path(p, sizeof p, path, "texture");
        if (!resolve_file(c, p, tex, resolved))
            return false;
        out->texture = add_texture(c->s, resolved, false);
        if (out->texture < 0)
            return fail(c, p, "too many textures (at most %d)", SCENE_MAX_TEXTURES);
    }
    return true;
}

static bool parse_materials(ctx *c, const cJSON *root)
{
    const cJSON *mats = cJSON_GetObjectItemCaseSensitive(root, "materials");
    if (!cJSON_IsObject(mats) || !mats->child)
        return fail(c, "materials", "expected an object of named materials, e.g. {\"red\": {\"base_color\": [0.8, 0.1, 0.1]}}");
    for (const cJSON *m = mats->child; m; m = m->next) {
        char p[512];
        child_path(p, sizeof p, "materials", m->string);
        if (c->s->material_count == SCENE_MAX_MATERIALS)
            return fail(c, p, "too many materials (at most %d)", SCENE_MAX_MATERIALS);
        if (strlen(m->string) == 0 || strlen(m->string) >= SCENE_NAME_MAX)
            return fail(c, p, "material names must have 1 to 63 characters");
        scene_material *out = &c->s->materials[c->s->material_count++];
        strcpy(out->name, m->string);
        if (!parse_material(c, m, p, out))
            return false;
    }
    return true;
}

static int find_material(const scene *s, const char *name)
{
    for (int i = 0; i < s->material_count; i++)
        if (!strcmp(s->materials[i].name, name))
            return i;
    return -1;
}

/* ---- CSG tree → GLSL ------------------------------------------------------------------------ */

/* Object-to-world rotation from Euler angles in degrees, applied X then Y then Z. The shader needs
 * world-to-object, the transpose; GLSL's mat3() takes columns, so we emit R's rows as columns. */
static bool emit_transform(ctx *c, const cJSON *node, const char *path, const char *pin, char *pout)
{
    static const float zero[3] = {0, 0, 0};
    float pos[3], rot[3];
    if (!get_vec3(c, node, path, "position", zero, -1e6f, 1e6f, pos) ||
        !get_vec3(c, node, path, "rotation", zero, -360, 360, rot))
        return false;
    int v = c->next_var++;
    sprintf(pout, "q%d", v);
    bool has_rot = rot[0] != 0 || rot[1] != 0 || rot[2] != 0;
    if (!has_rot) {
        if (pos[0] == 0 && pos[1] == 0 && pos[2] == 0)
            strcpy(pout, pin);
        else
            sb_printf(&c->code, "    vec3 %s = %s - vec3(%.9g, %.9g, %.9g);\n", pout, pin, (double)pos[0],
                      (double)pos[1], (double)pos[2]);
        return true;
    }
    double cx = cos(rot[0] * DEG2RAD), sx = sin(rot[0] * DEG2RAD);
    double cy = cos(rot[1] * DEG2RAD), sy = sin(rot[1] * DEG2RAD);
    double cz = cos(rot[2] * DEG2RAD), sz = sin(rot[2] * DEG2RAD);
    /* R = Rz * Ry * Rx, row-major r[row][col] */
    double r[3][3] = {
        {cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
        {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
        {-sy, cy * sx, cy * cx},
    };
    sb_printf(&c->code, "    vec3 %s = mat3(", pout);
    for (int row = 0; row < 3; row++) /* column j of R^T is row j of R */
        for (int col = 0; col < 3; col++)
            sb_printf(&c->code, "%.9g%s", r[row][col], (row == 2 && col == 2) ? "" : ", ");
    sb_printf(&c->code, ") * (%s - vec3(%.9g, %.9g, %.9g));\n", pin, (double)pos[0], (double)pos[1],
              (double)pos[2]);
    return true;
}

static int emit_node(ctx *c, const cJSON *node, const char *path, const char *pin);

static int emit_primitive(ctx *c, const cJSON *node, const char *path, const char *pin, const char *shape)
{
    static const char *const common[] = {"shape", "position", "rotation", "material"};
    static const struct {
        const char *shape;
        const char *keys[4];
    } SHAPES[] = {
        {"sphere", {"radius"}},          {"box", {"size"}},
        {"round_box", {"size", "radius"}}, {"torus", {"major", "minor"}},
        {"cylinder", {"radius", "height"}}, {"capsule", {"radius", "height"}},
        {"cone", {"radius_bottom", "radius_top", "height"}}, {"plane", {"normal"}},
    };
    int si = -1;
    for (int i = 0; i < (int)(sizeof SHAPES / sizeof SHAPES[0]); i++)
        if (!strcmp(shape, SHAPES[i].shape))
            si = i;
    if (si < 0) {
        char p[512];
        child_path(p, sizeof p, path, "shape");
        fail(c, p, "unknown shape '%s' (known: sphere, box, round_box, torus, cylinder, capsule, cone, plane)", shape);
        return -1;
    }
    const char *keys[10];
    int nk = 0;
    for (int i = 0; i < 4; i++)
        keys[nk++] = common[i];
    for (int i = 0; i < 4 && SHAPES[si].keys[i]; i++)
        keys[nk++] = SHAPES[si].keys[i];
    keys[nk] = NULL;
    if (!check_keys(c, node, path, keys))
        return -1;

    const char *mname = NULL;
    if (!get_str(c, node, path, "material", NULL, &mname))
        return -1;
    char mp[512];
    child_path(mp, sizeof mp, path, "material");
    if (!mname) {
        fail(c, mp, "every primitive needs a material, e.g. \"material\": \"%s\"", c->s->materials[0].name);
        return -1;
    }
    int mat = find_material(c->s, mname);
    if (mat < 0) {
        fail(c, mp, "no material named '%s' in \"materials\"", mname);
        return -1;
    }

    char q[32];
    if (!emit_transform(c, node, path, pin, q))
        return -1;
    const float BIG = 1e5f, TINY = 1e-5f;
    static const float up[3] = {0, 1, 0};
    static const float unit[3] = {1, 1, 1};
    char expr[512];
    float a, b, h, v3[3];
    if (!strcmp(shape, "sphere")) {
        if (!get_num(c, node, path, "radius", 1, TINY, BIG, &a)) return -1;
        snprintf(expr, sizeof expr, "sdSphere(%s, %.9g)", q, (double)a);
    } else if (!strcmp(shape, "box")) {
        if (!get_vec3(c, node, path, "size", unit, TINY, BIG, v3)) return -1;
        snprintf(expr, sizeof expr, "sdBox(%s, vec3(%.9g, %.9g, %.9g))", q, 0.5 * v3[0], 0.5 * v3[1], 0.5 * v3[2]);
    } else if (!strcmp(shape, "round_box")) {
        if (!get_vec3(c, node, path, "size", unit, TINY, BIG, v3) ||
            !get_num(c, node, path, "radius", 0.1f, 0, BIG, &a)) return -1;
        float m = fminf(v3[0], fminf(v3[1], v3[2]));
        if (2 * a > m) {
            fail(c, path, "radius must be at most half the smallest size");
            return -1;
        }
        snprintf(expr, sizeof expr, "sdRoundBox(%s, vec3(%.9g, %.9g, %.9g), %.9g)", q, 0.5 * v3[0], 0.5 * v3[1],
                 0.5 * v3[2], (double)a);
    } else if (!strcmp(shape, "torus")) {
        if (!get_num(c, node, path, "major", 1, TINY, BIG, &a) ||
            !get_num(c, node, path, "minor", 0.25f, TINY, BIG, &b)) return -1;
        snprintf(expr, sizeof expr, "sdTorus(%s, %.9g, %.9g)", q, (double)a, (double)b);
    } else if (!strcmp(shape, "cylinder") || !strcmp(shape, "capsule")) {
        if (!get_num(c, node, path, "radius", 0.5f, TINY, BIG, &a) ||
            !get_num(c, node, path, "height", 1, shape[1] == 'y' ? TINY : 0, BIG, &h)) return -1;
        snprintf(expr, sizeof expr, "%s(%s, %.9g, %.9g)", shape[1] == 'y' ? "sdCylinder" : "sdCapsule", q,
                 0.5 * h, (double)a);
    } else if (!strcmp(shape, "cone")) {
        if (!get_num(c, node, path, "radius_bottom", 0.5f, 0, BIG, &a) ||
            !get_num(c, node, path, "radius_top", 0, 0, BIG, &b) ||
            !get_num(c, node, path, "height", 1, TINY, BIG, &h)) return -1;
        if (a + b <= 0) {
            fail(c, path, "a cone needs radius_bottom or radius_top above 0");
            return -1;
        }
        snprintf(expr, sizeof expr, "sdCappedCone(%s, %.9g, %.9g, %.9g)", q, 0.5 * h, (double)a, (double)b);
    } else { /* plane through the position, facing `normal` */
        if (!get_vec3(c, node, path, "normal", up, -1, 1, v3)) return -1;
        double len = sqrt((double)v3[0] * v3[0] + (double)v3[1] * v3[1] + (double)v3[2] * v3[2]);
        if (len < 1e-6) {
            fail(c, path, "normal must not be zero");
            return -1;
        }
        snprintf(expr, sizeof expr, "sdPlane(%s, vec3(%.9g, %.9g, %.9g))", q, v3[0] / len, v3[1] / len, v3[2] / len);
    }
    int v = c->next_var++;
    sb_printf(&c->code, "    vec2 d%d = vec2(%s, %d.0);\n", v, expr, mat);
    c->s->primitive_count++;
    return v;
}

static int emit_op(ctx *c, const cJSON *node, const char *path, const char *pin, const char *op)
{
    static const char *const keys[] = {"op", "k", "children", "position", "rotation", NULL};
    static const struct { const char *name, *fn; bool smooth; } OPS[] = {
        {"union", "opUnion", false},
        {"intersection", "opIntersection", false},
        {"difference", "opDifference", false},
        {"smooth_union", "opSmoothUnion", true},
        {"smooth_intersection", "opSmoothIntersection", true},
        {"smooth_difference", "opSmoothDifference", true},
    };
    int oi = -1;
    for (int i = 0; i < (int)(sizeof OPS / sizeof OPS[0]); i++)
        if (!strcmp(op, OPS[i].name))
            oi = i;
    char p[512];
    if (oi < 0) {
        child_path(p, sizeof p, path, "op");
        fail(c, p, "unknown op '%s' (known: union, intersection, difference and smooth_ of each)", op);
        return -1;
    }
    if (!check_keys(c, node, path, keys))
        return -1;
    float k = 0;
    if (OPS[oi].smooth) {
        if (!cJSON_GetObjectItemCaseSensitive(node, "k")) {
            fail(c, path, "'%s' needs a blend radius \"k\" (metres, > 0)", op);
            return -1;
        }
        if (!get_num(c, node, path, "k", 0, 1e-5f, 1e4f, &k))
            return -1;
    } else if (cJSON_GetObjectItemCaseSensitive(node, "k")) {
        child_path(p, sizeof p, path, "k");
        fail(c, p, "'k' only applies to smooth_ ops");
        return -1;
    }
    const cJSON *kids = cJSON_GetObjectItemCaseSensitive(node, "children");
    child_path(p, sizeof p, path, "children");
    if (!cJSON_IsArray(kids) || cJSON_GetArraySize(kids) < 2) {
        fail(c, p, "expected an array of at least two nodes");
        return -1;
    }
    char q[32];
    if (!emit_transform(c, node, path, pin, q))
        return -1;
    int acc = -1, i = 0;
    for (const cJSON *kid = kids->child; kid; kid = kid->next, i++) {
        char kp[600];
        if (snprintf(kp, sizeof kp, "%s.%d", p, i) >= (int)sizeof kp)
            kp[sizeof kp - 1] = '\0';
        int v = emit_node(c, kid, kp, q);
        if (v < 0)
            return -1;
        if (acc < 0) {
            acc = v;
            continue;
        }
        int r = c->next_var++;
        if (OPS[oi].smooth)
            sb_printf(&c->code, "    vec2 d%d = %s(d%d, d%d, %.9g);\n", r, OPS[oi].fn, acc, v, (double)k);
        else
            sb_printf(&c->code, "    vec2 d%d = %s(d%d, d%d);\n", r, OPS[oi].fn, acc, v);
        acc = r;
    }
    return acc;
}

static int emit_node(ctx *c, const cJSON *node, const char *path, const char *pin)
{
    if (!cJSON_IsObject(node)) {
        fail(c, path, "expected a node: {\"shape\": ...} or {\"op\": ..., \"children\": [...]}");
        return -1;
    }
    const char *shape = NULL, *op = NULL;
    if (!get_str(c, node, path, "shape", NULL, &shape) || !get_str(c, node, path, "op", NULL, &op))
        return -1;
    if (shape && op) {
        fail(c, path, "a node has either \"shape\" or \"op\", not both");
        return -1;
    }
    if (shape)
        return emit_primitive(c, node, path, pin, shape);
    if (op)
        return emit_op(c, node, path, pin, op);
    fail(c, path, "a node needs \"shape\" (a primitive) or \"op\" (a CSG operation)");
    return -1;
}

static bool parse_objects(ctx *c, const cJSON *root)
{
    const cJSON *objs = cJSON_GetObjectItemCaseSensitive(root, "objects");
    if (!cJSON_IsArray(objs) || cJSON_GetArraySize(objs) < 1)
        return fail(c, "objects", "expected an array of at least one node");
    sb_append(&c->code, "vec2 map(vec3 p)\n{\n");
    int acc = -1, i = 0;
    for (const cJSON *n = objs->child; n; n = n->next, i++) {
        char p[64];
        snprintf(p, sizeof p, "objects.%d", i);
        int v = emit_node(c, n, p, "p");
        if (v < 0)
            return false;
        if (acc >= 0) {
            int r = c->next_var++;
            sb_printf(&c->code, "    vec2 d%d = opUnion(d%d, d%d);\n", r, acc, v);
            v = r;
        }
        acc = v;
    }
    sb_printf(&c->code, "    return d%d;\n}\n", acc);
    return true;
}

/* ---- the rest of the file ------------------------------------------------------------------- */

static bool parse_lights(ctx *c, const cJSON *root)
{
    const cJSON *lights = cJSON_GetObjectItemCaseSensitive(root, "lights");
    if (!lights)
        return true;
    if (!cJSON_IsArray(lights))
        return fail(c, "lights", "expected an array of lights");
    int i = 0;
    for (const cJSON *l = lights->child; l; l = l->next, i++) {
        char p[64];
        snprintf(p, sizeof p, "lights.%d", i);
        if (c->s->light_count == SCENE_MAX_LIGHTS)
            return fail(c, p, "too many lights (at most %d)", SCENE_MAX_LIGHTS);
        static const char *const keys[] = {"type", "position", "direction", "color", "intensity", "shadow",
                                           "softness", NULL};
        if (!check_keys(c, l, p, keys))
            return false;
        scene_light *out = &c->s->lights[c->s->light_count++];
        static const float white[3] = {1, 1, 1}, up[3] = {0, 1, 0}, zero[3] = {0, 0, 0};
        const char *type = NULL, *shadow = NULL;
        if (!get_str(c, l, p, "type", "point", &type) || !get_str(c, l, p, "shadow", "hard", &shadow) ||
            !get_vec3(c, l, p, "color", white, 0, 1e3f, out->color) ||
            !get_num(c, l, p, "intensity", 1, 0, 1e7f, &out->intensity) ||
            !get_num(c, l, p, "softness", 16, 1, 1024, &out->softness))
            return false;
        char kp[96];
        if (!strcmp(type, "point")) {
            out->type = LIGHT_POINT;
            if (cJSON_GetObjectItemCaseSensitive(l, "direction")) {
                child_path(kp, sizeof kp, p, "direction");
                return fail(c, kp, "a point light has a \"position\", not a direction");
            }
            if (!get_vec3(c, l, p, "position", zero, -1e6f, 1e6f, out->vec))
                return false;
        } else if (!strcmp(type, "directional")) {
            out->type = LIGHT_DIRECTIONAL;
            if (cJSON_GetObjectItemCaseSensitive(l, "position")) {
                child_path(kp, sizeof kp, p, "position");
                return fail(c, kp, "a directional light has a \"direction\" (toward the light), not a position");
            }
            if (!get_vec3(c, l, p, "direction", up, -1e6f, 1e6f, out->vec))
                return false;
            float len = sqrtf(out->vec[0] * out->vec[0] + out->vec[1] * out->vec[1] + out->vec[2] * out->vec[2]);
            if (len < 1e-6f)
                return fail(c, p, "direction must not be zero");
            for (int k = 0; k < 3; k++)
                out->vec[k] /= len;
        } else {
            child_path(kp, sizeof kp, p, "type");
            return fail(c, kp, "unknown light type '%s' (known: point, directional)", type);
        }
        if (!strcmp(shadow, "none"))
            out->shadow = SHADOW_NONE;
        else if (!strcmp(shadow, "hard"))
            out->shadow = SHADOW_HARD;
        else if (!strcmp(shadow, "soft"))
            out->shadow = SHADOW_SOFT;
        else {
            child_path(kp, sizeof kp, p, "shadow");
            return fail(c, kp, "unknown shadow '%s' (known: none, hard, soft)", shadow);
        }
    }
    return true;
}

static bool parse_environment(ctx *c, const cJSON *root)
{
    scene *s = c->s;
    static const float grey[3] = {0.5f, 0.6f, 0.7f};
    const cJSON *env = cJSON_GetObjectItemCaseSensitive(root, "environment");
    if (!env) {
        memcpy(s->env_color, grey, sizeof grey);
        s->env_intensity = 1;
        return true;
    }
    static const char *const keys[] = {"color", "intensity", "cubemap", NULL};
    if (!check_keys(c, env, "environment", keys) ||
        !get_vec3(c, env, "environment", "color", grey, 0, 1e3f, s->env_color) ||
        !get_num(c, env, "environment", "intensity", 1, 0, 1e6f, &s->env_intensity))
        return false;
    const cJSON *cube = cJSON_GetObjectItemCaseSensitive(env, "cubemap");
    if (!cube)
        return true;
    if (!cJSON_IsArray(cube) || cJSON_GetArraySize(cube) != 6)
        return fail(c, "environment.cubemap", "expected six image paths in the order +X, -X, +Y, -Y, +Z, -Z");
    int i = 0;
    for (const cJSON *f = cube->child; f; f = f->next, i++) {
        char p[64];
        snprintf(p, sizeof p, "environment.cubemap.%d", i);
        if (!cJSON_IsString(f))
            return fail(c, p, "expected an image path in quotes");
        if (!resolve_file(c, p, f->valuestring, s->cubemap[i]))
            return false;
    }
    s->has_cubemap = true;
    return true;
}

static bool parse_quality(ctx *c, const cJSON *root)
{
    scene *s = c->s;
    const cJSON *q = cJSON_GetObjectItemCaseSensitive(root, "quality");
    s->preset = PRESET_INTERACTIVE;
    if (!q) {
        s->quality = preset_quality(s->preset);
        return true;
    }
    static const char *const keys[] = {"preset", "max_steps", "hit_k", "step_factor", "max_dist", "shadow_steps",
                                       "ao_samples", "bounces", "aniso_taps", "over_relax", "linear_step", "step_growth",
                                       "binary_steps", "spp", NULL};
    if (!check_keys(c, q, "quality", keys))
        return false;
    const char *name = NULL;
    if (!get_str(c, q, "quality", "preset", "interactive", &name))
        return false;
    if (!preset_from_name(name, &s->preset))
        return fail(c, "quality.preset", "unknown preset '%s' (known: draft, interactive, final, reference)", name);
    quality d = preset_quality(s->preset), *o = &s->quality;
    return get_int(c, q, "quality", "max_steps", d.max_steps, 1, 100000, &o->max_steps) &&
           get_num(c, q, "quality", "hit_k", d.hit_k, 1e-3f, 1e3f, &o->hit_k) &&
           get_num(c, q, "quality", "step_factor", d.step_factor, 0.05f, 1, &o->step_factor) &&
           get_num(c, q, "quality", "max_dist", d.max_dist, 1e-2f, 1e7f, &o->max_dist) &&
           get_int(c, q, "quality", "shadow_steps", d.shadow_steps, 1, 100000, &o->shadow_steps) &&
           get_int(c, q, "quality", "ao_samples", d.ao_samples, 0, 64, &o->ao_samples) &&
           get_int(c, q, "quality", "bounces", d.bounces, 0, 64, &o->bounces) &&
           get_int(c, q, "quality", "aniso_taps", d.aniso_taps, 1, 64, &o->aniso_taps) &&
           get_num(c, q, "quality", "over_relax", d.over_relax, 1, 1.95f, &o->over_relax) &&
           get_num(c, q, "quality", "linear_step", d.linear_step, 0.01f, 1000, &o->linear_step) &&
           get_num(c, q, "quality", "step_growth", d.step_growth, 1, 2, &o->step_growth) &&
           get_int(c, q, "quality", "binary_steps", d.binary_steps, 0, 40, &o->binary_steps) &&
           get_int(c, q, "quality", "spp", d.spp, 1, 1 << 16, &o->spp);
}

static bool parse_effects(ctx *c, const cJSON *root)
{
    const cJSON *fx = cJSON_GetObjectItemCaseSensitive(root, "effects");
    if (!fx)
        return true;
    if (!cJSON_IsObject(fx))
        return fail(c, "effects", "expected an object like {\"fog\": \"off\"}");
    for (const cJSON *it = fx->child; it; it = it->next) {
        char p[128];
        child_path(p, sizeof p, "effects", it->string);
        effect e;
        if (!effect_from_name(it->string, &e)) {
            strbuf list = {0};
            for (int i = 0; i < EFFECT_COUNT; i++)
                sb_printf(&list, "%s%s", i ? ", " : "", effect_name((effect)i));
            bool r = fail(c, p, "unknown effect '%s' (known: %s)", it->string, list.data);
            sb_free(&list);
            return r;
        }
        const char *v = cJSON_IsString(it) ? it->valuestring : "";
        if (!strcmp(v, "auto"))
            c->s->effect_modes[e] = EFFECT_AUTO;
        else if (!strcmp(v, "on"))
            c->s->effect_modes[e] = EFFECT_ON;
        else if (!strcmp(v, "off"))
            c->s->effect_modes[e] = EFFECT_OFF;
        else
            return fail(c, p, "expected \"auto\", \"on\" or \"off\"");
    }
    return true;
}

/* An effect is compiled in when the scene's content calls for it ("auto"), then "on"/"off" force it. */
static unsigned derive_effects(const scene *s)
{
    bool shadows = false, soft = false, mirror = false, glass = false, relief = false;
    for (int i = 0; i < s->light_count; i++) {
        shadows |= s->lights[i].shadow != SHADOW_NONE;
        soft |= s->lights[i].shadow == SHADOW_SOFT;
    }
    for (int i = 0; i < s->material_count; i++) {
        const scene_material *m = &s->materials[i];
        glass |= m->transmission > 0;
        relief |= m->relief >= 0;
        mirror |= m->transmission == 0 && m->roughness <= MIRROR_ROUGHNESS;
    }
    bool want[EFFECT_COUNT] = {
        [EFFECT_SHADOWS] = shadows,
        [EFFECT_SOFT_SHADOWS] = soft,
        [EFFECT_AO] = s->env_intensity > 0 && s->quality.ao_samples > 0,
        [EFFECT_REFLECTIONS] = mirror && s->quality.bounces > 0,
        [EFFECT_REFRACTION] = glass && s->quality.bounces > 0,
        [EFFECT_FOG] = s->has_fog,
        [EFFECT_ENVMAP] = s->has_cubemap,
        [EFFECT_TEXTURES] = s->texture_count > 0 && !(s->texture_count == 1 && s->texture_linear[0]),
        [EFFECT_AA] = s->quality.spp > 1,
        [EFFECT_GLOW] = s->fractal.glow > 0,
        [EFFECT_RELIEF] = relief,
    };
    unsigned fx = 0;
    for (int e = 0; e < EFFECT_COUNT; e++) {
        bool on = s->effect_modes[e] == EFFECT_ON || (s->effect_modes[e] == EFFECT_AUTO && want[e]);
        fx |= (unsigned)on << e;
    }
    /* penumbrae are a kind of shadow: without shadow rays there is nothing to soften */
    if (!(fx & (1u << EFFECT_SHADOWS)))
        fx &= ~(1u << EFFECT_SOFT_SHADOWS);
    /* terrain programs run the lab's search themselves, over their own surface: no relief there */
    if (s->program == PROGRAM_TERRAIN || s->program == PROGRAM_NOISE)
        fx &= ~(1u << EFFECT_RELIEF);
    return fx;
}

static bool get_palette(ctx *c, const cJSON *f, float out[3][3])
{
    static const float def[3][3] = {{0.95f, 0.55f, 0.25f}, {0.25f, 0.45f, 0.75f}, {0.92f, 0.9f, 0.85f}};
    memcpy(out, def, sizeof def);
    const cJSON *pal = cJSON_GetObjectItemCaseSensitive(f, "palette");
    if (!pal)
        return true;
    if (!cJSON_IsArray(pal) || cJSON_GetArraySize(pal) != 3)
        return fail(c, "fractal.palette", "expected three colours [[r,g,b], [r,g,b], [r,g,b]] (near, middle, far)");
    int i = 0;
    for (const cJSON *col = pal->child; col; col = col->next, i++) {
        if (!cJSON_IsArray(col) || cJSON_GetArraySize(col) != 3)
            return fail(c, "fractal.palette", "colour %d: expected [r, g, b]", i);
        for (int k = 0; k < 3; k++) {
            const cJSON *v = cJSON_GetArrayItem(col, k);
            if (!cJSON_IsNumber(v) || v->valuedouble < 0 || v->valuedouble > 1)
                return fail(c, "fractal.palette", "colour %d: expected numbers from 0 to 1", i);
            out[i][k] = (float)v->valuedouble;
        }
    }
    return true;
}

/* The "fractal" block: which keys a program reads, and their defaults. */
static bool parse_fractal(ctx *c, const cJSON *root)
{
    scene *s = c->s;
    scene_fractal *fr = &s->fractal;
    const cJSON *f = cJSON_GetObjectItemCaseSensitive(root, "fractal");
    static const char *const bulb[] = {"iterations", "power", "bailout", "bound_radius", "palette", "glow",
                                       "glow_color", NULL};
    static const char *const menger[] = {"iterations", "size", "palette", "glow", "glow_color", NULL};
    static const char *const box[] = {"iterations", "scale", "min_radius", "fixed_radius", "fold_limit",
                                      "bound_radius", "palette", "glow", "glow_color", NULL};
    const char *const *keys = s->program == PROGRAM_MANDELBULB ? bulb : s->program == PROGRAM_MENGER ? menger : box;
    static const float warm[3] = {1.0f, 0.6f, 0.3f};
    const cJSON *empty = cJSON_CreateObject(), *use = f ? f : empty;
    bool ok = (!f || check_keys(c, f, "fractal", keys)) && get_palette(c, use, fr->palette) &&
              get_num(c, use, "fractal", "glow", 0, 0, 100, &fr->glow) &&
              get_vec3(c, use, "fractal", "glow_color", warm, 0, 100, fr->glow_color);
    if (ok && s->program == PROGRAM_MANDELBULB) {
        ok = get_int(c, use, "fractal", "iterations", 12, 1, 64, &fr->iterations) &&
             get_num(c, use, "fractal", "power", 8, 2, 16, &fr->power) &&
             get_num(c, use, "fractal", "bailout", 2, 1.5f, 64, &fr->bailout) &&
             get_num(c, use, "fractal", "bound_radius", 1.6f, 0.5f, 100, &fr->bound_radius);
    } else if (ok && s->program == PROGRAM_MENGER) {
        ok = get_int(c, use, "fractal", "iterations", 4, 1, 7, &fr->iterations) &&
             get_num(c, use, "fractal", "size", 1, 1e-3f, 1e4f, &fr->size);
        fr->bound_radius = fr->size * 1.7320508f;
    } else if (ok) {
        ok = get_int(c, use, "fractal", "iterations", 12, 1, 64, &fr->iterations) &&
             get_num(c, use, "fractal", "scale", 2, -4, 4, &fr->scale) &&
             get_num(c, use, "fractal", "min_radius", 0.5f, 0.01f, 10, &fr->min_radius) &&
             get_num(c, use, "fractal", "fixed_radius", 1, 0.01f, 10, &fr->fixed_radius) &&
             get_num(c, use, "fractal", "fold_limit", 1, 0.01f, 10, &fr->fold_limit);
        if (ok && fabsf(fr->scale) <= 1.05f)
            ok = fail(c, "fractal.scale", "|scale| must be above 1.05 (at or below 1 the set is unbounded or empty)");
        if (ok && fr->min_radius >= fr->fixed_radius)
            ok = fail(c, "fractal.min_radius", "must be below fixed_radius");
        /* With |s| > 1 the set lies in the cube of half-side 2(|s|+1)/(|s|-1) (Lowe's Mandelbox). */
        float half = 2.0f * (fabsf(fr->scale) + 1.0f) / (fabsf(fr->scale) - 1.0f);
        ok = ok && get_num(c, use, "fractal", "bound_radius", half * 1.7320508f, 0.5f, 1000, &fr->bound_radius);
    }
    cJSON_Delete((cJSON *)empty);
    if (!ok)
        return false;
    /* Fractals are drawn with material 0; a scene may omit "materials". */
    if (s->material_count == 0) {
        s->material_count = 1;
        s->materials[0] = (scene_material){.name = "surface", .base_color = {1, 1, 1}, .roughness = 0.5f,
                                           .ior = 1.5f, .texture = -1, .uv_scale = 1};
    }
    s->map_glsl = NULL; /* set by the caller: an #include of the program's file */
    return true;
}

static bool parse_noise(ctx *c, const cJSON *root)
{
    struct scene_terrain *t = &c->s->terrain;
    const cJSON *tb = cJSON_GetObjectItemCaseSensitive(root, "terrain");
    static const char *const keys[] = {"base", "amplitude", "frequency", "octaves", "sand_line", "snow_line",
                                       "grass_slope", NULL};
    const cJSON *empty = cJSON_CreateObject(), *use = tb ? tb : empty;
    bool ok = (!tb || check_keys(c, tb, "terrain", keys)) &&
              get_num(c, use, "terrain", "base", 0, -1e6f, 1e6f, &t->base) &&
              get_num(c, use, "terrain", "amplitude", 40, 0, 1e6f, &t->amplitude) &&
              get_num(c, use, "terrain", "frequency", 0.01f, 1e-7f, 1e3f, &t->frequency) &&
              get_int(c, use, "terrain", "octaves", 6, 1, 12, &t->octaves) &&
              get_num(c, use, "terrain", "sand_line", -1e9f, -1e9f, 1e9f, &t->sand_line) &&
              get_num(c, use, "terrain", "snow_line", 1e9f, -1e9f, 1e9f, &t->snow_line) &&
              get_num(c, use, "terrain", "grass_slope", 0.8f, 0, 1, &t->grass_slope);
    cJSON_Delete((cJSON *)empty);
    return ok;
}

static bool parse_terrain(ctx *c, const cJSON *root)
{
    struct scene_terrain *t = &c->s->terrain;
    const cJSON *tb = cJSON_GetObjectItemCaseSensitive(root, "terrain");
    static const char *const keys[] = {"heightmap", "spacing", "height_min", "height_max", "exaggeration", "method",
                                       "sand_line", "snow_line", "grass_slope", NULL};
    if (!tb)
        return fail(c, "terrain", "a terrain scene needs a \"terrain\" block with a \"heightmap\"");
    if (!check_keys(c, tb, "terrain", keys))
        return false;
    const char *hm = NULL, *method = NULL;
    static const float zero2[3] = {0, 0, 0};
    float sp[3];
    if (!get_str(c, tb, "terrain", "heightmap", NULL, &hm) || !get_str(c, tb, "terrain", "method", "maxmip", &method))
        return false;
    if (!hm)
        return fail(c, "terrain.heightmap", "missing: a heightmap image (16-bit PNG, EXR, TIFF…)");
    if (!resolve_file(c, "terrain.heightmap", hm, t->heightmap))
        return false;
    const cJSON *spacing = cJSON_GetObjectItemCaseSensitive(tb, "spacing");
    if (spacing) {
        if (!cJSON_IsArray(spacing) || cJSON_GetArraySize(spacing) != 2 || !cJSON_IsNumber(spacing->child) ||
            !cJSON_IsNumber(spacing->child->next) || spacing->child->valuedouble <= 0 || spacing->child->next->valuedouble <= 0)
            return fail(c, "terrain.spacing", "expected [dx, dz]: metres per texel, both above 0");
        sp[0] = (float)spacing->child->valuedouble;
        sp[1] = (float)spacing->child->next->valuedouble;
    } else {
        memcpy(sp, zero2, sizeof sp);
    }
    t->spacing[0] = sp[0];
    t->spacing[1] = sp[1];
    if (!get_num(c, tb, "terrain", "height_min", 0, -1e5f, 1e5f, &t->height_min) ||
        !get_num(c, tb, "terrain", "height_max", 0, -1e5f, 1e5f, &t->height_max) ||
        !get_num(c, tb, "terrain", "exaggeration", 1, 0.01f, 100, &t->exaggeration) ||
        !get_num(c, tb, "terrain", "sand_line", -1e9f, -1e9f, 1e9f, &t->sand_line) ||
        !get_num(c, tb, "terrain", "snow_line", 1e9f, -1e9f, 1e9f, &t->snow_line) ||
        !get_num(c, tb, "terrain", "grass_slope", 0.8f, 0, 1, &t->grass_slope))
        return false;
    if (!strcmp(method, "maxmip"))
        t->maxmip = true;
    else if (!strcmp(method, "linear"))
        t->maxmip = false;
    else
        return fail(c, "terrain.method", "unknown method '%s' (known: maxmip, linear)", method);
    return true;
}

static bool parse_root(ctx *c, cJSON *root)
{
    scene *s = c->s;
    static const char *const keys[] = {"title", "program", "camera", "environment", "lights", "fog",
                                       "materials", "objects", "fractal", "terrain", "quality", "effects", NULL};
    if (!check_keys(c, root, "", keys))
        return false;
    const char *title = NULL, *prog = NULL;
    if (!get_str(c, root, "", "title", "", &title) || !get_str(c, root, "", "program", NULL, &prog))
        return false;
    snprintf(s->title, sizeof s->title, "%s", title);
    if (!prog)
        return fail(c, "program", "missing: say which program draws the scene, e.g. \"program\": \"csg\"");
    if (!program_from_name(prog, &s->program))
        return fail(c, "program", "unknown program '%s' (known: csg, mandelbulb, menger, mandelbox, terrain, noise)", prog);
    bool fractal = program_is_fractal(s->program), terrain = s->program == PROGRAM_TERRAIN || s->program == PROGRAM_NOISE;
    if (terrain && cJSON_GetObjectItemCaseSensitive(root, "objects"))
        return fail(c, "objects", "a terrain scene has no objects (its shape is the \"terrain\" block)");
    if (!terrain && cJSON_GetObjectItemCaseSensitive(root, "terrain"))
        return fail(c, "terrain", "only the terrain and noise programs read a terrain block");
    if (fractal && cJSON_GetObjectItemCaseSensitive(root, "objects"))
        return fail(c, "objects", "a %s scene has no objects (its shape is the \"fractal\" block)", prog);
    if (!fractal && cJSON_GetObjectItemCaseSensitive(root, "fractal"))
        return fail(c, "fractal", "only fractal programs (mandelbulb, menger, mandelbox) read a fractal block");

    const cJSON *cam = cJSON_GetObjectItemCaseSensitive(root, "camera");
    static const float cam_pos[3] = {0, 1, 5}, cam_at[3] = {0, 0, 0};
    if (cam) {
        static const char *const ckeys[] = {"position", "look_at", "fov", "adaptive_speed", NULL};
        if (!check_keys(c, cam, "camera", ckeys))
            return false;
        const cJSON *adaptive = cJSON_GetObjectItemCaseSensitive(cam, "adaptive_speed");
        if (adaptive && !cJSON_IsBool(adaptive))
            return fail(c, "camera.adaptive_speed", "expected true or false");
        s->adaptive_speed = adaptive ? cJSON_IsTrue(adaptive) : fractal;
    } else {
        s->adaptive_speed = fractal;
    }
    if (!get_vec3(c, cam, "camera", "position", cam_pos, -1e7f, 1e7f, s->cam_position) ||
        !get_vec3(c, cam, "camera", "look_at", cam_at, -1e7f, 1e7f, s->cam_look_at) ||
        !get_num(c, cam, "camera", "fov", 50, 1, 170, &s->cam_fov_deg))
        return false;

    const cJSON *fog = cJSON_GetObjectItemCaseSensitive(root, "fog");
    if (fog) {
        static const char *const fkeys[] = {"color", "density", "falloff", "height", NULL};
        static const float fog_grey[3] = {0.6f, 0.65f, 0.7f};
        if (!check_keys(c, fog, "fog", fkeys) ||
            !get_vec3(c, fog, "fog", "color", fog_grey, 0, 1e3f, s->fog_color) ||
            !get_num(c, fog, "fog", "density", 0.02f, 0, 1e3f, &s->fog_density) ||
            !get_num(c, fog, "fog", "falloff", 0, -1e3f, 1e3f, &s->fog_falloff) ||
            !get_num(c, fog, "fog", "height", 0, -1e7f, 1e7f, &s->fog_height))
            return false;
        s->has_fog = true;
    }
    if (!parse_environment(c, root) || !parse_lights(c, root) || !parse_quality(c, root) || !parse_effects(c, root))
        return false;
    if (terrain) {
        if (!parse_materials(c, root) ||
            !(s->program == PROGRAM_NOISE ? parse_noise(c, root) : parse_terrain(c, root)))
            return false;
        sb_printf(&c->code, "#include \"%s\"\n", program_map_file(s->program));
    } else if (fractal) {
        if (cJSON_GetObjectItemCaseSensitive(root, "materials") && !parse_materials(c, root))
            return false;
        if (!parse_fractal(c, root))
            return false;
        sb_printf(&c->code, "#include \"%s\"\n", program_map_file(s->program));
    } else if (!parse_materials(c, root) || !parse_objects(c, root)) {
        return false;
    }
    s->effects = derive_effects(s);
    return true;
}

/* ---- overrides: "a.b.0.c=value" --------------------------------------------------------------- */

static cJSON *parse_value(const char *v)
{
    cJSON *j = cJSON_ParseWithOpts(v, NULL, true); /* all of it: "1,2,3" must not parse as 1 */
    if (j)
        return j;
    if (strchr(v, ',')) { /* "1,2,3" is a vector */
        strbuf b = {0};
        sb_printf(&b, "[%s]", v);
        j = cJSON_ParseWithOpts(b.data, NULL, true);
        sb_free(&b);
        if (j)
            return j;
    }
    return cJSON_CreateString(v);
}

static bool apply_set(cJSON *root, const char *kv, err_t *err)
{
    const char *eq = strchr(kv, '=');
    assert(eq);
    char key[256];
    if ((size_t)(eq - kv) >= sizeof key)
        return err_set(err, "--set %s: key too long", kv);
    memcpy(key, kv, (size_t)(eq - kv));
    key[eq - kv] = '\0';
    cJSON *node = root;
    char *save = NULL;
    for (char *seg = strtok_r(key, ".", &save); seg; seg = strtok_r(NULL, ".", &save)) {
        bool last = (save == NULL || *save == '\0');
        if (cJSON_IsArray(node)) {
            char *end;
            long idx = strtol(seg, &end, 10);
            if (*end || idx < 0 || idx >= cJSON_GetArraySize(node))
                return err_set(err, "--set %s: '%s' is not an index of that array (it has %d items)", kv, seg,
                               cJSON_GetArraySize(node));
            if (last)
                return cJSON_ReplaceItemInArray(node, (int)idx, parse_value(eq + 1)) ||
                       err_set(err, "--set %s: cannot replace", kv);
            node = cJSON_GetArrayItem(node, (int)idx);
        } else if (cJSON_IsObject(node)) {
            cJSON *next = cJSON_GetObjectItemCaseSensitive(node, seg);
            if (last) {
                if (next)
                    cJSON_ReplaceItemInObjectCaseSensitive(node, seg, parse_value(eq + 1));
                else
                    cJSON_AddItemToObject(node, seg, parse_value(eq + 1));
                return true;
            }
            if (!next)
                next = cJSON_AddObjectToObject(node, seg);
            node = next;
        } else {
            return err_set(err, "--set %s: '%s' is inside a value that is neither an object nor an array", kv, seg);
        }
    }
    return err_set(err, "--set %s: empty key", kv);
}

/* ---- entry points ------------------------------------------------------------------------------ */

static void line_col(const char *text, const char *at, int *line, int *col)
{
    *line = 1;
    *col = 1;
    for (const char *p = text; p < at && *p; p++) {
        if (*p == '\n') {
            (*line)++;
            *col = 1;
        } else {
            (*col)++;
        }
    }
}

bool scene_load_text(const char *text, const char *path, const char *const *sets, int set_count, scene *s,
                     err_t *err)
{
    *s = (scene){0};
    snprintf(s->path, sizeof s->path, "%s", path);
    util_dirname(path, s->dir, sizeof s->dir);
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(s->name, sizeof s->name, "%.*s", (int)strcspn(base, "."), base);

    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, true);
    if (!root) {
        int line, col;
        line_col(text, end ? end : text, &line, &col);
        return err_set(err, "%s:%d:%d: malformed JSON near here (check commas, quotes and brackets)", path, line, col);
    }
    ctx c = {.file = path, .err = err, .s = s};
    bool ok = true;
    /* Check the file as written first, so a mistake there is reported as the file's, not an override's. */
    if (set_count > 0) {
        scene probe;
        ok = scene_load_text(text, path, NULL, 0, &probe, err);
        scene_free(&probe);
        *s = (scene){0};
        snprintf(s->path, sizeof s->path, "%s", path);
        util_dirname(path, s->dir, sizeof s->dir);
        snprintf(s->name, sizeof s->name, "%.*s", (int)strcspn(base, "."), base);
    }
    for (int i = 0; ok && i < set_count; i++)
        ok = apply_set(root, sets[i], err);
    if (ok) {
        ok = parse_root(&c, root);
        if (!ok && set_count > 0) { /* the file alone was fine, so an override broke it */
            static const char SUFFIX[] = " (from --set)";
            size_t len = strlen(err->msg);
            if (len + sizeof SUFFIX <= sizeof err->msg)
                memcpy(err->msg + len, SUFFIX, sizeof SUFFIX);
        }
    }
    cJSON_Delete(root);
    if (ok) {
        s->map_glsl = c.code.data;
    } else {
        sb_free(&c.code);
        scene_free(s);
    }
    return ok;
}

bool scene_locate(const char *name_or_path, char *out, size_t n, err_t *err)
{
    if (strchr(name_or_path, '/') || strstr(name_or_path, ".json")) {
        if (!util_file_exists(name_or_path))
            return err_set(err, "scene file '%s' not found: check the path, or pass a name from --list-scenes",
                           name_or_path);
        snprintf(out, n, "%s", name_or_path);
        return true;
    }
    snprintf(out, n, "%s/scenes/%s.json", util_data_dir(), name_or_path);
    if (!util_file_exists(out)) {
        strbuf names = {0};
        scene_list(&names);
        for (char *p = names.data; p && *p; p++)
            if (*p == '\n')
                *p = p[1] ? ' ' : '\0';
        err_set(err, "unknown scene '%s' (known: %s); pass a name or a path to a .json scene file", name_or_path,
                names.data ? names.data : "none");
        sb_free(&names);
        return false;
    }
    return true;
}

bool scene_load(const char *name_or_path, const char *const *sets, int set_count, scene *s, err_t *err)
{
    char path[PATH_MAX_LEN];
    char *text;
    if (!scene_locate(name_or_path, path, sizeof path, err) || !util_read_file(path, &text, NULL, err))
        return false;
    bool ok = scene_load_text(text, path, sets, set_count, s, err);
    free(text);
    return ok;
}

void scene_free(scene *s)
{
    free(s->map_glsl);
    s->map_glsl = NULL;
}

variant scene_variant(const scene *s)
{
    return (variant){.program = s->program, .effects = s->effects, .q = s->quality,
                     .num_lights = s->light_count, .num_materials = s->material_count,
                     .fractal_iterations = s->fractal.iterations, .terrain_maxmip = s->terrain.maxmip};
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

void scene_list(strbuf *out)
{
    char dir[PATH_MAX_LEN];
    snprintf(dir, sizeof dir, "%s/scenes", util_data_dir());
    DIR *d = opendir(dir);
    if (!d)
        return;
    char *names[256];
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) && n < 256;) {
        size_t len = strlen(e->d_name);
        if (len > 5 && !strcmp(e->d_name + len - 5, ".json"))
            names[n++] = strndup(e->d_name, len - 5);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], cmp_str);
    for (int i = 0; i < n; i++) {
        sb_printf(out, "%s\n", names[i]);
        free(names[i]);
    }
}
