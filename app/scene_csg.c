/* scene_csg — the csg program's "objects" tree → GLSL `vec2 map(vec3 p)` (distance, material).
 *
 * Every primitive is an exact signed distance (shaders/common/sdf.glsl); rotations and translations
 * keep it exact; union, intersection and difference give a bound (the smooth variants a bound within
 * k/4 of it). A primitive's keys, defaults, ranges and emitted call live in one row of SHAPES.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene_parse.h"

#define DEG2RAD 0.017453292519943295
static const float BIG = 1e5f, TINY = 1e-5f; /* metres: the range of every size */

/* Object-to-world rotation from Euler angles in degrees, applied X then Y then Z. The shader needs
 * world-to-object, the transpose; GLSL's mat3() takes columns, so we emit R's rows as columns. */
static bool emit_transform(scene_ctx *c, const cJSON *node, const char *path, const char *pin, char *pout)
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

/* ---- primitives: one row each ------------------------------------------------------------------- */

/* An emitter reads the shape's own keys from node and writes the GLSL distance call for point q. */
typedef bool (*shape_emitter)(scene_ctx *c, const cJSON *node, const char *path, const char *q, char *expr,
                              size_t n);

static bool emit_sphere(scene_ctx *c, const cJSON *node, const char *path, const char *q, char *expr, size_t n)
{
    float r;
    if (!get_num(c, node, path, "radius", 1, TINY, BIG, &r))
        return false;
    snprintf(expr, n, "sdSphere(%s, %.9g)", q, (double)r);
    return true;
}

static bool emit_box(scene_ctx *c, const cJSON *node, const char *path, const char *q, char *expr, size_t n)
{
    static const float unit[3] = {1, 1, 1};
    float v[3];
    if (!get_vec3(c, node, path, "size", unit, TINY, BIG, v))
        return false;
    snprintf(expr, n, "sdBox(%s, vec3(%.9g, %.9g, %.9g))", q, 0.5 * v[0], 0.5 * v[1], 0.5 * v[2]);
    return true;
}

static bool emit_round_box(scene_ctx *c, const cJSON *node, const char *path, const char *q, char *expr, size_t n)
{
    static const float unit[3] = {1, 1, 1};
    float v[3], r;
    if (!get_vec3(c, node, path, "size", unit, TINY, BIG, v) || !get_num(c, node, path, "radius", 0.1f, 0, BIG, &r))
        return false;
    if (2 * r > fminf(v[0], fminf(v[1], v[2])))
        return fail(c, path, "radius must be at most half the smallest size");
    snprintf(expr, n, "sdRoundBox(%s, vec3(%.9g, %.9g, %.9g), %.9g)", q, 0.5 * v[0], 0.5 * v[1], 0.5 * v[2],
             (double)r);
    return true;
}

static bool emit_torus(scene_ctx *c, const cJSON *node, const char *path, const char *q, char *expr, size_t n)
{
    float a, b;
    if (!get_num(c, node, path, "major", 1, TINY, BIG, &a) || !get_num(c, node, path, "minor", 0.25f, TINY, BIG, &b))
        return false;
    snprintf(expr, n, "sdTorus(%s, %.9g, %.9g)", q, (double)a, (double)b);
    return true;
}

static bool emit_cylinder(scene_ctx *c, const cJSON *node, const char *path, const char *q, char *expr, size_t n)
{
    float r, h;
    if (!get_num(c, node, path, "radius", 0.5f, TINY, BIG, &r) || !get_num(c, node, path, "height", 1, TINY, BIG, &h))
        return false;
    snprintf(expr, n, "sdCylinder(%s, %.9g, %.9g)", q, 0.5 * h, (double)r);
    return true;
}

static bool emit_capsule(scene_ctx *c, const cJSON *node, const char *path, const char *q, char *expr, size_t n)
{
    float r, h;
    if (!get_num(c, node, path, "radius", 0.5f, TINY, BIG, &r) || !get_num(c, node, path, "height", 1, 0, BIG, &h))
        return false;
    snprintf(expr, n, "sdCapsule(%s, %.9g, %.9g)", q, 0.5 * h, (double)r);
    return true;
}

static bool emit_cone(scene_ctx *c, const cJSON *node, const char *path, const char *q, char *expr, size_t n)
{
    float a, b, h;
    if (!get_num(c, node, path, "radius_bottom", 0.5f, 0, BIG, &a) ||
        !get_num(c, node, path, "radius_top", 0, 0, BIG, &b) || !get_num(c, node, path, "height", 1, TINY, BIG, &h))
        return false;
    if (a + b <= 0)
        return fail(c, path, "a cone needs radius_bottom or radius_top above 0");
    snprintf(expr, n, "sdCappedCone(%s, %.9g, %.9g, %.9g)", q, 0.5 * h, (double)a, (double)b);
    return true;
}

/* A plane through the position, facing `normal`. */
static bool emit_plane(scene_ctx *c, const cJSON *node, const char *path, const char *q, char *expr, size_t n)
{
    static const float up[3] = {0, 1, 0};
    float v[3];
    if (!get_vec3(c, node, path, "normal", up, -1, 1, v))
        return false;
    double len = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    if (len < 1e-6)
        return fail(c, path, "normal must not be zero");
    snprintf(expr, n, "sdPlane(%s, vec3(%.9g, %.9g, %.9g))", q, v[0] / len, v[1] / len, v[2] / len);
    return true;
}

enum { SHAPE_MAX_KEYS = 3 };
static const struct {
    const char *name;
    const char *keys[SHAPE_MAX_KEYS + 1]; /* its own keys besides shape, position, rotation, material */
    shape_emitter emit;
} SHAPES[] = {
    {"sphere", {"radius"}, emit_sphere},
    {"box", {"size"}, emit_box},
    {"round_box", {"size", "radius"}, emit_round_box},
    {"torus", {"major", "minor"}, emit_torus},
    {"cylinder", {"radius", "height"}, emit_cylinder},
    {"capsule", {"radius", "height"}, emit_capsule},
    {"cone", {"radius_bottom", "radius_top", "height"}, emit_cone},
    {"plane", {"normal"}, emit_plane},
};
enum { SHAPE_COUNT = sizeof SHAPES / sizeof SHAPES[0] };

static int find_shape(scene_ctx *c, const char *path, const char *shape)
{
    for (int i = 0; i < SHAPE_COUNT; i++)
        if (!strcmp(shape, SHAPES[i].name))
            return i;
    char p[KEY_PATH_MAX];
    child_path(p, sizeof p, path, "shape");
    strbuf known = {0};
    for (int i = 0; i < SHAPE_COUNT; i++)
        sb_printf(&known, "%s%s", i ? ", " : "", SHAPES[i].name);
    fail(c, p, "unknown shape '%s' (known: %s)", shape, known.data);
    sb_free(&known);
    return -1;
}

static int primitive_material(scene_ctx *c, const cJSON *node, const char *path)
{
    const char *mname = NULL;
    if (!get_str(c, node, path, "material", NULL, &mname))
        return -1;
    char mp[KEY_PATH_MAX];
    child_path(mp, sizeof mp, path, "material");
    if (!mname) {
        fail(c, mp, "every primitive needs a material, e.g. \"material\": \"%s\"", c->s->materials[0].name);
        return -1;
    }
    int mat = find_material(c->s, mname);
    if (mat < 0)
        fail(c, mp, "no material named '%s' in \"materials\"", mname);
    return mat;
}

static int emit_primitive(scene_ctx *c, const cJSON *node, const char *path, const char *pin, const char *shape)
{
    int si = find_shape(c, path, shape);
    if (si < 0)
        return -1;
    const char *keys[4 + SHAPE_MAX_KEYS + 1] = {"shape", "position", "rotation", "material"};
    int nk = 4;
    for (int i = 0; i < SHAPE_MAX_KEYS && SHAPES[si].keys[i]; i++)
        keys[nk++] = SHAPES[si].keys[i];
    keys[nk] = NULL;
    if (!check_keys(c, node, path, keys))
        return -1;
    int mat = primitive_material(c, node, path);
    char q[32], expr[512];
    if (mat < 0 || !emit_transform(c, node, path, pin, q) || !SHAPES[si].emit(c, node, path, q, expr, sizeof expr))
        return -1;
    int v = c->next_var++;
    sb_printf(&c->code, "    vec2 d%d = vec2(%s, %d.0);\n", v, expr, mat);
    c->s->primitive_count++;
    return v;
}

/* ---- operations ---------------------------------------------------------------------------------- */

static int emit_node(scene_ctx *c, const cJSON *node, const char *path, const char *pin);

static int emit_op(scene_ctx *c, const cJSON *node, const char *path, const char *pin, const char *op)
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
        strbuf known = {0};
        for (size_t i = 0; i < sizeof OPS / sizeof OPS[0]; i++)
            sb_printf(&known, "%s%s", i ? ", " : "", OPS[i].name);
        fail(c, p, "unknown op '%s' (known: %s)", op, known.data);
        sb_free(&known);
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

static int emit_node(scene_ctx *c, const cJSON *node, const char *path, const char *pin)
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

/* The "objects" array: one map() that unions the top-level nodes. */
bool csg_parse(scene_ctx *c, const cJSON *root)
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

