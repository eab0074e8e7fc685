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
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "scene/formula/formula.h"
#include "scene/formula/frag.h"
#include "scene/scene.h"
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
    char inner[PATH_MAX_LEN], cmd[4 * PATH_MAX_LEN];
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
        /* textures: found as includes are, images only, no more than four */
        {"tex.frag", "+uniform sampler2D tex; file[texture.jpg]\n",
         "tex.frag:3: texture 'tex': no such file in the fragment's folder or its collection's Include folder"},
        {"texup.frag", "+uniform sampler2D tex; file[../x.png]\n", "texup.frag:3: texture 'tex': a '..' part"},
        {"texabs.frag", "+uniform samplerCube sky; file[/etc/x.png]\n", "texabs.frag:3: texture 'sky': an absolute path"},
        {"textok.frag", "+uniform sampler2D tex; file[token.txt]\n", "texture 'tex': not an image file"},
        {"texlink.frag", "+uniform sampler2D tex; file[link.png]\n", "texture 'tex': it leads out of the fragment's folder"},
        {"texfile.frag", "+uniform sampler2D tex; file(a.png)\n", "texture 'tex': expected file[IMAGE] after the sampler"},
        {"texfloat.frag", "+uniform float F; file[a.png]\n", "'F': file[...] names a texture: it goes on a sampler2D"},
        {"slider.frag", "+uniform float S; slider[2,1]\n", "slider.frag:3: 'S': expected slider[LO,DEFAULT,HI]"},
        {"replace.frag", "+#replace \"a\" \"b\"\n", "#replace"},
        {"julia.frag", "+uniform float julia; slider[0,1,2]\n", "parameter 'julia': the name of a key of every fractal block"},
        {"ctl.frag", "#include \"DE-Raytracer.frag\"\nfloat DE(vec3 p) { return 1.0; }\x01\n", "ctl.frag:2: a control character (0x01)"},
        {"del.frag", "#include \"DE-Raytracer.frag\"\nfloat DE(vec3 p) { return 1.0; }\x7f\n", "del.frag:2: a control character (0x7f)"},
    };
    put(dir, "outside.frag", "#donotrun\nfloat leak() { return 1.0; }\n");
    put(dir, "x.png", "outside the fragment's folder\n");
    snprintf(cmd, sizeof cmd, "ln -s ../outside.frag '%s/link.frag' && ln -s .. '%s/Include' && ln -s ../x.png '%s/link.png'",
             inner, inner, inner);
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
    /* no fixed cap below fathom's 160 (the renderer's 32 colouring and look parameters with them): 128 of
     * the fragment's own open, 129 do not */
    for (int n = 128; n <= 129; n++) {
        sb_free(&t);
        sb_append(&t, de);
        for (int i = 0; i < n; i++)
            sb_printf(&t, "uniform float P%d; slider[0,%d,200]\n", i, i);
        put(inner, "many.frag", t.data);
        formula f;
        err_t e;
        bool ok = formula_load((snprintf(cmd, sizeof cmd, "%s/many.frag", inner), cmd), NULL, &f, &e);
        if (n == 128)
            assert_true(ok && f.param_count == 160 && formula_find(&f, "P127")->def[0] == 127);
        else
            assert_true(!ok && strstr(e.msg, "more parameters than fathom's limit of 160"));
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
    assert_true(has_set(&d, "fractal.detail=-3")); /* Fragmentarium's rule: relative to the distance */
    assert_non_null(strstr(d.sets[0], "fractal.formula="));
    assert_true(has_set(&d, "fractal.Specular=0.4")); /* the renderer's look: a parameter */
    assert_string_equal(ignored, "Reflection"); /* a control fathom does not draw: said */
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
    assert_true(has_set(&d, "fractal.detail=0"));
    assert_true(has_set(&d, "quality.step_factor=1")); /* silent: the renderer's FudgeFactor */
    assert_true(has_set(&d, "quality.max_steps=4096"));
    shot_free(&d);
    sb_free(&text);
    assert_false(frag_preset_shot(path, "Nope", &text, NULL, &e));
    assert_non_null(strstr(e.msg, "sphere has no preset \"Nope\" (its presets: \"Default\", \"Rolled\")"));
}

/* Where a fragment starts, as FragM starts it: the first preset whose name holds "default" (any case), else
 * the sliders' defaults (3D.frag's camera, the renderer's MaxRaySteps 56 and FudgeFactor 1); the renderer's
 * Detail and MaxDistance are the scene's defaults, with Fragmentarium's hit rule. */
static void where_presets_start(void **st)
{
    (void)st;
    const char *head = "#include \"Fast-Raytracer.frag\"\nfloat DE(vec3 p) { return length(p) - 1.0; }\n";
    const char *views[] = {("#preset Wide\nEye = 0,0,-20\n#endpreset\n#preset My DEFAULT look\nEye = 0,3,-4\n"
                            "Detail = -4\n#endpreset\n#preset Close\nEye = 0,0,-2\n#endpreset\n"),
                           "#preset Wide\nEye = 0,0,-20\n#endpreset\n#preset Close\nEye = 0,0,-2\n#endpreset\n", ""};
    const int start[] = {1, -1, -1};
    const double eye_y[] = {3, 0, 0}, eye_z[] = {-4, -10, -10};
    for (int i = 0; i < 3; i++) {
        char name[16], path[2 * PATH_MAX_LEN], text[1024];
        snprintf(name, sizeof name, "start%d.frag", i);
        snprintf(text, sizeof text, "%s%s", head, views[i]);
        put(dir, name, text);
        snprintf(path, sizeof path, "%s/%s", dir, name);
        assert_int_equal(frag_preset_index(path, NULL), start[i]);
        strbuf shot = {0};
        shot_desc d;
        err_t e;
        if (!frag_preset_shot(path, NULL, &shot, NULL, &e) || !shot_parse(shot.data, path, &d, &e))
            fail_msg("%s: %s", name, e.msg);
        assert_float_equal(d.cam.position[1], eye_y[i], 1e-9);
        assert_float_equal(d.cam.position[2], eye_z[i], 1e-9);
        assert_float_equal(d.cam.fov_y, (float)(2 * atan(0.4)), 1e-6);
        assert_true(has_set(&d, "quality.max_steps=56"));
        assert_true(has_set(&d, "quality.step_factor=1"));
        assert_true(has_set(&d, "fractal.detail=-4") == (i == 0));
        scene s;
        const char *sets[SHOT_SET_MAX];
        for (int k = 0; k < d.set_count; k++)
            sets[k] = d.sets[k];
        if (!scene_load("fractal", sets, d.set_count, &s, &e))
            fail_msg("%s: %s", name, e.msg);
        assert_int_equal(s.fractal.hit_rule, HIT_RULE_FRAGMENT);
        assert_float_equal(s.fractal.detail, i == 0 ? -4.0f : -2.3f, 1e-6);
        assert_float_equal(s.fractal.max_distance, 100, 1e-6); /* Fast-Raytracer's MaxDistance */
        scene_free(&s);
        shot_free(&d);
        sb_free(&shot);
    }
    char path[2 * PATH_MAX_LEN];
    snprintf(path, sizeof path, "%s/start0.frag", dir);
    assert_int_equal(frag_preset_index(path, "Close"), 2);
    assert_int_equal(frag_preset_index(path, "Nope"), -1);
    /* the collection's own DE-Raytracer says whether it is Syntopia's (a shadow takes the camera light too; a
     * preset's value past a slider is taken as it is) or FragM's (the line commented out; the value clamped) */
    for (int syntopia = 0; syntopia < 2; syntopia++) {
        char coll[PATH_MAX_LEN], inc[PATH_MAX_LEN + 16], group[PATH_MAX_LEN + 16];
        snprintf(coll, sizeof coll, "%s/coll%d", dir, syntopia);
        snprintf(inc, sizeof inc, "%s/Include", coll);
        snprintf(group, sizeof group, "%s/Group", coll);
        assert_int_equal(mkdir(coll, 0755) | mkdir(inc, 0755) | mkdir(group, 0755), 0);
        put(inc, "DE-Raytracer.frag", syntopia ? "\t\tambient = mix(ambient,0.0,HardShadow*shadowStrength);\n"
                                               : "\t\t//ambient = mix(ambient,0.0,HardShadow*shadowStrength);\n");
        put(group, "f.frag", "#include \"DE-Raytracer.frag\"\nuniform float Zmul; slider[0,1,310]\n"
                             "float DE(vec3 p) { return length(p) - Zmul; }\n#preset Default\nZmul = -26\n#endpreset\n");
        snprintf(path, sizeof path, "%s/f.frag", group);
        formula f;
        err_t e;
        if (!formula_load(path, NULL, &f, &e))
            fail_msg("%s", e.msg);
        assert_int_equal(f.frag_syntopia, syntopia);
        strbuf shot = {0};
        shot_desc d;
        char *ignored = NULL;
        if (!frag_preset_shot(path, NULL, &shot, &ignored, &e) || !shot_parse(shot.data, path, &d, &e))
            fail_msg("%s", e.msg);
        assert_true(has_set(&d, syntopia ? "fractal.Zmul=-26" : "fractal.Zmul=0"));
        assert_true((ignored && strstr(ignored, "clamped")) == !syntopia);
        const char *sets[SHOT_SET_MAX];
        for (int k = 0; k < d.set_count; k++)
            sets[k] = d.sets[k];
        scene s;
        if (!scene_load("fractal", sets, d.set_count, &s, &e)) /* the value the preset gave loads */
            fail_msg("%s", e.msg);
        scene_free(&s);
        free(ignored);
        shot_free(&d);
        sb_free(&shot);
    }
}

/* The hit rule's and the look's keys at both ends of their ranges and just outside (fractal.detail -7..0,
 * fractal.max_distance 1e-3..1e6, the two rules and looks by name). */
static void rule_keys(void **st)
{
    (void)st;
    char formula_set[PATH_MAX_LEN + 32], path[PATH_MAX_LEN];
    fixture("sphere.frag", path, sizeof path);
    snprintf(formula_set, sizeof formula_set, "fractal.formula=%s", path);
    static const struct { const char *set; bool ok; } CASES[] = {
        {"fractal.detail=-7", true},          {"fractal.detail=0", true},
        {"fractal.detail=-7.01", false},      {"fractal.detail=0.01", false},
        {"fractal.max_distance=0.001", true}, {"fractal.max_distance=1000000", true},
        {"fractal.max_distance=0.0009", false}, {"fractal.max_distance=1000001", false},
        {"fractal.hit_rule=footprint", true}, {"fractal.hit_rule=relative", false},
        {"fractal.look=fathom", true},        {"fractal.look=fragmentarium", false},
    };
    for (size_t i = 0; i < sizeof CASES / sizeof *CASES; i++) {
        scene s;
        err_t e;
        bool ok = scene_load("fractal", (const char *const[]){formula_set, CASES[i].set}, 2, &s, &e);
        if (ok != CASES[i].ok)
            fail_msg("%s: %s", CASES[i].set, ok ? "loaded" : e.msg);
        if (ok)
            scene_free(&s);
    }
}

int main(void)
{
    setenv("FATHOM_DATA_DIR", FATHOM_SOURCE_DIR, 1);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(annotations),
        cmocka_unit_test_setup_teardown(refusals, make_dir, remove_dir),
        cmocka_unit_test_setup_teardown(many_fragments, make_dir, remove_dir),
        cmocka_unit_test(presets),
        cmocka_unit_test_setup_teardown(where_presets_start, make_dir, remove_dir),
        cmocka_unit_test(rule_keys),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
