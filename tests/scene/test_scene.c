/* Scene files: the shipped scene's content, syntax and value errors, overrides, effect derivation and
 * the CSG → GLSL code generation (the window's edits, shots and views: test_scene_edits.c; formulas:
 * test_formula.c). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <fcntl.h>
#include <unistd.h>

#include <cmocka.h>

#include "check.h"

#include "scene/overrides.h"
#include "scene/params.h"
#include "scene/formula/formula.h"
#include "scene/scene.h"
#include "view/shot.h"
#include "view/views.h"
#include "scene_text.h"

#define FX(e) (1u << EFFECT_##e)

static const char MINIMAL[] =
    "{\n"
    "  \"program\": \"csg\",\n"
    "  \"materials\": { \"a\": { \"base_color\": [0.5, 0.5, 0.5] } },\n"
    "  \"objects\": [ { \"shape\": \"sphere\", \"radius\": 1, \"material\": \"a\" } ]\n"
    "}\n";

/* n spheres on a grid, as JSON nodes: "{...}, {...}" */
static void spheres(strbuf *out, int n)
{
    for (int i = 0; i < n; i++)
        sb_printf(out, "%s{\"shape\": \"sphere\", \"radius\": 0.1, \"position\": [%d, %d, %d], \"material\": \"a\"}",
                  i ? ", " : "", i % 100, (i / 100) % 100, i / 10000);
}

/* Many primitives: the bounded ones in the objects' union (also through plain unions) go to the list,
 * whatever the count; code is limited, and the limit is an error before anything compiles. */
static void big_csg_scenes(void **st)
{
    (void)st;
    strbuf j = {0};
    sb_append(&j, "{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"shape\": \"plane\", "
                  "\"material\": \"a\"}, {\"op\": \"union\", \"children\": [");
    spheres(&j, 10000);
    sb_append(&j, "]}]}");
    scene s;
    err_t e;
    if (!scene_text_load(j.data, NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(s.csg_list_count, 10000);
    assert_int_equal(s.primitive_count, 10001); /* the plane stays code */
    assert_true(s.csg_node_count >= 10000 / 4 && s.csg_node_count < 2 * 10000);
    assert_int_equal(scene_text_count(s.map_glsl, "sdSphere("), 1); /* the dispatch, once */
    assert_int_equal(scene_text_count(s.map_glsl, "sdPlane("), 1);
    assert_non_null(strstr(s.map_glsl, "listMap(p, d"));
    scene_free(&s);
    sb_free(&j);

    /* below CSG_LIST_MIN: all code, as before */
    sb_append(&j, "{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [");
    spheres(&j, CSG_LIST_MIN - 1);
    sb_append(&j, "]}");
    if (!scene_text_load(j.data, NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(s.csg_list_count, 0);
    assert_int_equal(scene_text_count(s.map_glsl, "sdSphere("), CSG_LIST_MIN - 1);
    scene_free(&s);
    sb_free(&j);

    /* a moved union is not plain: its primitives are code, and too many of them are refused */
    sb_append(&j, "{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"op\": \"union\", "
                  "\"position\": [0, 1, 0], \"children\": [");
    spheres(&j, CSG_CODE_MAX + 1);
    sb_append(&j, "]}]}");
    scene_text_error(j.data, NULL, 0, "257 primitives inside operations would be compiled into the shader; at most 256");
    sb_free(&j);
}

static void shipped_csg_scene(void **st)
{
    (void)st;
    scene s;
    err_t e;
    if (!scene_load("csg", NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(s.program, PROGRAM_CSG);
    /* the bar: >= 8 primitives of >= 5 types, >= 4 materials, >= 2 lights + environment */
    assert_true(s.primitive_count >= 8);
    static const char *const kinds[] = {"sdSphere(", "sdBox(", "sdRoundBox(", "sdTorus(", "sdCylinder(",
                                        "sdCapsule(", "sdCappedCone(", "sdPlane("};
    int types = 0;
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
        types += strstr(s.map_glsl, kinds[i]) != NULL;
    assert_true(types >= 5);
    static const char *const ops[] = {"opUnion(", "opIntersection(", "opDifference(", "opSmoothUnion(",
                                      "opSmoothDifference("};
    for (size_t i = 0; i < sizeof ops / sizeof ops[0]; i++)
        if (!strstr(s.map_glsl, ops[i]))
            fail_msg("shipped scene lacks %s", ops[i]);
    bool metal = false, rough = false, mirror = false, glass = false;
    for (int i = 0; i < s.material_count; i++) {
        const scene_material *m = &s.materials[i];
        metal |= m->metallic == 1 && m->roughness > 0 && m->roughness <= MIRROR_ROUGHNESS;
        rough |= m->metallic == 0 && m->transmission == 0 && m->roughness >= 0.4f;
        mirror |= m->metallic == 1 && m->roughness == 0;
        glass |= m->transmission == 1 && m->ior > 1;
    }
    assert_true(metal && rough && mirror && glass);
    assert_true(s.light_count >= 2);
    assert_true(s.has_cubemap);
    assert_int_equal(s.texture_count, 2); /* the rock colour, and a heightmap for the relief */
    assert_true(s.texture_linear[1] && !s.texture_linear[0]);
    unsigned want = FX(SHADOWS) | FX(SOFT_SHADOWS) | FX(AO) | FX(REFLECTIONS) | FX(REFRACTION) | FX(ENVMAP) |
                    FX(TEXTURES) | FX(AA) | FX(RELIEF);
    assert_int_equal(s.effects, want); /* and no fog: the scene has none */
    scene_free(&s);
}

static void minimal_defaults(void **st)
{
    (void)st;
    scene s;
    err_t e;
    assert_true(scene_text_load(MINIMAL, NULL, 0, &s, &e));
    assert_int_equal(s.preset, PRESET_INTERACTIVE);
    assert_int_equal(s.quality.max_steps, preset_quality(PRESET_INTERACTIVE).max_steps);
    assert_near(s.materials[0].roughness, 0.5f, 0);
    assert_near(s.materials[0].ior, 1.5f, 0);
    assert_int_equal(s.materials[0].texture, -1);
    /* no lights: no shadows; constant environment: AO yes, envmap no; 4 spp (interactive): AA */
    assert_int_equal(s.effects, FX(AO) | FX(AA));
    assert_string_equal(s.name, "test");
    scene_free(&s);
}

static void syntax_error_has_line_and_column(void **st)
{
    (void)st;
    static const char text[] = "{\n  \"program\": \"csg\",\n  \"materials\": {\n    \"a\": { \"roughness\": 0.5,, }\n";
    scene_text_error(text, NULL, 0, "/tmp/test.json:4:");
    scene_text_error("", NULL, 0, "/tmp/test.json:1:1");
}

static void value_errors_name_the_key(void **st)
{
    (void)st;
    const char *cases[][2] = {
        {"\"rouhgness\": 0.5", "materials.a.rouhgness: unknown key 'rouhgness' (allowed here: base_color,"},
        {"\"roughness\": 1.5", "materials.a.roughness: expected a number from 0 to 1"},
        {"\"roughness\": \"high\"", "materials.a.roughness"},
        {"\"base_color\": [1, 1]", "materials.a.base_color: expected three numbers"},
        {"\"ior\": 0.5", "materials.a.ior"},
        {"\"texture\": \"nope.png\"", "materials.a.texture: file '/tmp/nope.png' not found"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "{\"program\": \"csg\", \"materials\": {\"a\": {%s}},"
                 " \"objects\": [{\"shape\": \"sphere\", \"material\": \"a\"}]}",
                 cases[i][0]);
        scene_text_error(text, NULL, 0, cases[i][1]);
    }
    scene_text_error("{\"program\": \"terrain9\"}", NULL, 0, "unknown program 'terrain9'");
    scene_text_error("{\"materials\": {}}", NULL, 0, "program");
    scene_text_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"shape\": \"blob\", "
                 "\"material\": \"a\"}]}", NULL, 0, "objects.0.shape: unknown shape 'blob'");
    scene_text_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"shape\": \"sphere\", "
                 "\"material\": \"b\"}]}", NULL, 0, "no material named 'b'");
    scene_text_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"op\": \"union\", "
                 "\"children\": [{\"shape\": \"sphere\", \"material\": \"a\"}]}]}", NULL, 0,
                 "objects.0.children: expected an array of at least two");
    scene_text_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"op\": \"smooth_union\", "
                 "\"children\": [{\"shape\": \"sphere\", \"material\": \"a\"}, {\"shape\": \"sphere\", "
                 "\"material\": \"a\"}]}]}", NULL, 0, "needs a blend radius");
    scene_text_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"lights\": [{\"type\": \"spot\"}], "
                 "\"objects\": [{\"shape\": \"sphere\", \"material\": \"a\"}]}", NULL, 0,
                 "lights.0.type: unknown light type 'spot'");
}

static void set_overrides(void **st)
{
    (void)st;
    scene s;
    err_t e;
    const char *sets[] = {"materials.a.roughness=0.1", "quality.preset=final", "quality.max_steps=300",
                          "camera.position=1,2,3", "effects.fog=on", "title=\"hello world\""};
    if (!scene_text_load(MINIMAL, sets, 6, &s, &e))
        fail_msg("%s", e.msg);
    assert_near(s.materials[0].roughness, 0.1f, 1e-7);
    assert_int_equal(s.preset, PRESET_FINAL);
    assert_int_equal(s.quality.max_steps, 300);
    assert_int_equal(s.quality.spp, preset_quality(PRESET_FINAL).spp);
    assert_near(s.cam_position[2], 3.0f, 0);
    assert_true(s.effects & FX(FOG));
    assert_string_equal(s.title, "hello world");
    scene_free(&s);

    const char *typo[] = {"materials.a.rouhgness=0.1"};
    scene_text_error(MINIMAL, typo, 1, "(from the override materials.a.rouhgness=0.1)");
    /* the override that breaks the scene is named, not the good one beside it */
    const char *two[] = {"materials.a.roughness=0.5", "materials.a.rouhgness=0.1"};
    scene_text_error(MINIMAL, two, 2, "(from the override materials.a.rouhgness=0.1)");
    /* a newline in a key stays out of the one-line message */
    const char *nl[] = {"materials.a.rough\nness=0.1"};
    scene_text_error(MINIMAL, nl, 1, "rough?ness");
    const char *bad_index[] = {"objects.5.radius=2"};
    scene_text_error(MINIMAL, bad_index, 1, "not an index");
    const char *bad_preset[] = {"quality.preset=ultra"};
    scene_text_error(MINIMAL, bad_preset, 1, "unknown preset 'ultra'");
    const char *bad_mode[] = {"effects.fog=maybe"};
    scene_text_error(MINIMAL, bad_mode, 1, "effects.fog: unknown mode 'maybe' (known: auto, on, off)");
    /* a material's name mistyped: no new, unused material (it was accepted, silently) */
    const char *bad_material[] = {"materials.b.roughness=0.1"};
    scene_text_error(MINIMAL, bad_material, 1, "the scene has no material 'b' (its materials: a)");
}

static void effects_follow_content(void **st)
{
    (void)st;
    static const char text[] =
        "{\"program\": \"csg\", \"fog\": {\"density\": 0.1},"
        " \"lights\": [{\"position\": [0, 3, 0], \"shadow\": \"soft\"}],"
        " \"materials\": {\"glass\": {\"transmission\": 1}, \"chrome\": {\"metallic\": 1, \"roughness\": 0.05}},"
        " \"objects\": [{\"shape\": \"sphere\", \"material\": \"glass\"}]}";
    scene s;
    err_t e;
    assert_true(scene_text_load(text, NULL, 0, &s, &e));
    assert_int_equal(s.effects,
                     FX(SHADOWS) | FX(SOFT_SHADOWS) | FX(AO) | FX(REFLECTIONS) | FX(REFRACTION) | FX(FOG) | FX(AA));
    scene_free(&s);
    /* switching shadows off takes their penumbrae too; no bounces leaves nothing to refract or reflect */
    const char *sets[] = {"effects.shadows=off", "quality.bounces=0", "effects.envmap=on", "quality.spp=1"};
    assert_true(scene_text_load(text, sets, 4, &s, &e));
    assert_int_equal(s.effects, FX(AO) | FX(FOG) | FX(ENVMAP));
    scene_free(&s);
}

/* Reads the nine numbers of the first `mat3(` in code. */
static void first_mat3(const char *code, double m[9])
{
    const char *p = strstr(code, "mat3(");
    assert_non_null(p);
    p += 5;
    for (int i = 0; i < 9; i++) {
        char *end;
        m[i] = strtod(p, &end);
        assert_true(end != p);
        p = end + strspn(end, ", ");
    }
}

static void csg_codegen(void **st)
{
    (void)st;
    static const char text[] =
        "{\"program\": \"csg\", \"materials\": {\"a\": {}, \"b\": {}},"
        " \"objects\": [{\"op\": \"difference\", \"position\": [1, 2, 3], \"children\": ["
        "   {\"shape\": \"box\", \"size\": [2, 4, 6], \"rotation\": [0, 90, 0], \"material\": \"a\"},"
        "   {\"shape\": \"sphere\", \"radius\": 0.5, \"material\": \"b\"}]},"
        "  {\"op\": \"smooth_intersection\", \"k\": 0.25, \"children\": ["
        "   {\"shape\": \"torus\", \"major\": 1, \"minor\": 0.2, \"material\": \"b\"},"
        "   {\"shape\": \"cone\", \"radius_bottom\": 1, \"height\": 2, \"material\": \"a\"}]}]}";
    scene s;
    err_t e;
    if (!scene_text_load(text, NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    const char *c = s.map_glsl;
    assert_int_equal(s.primitive_count, 4);
    assert_non_null(strstr(c, "vec2 map(vec3 p)"));
    assert_non_null(strstr(c, "p - vec3(1, 2, 3)"));   /* the group's translation */
    assert_non_null(strstr(c, "vec3(1, 2, 3))"));      /* box half extents */
    assert_non_null(strstr(c, "sdSphere("));
    assert_non_null(strstr(c, ", 0.5), 1.0)"));         /* the sphere carries material b = 1 */
    assert_non_null(strstr(c, "sdTorus("));
    assert_non_null(strstr(c, "sdCappedCone("));
    assert_int_equal(scene_text_count(c, "opDifference("), 1);
    assert_int_equal(scene_text_count(c, "opSmoothIntersection("), 1);
    assert_non_null(strstr(c, ", 0.25);"));
    assert_int_equal(scene_text_count(c, "opUnion("), 1); /* the two top-level nodes */
    /* 90° about Y: R maps +X to −Z. The shader needs world→object = Rᵀ; mat3() takes columns,
     * so its nine numbers are R's rows: (0,0,1), (0,1,0), (−1,0,0). */
    double m[9];
    first_mat3(c, m);
    static const double want[9] = {0, 0, 1, 0, 1, 0, -1, 0, 0};
    for (int i = 0; i < 9; i++)
        assert_near(m[i], want[i], 1e-7);
    scene_free(&s);
}

static void locate(void **st)
{
    (void)st;
    char path[PATH_MAX_LEN];
    err_t e;
    assert_true(scene_locate("csg", path, sizeof path, &e));
    assert_non_null(strstr(path, "scenes/csg.json"));
    assert_false(scene_locate("nosuchscene", path, sizeof path, &e));
    assert_non_null(strstr(e.msg, "unknown scene 'nosuchscene' (known: csg"));
    assert_false(scene_locate("/tmp/does/not/exist.json", path, sizeof path, &e));
    assert_non_null(strstr(e.msg, "not found"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shipped_csg_scene),
        cmocka_unit_test(minimal_defaults),
        cmocka_unit_test(syntax_error_has_line_and_column),
        cmocka_unit_test(value_errors_name_the_key),
        cmocka_unit_test(set_overrides),
        cmocka_unit_test(effects_follow_content),
        cmocka_unit_test(csg_codegen),
        cmocka_unit_test(big_csg_scenes),
        cmocka_unit_test(locate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
