/* glsl_budget: the compiler's view of a stranger's GLSL, macros expanded (app/scene/formula/glsl_budget.h).
 * Counts against expansions worked out by hand, every bound met just inside and just past, the bombs
 * that took Mesa's compiler down (issue 50, item 4) refused at once, and recursion that must end. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "scene/formula/glsl_budget.h"
#include "util.h"

static glsl_measure measure_ok(const char *src)
{
    glsl_measure m;
    err_t e = {0};
    bool ok = glsl_budget_check(src, "t.glsl", &m, &e);
    if (!ok)
        fprintf(stderr, "unexpected refusal: %s\n", e.msg);
    assert_true(ok);
    return m;
}

static void refused(const char *src, const char *needle)
{
    err_t e = {0};
    clock_t t0 = clock();
    assert_false(glsl_budget_check(src, "t.glsl", NULL, &e));
    assert_non_null(strstr(e.msg, needle));
    assert_non_null(strstr(e.msg, "t.glsl"));
    assert_true((double)(clock() - t0) / CLOCKS_PER_SEC < 5.0); /* refused by the budget, not by exhausting it */
}

/* text with its own buffer, built by a printf-like format repeated n times */
static char *repeat(const char *head, const char *unit, int n, const char *tail)
{
    size_t len = strlen(head) + strlen(unit) * (size_t)n + strlen(tail) + 1;
    char *s = malloc(len);
    strcpy(s, head);
    for (int i = 0; i < n; i++)
        strcat(s, unit);
    strcat(s, tail);
    return s;
}

static void counts_as_expanded_by_hand(void **state)
{
    (void)state;
    /* "float a = 1.0 ;" is 5 tokens */
    assert_int_equal(measure_ok("float a = 1.0;\n").tokens, 5);
    /* X -> 1.0 + 2.0 (3 tokens): "float a = X ;" is 4 + 3 - 1 = 6 */
    assert_int_equal(measure_ok("#define X 1.0 + 2.0\nfloat a = X;\n").tokens, 7);
    /* F(a, b) -> (a * b * a): "F(x, y)" is ( x * y * x ) = 7 tokens, plus "float v =" and ";" */
    assert_int_equal(measure_ok("#define F(a, b) (a * b * a)\nfloat v = F(x, y);\n").tokens, 11);
    /* arguments expanded before substitution: F(X) with X -> 1.0 + 2.0 is (3 * 3 * 3 tokens) + 4 */
    assert_int_equal(measure_ok("#define X 1.0 + 2.0\n#define F(a, b) (a * b * a)\nfloat v = F(X, X);\n").tokens,
                     3 + 13 + 1);
    /* rescanning with what follows: A -> G, then G(2.0) -> 2.0 2.0 */
    assert_int_equal(measure_ok("#define G(x) x x\n#define A G\nA(2.0);\n").tokens, 3);
    /* a function-like name without '(' is a plain token */
    assert_int_equal(measure_ok("#define G(x) x x\nfloat G;\n").tokens, 3);
    /* #undef ends a macro; comments and continued lines are no tokens */
    assert_int_equal(measure_ok("#define X a b c\n#undef X\nX; // X X X\n/* X */\n").tokens, 2);
    assert_int_equal(measure_ok("#define X a \\\n b\nX;\n").tokens, 3);
    /* a macro is not expanded inside itself, directly or through another: these end */
    assert_int_equal(measure_ok("#define X X + 1\nX;\n").tokens, 4);
    assert_int_equal(measure_ok("#define A B\n#define B A\nA;\n").tokens, 2);
    /* #if sections count on both sides (an upper bound), other directives not at all */
    assert_int_equal(measure_ok("#version 330 core\n#ifdef Q\na;\n#else\nb c;\n#endif\n").tokens, 5);
}

static void bounds_just_inside_and_past(void **state)
{
    (void)state;
    char *s = repeat("float v = ", "(", GLSL_DEPTH_MAX, "1.0");
    char *t = repeat(s, ")", GLSL_DEPTH_MAX, ";\n");
    assert_int_equal(measure_ok(t).depth_max, GLSL_DEPTH_MAX);
    free(s), free(t);
    s = repeat("float v = (", "\n(", GLSL_DEPTH_MAX, "1.0"); /* one more, across lines */
    refused(s, "brackets nest deeper than");
    free(s);
    /* a statement: "v = " then n terms "+ 1.0" */
    s = repeat("v =", "\n+ 1.0", GLSL_STATEMENT_MAX / 2 - 1, ";\n");
    assert_true(measure_ok(s).statement_max <= GLSL_STATEMENT_MAX);
    free(s);
    s = repeat("v =", "\n+ 1.0", GLSL_STATEMENT_MAX / 2 + 1, ";\n");
    refused(s, "a statement (its macros expanded) is longer than");
    free(s);
    char line[GLSL_LINE_MAX + 3];
    memset(line, 'a', sizeof line);
    line[GLSL_LINE_MAX] = '\n', line[GLSL_LINE_MAX + 1] = '\0';
    assert_int_equal(measure_ok(line).line_max, GLSL_LINE_MAX);
    line[GLSL_LINE_MAX] = 'a', line[GLSL_LINE_MAX + 1] = '\n', line[GLSL_LINE_MAX + 2] = '\0';
    refused(line, "a line is longer than");
}

static void bombs_refused_at_once(void **state)
{
    (void)state;
    /* M30 is 2^30 tokens: the doubling chain that crashed Mesa after 80 s */
    strbuf b = {0};
    sb_append(&b, "#define M0 +0.0\n");
    for (int i = 1; i <= 30; i++)
        sb_printf(&b, "#define M%d M%d M%d\n", i, i - 1, i - 1);
    sb_append(&b, "float v = 1.0 M30;\n");
    refused(b.data, "the GL compiler could crash");
    sb_free(&b);
    /* a function-like bomb: each call doubles its argument, nested 40 deep */
    char *open = repeat("#define F(x) (x+x)\nfloat v = ", "F(", 40, "0.0");
    char *all = repeat(open, ")", 40, ";\n");
    refused(all, "the GL compiler could crash");
    free(open), free(all);
    /* the bomb through rescanning: A -> B, and B(x) quadruples x */
    open = repeat("#define B(x) x x x x\n#define A B\nfloat v = ", "A(", 20, "1.0");
    all = repeat(open, ")", 20, ";\n");
    refused(all, "the GL compiler could crash");
    free(open), free(all);
}

/* The doubling chain M0 … M30 (2^30 tokens) as text, for the bypasses below */
static void chain(strbuf *b)
{
    sb_append(b, "#define M0 +0.0\n");
    for (int i = 1; i <= 30; i++)
        sb_printf(b, "#define M%d M%d M%d\n", i, i - 1, i - 1);
}

/* Ways around a measure that is only a reading of the text (the review of issue 50): each must still see
 * the bomb the compiler will see. */
static void bypasses_seen(void **state)
{
    (void)state;
    const char *tails[] = {
        "#if 0\n#undef M30\n#endif\nfloat v = 1.0 M30;\n",          /* an #undef the compiler skips */
        "#if 0\n#define M30 small\n#endif\nfloat v = 1.0 M30;\n",   /* a redefinition it skips */
        "float v = 1.0 M3\\\n0;\n",                                  /* a name cut by a continuation */
        "#def\\\nine M31 M30 M30\nfloat v = 1.0 M31;\n",            /* a directive cut by one */
        "#define F(x) x\nfloat v = F(\n# undef M30\n) 1.0 M30;\n",   /* a directive in an argument */
    };
    for (size_t i = 0; i < sizeof tails / sizeof tails[0]; i++) {
        strbuf b = {0};
        chain(&b);
        sb_append(&b, tails[i]);
        refused(b.data, "the GL compiler could crash");
        sb_free(&b);
    }
    /* token pasting and macros past the parameters the measure follows are refused outright */
    refused("#define C(a, b) a##b\nfloat v = C(M, 30);\n", "##");
    strbuf b = {0};
    sb_append(&b, "#define D(");
    for (int i = 0; i < 40; i++)
        sb_printf(&b, "%sp%d", i ? ", " : "", i);
    sb_append(&b, ") p39 p39\n");
    refused(b.data, "parameters");
    sb_free(&b);
    /* 30,000 names in one text: their lookups are work, refused (or measured) in bounded time */
    for (int i = 0; i < 30000; i++)
        sb_printf(&b, "#define N%d\n", i);
    for (int i = 0; i < 2000; i++)
        sb_append(&b, "x x x x x x x x x x;\n");
    err_t e;
    clock_t t0 = clock();
    glsl_budget_check(b.data, "t.glsl", NULL, &e);
    assert_true((double)(clock() - t0) / CLOCKS_PER_SEC < 5.0);
    sb_free(&b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(counts_as_expanded_by_hand),
        cmocka_unit_test(bounds_just_inside_and_past),
        cmocka_unit_test(bombs_refused_at_once),
        cmocka_unit_test(bypasses_seen),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
