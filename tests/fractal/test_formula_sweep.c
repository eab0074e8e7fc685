/* The sweep suite (label "sweep": cmake -DFATHOM_SWEEPS=ON; docs/guide/tests.md says when it runs):
 * check-formula (jobs/check/check.h) at the ends of every range of every shipped formula, 131 parameter
 * sets, as `fathom check-formula` runs them (at the defaults: test_formula_check.c). Six minutes on two
 * cores. */
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

/* Every shipped formula passes its check at each end of each of its ranges (check_corners). */
static void range_ends_pass_their_check(void **st)
{
    (void)st;
    strbuf names = {0};
    formula_list(&names);
    int ends = 0;
    for (char *name = names.data, *nl; name && *name; name = nl + 1) {
        nl = strchr(name, '\n');
        *nl = '\0';
        scene s;
        err_t e;
        if (!scene_load(name, NULL, 0, &s, &e))
            fail_msg("%s", e.msg);
        /* and at the ends of its ranges (check_corners), as `fathom check-formula` runs them */
        char corners[CHECK_CORNERS_MAX][CHECK_SET_MAX];
        int n = check_corners(&s.fractal.formula, &(check_desc){0}, corners, CHECK_CORNERS_MAX), refused = 0, dust = 0;
        double worst = 0;
        const char *worst_at = "none";
        for (int k = 0; k < n; k++) {
            scene t; /* the scene check-formula checks in: any formula's, framed from its bound */
            char formula_set[96];
            snprintf(formula_set, sizeof formula_set, "fractal.formula=%s", name);
            const char *over[] = {formula_set, corners[k]};
            if (!scene_load("fractal", over, 2, &t, &e)) {
                if (!strstr(e.msg, "(formula ")) /* only a @require may refuse an end */
                    fail_msg("%s %s: %s", name, corners[k], e.msg);
                refused++;
                continue;
            }
            formula_check ck;
            if (!check_formula(&t, 7u, CHECK_CORNER_RAYS, &ck, &e))
                fail_msg("%s %s: %s", name, corners[k], e.msg);
            if (!check_passes(&ck, false))
                fail_msg("formula %s at %s fails its check: worst %.3f at step %.2f at (%.4g, %.4g, %.4g), %d non-finite, %s, "
                         "loops %d of %d", name, corners[k], ck.worst, ck.step, ck.worst_at[0], ck.worst_at[1], ck.worst_at[2],
                         ck.nonfinite, ck.contained ? "contained" : "crosses its bound", ck.loops, ck.loops_declared);
            dust += ck.crossing == 0;
            if (ck.step * ck.worst > worst)
                worst = ck.step * ck.worst, worst_at = corners[k];
            scene_free(&t);
        }
        ends += n - refused;
        fprintf(stderr, "  %-22s %2d range ends pass (%d met by no ray), %d refused by @require; the worst step x "
                "ratio %.3f (%s)\n", name, n - refused, dust, refused, worst, worst_at);
        scene_free(&s);
    }
    sb_free(&names);
    assert_true(ends > 100);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(range_ends_pass_their_check),
    };
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
