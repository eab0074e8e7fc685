/* Scene files: the shipped scene's content, syntax and value errors, overrides, effect derivation
 * and the CSG → GLSL code generation. */
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

#define FX(e) (1u << EFFECT_##e)

static const char MINIMAL[] =
    "{\n"
    "  \"program\": \"csg\",\n"
    "  \"materials\": { \"a\": { \"base_color\": [0.5, 0.5, 0.5] } },\n"
    "  \"objects\": [ { \"shape\": \"sphere\", \"radius\": 1, \"material\": \"a\" } ]\n"
    "}\n";

static bool load(const char *text, const char *const *sets, int n, scene *s, err_t *e)
{
    return scene_load_text(text, "/tmp/test.json", sets, n, s, e);
}

static void expect_error(const char *text, const char *const *sets, int n, const char *needle)
{
    scene s;
    err_t e = {{0}};
    assert_false(load(text, sets, n, &s, &e));
    if (!strstr(e.msg, needle))
        fail_msg("error '%s' does not mention '%s'", e.msg, needle);
}

static int count(const char *hay, const char *needle)
{
    int n = 0;
    for (const char *p = strstr(hay, needle); p; p = strstr(p + 1, needle))
        n++;
    return n;
}

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
    if (!load(j.data, NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(s.csg_list_count, 10000);
    assert_int_equal(s.primitive_count, 10001); /* the plane stays code */
    assert_true(s.csg_node_count >= 10000 / 4 && s.csg_node_count < 2 * 10000);
    assert_int_equal(count(s.map_glsl, "sdSphere("), 1); /* the dispatch, once */
    assert_int_equal(count(s.map_glsl, "sdPlane("), 1);
    assert_non_null(strstr(s.map_glsl, "listMap(p, d"));
    scene_free(&s);
    sb_free(&j);

    /* below CSG_LIST_MIN: all code, as before */
    sb_append(&j, "{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [");
    spheres(&j, CSG_LIST_MIN - 1);
    sb_append(&j, "]}");
    if (!load(j.data, NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(s.csg_list_count, 0);
    assert_int_equal(count(s.map_glsl, "sdSphere("), CSG_LIST_MIN - 1);
    scene_free(&s);
    sb_free(&j);

    /* a moved union is not plain: its primitives are code, and too many of them are refused */
    sb_append(&j, "{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"op\": \"union\", "
                  "\"position\": [0, 1, 0], \"children\": [");
    spheres(&j, CSG_CODE_MAX + 1);
    sb_append(&j, "]}]}");
    expect_error(j.data, NULL, 0, "257 primitives inside operations would be compiled into the shader; at most 256");
    sb_free(&j);
}

/* A shot's description round-trips exactly, and damaged ones are refused. */
static void shot_descriptions(void **st)
{
    (void)st;
    camera cam = {.position = {0.1, -2.5, 1e6 + 1e-9}, .yaw = 3.0f, .pitch = -1.2f, .fov_y = 0.7f};
    const char *sets[] = {"fractal.power=6", "materials.a.texture=/x y/z.png"};
    strbuf t = {0};
    shot_describe("/no/such/scene.json", sets, 2, &cam, 640, 360, &t);
    shot_desc d;
    err_t e;
    if (!shot_parse(t.data, "t", &d, &e))
        fail_msg("%s", e.msg);
    assert_string_equal(d.scene, "/no/such/scene.json");
    assert_int_equal(d.set_count, 2);
    assert_string_equal(d.sets[1], sets[1]);
    assert_memory_equal(&d.cam, &cam, sizeof cam); /* every float and double exact */
    assert_int_equal(d.width, 640);
    assert_int_equal(d.height, 360);
    assert_null(d.scene_text); /* no such file to carry */
    shot_free(&d);
    static const char *const BAD[] = {
        "", "{}", "[1]", "{\"scene\": 3}",
        "{\"scene\": \"/a.json\", \"sets\": [], \"camera\": {\"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 9, "
        "\"fov_y\": 1}, \"size\": [10, 10]}",
        "{\"scene\": \"/a.json\", \"sets\": [\"noequals\"], \"camera\": {\"position\": [0, 0, 0], \"yaw\": 0, "
        "\"pitch\": 0, \"fov_y\": 1}, \"size\": [10, 10]}",
        "{\"scene\": \"/a.json\", \"sets\": [], \"camera\": {\"position\": [0, 0, 1e400], \"yaw\": 0, \"pitch\": 0, "
        "\"fov_y\": 1}, \"size\": [10, 10]}",
        "{\"scene\": \"/a.json\", \"sets\": [], \"camera\": {\"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 0, "
        "\"fov_y\": 1}, \"size\": [0, 10]}",
    };
    for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; i++) {
        assert_false(shot_parse(BAD[i], "shot.png", &d, &e));
        assert_non_null(strstr(e.msg, "shot.png: its fathom shot description is damaged"));
    }
    sb_free(&t);
}

/* Presets travel: a shipped scene is named, a user's own is carried whole and reopens after its file
 * has gone (scene_provide_text); the overrides and camera come back exactly. */
static void presets_travel(void **st)
{
    (void)st;
    camera cam = {.position = {0.55991060388651759, 0.31993295291488832, 0.8398659058297766}, .yaw = 0.5f, .fov_y = 0.9f};
    const char *sets[] = {"fractal.power=6", "fractal.palette=[[1, 0, 0], [0, 1, 0], [0, 0, 1]]"};
    char path[PATH_MAX_LEN];
    err_t e;
    assert_true(scene_locate("mandelbulb", path, sizeof path, &e));
    strbuf t = {0};
    shot_describe(path, sets, 2, &cam, 64, 36, &t);
    shot_desc d;
    assert_true(shot_parse(t.data, "p.fathom", &d, &e));
    assert_string_equal(d.scene, "mandelbulb"); /* by name: found on any machine that has fathom */
    assert_null(d.scene_text);
    assert_memory_equal(&d.cam, &cam, sizeof cam);
    assert_string_equal(d.sets[1], sets[1]);
    shot_free(&d);
    sb_free(&t);
    /* a user's scene: carried, and loaded from the preset once the file is gone */
    char dir[] = "/tmp/fathom-preset-XXXXXX";
    assert_non_null(mkdtemp(dir));
    char file[PATH_MAX_LEN + 32];
    snprintf(file, sizeof file, "%s/mine.json", dir);
    FILE *f = fopen(file, "w");
    assert_non_null(f);
    fputs("{\"program\": \"mandelbulb\", \"fractal\": {\"power\": 5}}", f);
    fclose(f);
    t = (strbuf){0};
    shot_describe(file, NULL, 0, &cam, 64, 36, &t);
    remove(file);
    rmdir(dir);
    assert_true(shot_parse(t.data, "p.fathom", &d, &e));
    assert_non_null(d.scene_text);
    scene s;
    assert_false(scene_load(d.scene, NULL, 0, &s, &e)); /* gone... */
    scene_provide_text(d.scene, d.scene_text);
    if (!scene_load(d.scene, NULL, 0, &s, &e)) /* ...but carried */
        fail_msg("%s", e.msg);
    assert_near(s.fractal.values[0][0], 5, 0);
    scene_free(&s);
    shot_free(&d);
    sb_free(&t);
}

/* The panel's model: every value the parser reads, with its range; each formula parameter with its
 * declaration's range and words; only the knobs the scene uses; an edit's override reads back. */
static void panel_params(void **st)
{
    (void)st;
    param_list l = {0};
    scene s;
    err_t e;
    if (!scene_load_params("mandelbox", NULL, 0, &s, &l, &e))
        fail_msg("%s", e.msg);
    const formula *f = &s.fractal.formula;
    for (int i = 0; i < f->param_count; i++) {
        char key[PARAM_KEY_MAX];
        snprintf(key, sizeof key, "fractal.%s", f->params[i].key);
        const scene_param *p = params_find(&l, key);
        if (!p)
            fail_msg("%s is not in the panel", key);
        assert_true(p->lo == f->params[i].lo && p->hi == f->params[i].hi);
        assert_string_equal(p->help, f->params[i].description);
    }
    const scene_param *p = params_find(&l, "quality.max_steps");
    assert_true(p && p->type == PARAM_INT && p->lo == 1 && p->hi == 100000 && p->help[0]);
    assert_null(params_find(&l, "quality.droplet_lod"));   /* no droplets here */
    assert_null(params_find(&l, "quality.binary_steps"));  /* nor the lab's search */
    assert_non_null(params_find(&l, "fractal.glow"));
    /* the palette's colours in their order (the knobs a scene does not use were removed by moving the
     * last parameter into their place: the panel listed the palette 2, 0, 1) */
    const char *const ORDERED[] = {"mandelbox", "mandelbulb", "menger", "sierpinski"};
    for (size_t k = 0; k < sizeof ORDERED / sizeof ORDERED[0]; k++) {
        param_list o = {0};
        scene t;
        if (!scene_load_params(ORDERED[k], NULL, 0, &t, &o, &e))
            fail_msg("%s", e.msg);
        const scene_param *c0 = params_find(&o, "fractal.palette.0"), *c1 = params_find(&o, "fractal.palette.1"),
                          *c2 = params_find(&o, "fractal.palette.2");
        assert_true(c0 && c1 && c2 && c0 < c1 && c1 < c2);
        params_free(&o);
        scene_free(&t);
    }
    p = params_find(&l, "lights.0.intensity");
    assert_true(p && p->type == PARAM_FLOAT);
    p = params_find(&l, "effects.fog");
    assert_true(p && p->type == PARAM_ENUM && p->name_count == 3);
    /* an edit's override goes back through the parser and reads back */
    char kv[1024];
    p = params_find(&l, "fractal.scale");
    params_override(&l, p, (const double[3]){-1.7, 0, 0}, kv, sizeof kv);
    assert_string_equal(kv, "fractal.scale=-1.7");
    p = params_find(&l, "fractal.palette.1");
    assert_true(p && p->type == PARAM_COLOR && p->array_len == 3);
    params_override(&l, p, (const double[3]){0, 0.5, 1}, kv, sizeof kv);
    const char *sets[] = {kv};
    scene t;
    if (!scene_load("mandelbox", sets, 1, &t, &e)) /* a palette the file never had */
        fail_msg("%s: %s", kv, e.msg);
    assert_true(t.fractal.palette[1][1] == 0.5f && t.fractal.palette[0][0] == s.fractal.palette[0][0]);
    scene_free(&t);
    /* a value the slider gives, to all its digits: 0.123456789 reads back as the same float (with %g it
     * was 0.123457), a number and a vector component both */
    p = params_find(&l, "fractal.fold_limit");
    params_override(&l, p, (const double[3]){0.123456789, 0, 0}, kv, sizeof kv);
    char kv2[1024];
    params_override(&l, params_find(&l, "fractal.palette.2"), (const double[3]){0.123456789, 0.987654321, 0.5}, kv2,
                    sizeof kv2);
    const char *digits[] = {kv, kv2};
    if (!scene_load("mandelbox", digits, 2, &t, &e))
        fail_msg("%s: %s", kv, e.msg);
    assert_true(t.fractal.values[formula_find(&t.fractal.formula, "fold_limit") - t.fractal.formula.params][0] ==
                0.123456789f);
    assert_true(t.fractal.palette[2][0] == 0.123456789f && t.fractal.palette[2][1] == 0.987654321f);
    scene_free(&t);
    p = params_find(&l, "effects.fog");
    params_override(&l, p, (const double[3]){2, 0, 0}, kv, sizeof kv);
    assert_string_equal(kv, "effects.fog=off");
    scene_free(&s);
    params_free(&l);
    /* a CSG scene's primitives and materials are there too */
    if (!scene_load_params("csg", NULL, 0, &s, &l, &e))
        fail_msg("%s", e.msg);
    assert_non_null(params_find(&l, "materials.glass.ior"));
    assert_non_null(params_find(&l, "objects.1.radius")); /* the glass sphere (0 is the ground plane) */
    /* the panel titles each element by what it is */
    assert_string_equal(params_label_of(&l, "objects.1"), "sphere (glass)");
    assert_string_equal(params_label_of(&l, "objects.3"), "difference");
    assert_string_equal(params_label_of(&l, "objects.3.children.0"), "round_box (ceramic)");
    assert_string_equal(params_label_of(&l, "lights.1"), "directional");
    assert_null(params_label_of(&l, "objects.99"));
    scene_free(&s);
    params_free(&l);
}

/* Edits: one value a key, undo and redo over whole states, the oldest dropped when full. */
static void edits_undo(void **st)
{
    (void)st;
    static overrides o;
    memset(&o, 0, sizeof o);
    assert_false(overrides_set(&o, "no equals"));
    overrides_checkpoint(&o);
    assert_true(overrides_set(&o, "fractal.power=6"));
    overrides_checkpoint(&o);
    assert_true(overrides_set(&o, "fractal.power=7"));
    assert_true(overrides_set(&o, "fractal.bailout=3"));
    assert_int_equal(o.now.count, 2);
    assert_string_equal(overrides_get(&o, "fractal.power"), "7");
    assert_true(overrides_undo(&o));
    assert_string_equal(overrides_get(&o, "fractal.power"), "6");
    assert_null(overrides_get(&o, "fractal.bailout"));
    assert_true(overrides_undo(&o) && o.now.count == 0);
    assert_false(overrides_undo(&o));
    assert_true(overrides_redo(&o) && overrides_redo(&o));
    assert_string_equal(overrides_get(&o, "fractal.bailout"), "3");
    assert_false(overrides_redo(&o));
    for (int i = 0; i < OVERRIDES_UNDO + 5; i++) { /* a long session keeps the newest steps */
        char kv[32];
        snprintf(kv, sizeof kv, "fractal.power=%d", i);
        overrides_checkpoint(&o);
        overrides_set(&o, kv);
    }
    int undone = 0;
    while (overrides_undo(&o))
        undone++;
    assert_int_equal(undone, OVERRIDES_UNDO);
    assert_string_equal(overrides_get(&o, "fractal.power"), "4");
}

/* Saved views: saved, replaced, loaded, listed when unknown, slots, a broken file refused. */
static void saved_views(void **st)
{
    (void)st;
    char dir[] = "/tmp/fathom-views-XXXXXX", file[PATH_MAX_LEN];
    assert_non_null(mkdtemp(dir));
    char nested[PATH_MAX_LEN];
    snprintf(nested, sizeof nested, "%s/a/b", dir); /* a folder that does not exist yet */
    setenv("FATHOM_VIEWS_DIR", nested, 1);
    err_t e;
    assert_true(views_file("menger", file, sizeof file, &e));
    assert_int_equal(views_next_free(file), 1);
    assert_true(views_save(file, "1", "{\"x\": 1}", &e));
    assert_true(views_save(file, "2", "{\"x\": 2}", &e));
    assert_true(views_save(file, "1", "{\"x\": 3}", &e)); /* replaces */
    assert_int_equal(views_next_free(file), 3);
    char *text;
    assert_true(views_load(file, "1", &text, &e));
    assert_string_equal(text, "{\"x\":3}");
    free(text);
    assert_false(views_load(file, "7", &text, &e));
    assert_non_null(strstr(e.msg, "no saved view '7'"));
    assert_non_null(strstr(e.msg, "(1, 2)"));
    FILE *f = fopen(file, "w");
    fputs("[1, 2]", f);
    fclose(f);
    assert_false(views_load(file, "1", &text, &e));
    assert_non_null(strstr(e.msg, "not a views file"));
    unsetenv("FATHOM_VIEWS_DIR");
    unlink(file);
    char p[PATH_MAX_LEN];
    snprintf(p, sizeof p, "%s/a/b", dir);
    rmdir(p);
    snprintf(p, sizeof p, "%s/a", dir);
    rmdir(p);
    rmdir(dir);
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
    assert_true(load(MINIMAL, NULL, 0, &s, &e));
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
    expect_error(text, NULL, 0, "/tmp/test.json:4:");
    expect_error("", NULL, 0, "/tmp/test.json:1:1");
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
        expect_error(text, NULL, 0, cases[i][1]);
    }
    expect_error("{\"program\": \"terrain9\"}", NULL, 0, "unknown program 'terrain9'");
    expect_error("{\"materials\": {}}", NULL, 0, "program");
    expect_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"shape\": \"blob\", "
                 "\"material\": \"a\"}]}", NULL, 0, "objects.0.shape: unknown shape 'blob'");
    expect_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"shape\": \"sphere\", "
                 "\"material\": \"b\"}]}", NULL, 0, "no material named 'b'");
    expect_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"op\": \"union\", "
                 "\"children\": [{\"shape\": \"sphere\", \"material\": \"a\"}]}]}", NULL, 0,
                 "objects.0.children: expected an array of at least two");
    expect_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"objects\": [{\"op\": \"smooth_union\", "
                 "\"children\": [{\"shape\": \"sphere\", \"material\": \"a\"}, {\"shape\": \"sphere\", "
                 "\"material\": \"a\"}]}]}", NULL, 0, "needs a blend radius");
    expect_error("{\"program\": \"csg\", \"materials\": {\"a\": {}}, \"lights\": [{\"type\": \"spot\"}], "
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
    if (!load(MINIMAL, sets, 6, &s, &e))
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
    expect_error(MINIMAL, typo, 1, "(from the override materials.a.rouhgness=0.1)");
    /* the override that breaks the scene is named, not the good one beside it */
    const char *two[] = {"materials.a.roughness=0.5", "materials.a.rouhgness=0.1"};
    expect_error(MINIMAL, two, 2, "(from the override materials.a.rouhgness=0.1)");
    /* a newline in a key stays out of the one-line message */
    const char *nl[] = {"materials.a.rough\nness=0.1"};
    expect_error(MINIMAL, nl, 1, "rough?ness");
    const char *bad_index[] = {"objects.5.radius=2"};
    expect_error(MINIMAL, bad_index, 1, "not an index");
    const char *bad_preset[] = {"quality.preset=ultra"};
    expect_error(MINIMAL, bad_preset, 1, "unknown preset 'ultra'");
    const char *bad_mode[] = {"effects.fog=maybe"};
    expect_error(MINIMAL, bad_mode, 1, "effects.fog: unknown mode 'maybe' (known: auto, on, off)");
    /* a material's name mistyped: no new, unused material (it was accepted, silently) */
    const char *bad_material[] = {"materials.b.roughness=0.1"};
    expect_error(MINIMAL, bad_material, 1, "the scene has no material 'b' (its materials: a)");
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
    assert_true(load(text, NULL, 0, &s, &e));
    assert_int_equal(s.effects,
                     FX(SHADOWS) | FX(SOFT_SHADOWS) | FX(AO) | FX(REFLECTIONS) | FX(REFRACTION) | FX(FOG) | FX(AA));
    scene_free(&s);
    /* switching shadows off takes their penumbrae too; no bounces leaves nothing to refract or reflect */
    const char *sets[] = {"effects.shadows=off", "quality.bounces=0", "effects.envmap=on", "quality.spp=1"};
    assert_true(load(text, sets, 4, &s, &e));
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
    if (!load(text, NULL, 0, &s, &e))
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
    assert_int_equal(count(c, "opDifference("), 1);
    assert_int_equal(count(c, "opSmoothIntersection("), 1);
    assert_non_null(strstr(c, ", 0.25);"));
    assert_int_equal(count(c, "opUnion("), 1); /* the two top-level nodes */
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

/* ---- formulas: declarations read from the GLSL file, parameters by name ------------------------- */

static const char DECLARED[] =
    "// @formula A test formula (no one's)\n"
    "// @iterations 5 [2, 9]\n"
    "// @bound 2 * (abs(scale) + 1) / (abs(scale) - 1) * size\n"
    "// @step 0.75\n"
    "// @require inner < outer \"inner must be below outer\"\n"
    "uniform float uScale;      // @param 2 [-4, 4] not (-1.05, 1.05) the scale\n"
    "uniform int uFolds;        // @param 3 [1, 8] folds\n"
    "uniform bool uSwapAxes;    // @param true swap them\n"
    "uniform vec3 uSeed;        // @param 0.1,-0.2,0.3 [-2, 2] c\n"
    "uniform vec3 uTint;        // @color 0.9,0.5,0.1 a colour\n"
    "uniform float uInner;      // @param 0.5 [0.01, 10] inner\n"
    "uniform float uOuter;      // @param 1 [0.01, 10] outer\n"
    "uniform float uSize;       // @param 1.5 [0.1, 10] size\n"
    "uniform float uNotAParam;  // no annotation: the formula's own business\n";

static void formula_declarations(void **st)
{
    (void)st;
    formula f;
    err_t e;
    if (!formula_parse(DECLARED, "t.glsl", &f, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(f.param_count, 8);
    assert_int_equal(f.iterations, 5);
    assert_int_equal(f.iterations_lo, 2);
    assert_int_equal(f.iterations_hi, 9);
    assert_string_equal(f.step, "0.75");
    const formula_param *q = formula_find(&f, "swap_axes"); /* uSwapAxes: snake case */
    assert_non_null(q);
    assert_int_equal(q->type, FORMULA_BOOL);
    assert_near(q->def[0], 1, 0);
    q = formula_find(&f, "scale");
    assert_true(q->has_gap && q->gap_lo == -1.05f && q->gap_hi == 1.05f && q->lo == -4 && q->hi == 4);
    assert_string_equal(q->uniform, "uScale");
    assert_string_equal(q->description, "the scale");
    q = formula_find(&f, "seed");
    assert_int_equal(q->type, FORMULA_VEC3);
    assert_near(q->def[1], -0.2, 1e-7);
    assert_int_equal(formula_find(&f, "tint")->type, FORMULA_COLOR);
    assert_null(formula_find(&f, "not_a_param"));
    assert_int_equal(f.require_count, 1);
    assert_string_equal(f.requires[0].lhs, "inner");
    assert_string_equal(f.requires[0].rhs, "outer");
    /* the bound, an expression of the parameters (in declared order) */
    const float v[8][4] = {{-3}, {3}, {1}, {0.1f, -0.2f, 0.3f}, {0.9f, 0.5f, 0.1f}, {0.5f}, {1}, {1.5f}};
    double b;
    if (!formula_eval(&f, f.bound, v, 5, &b, &e))
        fail_msg("%s", e.msg);
    assert_near(b, 2.0 * 4.0 / 2.0 * 1.5, 1e-6);
    /* the grammar: precedence, left to right, unary minus, functions, a vector's components */
    static const struct { const char *text; double want; } GRAMMAR[] = {
        {"min(iterations, 3) + max(1, sqrt(16)) - -2", 3 + 4 + 2},
        {"size - inner * outer", 1.5 - 0.5 * 1}, /* a - b*c, not (a - b)*c */
        {"size - inner - outer", 1.5 - 0.5 - 1}, /* left to right */
        {"size / inner / 3", 1.5 / 0.5 / 3},
        {"-scale * -2", -6},
        {"-(size + 1) * 2", -5},
        {"2 + 3 * 4 - 6 / 2", 11},
        {"pow(2, 1 / (4 - 1))", 1.2599210498948732},
        {"abs(scale) + seed.y + seed.z", 3 - 0.2 + 0.3},
        {"seed", 0.1},
        {"sqrt(seed.x * seed.x + seed.y * seed.y + seed.z * seed.z)", 0.37416573867739417},
        {" ( size ) ", 1.5},
    };
    for (size_t k = 0; k < sizeof GRAMMAR / sizeof GRAMMAR[0]; k++) {
        if (!formula_eval(&f, GRAMMAR[k].text, v, 5, &b, &e))
            fail_msg("'%s': %s", GRAMMAR[k].text, e.msg);
        if (fabs(b - GRAMMAR[k].want) > 1e-6)
            fail_msg("'%s' = %.9g, not %.9g", GRAMMAR[k].text, b, GRAMMAR[k].want);
    }
    static const struct { const char *text, *why; } WRONG[] = {
        {"radius * 2", "unknown name 'radius'"},
        {"2 * (scale", "malformed"},
        {"1 / (scale + 3)", "not a finite number"},
        {"size.x", "'size' is a number: it has no .x"},
        {"max(1)", "malformed"},
        {"sqrt 4", "malformed"},
        {"2 3", "malformed"},
        {"", "malformed"},
        {"pow(-1, 0.5)", "not a finite number"},
    };
    for (size_t k = 0; k < sizeof WRONG / sizeof WRONG[0]; k++) {
        if (formula_eval(&f, WRONG[k].text, v, 5, &b, &e))
            fail_msg("'%s' was taken (= %g)", WRONG[k].text, b);
        if (!strstr(e.msg, WRONG[k].why))
            fail_msg("'%s': '%s' does not say '%s'", WRONG[k].text, e.msg, WRONG[k].why);
    }
    /* malformed declarations name the file and line */
    static const struct { const char *text, *want; } bad[] = {
        {"uniform float uX; // @param 1 [0, 1] x\n", "t.glsl: no '// @formula' line"},
        {"// @formula f\nuniform float uX; // @param 5 [0, 1] x\n", "t.glsl:2: the default is outside its range"},
        {"// @formula f\nuniform float uX; // @param 1 x\n", "t.glsl:2: expected DEFAULT [LO, HI]"},
        {"// @formula f\nuniform mat3 uX; // @param 1 [0, 2] x\n", "t.glsl:2: 'mat3': a parameter is a float, int, bool or vec3"},
        {"// @formula f\nuniform float x; // @param 1 [0, 2] x\n", "t.glsl:2: 'x': a parameter's uniform is named uName"},
        {"// @formula f\nuniform float uGlow; // @param 1 [0, 2] x\n", "t.glsl:2: 'glow' is a key of every fractal block"},
        {"// @formula f\n\n// @iterations 0 [0, 3]\n", "t.glsl:3: expected @iterations"},
        {"// @formula f\n// @frobnicate\n", "t.glsl:2: unknown directive"},
        {"// @formula f\nuniform float uA; // @param 1 [0, 2] a\nuniform float uA; // @param 1 [0, 2] a\n",
         "t.glsl:3: 'a' is declared twice"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err_t e2 = {{0}};
        assert_false(formula_parse(bad[i].text, "t.glsl", &f, &e2));
        if (!strstr(e2.msg, bad[i].want))
            fail_msg("case %zu: '%s' lacks '%s'", i, e2.msg, bad[i].want);
    }
}

/* Shipped formulas by name: the program's name may be a formula's; parameters by their keys, with the
 * ranges, gaps and requirements their files declare; every shipped formula parses. */
static void formula_scenes(void **st)
{
    (void)st;
    strbuf names = {0};
    formula_list(&names);
    int n = 0;
    for (char *name = names.data, *nl; name && *name; name = nl + 1, n++) {
        nl = strchr(name, '\n');
        *nl = '\0';
        formula f;
        err_t e;
        if (!formula_load(name, NULL, &f, &e))
            fail_msg("%s", e.msg);
        assert_true(f.summary[0] && f.iterations >= f.iterations_lo && f.iterations <= f.iterations_hi);
    }
    sb_free(&names);
    assert_true(n >= 12);
    static const char BOX[] = "{\"program\": \"mandelbox\"}";
    scene s;
    err_t e;
    const char *scale[] = {"fractal.scale=-3", "fractal.fold_limit=0.5"};
    assert_true(load(BOX, scale, 2, &s, &e));
    assert_int_equal(s.program, PROGRAM_FRACTAL);
    assert_string_equal(s.fractal.formula.name, "mandelbox");
    assert_near(s.fractal.values[0][0], -3, 0);
    assert_near(s.fractal.bound_radius, 2.0 * 4.0 / 2.0 * 1.7320508, 1e-5); /* its @bound at scale -3 */
    scene_free(&s);
    const char *gap[] = {"fractal.scale=1"};
    expect_error(BOX, gap, 1, "fractal.scale: 1 is between -1.05 and 1.05");
    const char *range[] = {"fractal.scale=9"};
    expect_error(BOX, range, 1, "fractal.scale: expected a number from -4 to 4");
    const char *order[] = {"fractal.min_radius=2", "fractal.fixed_radius=1"};
    expect_error(BOX, order, 2, "fractal.min_radius must be below fixed_radius");
    const char *unknown[] = {"fractal.power=8"};
    expect_error(BOX, unknown, 1, "unknown key 'power' (allowed here: formula, iterations, bound_radius, palette, "
                                  "glow, glow_color, julia, julia_c, hybrid, steps, precision, hit_distance, scale, min_radius, "
                                  "fixed_radius, fold_limit)");
    /* the formula switched by an override: its own keys apply */
    const char *bulb[] = {"fractal.formula=mandelbulb", "fractal.power=6"};
    assert_true(load(BOX, bulb, 2, &s, &e));
    assert_string_equal(s.fractal.formula.name, "mandelbulb");
    assert_near(s.fractal.values[0][0], 6, 0);
    assert_non_null(strstr(s.map_glsl, "#include \"fractal/mandelbulb.glsl\""));
    scene_free(&s);
    expect_error("{\"program\": \"fractal\"}", NULL, 0, "fractal.formula: missing");
    expect_error("{\"program\": \"fractal\", \"fractal\": {\"formula\": \"nosuch\"}}", NULL, 0,
                 "unknown formula 'nosuch' (known: amazing_surf");
    expect_error("{\"program\": \"nosuch\"}", NULL, 0, "or a formula's name: amazing_surf");
    /* the Mandelbulb's power as its file declares it: 0 and 1 have no bulb (issue 24's mutant accepted 0) */
    const char *power0[] = {"fractal.power=0"};
    expect_error("{\"program\": \"mandelbulb\"}", power0, 1, "fractal.power: expected a number from 3 to 16");
    const char *julia[] = {"fractal.julia=true", "fractal.julia_c=[0.1, 0.2, 0.3]", "fractal.iterations=65"};
    expect_error("{\"program\": \"mandelbulb\"}", julia, 3, "fractal.iterations: expected a number from 8 to 64");
    /* Julia sets and hybrids: step formulas only, and a hybrid's own keys are its formula's */
    const char *julia_menger[] = {"fractal.julia=true"};
    expect_error("{\"program\": \"menger\"}", julia_menger, 1, "julia, julia_c and steps belong to step formulas");
    const char *hybrid_menger[] = {"fractal.hybrid.formula=menger"};
    expect_error(BOX, hybrid_menger, 1, "fractal.hybrid.formula: menger has its own estimate (no @de)");
    const char *hybrid_self[] = {"fractal.hybrid.formula=mandelbox"};
    expect_error(BOX, hybrid_self, 1, "mandelbox with itself is mandelbox with more iterations");
    const char *hybrid_key[] = {"fractal.hybrid.formula=mandelbulb", "fractal.hybrid.scale=2"};
    expect_error(BOX, hybrid_key, 2, "fractal.hybrid.scale: unknown key 'scale' (allowed here: formula, steps, power, bailout)");
    const char *hybrid_range[] = {"fractal.hybrid.formula=mandelbulb", "fractal.hybrid.power=40"};
    expect_error(BOX, hybrid_range, 2, "fractal.hybrid.power: expected a number from 3 to 16");
    const char *hybrid[] = {"fractal.hybrid.formula=mandelbulb", "fractal.hybrid.power=6", "fractal.steps=2"};
    assert_true(load(BOX, hybrid, 3, &s, &e));
    assert_true(s.fractal.has_hybrid && s.fractal.steps[0] == 2 && s.fractal.steps[1] == 1);
    assert_near(s.fractal.hybrid_values[0][0], 6, 0);
    assert_near(s.fractal.escape, 64, 0); /* a log hybrid's escape: the larger radius, at most 64 */
    assert_non_null(strstr(s.map_glsl, "#define uPower " HYBRID_PREFIX "uPower"));
    scene_free(&s);
    /* precision: double needs a formula written for it, and a whole power for the bulb */
    const char *deep_surf[] = {"fractal.precision=double"};
    expect_error("{\"program\": \"amazing_surf\"}", deep_surf, 1, "fractal.precision: double needs a formula written for it");
    const char *deep_power[] = {"fractal.precision=double", "fractal.power=7.5"};
    expect_error("{\"program\": \"mandelbulb\"}", deep_power, 2, "fractal.precision: double needs a formula written for it (@deep) with whole power");
    const char *deep_ok[] = {"fractal.precision=double", "fractal.power=7"};
    assert_true(load("{\"program\": \"mandelbulb\"}", deep_ok, 2, &s, &e) && s.fractal.deep_now);
    scene_free(&s);
}

/* The new directives: a step formula declares @de and @escape together; @deep names real parameters. */
static void formula_step_declarations(void **st)
{
    (void)st;
    formula f;
    err_t e;
    static const char STEP[] = "// @formula s\n// @de log\n// @escape 2 * bailout\n// @trap 0 (bailout / 2)\n"
                               "// @deep whole power\nuniform float uPower; // @param 8 [2, 16] n\n"
                               "uniform float uBailout; // @param 2 [1, 9] b\n";
    if (!formula_parse(STEP, "s.glsl", &f, &e))
        fail_msg("%s", e.msg);
    assert_true(f.step_formula && f.de_log && f.deep);
    assert_string_equal(f.escape, "2 * bailout");
    assert_string_equal(f.trap[0], "0");
    assert_string_equal(f.trap[1], "(bailout / 2)");
    assert_string_equal(f.deep_whole, "power");
    static const struct { const char *text, *error; } BAD[] = {
        {"// @formula s\n// @de log\n", "s.glsl: a step formula (formulaStep) declares both @de and @escape"},
        {"// @formula s\n// @escape 2\n", "declares both @de and @escape"},
        {"// @formula s\n// @de quadratic\n", "s.glsl:2: expected @de log"},
        {"// @formula s\n// @trap 0\n", "s.glsl:2: expected @trap LO HI"},
        {"// @formula s\n// @deep whole nosuch\n", "@deep whole nosuch: no such parameter"},
        {"// @formula s\n// @deep maybe\n", "s.glsl:2: expected @deep, or @deep whole KEY"},
    };
    for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; i++) {
        assert_false(formula_parse(BAD[i].text, "s.glsl", &f, &e));
        if (!strstr(e.msg, BAD[i].error))
            fail_msg("'%s' does not mention '%s'", e.msg, BAD[i].error);
    }
}

/* Every shipped formula's declared range ends are accepted, typed as --help-formula prints them (%g),
 * and a step past either end is refused: 1.2 was below (double)1.2f, and "from 1.2 to 4" refused 1.2.
 * An end a formula's own requirement (@require) forbids with the other defaults is left out, named. */
static void formula_range_ends(void **st)
{
    (void)st;
    strbuf names = {0};
    formula_list(&names);
    int ends = 0, outside = 0, required = 0;
    for (char *name = strtok(names.data, "\n"); name; name = strtok(NULL, "\n")) {
        if (!strncmp(name, "note:", 5))
            continue;
        formula f;
        err_t e;
        if (!formula_load(name, NULL, &f, &e))
            fail_msg("%s", e.msg);
        for (int i = 0; i < f.param_count; i++) {
            const formula_param *q = &f.params[i];
            if (q->type == FORMULA_BOOL)
                continue;
            double span = (double)q->hi - (double)q->lo, step = span > 0 ? 1e-3 * span : 1e-3;
            /* the range's ends and a gap's (its ends are allowed: the gap is open), then steps past them
             * (into the gap too) */
            const double values[8] = {q->lo, q->hi, q->gap_lo, q->gap_hi, (double)q->lo - step, (double)q->hi + step,
                                      (double)q->gap_lo + step, (double)q->gap_hi - step};
            for (int j = 0; j < 8; j++) {
                int k = j < 4 ? j % 2 : 2 + j % 2; /* k < 2: an end, else a step past one */
                if (!q->has_gap && (j == 2 || j == 3 || j == 6 || j == 7))
                    continue;
                char kv[160], v[48], scene_name[96];
                /* the ends as --help-formula prints them (what a user types), the steps past them exact */
                snprintf(v, sizeof v, q->type == FORMULA_INT ? "%.0f" : k < 2 ? "%g" : "%.9g", values[j]);
                if (q->type >= FORMULA_VEC3)
                    snprintf(kv, sizeof kv, "fractal.%s=%s,%s,%s", q->key, v, v, v);
                else
                    snprintf(kv, sizeof kv, "fractal.%s=%s", q->key, v);
                snprintf(scene_name, sizeof scene_name, "fractal.formula=%s", name);
                const char *sets[] = {scene_name, kv};
                scene sc;
                bool ok = scene_load("fractal", sets, 2, &sc, &e);
                if (ok)
                    scene_free(&sc);
                if (k < 2 && !ok && strstr(e.msg, "(formula ")) { /* its @require, with the other defaults */
                    required++;
                    continue;
                }
                if (k < 2 && !ok)
                    fail_msg("%s: the range end %s is refused: %s", name, kv, e.msg);
                if (k >= 2 && ok)
                    fail_msg("%s: %s, past the declared range, is accepted", name, kv);
                k < 2 ? ends++ : outside++;
            }
        }
    }
    fprintf(stderr, "  %d range ends accepted, %d values past them refused, %d ends left to a requirement\n", ends,
            outside, required);
    assert_true(ends > 40 && outside == ends + required);
    sb_free(&names);
    /* a bool defaults to false as well as true, and takes both */
    formula f;
    err_t e;
    if (!formula_parse("// @formula b\nuniform bool uFlip; // @param false flip\n", "b.glsl", &f, &e))
        fail_msg("a bool defaulting to false: %s", e.msg);
    assert_true(f.param_count == 1 && f.params[0].type == FORMULA_BOOL && f.params[0].def[0] == 0);
    /* a @require is strict: min_radius equal to fixed_radius is refused, just below is taken */
    scene sc;
    const char *equal[] = {"fractal.formula=mandelbox", "fractal.min_radius=1", "fractal.fixed_radius=1"};
    assert_false(scene_load("fractal", equal, 3, &sc, &e));
    assert_non_null(strstr(e.msg, "min_radius must be below fixed_radius"));
    const char *below[] = {"fractal.formula=mandelbox", "fractal.min_radius=0.999", "fractal.fixed_radius=1"};
    if (!scene_load("fractal", below, 3, &sc, &e))
        fail_msg("%s", e.msg);
    scene_free(&sc);
    /* a hybrid's bounding sphere holds both formulas' sets: the larger of their bounds */
    const char *hybrid[2][2] = {{"fractal.formula=mandelbox", "fractal.hybrid.formula=mandelbulb"},
                                {"fractal.formula=mandelbulb", "fractal.hybrid.formula=mandelbox"}};
    for (int k = 0; k < 2; k++) {
        if (!scene_load("fractal", hybrid[k], 2, &sc, &e))
            fail_msg("%s", e.msg);
        assert_near(sc.fractal.bound_radius, 2 * 3.0 / 1.0 * 1.7320508, 1e-4); /* the Mandelbox's at scale 2 */
        scene_free(&sc);
    }
}

/* What a formula's declarations do to a scene: @step is an expression of the parameters, and caps
 * the step factor the shader is compiled with (a Julia set's or hybrid's is the scene's own); an int
 * parameter's range end is taken; the switch to double precision comes DEEP_MARGIN (4) times above a
 * float's resolution. */
static void formula_steps_and_precision(void **st)
{
    (void)st;
    scene s;
    err_t e;
    /* @step as an expression of a parameter, in a user's formula */
    char dir[] = "/tmp/fathom-int-XXXXXX", path[64], stepped[64];
    assert_non_null(mkdtemp(dir));
    snprintf(stepped, sizeof stepped, "%s/stepped.glsl", dir);
    static const char STEPPED[] = "// @formula a step factor that follows a parameter\n// @bound 1\n"
                                  "// @step 0.9 - 0.3 * min(1, abs(size - 1))\nuniform float uSize; // @param 1 [0.5, 3] size\n"
                                  "#include \"fractal/common.glsl\"\nreal formulaDE(real3 p, out float trap) { trap = 0.0; "
                                  "return length(p) - 0.5; }\n";
    int fd = open(stepped, O_WRONLY | O_CREAT | O_EXCL, 0600);
    assert_true(fd >= 0 && write(fd, STEPPED, sizeof STEPPED - 1) == (ssize_t)(sizeof STEPPED - 1));
    close(fd);
    char stepped_set[96];
    snprintf(stepped_set, sizeof stepped_set, "fractal.formula=%s", stepped);
    static const struct { const char *size; double step; } STEPS[] = {{"1", 0.9}, {"1.5", 0.75}, {"3", 0.6}, {"0.75", 0.825}};
    for (size_t k = 0; k < sizeof STEPS / sizeof STEPS[0]; k++) {
        char size[48];
        snprintf(size, sizeof size, "fractal.size=%s", STEPS[k].size);
        const char *over[] = {stepped_set, size, "quality.step_factor=1"};
        if (!scene_load("fractal", over, 3, &s, &e))
            fail_msg("%s", e.msg);
        assert_near(s.fractal.step, STEPS[k].step, 1e-6);
        strbuf pre = {0};
        scene_preamble(&s, &pre);
        char want[64];
        snprintf(want, sizeof want, "#define STEP_FACTOR %.9g\n", (double)(float)STEPS[k].step);
        if (!strstr(pre.data, want))
            fail_msg("size %s: the preamble lacks '%s'", STEPS[k].size, want);
        sb_free(&pre);
        scene_free(&s);
    }
    remove(stepped);
    /* below the cap (the Mandelbulb's 0.9) the scene's own step factor stands; a Julia set keeps the scene's */
    const char *lower[] = {"quality.step_factor=0.5"}, *julia[] = {"fractal.julia=true", "quality.step_factor=1"};
    for (int k = 0; k < 2; k++) {
        if (!scene_load("mandelbulb", k ? julia : lower, k ? 2 : 1, &s, &e))
            fail_msg("%s", e.msg);
        strbuf pre = {0};
        scene_preamble(&s, &pre);
        assert_non_null(strstr(pre.data, k ? "#define STEP_FACTOR 1\n" : "#define STEP_FACTOR 0.5\n"));
        sb_free(&pre);
        scene_free(&s);
    }
    /* an int parameter's ends are taken, a step past them refused */
    snprintf(path, sizeof path, "%s/folds.glsl", dir);
    fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0600);
    assert_true(fd >= 0);
    static const char TEXT[] = "// @formula an int parameter\n// @bound 1\nuniform int uFolds; // @param 3 [1, 8] folds\n"
                               "#include \"fractal/common.glsl\"\nreal formulaDE(real3 p, out float trap) { trap = 0.0; "
                               "return length(p) - 0.5; }\n";
    assert_true(write(fd, TEXT, sizeof TEXT - 1) == (ssize_t)(sizeof TEXT - 1));
    close(fd);
    char formula_set[96];
    snprintf(formula_set, sizeof formula_set, "fractal.formula=%s", path);
    static const struct { const char *set; bool ok; } INTS[] = {
        {"fractal.folds=8", true}, {"fractal.folds=1", true}, {"fractal.folds=9", false}, {"fractal.folds=0", false}};
    for (size_t k = 0; k < sizeof INTS / sizeof INTS[0]; k++) {
        const char *over[] = {formula_set, INTS[k].set};
        bool ok = scene_load("fractal", over, 2, &s, &e);
        if (ok != INTS[k].ok)
            fail_msg("%s: %s", INTS[k].set, ok ? "taken" : e.msg);
        if (ok)
            scene_free(&s);
    }
    remove(path);
    rmdir(dir);
    /* double precision from DEEP_MARGIN times a float's resolution: a view at twice it needs double, one
     * at 6 times does not (unless it already runs in double: twice the margin then) */
    if (!scene_load("deep_zoom", NULL, 0, &s, &e))
        fail_msg("%s", e.msg);
    assert_true(s.fractal.deep_ok && s.fractal.precision == PRECISION_AUTO);
    double eye[3] = {0, 0, 1.2}, at[3] = {0, 0, 0};
    camera cam = camera_look_at_deg(eye, at, 45);
    const int rows = 1080;
    double pa = camera_pixel_angle(&cam, rows), hk = s.quality.hit_k, pr = PRECISION_REL, norm = camera_norm(eye);
    static const struct { double times; bool now, want; } MARGIN[] = {{2, false, true}, {6, false, false}, {6, true, true},
                                                                        {3.9, false, true}, {4.1, false, false}};
    for (size_t k = 0; k < sizeof MARGIN / sizeof MARGIN[0]; k++) {
        /* the distance at which the threshold hk·d·pa is `times` the resolution pr·(|eye| + d) */
        double t = MARGIN[k].times, d = t * pr * norm / (hk * pa - t * pr);
        if (scene_needs_double(&s, d, &cam, rows, MARGIN[k].now) != MARGIN[k].want)
            fail_msg("at %g times a float's resolution (now %d): double %s", t, MARGIN[k].now, MARGIN[k].want ? "not chosen" : "chosen");
    }
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(formula_declarations),
        cmocka_unit_test(presets_travel),
        cmocka_unit_test(panel_params),
        cmocka_unit_test(edits_undo),
        cmocka_unit_test(formula_step_declarations),
        cmocka_unit_test(formula_scenes),
        cmocka_unit_test(shipped_csg_scene),
        cmocka_unit_test(minimal_defaults),
        cmocka_unit_test(syntax_error_has_line_and_column),
        cmocka_unit_test(value_errors_name_the_key),
        cmocka_unit_test(set_overrides),
        cmocka_unit_test(formula_range_ends),
        cmocka_unit_test(formula_steps_and_precision),
        cmocka_unit_test(effects_follow_content),
        cmocka_unit_test(csg_codegen),
        cmocka_unit_test(big_csg_scenes),
        cmocka_unit_test(shot_descriptions),
        cmocka_unit_test(saved_views),
        cmocka_unit_test(locate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
