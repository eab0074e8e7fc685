/* Fractal formulas read from their files (scene/formula/formula.h): every declaration form and the
 * malformed ones (each error names file and line), steps, the shipped formulas' scenes, every range's
 * ends and the switch to double precision. */
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
    assert_true(scene_text_load(BOX, scale, 2, &s, &e));
    assert_int_equal(s.program, PROGRAM_FRACTAL);
    assert_string_equal(s.fractal.formula.name, "mandelbox");
    assert_near(s.fractal.values[0][0], -3, 0);
    assert_near(s.fractal.bound_radius, 2.0 * 4.0 / 2.0 * 1.7320508, 1e-5); /* its @bound at scale -3 */
    scene_free(&s);
    const char *gap[] = {"fractal.scale=1"};
    scene_text_error(BOX, gap, 1, "fractal.scale: 1 is between -1.05 and 1.05");
    const char *range[] = {"fractal.scale=9"};
    scene_text_error(BOX, range, 1, "fractal.scale: expected a number from -4 to 4");
    const char *order[] = {"fractal.min_radius=2", "fractal.fixed_radius=1"};
    scene_text_error(BOX, order, 2, "fractal.min_radius must be below fixed_radius");
    const char *unknown[] = {"fractal.power=8"};
    scene_text_error(BOX, unknown, 1, "unknown key 'power' (allowed here: formula, iterations, bound_radius, palette, "
                                  "glow, glow_color, julia, julia_c, hybrid, steps, precision, hit_distance, hit_rule, detail, "
                                  "max_distance, look, scale, min_radius, "
                                  "fixed_radius, fold_limit)");
    /* the formula switched by an override: its own keys apply */
    const char *bulb[] = {"fractal.formula=mandelbulb", "fractal.power=6"};
    assert_true(scene_text_load(BOX, bulb, 2, &s, &e));
    assert_string_equal(s.fractal.formula.name, "mandelbulb");
    assert_near(s.fractal.values[0][0], 6, 0);
    assert_non_null(strstr(s.map_glsl, "#include \"fractal/mandelbulb.glsl\""));
    scene_free(&s);
    scene_text_error("{\"program\": \"fractal\"}", NULL, 0, "fractal.formula: missing");
    scene_text_error("{\"program\": \"fractal\", \"fractal\": {\"formula\": \"nosuch\"}}", NULL, 0,
                 "unknown formula 'nosuch' (known: amazing_surf");
    scene_text_error("{\"program\": \"nosuch\"}", NULL, 0, "or a formula's name: amazing_surf");
    /* the Mandelbulb's power as its file declares it: 0 and 1 have no bulb (issue 24's mutant accepted 0) */
    const char *power0[] = {"fractal.power=0"};
    scene_text_error("{\"program\": \"mandelbulb\"}", power0, 1, "fractal.power: expected a number from 3 to 16");
    const char *julia[] = {"fractal.julia=true", "fractal.julia_c=[0.1, 0.2, 0.3]", "fractal.iterations=65"};
    scene_text_error("{\"program\": \"mandelbulb\"}", julia, 3, "fractal.iterations: expected a number from 8 to 64");
    /* Julia sets and hybrids: step formulas only, and a hybrid's own keys are its formula's */
    const char *julia_menger[] = {"fractal.julia=true"};
    scene_text_error("{\"program\": \"menger\"}", julia_menger, 1, "julia, julia_c and steps belong to step formulas");
    const char *hybrid_menger[] = {"fractal.hybrid.formula=menger"};
    scene_text_error(BOX, hybrid_menger, 1, "fractal.hybrid.formula: menger has its own estimate (no @de)");
    const char *hybrid_self[] = {"fractal.hybrid.formula=mandelbox"};
    scene_text_error(BOX, hybrid_self, 1, "mandelbox with itself is mandelbox with more iterations");
    const char *hybrid_key[] = {"fractal.hybrid.formula=mandelbulb", "fractal.hybrid.scale=2"};
    scene_text_error(BOX, hybrid_key, 2, "fractal.hybrid.scale: unknown key 'scale' (allowed here: formula, steps, power, bailout)");
    const char *hybrid_range[] = {"fractal.hybrid.formula=mandelbulb", "fractal.hybrid.power=40"};
    scene_text_error(BOX, hybrid_range, 2, "fractal.hybrid.power: expected a number from 3 to 16");
    const char *hybrid[] = {"fractal.hybrid.formula=mandelbulb", "fractal.hybrid.power=6", "fractal.steps=2"};
    assert_true(scene_text_load(BOX, hybrid, 3, &s, &e));
    assert_true(s.fractal.has_hybrid && s.fractal.steps[0] == 2 && s.fractal.steps[1] == 1);
    assert_near(s.fractal.hybrid_values[0][0], 6, 0);
    assert_near(s.fractal.escape, 64, 0); /* a log hybrid's escape: the larger radius, at most 64 */
    assert_non_null(strstr(s.map_glsl, "#define uPower " HYBRID_PREFIX "uPower"));
    scene_free(&s);
    /* precision: double needs a formula written for it, and a whole power for the bulb */
    const char *deep_surf[] = {"fractal.precision=double"};
    scene_text_error("{\"program\": \"amazing_surf\"}", deep_surf, 1, "fractal.precision: double needs a formula written for it");
    const char *deep_power[] = {"fractal.precision=double", "fractal.power=7.5"};
    scene_text_error("{\"program\": \"mandelbulb\"}", deep_power, 2, "fractal.precision: double needs a formula written for it (@deep) with whole power");
    const char *deep_ok[] = {"fractal.precision=double", "fractal.power=7"};
    assert_true(scene_text_load("{\"program\": \"mandelbulb\"}", deep_ok, 2, &s, &e) && s.fractal.deep_now);
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
        cmocka_unit_test(formula_step_declarations),
        cmocka_unit_test(formula_scenes),
        cmocka_unit_test(formula_range_ends),
        cmocka_unit_test(formula_steps_and_precision),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
