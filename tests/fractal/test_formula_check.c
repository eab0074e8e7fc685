/* check-formula (jobs/check/check.h): every shipped formula passes at its declared step at its defaults,
 * and the check fails each planted fault for its own reason (each range's ends: test_formula_sweep.c). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "check.h"
#include "gltest.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"
#include "jobs/check/check.h"

/* check-formula: every shipped formula passes at its declared step factor at its defaults, and so do the
 * Julia bulb and the hybrid at their scenes' step factors (at the ends of every range: the sweep suite's
 * test_formula_sweep.c). */
static void formulas_pass_their_check(void **st)
{
    (void)st;
    strbuf names = {0};
    formula_list(&names);
    int formulas = 0;
    for (char *name = names.data, *nl; name && *name; name = nl + 1, formulas++) {
        nl = strchr(name, '\n');
        *nl = '\0';
        scene s;
        err_t e;
        if (!scene_load(name, NULL, 0, &s, &e))
            fail_msg("%s", e.msg);
        formula_check c;
        if (!check_formula(&s, 7u, 0, &c, &e))
            fail_msg("%s: %s", name, e.msg);
        if (!c.ok)
            fail_msg("formula %s fails its check: worst %.3f at step %.2f, %d non-finite, %d rays met it, %s", name,
                     c.worst, c.step, c.nonfinite, c.crossing, c.contained ? "contained" : "crosses its bound");
        fprintf(stderr, "  %-22s worst %.3f at step %.2f, %d/%d rays met it\n", name, c.worst, c.step, c.crossing, c.rays);
        scene_free(&s);
    }
    sb_free(&names);
    assert_true(formulas > 8);
    /* Julia sets and hybrids are checked at their scenes' step factors */
    static const char *const MODES[][5] = {
        {"mandelbulb", "fractal.julia=true", "fractal.iterations=10", "quality.step_factor=0.7", NULL},
        {"mandelbox", "fractal.scale=-1.5", "fractal.hybrid.formula=mandelbulb", "fractal.bound_radius=4",
         "quality.step_factor=0.7"}};
    for (int k = 0; k < 2; k++) {
        scene s;
        err_t e;
        int n = MODES[k][4] ? 4 : 3;
        if (!scene_load(MODES[k][0], &MODES[k][1], n, &s, &e))
            fail_msg("%s", e.msg);
        formula_check c;
        if (!check_formula(&s, 7u, 0, &c, &e))
            fail_msg("%s: %s", MODES[k][0], e.msg);
        fprintf(stderr, "  %-22s worst %.3f at the scene's step %.2f, %d/%d rays\n", k ? "hybrid box + bulb" : "Julia bulb",
                c.worst, c.step, c.crossing, c.rays);
        assert_true(c.mode && c.ok);
        scene_free(&s);
    }

}

/* check-formula on planted faults, each of which it must fail for its own reason: estimates too long
 * everywhere (2 and 1.1 times), in a narrow cone or a thin fin's wedge only (which 96 random rays
 * passed), a NaN, a set past its bound (a ball, a needle 0.01 thick). */
static void check_catches_planted_faults(void **st)
{
    (void)st;
    /* the corners are the ends of every range, a gap's too, and a vector's components one at a time */
    formula f;
    err_t fe;
    if (!formula_load("mandelbox", NULL, &f, &fe))
        fail_msg("%s", fe.msg);
    char corners[CHECK_CORNERS_MAX][CHECK_SET_MAX];
    int nc = check_corners(&f, &(check_desc){0}, corners, CHECK_CORNERS_MAX);
    static const char *const WANT[] = {"fractal.iterations=1", "fractal.iterations=64", "fractal.scale=-4", "fractal.scale=4",
                                       "fractal.scale=-1.05", "fractal.scale=1.05", "fractal.min_radius=0.01",
                                       "fractal.min_radius=10", "fractal.fixed_radius=0.01", "fractal.fixed_radius=10",
                                       "fractal.fold_limit=0.01", "fractal.fold_limit=10"};
    assert_int_equal(nc, (int)(sizeof WANT / sizeof WANT[0]));
    for (int k = 0; k < nc; k++)
        assert_string_equal(corners[k], WANT[k]);
    const char *given[] = {"fractal.scale=3"}; /* a parameter the user sets is not varied */
    assert_int_equal(check_corners(&f, &(check_desc){.sets = given, .set_count = 1}, corners, CHECK_CORNERS_MAX), nc - 4);
    if (!formula_load("quaternion_julia", NULL, &f, &fe))
        fail_msg("%s", fe.msg);
    nc = check_corners(&f, &(check_desc){0}, corners, CHECK_CORNERS_MAX);
    assert_string_equal(corners[2], "fractal.c=-2,0.6,0.2");
    assert_string_equal(corners[5], "fractal.c=-0.2,2,0.2");
    assert_int_equal(nc, 2 + 6 + 2 + 2);
    static const struct {
        const char *what, *bound, *de;
        double worst_min; /* the worst ratio it must find (0: not an estimate fault) */
        bool nonfinite, outside;
    } BAD[] = {
        {"an estimate twice the distance", "1", "2.0 * (length(p) - 0.8)", 1.95, false, false},
        {"an estimate 1.1 times the distance", "1", "1.1 * (length(p) - 0.8)", 1.08, false, false},
        {"NaN near the origin", "1", "length(p) < 0.1 ? 0.0 / 0.0 : length(p) - 0.8", 0, true, false},
        {"no set at all: nothing to check it on", "1", "length(p) + 0.5", 0, false, false},
        /* 1.3 times the distance, but only in a cone of 8 degrees about a direction off every axis */
        {"a 1.3x overshoot in an 8-degree cone", "1",
         "(dot(vec3(p), normalize(vec3(0.36, 0.48, 0.8))) > cos(radians(4.0)) * float(length(p)) ? 1.3 : 1.0)"
         " * (length(p) - 0.8)", 1.25, false, false},
        /* a fin 0.02 thick, its estimate 2.5 times too long in a wedge of 20 degrees */
        {"a 2.5x overshoot in a 20-degree wedge of a thin fin", "1",
         "(atan(float(p.z), float(p.x)) > 0.0 && atan(float(p.z), float(p.x)) < radians(20.0) ? 2.5 : 1.0)"
         " * max(abs(p.y) - 0.01, length(p.xz) - 0.9)", 2.0, false, false},
        {"a ball larger than its bound", "1", "length(p) - 1.2", 0, false, true},
        /* a part of the set apart from the rest, wholly past the bound: no crossing of the sphere */
        {"a detached ball past the bound", "1", "min(length(p) - 0.5, length(p - real3(0.9, 1.1, -0.7)) - 0.2)", 0, false,
         true},
        /* a needle 0.01 thick from a ball, past the bound in a direction off every axis */
        {"a needle through the bound", "1",
         "min(length(p) - 0.8, max(length(p - dot(p, normalize(real3(0.3, -0.5, 0.81))) *"
         " normalize(real3(0.3, -0.5, 0.81))) - 0.01, length(p) - 1.3))", 0, false, true},
    };
    for (size_t k = 0; k < sizeof BAD / sizeof BAD[0]; k++) {
        char json[1024];
        scene s;
        /* the process's own name: test_fractal and test_fractal_compute may run at once (ctest -j) */
        snprintf(json, sizeof json,
                 "{\"program\": \"fractal\", \"fractal\": {\"formula\": \"/tmp/fathom-bad%d-%zu.glsl\"}}", (int)getpid(), k);
        char path[300], text[1200];
        snprintf(path, sizeof path, "/tmp/fathom-bad%d-%zu.glsl", (int)getpid(), k);
        snprintf(text, sizeof text,
                 "// @formula %s\n// @bound %s\n#include \"fractal/common.glsl\"\n"
                 "real formulaDE(real3 p, out float trap) { trap = 0.0; return real(%s); }\n", BAD[k].what, BAD[k].bound,
                 BAD[k].de);
        write_text(path, text);
        load_text(json, NULL, 0, &s);
        formula_check c;
        err_t e;
        if (!check_formula(&s, 7u, 0, &c, &e))
            fail_msg("%s", e.msg);
        fprintf(stderr, "  planted: %-52s %s: worst %.3f, %d non-finite, %s\n", BAD[k].what, c.ok ? "passes" : "fails",
                c.worst, c.nonfinite, c.contained ? "contained" : "crosses its bound");
        assert_false(c.ok);
        assert_true(c.worst >= BAD[k].worst_min);
        assert_true((c.nonfinite > 0) == BAD[k].nonfinite);
        assert_true(c.contained == !BAD[k].outside);
        if (BAD[k].worst_min == 0 && !BAD[k].nonfinite && !BAD[k].outside) /* the estimate itself is right */
            assert_true(c.worst <= 1.02);
        if (k == 0)
            assert_near(c.suggested, 0.5, 0.02);
        scene_free(&s);
        remove(path);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(formulas_pass_their_check),
        cmocka_unit_test(check_catches_planted_faults),
    };
    if (getenv("FATHOM_TEST_FILTER")) /* one test while working on it: FATHOM_TEST_FILTER='far*' */
        cmocka_set_test_filter(getenv("FATHOM_TEST_FILTER"));
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
