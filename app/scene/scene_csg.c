/* scene_csg — the csg program's "objects" tree → GLSL `vec2 map(vec3 p)` (distance, material).
 *
 * Every primitive is an exact signed distance (shaders/common/sdf.glsl); rotations and translations
 * keep it exact; union, intersection and difference give a bound (the smooth variants a bound within
 * k/4 of it). A primitive's keys, defaults, ranges and emitted call live in one row of SHAPES.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/droplets/bvh.h"
#include "scene/scene_parse.h"

#define DEG2RAD 0.017453292519943295
static const float BIG = 1e5f, TINY = 1e-5f; /* metres: the range of every size */

/* A node's placement: position and the world-to-object rotation (rows of w2o). */
typedef struct xform {
    float pos[3];
    double w2o[3][3];
    bool rotated;
} xform;

/* Object-to-world rotation R from Euler angles in degrees, applied X then Y then Z; world to object is
 * its transpose. */
static bool read_transform(scene_ctx *c, const cJSON *node, const char *path, xform *x)
{
    static const float zero[3] = {0, 0, 0};
    float rot[3];
    if (!scene_get_vec3(c, node, path, "position", zero, -1e6f, 1e6f, x->pos) ||
        !scene_get_vec3(c, node, path, "rotation", zero, -360, 360, rot))
        return false;
    x->rotated = rot[0] != 0 || rot[1] != 0 || rot[2] != 0;
    double cx = cos(rot[0] * DEG2RAD), sx = sin(rot[0] * DEG2RAD);
    double cy = cos(rot[1] * DEG2RAD), sy = sin(rot[1] * DEG2RAD);
    double cz = cos(rot[2] * DEG2RAD), sz = sin(rot[2] * DEG2RAD);
    /* R = Rz * Ry * Rx, row-major r[row][col] */
    const double r[3][3] = {
        {cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
        {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
        {-sy, cy * sx, cy * cx},
    };
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            x->w2o[i][j] = r[j][i];
    return true;
}

/* Emits the point in the node's frame; pout names it (pin itself when the node is not moved). */
static void emit_transform(scene_ctx *c, const xform *x, const char *pin, char *pout)
{
    const float *pos = x->pos;
    int v = c->next_var++;
    sprintf(pout, "q%d", v);
    if (!x->rotated) {
        if (pos[0] == 0 && pos[1] == 0 && pos[2] == 0)
            strcpy(pout, pin);
        else
            sb_printf(&c->code, "    vec3 %s = %s - vec3(%.9g, %.9g, %.9g);\n", pout, pin, (double)pos[0],
                      (double)pos[1], (double)pos[2]);
        return;
    }
    sb_printf(&c->code, "    vec3 %s = mat3(", pout);
    for (int col = 0; col < 3; col++) /* GLSL's mat3() takes columns: column j of w2o */
        for (int row = 0; row < 3; row++)
            sb_printf(&c->code, "%.9g%s", x->w2o[row][col], (row == 2 && col == 2) ? "" : ", ");
    sb_printf(&c->code, ") * (%s - vec3(%.9g, %.9g, %.9g));\n", pin, (double)pos[0], (double)pos[1],
              (double)pos[2]);
}

/* ---- primitives: one row each ------------------------------------------------------------------- */

enum { SHAPE_PARAMS = 4 };

/* A reader checks the shape's own keys and fills its parameters as the GLSL call takes them. */
typedef bool (*shape_reader)(scene_ctx *c, const cJSON *node, const char *path, float k[SHAPE_PARAMS]);
/* Half size of the box around the shape in its own frame (the primitive list's bounding boxes). */
typedef void (*shape_extent)(const float k[SHAPE_PARAMS], float half[3]);

static bool read_sphere(scene_ctx *c, const cJSON *node, const char *path, float k[SHAPE_PARAMS])
{
    return scene_get_num(c, node, path, "radius", 1, TINY, BIG, &k[0]);
}

static bool read_box(scene_ctx *c, const cJSON *node, const char *path, float k[SHAPE_PARAMS])
{
    static const float unit[3] = {1, 1, 1};
    if (!scene_get_vec3(c, node, path, "size", unit, TINY, BIG, k))
        return false;
    for (int i = 0; i < 3; i++)
        k[i] *= 0.5f;
    return true;
}

static bool read_round_box(scene_ctx *c, const cJSON *node, const char *path, float k[SHAPE_PARAMS])
{
    if (!read_box(c, node, path, k) || !scene_get_num(c, node, path, "radius", 0.1f, 0, BIG, &k[3]))
        return false;
    if (k[3] > fminf(k[0], fminf(k[1], k[2])))
        return scene_fail(c, path, "radius must be at most half the smallest size");
    return true;
}

static bool read_torus(scene_ctx *c, const cJSON *node, const char *path, float k[SHAPE_PARAMS])
{
    return scene_get_num(c, node, path, "major", 1, TINY, BIG, &k[0]) && scene_get_num(c, node, path, "minor", 0.25f, TINY, BIG, &k[1]);
}

/* Cylinder and capsule: half height, radius. */
static bool read_cylinder(scene_ctx *c, const cJSON *node, const char *path, float k[SHAPE_PARAMS])
{
    if (!scene_get_num(c, node, path, "radius", 0.5f, TINY, BIG, &k[1]) || !scene_get_num(c, node, path, "height", 1, TINY, BIG, &k[0]))
        return false;
    k[0] *= 0.5f;
    return true;
}

static bool read_capsule(scene_ctx *c, const cJSON *node, const char *path, float k[SHAPE_PARAMS])
{
    if (!scene_get_num(c, node, path, "radius", 0.5f, TINY, BIG, &k[1]) || !scene_get_num(c, node, path, "height", 1, 0, BIG, &k[0]))
        return false;
    k[0] *= 0.5f;
    return true;
}

static bool read_cone(scene_ctx *c, const cJSON *node, const char *path, float k[SHAPE_PARAMS])
{
    if (!scene_get_num(c, node, path, "radius_bottom", 0.5f, 0, BIG, &k[1]) ||
        !scene_get_num(c, node, path, "radius_top", 0, 0, BIG, &k[2]) || !scene_get_num(c, node, path, "height", 1, TINY, BIG, &k[0]))
        return false;
    if (k[1] + k[2] <= 0)
        return scene_fail(c, path, "a cone needs radius_bottom or radius_top above 0");
    k[0] *= 0.5f;
    return true;
}

/* A plane through the position, facing `normal` (unbounded: never in the primitive list). */
static bool read_plane(scene_ctx *c, const cJSON *node, const char *path, float k[SHAPE_PARAMS])
{
    static const float up[3] = {0, 1, 0};
    if (!scene_get_vec3(c, node, path, "normal", up, -1, 1, k))
        return false;
    double len = sqrt((double)k[0] * k[0] + (double)k[1] * k[1] + (double)k[2] * k[2]);
    if (len < 1e-6)
        return scene_fail(c, path, "normal must not be zero");
    for (int i = 0; i < 3; i++)
        k[i] = (float)(k[i] / len);
    return true;
}

static void extent_sphere(const float k[SHAPE_PARAMS], float e[3]) { e[0] = e[1] = e[2] = k[0]; }
static void extent_box(const float k[SHAPE_PARAMS], float e[3]) { memcpy(e, k, sizeof(float) * 3); }
static void extent_torus(const float k[SHAPE_PARAMS], float e[3]) { e[0] = e[2] = k[0] + k[1], e[1] = k[1]; }
static void extent_cylinder(const float k[SHAPE_PARAMS], float e[3]) { e[0] = e[2] = k[1], e[1] = k[0]; }
static void extent_capsule(const float k[SHAPE_PARAMS], float e[3]) { e[0] = e[2] = k[1], e[1] = k[0] + k[1]; }
static void extent_cone(const float k[SHAPE_PARAMS], float e[3]) { e[0] = e[2] = fmaxf(k[1], k[2]), e[1] = k[0]; }

/* `form`: the GLSL call's arguments after the point, f a float and v a vec3, from k in order. */
enum { SHAPE_MAX_KEYS = 3 };
static const struct {
    const char *name;
    const char *keys[SHAPE_MAX_KEYS + 1]; /* its own keys besides shape, position, rotation, material */
    shape_reader read;
    const char *glsl, *form;
    shape_extent extent; /* NULL: unbounded */
} SHAPES[] = {
    {"sphere", {"radius"}, read_sphere, "sdSphere", "f", extent_sphere},
    {"box", {"size"}, read_box, "sdBox", "v", extent_box},
    {"round_box", {"size", "radius"}, read_round_box, "sdRoundBox", "vf", extent_box},
    {"torus", {"major", "minor"}, read_torus, "sdTorus", "ff", extent_torus},
    {"cylinder", {"radius", "height"}, read_cylinder, "sdCylinder", "ff", extent_cylinder},
    {"capsule", {"radius", "height"}, read_capsule, "sdCapsule", "ff", extent_capsule},
    {"cone", {"radius_bottom", "radius_top", "height"}, read_cone, "sdCappedCone", "fff", extent_cone},
    {"plane", {"normal"}, read_plane, "sdPlane", "v", NULL},
};
enum { SHAPE_COUNT = sizeof SHAPES / sizeof SHAPES[0] };

/* The GLSL call for shape si at point q: the arguments are k's values (literals) or, with vec, the
 * components of a vec4 named vec (the primitive list's dispatch). */
static void shape_call(int si, const char *q, const float k[SHAPE_PARAMS], const char *vec, strbuf *out)
{
    static const char COMP[] = "xyzw";
    sb_printf(out, "%s(%s", SHAPES[si].glsl, q);
    int i = 0;
    for (const char *f = SHAPES[si].form; *f; f++) {
        int n = *f == 'v' ? 3 : 1;
        sb_append(out, n == 3 ? ", vec3(" : ", ");
        for (int j = 0; j < n; j++, i++) {
            if (vec)
                sb_printf(out, "%s%s.%c", j ? ", " : "", vec, COMP[i]);
            else
                sb_printf(out, "%s%.9g", j ? ", " : "", (double)k[i]);
        }
        if (n == 3)
            sb_append(out, ")");
    }
    sb_append(out, ")");
}

static int find_shape(scene_ctx *c, const char *path, const char *shape)
{
    for (int i = 0; i < SHAPE_COUNT; i++)
        if (!strcmp(shape, SHAPES[i].name))
            return i;
    char p[KEY_PATH_MAX];
    scene_child_path(p, sizeof p, path, "shape");
    strbuf known = {0};
    for (int i = 0; i < SHAPE_COUNT; i++)
        sb_printf(&known, "%s%s", i ? ", " : "", SHAPES[i].name);
    scene_fail(c, p, "unknown shape '%s' (known: %s)", shape, known.data);
    sb_free(&known);
    return -1;
}

static int primitive_material(scene_ctx *c, const cJSON *node, const char *path)
{
    const char *mname = NULL;
    if (!scene_get_str(c, node, path, "material", NULL, &mname))
        return -1;
    char mp[KEY_PATH_MAX];
    scene_child_path(mp, sizeof mp, path, "material");
    if (!mname) {
        scene_fail(c, mp, "every primitive needs a material, e.g. \"material\": \"%s\"", c->s->materials[0].name);
        return -1;
    }
    int mat = scene_find_material(c->s, mname);
    if (mat < 0)
        scene_fail(c, mp, "no material named '%s' in \"materials\"", mname);
    return mat;
}

/* A primitive as read from its node: for the generated code or the primitive list. */
typedef struct csg_prim {
    int shape, material;
    xform x;
    float k[SHAPE_PARAMS];
} csg_prim;

static bool read_primitive(scene_ctx *c, const cJSON *node, const char *path, const char *shape, csg_prim *pr)
{
    *pr = (csg_prim){.shape = find_shape(c, path, shape)};
    if (pr->shape < 0)
        return false;
    const char *keys[4 + SHAPE_MAX_KEYS + 1] = {"shape", "position", "rotation", "material"};
    int nk = 4;
    for (int i = 0; i < SHAPE_MAX_KEYS && SHAPES[pr->shape].keys[i]; i++)
        keys[nk++] = SHAPES[pr->shape].keys[i];
    keys[nk] = NULL;
    if (!scene_check_keys(c, node, path, keys))
        return false;
    pr->material = primitive_material(c, node, path);
    return pr->material >= 0 && read_transform(c, node, path, &pr->x) &&
           SHAPES[pr->shape].read(c, node, path, pr->k);
}

static int emit_primitive(scene_ctx *c, const cJSON *node, const char *path, const char *pin, const char *shape)
{
    csg_prim pr;
    if (!read_primitive(c, node, path, shape, &pr))
        return -1;
    char q[32];
    emit_transform(c, &pr.x, pin, q);
    int v = c->next_var++;
    sb_printf(&c->code, "    vec2 d%d = vec2(", v);
    shape_call(pr.shape, q, pr.k, NULL, &c->code);
    sb_printf(&c->code, ", %d.0);\n", pr.material);
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
        scene_child_path(p, sizeof p, path, "op");
        strbuf known = {0};
        for (size_t i = 0; i < sizeof OPS / sizeof OPS[0]; i++)
            sb_printf(&known, "%s%s", i ? ", " : "", OPS[i].name);
        scene_fail(c, p, "unknown op '%s' (known: %s)", op, known.data);
        sb_free(&known);
        return -1;
    }
    if (!scene_check_keys(c, node, path, keys))
        return -1;
    float k = 0;
    if (OPS[oi].smooth) {
        if (!cJSON_GetObjectItemCaseSensitive(node, "k")) {
            scene_fail(c, path, "'%s' needs a blend radius \"k\" (metres, > 0)", op);
            return -1;
        }
        if (!scene_get_num(c, node, path, "k", 0, 1e-5f, 1e4f, &k))
            return -1;
    } else if (cJSON_GetObjectItemCaseSensitive(node, "k")) {
        scene_child_path(p, sizeof p, path, "k");
        scene_fail(c, p, "'k' only applies to smooth_ ops");
        return -1;
    }
    const cJSON *kids = cJSON_GetObjectItemCaseSensitive(node, "children");
    scene_child_path(p, sizeof p, path, "children");
    if (!cJSON_IsArray(kids) || cJSON_GetArraySize(kids) < 2) {
        scene_fail(c, p, "expected an array of at least two nodes");
        return -1;
    }
    char q[32];
    xform x;
    if (!read_transform(c, node, path, &x))
        return -1;
    emit_transform(c, &x, pin, q);
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
        scene_fail(c, path, "expected a node: {\"shape\": ...} or {\"op\": ..., \"children\": [...]}");
        return -1;
    }
    const char *shape = NULL, *op = NULL;
    if (!scene_get_str(c, node, path, "shape", NULL, &shape) || !scene_get_str(c, node, path, "op", NULL, &op))
        return -1;
    if (shape && op) {
        scene_fail(c, path, "a node has either \"shape\" or \"op\", not both");
        return -1;
    }
    if (c->params && (shape || op)) {
        const cJSON *material = cJSON_GetObjectItemCaseSensitive(node, "material");
        char text[64];
        snprintf(text, sizeof text, cJSON_IsString(material) ? "%s (%s)" : "%s", shape ? shape : op,
                 cJSON_IsString(material) ? material->valuestring : "");
        params_label(c->params, path, text);
    }
    if (shape)
        return emit_primitive(c, node, path, pin, shape);
    if (op)
        return emit_op(c, node, path, pin, op);
    scene_fail(c, path, "a node needs \"shape\" (a primitive) or \"op\" (a CSG operation)");
    return -1;
}

/* ---- the primitive list ------------------------------------------------------------------------- */

/* A plain union: no placement, no blend. Its children are the objects' union as much as its siblings. */
static bool plain_union(const cJSON *node)
{
    const cJSON *op = cJSON_GetObjectItemCaseSensitive(node, "op");
    return cJSON_IsString(op) && !strcmp(op->valuestring, "union") &&
           !cJSON_GetObjectItemCaseSensitive(node, "position") && !cJSON_GetObjectItemCaseSensitive(node, "rotation") &&
           cJSON_IsArray(cJSON_GetObjectItemCaseSensitive(node, "children"));
}

static bool listable(const cJSON *node)
{
    const cJSON *shape = cJSON_GetObjectItemCaseSensitive(node, "shape");
    return cJSON_IsString(shape) && strcmp(shape->valuestring, "plane") != 0;
}

/* The objects' union, flattened through plain unions: every node, and its key path. */
typedef struct item {
    const cJSON *node;
    char path[KEY_PATH_MAX];
} item;

typedef struct items {
    item *v;
    int n, cap, listable;
} items;

static void flatten(const cJSON *arr, const char *path, items *out)
{
    int i = 0;
    for (const cJSON *n = arr->child; n; n = n->next, i++) {
        char p[KEY_PATH_MAX];
        char idx[16];
        snprintf(idx, sizeof idx, "%d", i);
        scene_child_path(p, sizeof p, path, idx);
        if (cJSON_IsObject(n) && plain_union(n)) {
            char kp[KEY_PATH_MAX];
            scene_child_path(kp, sizeof kp, p, "children");
            flatten(cJSON_GetObjectItemCaseSensitive(n, "children"), kp, out);
            continue;
        }
        if (out->n == out->cap) {
            out->cap = out->cap ? 2 * out->cap : 64;
            out->v = util_realloc(out->v, sizeof *out->v * (size_t)out->cap, "the objects");
        }
        out->v[out->n].node = n;
        snprintf(out->v[out->n].path, sizeof out->v[out->n].path, "%s", p);
        out->listable += cJSON_IsObject(n) && listable(n);
        out->n++;
    }
}

/* Packs a primitive as CSG_LIST_TEXELS texels (shaders/csg/list.glsl) and returns its world box. */
static void pack_primitive(const csg_prim *pr, float *t, float lo[3], float hi[3])
{
    float e[3];
    SHAPES[pr->shape].extent(pr->k, e);
    for (int i = 0; i < 3; i++) {
        /* the world box of a rotated box: |R| e, R = w2o transposed */
        float h = (float)(fabs(pr->x.w2o[0][i]) * e[0] + fabs(pr->x.w2o[1][i]) * e[1] + fabs(pr->x.w2o[2][i]) * e[2]);
        h = h * (1 + 1e-6f) + 1e-6f; /* rounding of the rotation must not cut the shape */
        lo[i] = pr->x.pos[i] - h;
        hi[i] = pr->x.pos[i] + h;
    }
    const float v[CSG_LIST_TEXELS * 4] = {
        pr->x.pos[0], pr->x.pos[1], pr->x.pos[2], (float)pr->shape,
        (float)pr->x.w2o[0][0], (float)pr->x.w2o[0][1], (float)pr->x.w2o[0][2], (float)pr->material,
        (float)pr->x.w2o[1][0], (float)pr->x.w2o[1][1], (float)pr->x.w2o[1][2], pr->k[0],
        (float)pr->x.w2o[2][0], (float)pr->x.w2o[2][1], (float)pr->x.w2o[2][2], pr->k[1],
        pr->k[2], pr->k[3], 0, 0,
    };
    memcpy(t, v, sizeof v);
}

/* Reads the listable items into the list, builds the BVH, and emits the dispatch list.glsl calls. */
static bool build_list(scene_ctx *c, const items *it)
{
    scene *s = c->s;
    int n = it->listable;
    if (n > CSG_LIST_MAX)
        return scene_fail(c, "objects", "%d primitives: at most %d are supported", n, CSG_LIST_MAX);
    float *packed = malloc(sizeof(float) * 4 * CSG_LIST_TEXELS * (size_t)n);
    float(*lo)[3] = malloc(sizeof *lo * (size_t)n), (*hi)[3] = malloc(sizeof *hi * (size_t)n);
    bvh_node *nodes = malloc(sizeof *nodes * (size_t)bvh_max_nodes(n));
    int *order = malloc(sizeof *order * (size_t)n);
    bool used[SHAPE_COUNT] = {0}, ok = packed && lo && hi && nodes && order;
    if (!ok)
        scene_fail(c, "objects", "out of memory for %d primitives", n);
    for (int i = 0, k = 0; ok && i < it->n; i++) {
        if (!cJSON_IsObject(it->v[i].node) || !listable(it->v[i].node))
            continue;
        csg_prim pr;
        ok = read_primitive(c, it->v[i].node, it->v[i].path, cJSON_GetObjectItemCaseSensitive(it->v[i].node, "shape")->valuestring, &pr);
        if (ok) {
            pack_primitive(&pr, packed + (size_t)k * 4 * CSG_LIST_TEXELS, lo[k], hi[k]);
            used[pr.shape] = true;
            k++;
        }
    }
    if (ok) {
        int count = bvh_build(n, (const float(*)[3])lo, (const float(*)[3])hi, nodes, order);
        /* the list in leaf order, so a leaf's primitives are consecutive: nodes point into it */
        s->csg_list = malloc(sizeof(float) * 4 * CSG_LIST_TEXELS * (size_t)n);
        s->csg_nodes = malloc(sizeof(float) * 4 * CSG_NODE_TEXELS * (size_t)count);
        ok = s->csg_list && s->csg_nodes;
        for (int i = 0; ok && i < n; i++)
            memcpy(s->csg_list + (size_t)i * 4 * CSG_LIST_TEXELS, packed + (size_t)order[i] * 4 * CSG_LIST_TEXELS,
                   sizeof(float) * 4 * CSG_LIST_TEXELS);
        for (int i = 0; ok && i < count; i++) {
            const float t[CSG_NODE_TEXELS * 4] = {nodes[i].lo[0], nodes[i].lo[1], nodes[i].lo[2], (float)nodes[i].first,
                                                  nodes[i].hi[0], nodes[i].hi[1], nodes[i].hi[2], (float)nodes[i].count};
            memcpy(s->csg_nodes + (size_t)i * 4 * CSG_NODE_TEXELS, t, sizeof t);
        }
        s->csg_list_count = n;
        s->csg_node_count = count;
        s->primitive_count += n;
        if (!ok)
            scene_fail(c, "objects", "out of memory for %d primitives", n);
    }
    free(packed);
    free(lo);
    free(hi);
    free(nodes);
    free(order);
    if (!ok)
        return false;
    /* the shapes the list holds, and nothing else, in the dispatch list.glsl calls */
    sb_append(&c->code, "float listShape(int shape, vec3 q, vec4 k)\n{\n");
    for (int i = 0; i < SHAPE_COUNT; i++)
        if (used[i]) {
            sb_printf(&c->code, "    if (shape == %d) return ", i);
            shape_call(i, "q", NULL, "k", &c->code);
            sb_append(&c->code, ";\n");
        }
    sb_append(&c->code, "    return 1e30;\n}\n#include \"csg/list.glsl\"\n");
    return true;
}

/* Emits node and unions it into *acc (the variable number of the union so far, -1 before the first). */
static bool emit_into_union(scene_ctx *c, const cJSON *node, const char *path, int *acc)
{
    int v = emit_node(c, node, path, "p");
    if (v < 0)
        return false;
    if (*acc >= 0) {
        int r = c->next_var++;
        sb_printf(&c->code, "    vec2 d%d = opUnion(d%d, d%d);\n", r, *acc, v);
        v = r;
    }
    *acc = v;
    return true;
}

/* The "objects" array: one map() that unions the top-level nodes. With CSG_LIST_MIN bounded primitives
 * or more in the objects' union, those come from the primitive list and the rest is code. */
bool scene_csg_parse(scene_ctx *c, const cJSON *root)
{
    const cJSON *objs = cJSON_GetObjectItemCaseSensitive(root, "objects");
    if (!cJSON_IsArray(objs) || cJSON_GetArraySize(objs) < 1)
        return scene_fail(c, "objects", "expected an array of at least one node");
    items it = {0};
    flatten(objs, "objects", &it);
    bool list = it.listable >= CSG_LIST_MIN, ok = !list || build_list(c, &it);
    if (ok)
        sb_append(&c->code, "vec2 map(vec3 p)\n{\n");
    int acc = -1, i = 0;
    for (const cJSON *n = objs->child; ok && !list && n; n = n->next, i++) {
        char p[64];
        snprintf(p, sizeof p, "objects.%d", i);
        ok = emit_into_union(c, n, p, &acc);
    }
    for (int k = 0; ok && list && k < it.n; k++)
        if (!cJSON_IsObject(it.v[k].node) || !listable(it.v[k].node))
            ok = emit_into_union(c, it.v[k].node, it.v[k].path, &acc);
    free(it.v);
    if (!ok)
        return false;
    int code = c->s->primitive_count - c->s->csg_list_count;
    if (code > CSG_CODE_MAX)
        return scene_fail(c, "objects", "%d primitives inside operations would be compiled into the shader; at most %d "
                    "are (compile time grows fast): put primitives at the top level of \"objects\" or in plain "
                    "unions (no position or rotation), where any number is drawn from a list", code, CSG_CODE_MAX);
    if (!list)
        sb_printf(&c->code, "    return d%d;\n}\n", acc);
    else if (acc < 0)
        sb_append(&c->code, "    return listMap(p, vec2(1e30, 0.0));\n}\n");
    else /* the code's distance is the bound the list's search starts from */
        sb_printf(&c->code, "    return listMap(p, d%d);\n}\n", acc);
    return true;
}
