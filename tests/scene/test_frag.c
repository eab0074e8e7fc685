/* Fragmentarium fragments read as data (scene/formula/frag.h), without GL: every annotation a parameter with
 * its type, default, range, group and description; presets as views (the camera from Eye, Target, Up
 * and FOV; Detail, FudgeFactor, MaxRaySteps and the parameters as overrides); the translation keeps
 * every line where it was and renames the fragment's own names; and each refusal in one line that
 * says why (with the include chain). The fragments are fathom's own (tests/frag/). */
/* realpath() is XSI */
#define _XOPEN_SOURCE 700
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "scene/formula/formula.h"
#include "scene/formula/frag.h"
#include "view/camera.h"
#include "view/shot.h"

static void fixture(const char *name, char *out, size_t n)
{
    snprintf(out, n, "%s/tests/frag/%s", FATHOM_SOURCE_DIR, name);
}

static const formula_param *param(const formula *f, const char *key)
{
    const formula_param *q = formula_find(f, key);
    if (!q)
        fail_msg("no parameter %s", key);
    return q;
}

static void annotations(void **st)
{
    (void)st;
    char path[PATH_MAX_LEN];
    fixture("sphere.frag", path, sizeof path);
    formula f;
    err_t e;
    if (!formula_load(path, NULL, &f, &e))
        fail_msg("%s", e.msg);
    assert_true(f.fragment);
    assert_string_equal(f.name, "sphere");
    assert_non_null(strstr(f.summary, "A sphere of radius Radius"));
    /* the include set's colouring first (DE-Raytracer.frag's group), then the fragment's own */
    const formula_param *q = param(&f, "Radius");
    assert_int_equal(q->type, FORMULA_FLOAT);
    assert_true(q->def[0] == 1 && q->lo == 0.1f && q->hi == 3);
    assert_string_equal(q->group, "Sphere");
    assert_string_equal(q->description, "the sphere's radius");
    q = param(&f, "Centre");
    assert_int_equal(q->type, FORMULA_VEC3);
    assert_true(q->lo == -2 && q->hi == 2 && q->def[2] == 0);
    q = param(&f, "Squash");
    assert_int_equal(q->type, FORMULA_VEC2);
    assert_true(q->def[0] == 1 && q->def[1] == 1 && q->hi == 2);
    q = param(&f, "Spare");
    assert_int_equal(q->type, FORMULA_VEC4);
    assert_true(q->def[3] == 0.4f && q->hi == 1);
    q = param(&f, "Hollow");
    assert_true(q->type == FORMULA_BOOL && q->def[0] == 0);
    q = param(&f, "Tint");
    assert_true(q->type == FORMULA_COLOR && q->def[0] == 0.9f && q->def[2] == 0.3f);
    q = param(&f, "Glint"); /* color[LO,DEFAULT,HI,R,G,B]: the colour, then its intensity in w */
    assert_true(q->type == FORMULA_COLOR4 && q->def[0] == 0.1f && q->def[2] == 0.3f && q->def[3] == 0.5f);
    assert_true(q->lo == 0 && q->hi == 2);
    assert_true(param(&f, "Detailed")->locked && !param(&f, "Radius")->locked); /* Radius: NotLocked */
    q = param(&f, "time");
    assert_true(q->type == FORMULA_FLOAT && q->def[0] == 0);
    assert_string_equal(param(&f, "BaseColor")->group, "Coloring");
    assert_int_equal(param(&f, "X")->type, FORMULA_COLOR4);
    /* an int slider named Iterations is the block's iterations: [max(1, 0), 20], default 4 */
    assert_null(formula_find(&f, "Iterations"));
    assert_true(f.iterations == 4 && f.iterations_lo == 1 && f.iterations_hi == 20);
    /* the translation keeps every line where it was: the DE on the same line of both */
    const char *t = frag_text(path);
    assert_non_null(t);
    int line = 1;
    for (const char *c = t; *c && strncmp(c, "float DE(vec3 p)", 16); c++)
        line += *c == '\n' && c[1] != '\0';
    char *src;
    assert_true(util_read_file(path, &src, NULL, &e));
    int want = 1;
    for (const char *c = src; *c && strncmp(c, "float DE(vec3 p)", 16); c++)
        want += *c == '\n';
    free(src);
    assert_int_equal(line, want);
    assert_non_null(strstr(t, "uniform float Radius;\n"));
    assert_non_null(strstr(t, "const float Detailed = FRAG_LOCKED_Detailed;\n"));
    assert_non_null(strstr(t, "const int Iterations = FRACTAL_ITERATIONS;\n"));
    assert_null(strstr(t, "#preset"));
    assert_null(strstr(t, "slider["));
    /* the prelude renames the fragment's names; the postlude takes them and its macros away */
    char name[PATH_MAX_LEN + 16];
    snprintf(name, sizeof name, "%s:prelude", path);
    assert_non_null(strstr(frag_text(name), "#define DE frag_DE\n"));
    assert_non_null(strstr(frag_text(name), "#define rotationMatrix3 frag_rotationMatrix3\n"));
    assert_non_null(strstr(frag_text(name), "#define PI 3.14159265358979323846264\n"));
    snprintf(name, sizeof name, "%s:postlude", path);
    assert_non_null(strstr(frag_text(name), "#undef orbitTrap\n"));
    assert_non_null(strstr(frag_text(name), "#undef PI\n"));
    assert_int_not_equal(frag_digest(path), 0);
}

/* Writes text to DIR/name (creating DIR), for the refusals. */
static void put(const char *dir, const char *name, const char *text)
{
    char path[2 * PATH_MAX_LEN];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void refused(const char *dir, const char *name, const char *want)
{
    char path[2 * PATH_MAX_LEN];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    formula f;
    err_t e = {""};
    if (formula_load(path, NULL, &f, &e))
        fail_msg("%s was opened (expected: %s)", name, want);
    if (!strstr(e.msg, want))
        fail_msg("%s: '%s' does not say '%s'", name, e.msg, want);
    assert_null(strchr(e.msg, '\n'));
}

/* The refusals' folder, made before and removed after the test (whether it passes or not). */
static char dir[] = "/tmp/fathom-frag-XXXXXX";
static int make_dir(void **st)
{
    (void)st;
    memcpy(dir, "/tmp/fathom-frag-XXXXXX", sizeof dir);
    return mkdtemp(dir) ? 0 : -1;
}
static int remove_dir(void **st)
{
    (void)st;
    char cmd[PATH_MAX_LEN];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

static void refusals(void **st)
{
    (void)st;
    char inner[PATH_MAX_LEN], cmd[3 * PATH_MAX_LEN];
    snprintf(inner, sizeof inner, "%s/in", dir);
    assert_int_equal(system((snprintf(cmd, sizeof cmd, "mkdir '%s'", inner), cmd)), 0);
    const char *de = "#include \"DE-Raytracer.frag\"\nfloat DE(vec3 p) { return length(p) - 1.0; }\n";
    /* each a file of the folder `in` (a DE fragment when its text starts with '+': de, then the rest) */
    static const struct { const char *name, *text, *want; } CASES[] = {
        {"main.frag", "+void main() { gl_FragColor = vec4(1.0); }\n", "main.frag:3: the fragment brings its own main(), a whole renderer"},
        {"flat.frag", "#include \"Progressive2D.frag\"\nvec3 color(vec2 p) { return vec3(p, 0.0); }\n",
         "#include \"Progressive2D.frag\": a 2D fragment"},
        {"node.frag", "#include \"DE-Raytracer.frag\"\nfloat notDE(vec3 p) { return 1.0; }\n", "no float DE(vec3 p)"},
        {"bare.frag", "float DE(vec3 p) { return length(p) - 1.0; }\n", "includes no DE renderer"},
        /* a missing include two deep: the chain says where from */
        {"mid.frag", "#donotrun\n\n#include \"Missing.frag\"\n", NULL},
        {"chain.frag", "#include \"mid.frag\"\n#include \"DE-Raytracer.frag\"\nfloat DE(vec3 p) { return 1.0; }\n",
         "mid.frag:3: #include \"Missing.frag\": no such file in the fragment's folder"},
        {"chain.frag", NULL, "(included from chain.frag:1)"},
        {"up.frag", "#include \"../outside.frag\"\n", "#include \"../outside.frag\": a '..' part"},
        {"abs.frag", "#include \"/etc/passwd\"\n", "#include \"/etc/passwd\": an absolute path"},
        {"link2.frag", "#include \"link.frag\"\n", "#include \"link.frag\": it leads out of the fragment's folder"},
        /* a link into a folder beside `in` whose name starts as its does (`inx`): out, though a bare prefix test
         * passes it (issue 58 item 17) */
        {"sib2.frag", "#include \"sib.frag\"\n", "#include \"sib.frag\": it leads out of the fragment's folder"},
        {"token.frag", "#include \"token.txt\"\n", "#include \"token.txt\": not a .frag file"},
        /* in/Include is a planted link to the folder above: not the collection's Include folder */
        {"planted.frag", "#include \"outside.frag\"\n", "#include \"outside.frag\": no such file"},
        {"tex.frag", "+uniform sampler2D tex; file[texture.jpg]\n", "tex.frag:3: 'sampler2D tex': a texture (file[...])"},
        {"slider.frag", "+uniform float S; slider[2,1]\n", "slider.frag:3: 'S': expected slider[LO,DEFAULT,HI]"},
        {"replace.frag", "+#replace \"a\" \"b\"\n", "#replace"},
        {"julia.frag", "+uniform float julia; slider[0,1,2]\n", "parameter 'julia': the name of a key of every fractal block"},
        {"ctl.frag", "#include \"DE-Raytracer.frag\"\nfloat DE(vec3 p) { return 1.0; }\x01\n", "ctl.frag:2: a control character (0x01)"},
        {"del.frag", "#include \"DE-Raytracer.frag\"\nfloat DE(vec3 p) { return 1.0; }\x7f\n", "del.frag:2: a control character (0x7f)"},
    };
    put(dir, "outside.frag", "#donotrun\nfloat leak() { return 1.0; }\n");
    snprintf(cmd, sizeof cmd, "ln -s ../outside.frag '%s/link.frag' && ln -s .. '%s/Include'", inner, inner);
    assert_int_equal(system(cmd), 0);
    snprintf(cmd, sizeof cmd, "mkdir '%sx' && ln -s ../inx/evil.frag '%s/sib.frag'", inner, inner);
    assert_int_equal(system(cmd), 0);
    char sib[PATH_MAX_LEN + 2];
    snprintf(sib, sizeof sib, "%sx", inner);
    put(sib, "evil.frag", "#donotrun\nfloat leak() { return 1.0; }\n");
    put(inner, "token.txt", "a secret\n");
    strbuf t = {0};
    for (size_t i = 0; i < sizeof CASES / sizeof *CASES; i++) {
        if (CASES[i].text) {
            sb_free(&t);
            sb_printf(&t, "%s%s", CASES[i].text[0] == '+' ? de : "", CASES[i].text + (CASES[i].text[0] == '+'));
            put(inner, CASES[i].name, t.data);
        }
        if (CASES[i].want)
            refused(inner, CASES[i].name, CASES[i].want);
    }
    /* no fixed cap below fathom's 128 (the renderer's 8 colouring parameters with them): 120 of the
     * fragment's own open, 121 do not */
    for (int n = 120; n <= 121; n++) {
        sb_free(&t);
        sb_append(&t, de);
        for (int i = 0; i < n; i++)
            sb_printf(&t, "uniform float P%d; slider[0,%d,200]\n", i, i);
        put(inner, "many.frag", t.data);
        formula f;
        err_t e;
        bool ok = formula_load((snprintf(cmd, sizeof cmd, "%s/many.frag", inner), cmd), NULL, &f, &e);
        if (n == 120)
            assert_true(ok && f.param_count == 128 && formula_find(&f, "P119")->def[0] == 119);
        else
            assert_true(!ok && strstr(e.msg, "more parameters than fathom's limit of 128"));
    }
    sb_free(&t);
}

/* Forty fragments opened one after another (the window's R, a corpus): the newest one's files are all
 * still kept for the compiler (the table drops the oldest; a file translated again counts as new). */
static void many_fragments(void **st)
{
    (void)st;
    char raytracer[PATH_MAX_LEN], real[PATH_MAX];
    snprintf(raytracer, sizeof raytracer, "%s/shaders/frag/raytracer.frag", FATHOM_SOURCE_DIR);
    assert_non_null(realpath(raytracer, real));
    for (int i = 0; i < 40; i++) {
        char name[32], path[2 * PATH_MAX_LEN], wrapper[2 * PATH_MAX_LEN + 16];
        snprintf(name, sizeof name, "f%d.frag", i);
        put(dir, name, "#include \"MathUtils.frag\"\n#include \"DE-Raytracer.frag\"\nfloat DE(vec3 p) { return 1.0; }\n");
        snprintf(path, sizeof path, "%s/%s", dir, name);
        formula f;
        err_t e;
        if (!formula_load(path, NULL, &f, &e))
            fail_msg("%s", e.msg);
        snprintf(wrapper, sizeof wrapper, "%s:prelude", f.file);
        if (!frag_text(f.file) || !frag_text(wrapper) || !frag_text(real))
            fail_msg("after %d fragments, one of the newest one's files is no longer kept", i + 1);
    }
}

static bool has_set(const shot_desc *d, const char *set)
{
    for (int i = 0; i < d->set_count; i++)
        if (!strcmp(d->sets[i], set))
            return true;
    return false;
}

static void presets(void **st)
{
    (void)st;
    char path[PATH_MAX_LEN], names[8][FRAG_PRESET_NAME_MAX];
    fixture("sphere.frag", path, sizeof path);
    err_t e;
    assert_int_equal(frag_presets(path, names, 8, &e), 2); /* KeyFrame.001 is a flight's key, not a view */
    assert_string_equal(names[0], "Default");
    assert_string_equal(names[1], "Rolled");
    strbuf text = {0};
    char *ignored = NULL;
    if (!frag_preset_shot(path, NULL, &text, &ignored, &e))
        fail_msg("%s", e.msg);
    shot_desc d;
    if (!shot_parse(text.data, "preset", &d, &e))
        fail_msg("%s", e.msg);
    assert_true(d.cam.position[0] == 0 && d.cam.position[1] == 0 && d.cam.position[2] == -5);
    assert_float_equal(d.cam.fov_y, (float)(2 * atan(0.4)), 1e-6); /* FOV is tan(vertical fov / 2) */
    assert_float_equal(d.cam.roll, 0, 1e-6);
    assert_true(has_set(&d, "fractal.Radius=1.5"));
    assert_true(has_set(&d, "quality.step_factor=0.8"));
    assert_true(has_set(&d, "quality.max_steps=300"));
    assert_true(has_set(&d, "fractal.hit_distance=0.001"));
    assert_non_null(strstr(d.sets[0], "fractal.formula="));
    assert_string_equal(ignored, "Specular"); /* the host's own light: fathom's stand for it */
    free(ignored);
    shot_free(&d);
    sb_free(&text);
    /* Rolled: the camera on +x looking at the origin with Up (0, 0.5, 1): the image's up is Up made
     * square to the view, (0, 1, 2) / √5 */
    if (!frag_preset_shot(path, "Rolled", &text, NULL, &e) || !shot_parse(text.data, "preset", &d, &e))
        fail_msg("%s", e.msg);
    camera_basis b = camera_get_basis(&d.cam);
    assert_float_equal(b.forward[0], -1, 1e-6);
    assert_float_equal(b.up[1], (float)(1 / sqrt(5)), 1e-6);
    assert_float_equal(b.up[2], (float)(2 / sqrt(5)), 1e-6);
    assert_float_equal(d.cam.fov_y, (float)(2 * atan(0.5)), 1e-6);
    assert_true(has_set(&d, "camera.aperture=0.0500000007") || has_set(&d, "camera.aperture=0.05"));
    assert_true(has_set(&d, "camera.focus=3.5"));
    assert_true(has_set(&d, "fractal.Centre=0,0.5,0"));
    assert_true(has_set(&d, "fractal.Hollow=true"));
    assert_true(has_set(&d, "fractal.Glint=0.4,0.5,0.6,1.5")); /* RGB, then the intensity */
    assert_true(has_set(&d, "fractal.Spare=1,0.2,0.3,0.4"));   /* 9 is past the slider: clamped */
    /* Detail 2 and MaxRaySteps 100000 clamped to fathom's bounds (issue 58 item 17: dropping either survived) */
    assert_true(has_set(&d, "fractal.hit_distance=1"));
    assert_true(has_set(&d, "quality.max_steps=4096"));
    shot_free(&d);
    sb_free(&text);
    assert_false(frag_preset_shot(path, "Nope", &text, NULL, &e));
    assert_non_null(strstr(e.msg, "sphere has no preset \"Nope\" (its presets: \"Default\", \"Rolled\")"));
}

int main(void)
{
    setenv("FATHOM_DATA_DIR", FATHOM_SOURCE_DIR, 1);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(annotations),
        cmocka_unit_test_setup_teardown(refusals, make_dir, remove_dir),
        cmocka_unit_test_setup_teardown(many_fragments, make_dir, remove_dir),
        cmocka_unit_test(presets),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
