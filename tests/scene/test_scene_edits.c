/* A scene as the window edits it and as images remember it: presets travel, the panel's parameters,
 * edits undone, shot descriptions read back, saved views. */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(presets_travel),
        cmocka_unit_test(panel_params),
        cmocka_unit_test(edits_undo),
        cmocka_unit_test(shot_descriptions),
        cmocka_unit_test(saved_views),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
