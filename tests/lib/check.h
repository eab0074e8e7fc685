/* Test helpers on top of cmocka: comparisons in double precision (cmocka 1.1 compares floats), fixture
 * files. Include after cmocka.h. */
#ifndef FATHOM_TEST_CHECK_H
#define FATHOM_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

#define assert_near(a, b, tol)                                                                      \
    do {                                                                                            \
        double a_ = (double)(a), b_ = (double)(b);                                                  \
        if (!(fabs(a_ - b_) <= (double)(tol)))                                                      \
            fail_msg("%s = %.9g, expected %.9g within %g", #a, a_, b_, (double)(tol));              \
    } while (0)

/* Writes text to path (a test's fixture file); a failure fails the test. */
static inline void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

#endif
