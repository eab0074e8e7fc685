/* Test helpers on top of cmocka: comparisons in double precision (cmocka 1.1 compares floats), fixture
 * files. Include after cmocka.h. */
#ifndef FATHOM_TEST_CHECK_H
#define FATHOM_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "util.h"

#define assert_near(a, b, tol)                                                                      \
    do {                                                                                            \
        double a_ = (double)(a), b_ = (double)(b);                                                  \
        if (!(fabs(a_ - b_) <= (double)(tol)))                                                      \
            fail_msg("%s = %.9g, expected %.9g within %g", #a, a_, b_, (double)(tol));              \
    } while (0)

/* Writes text to file (a test's fixture file); a failure fails the test. */
static inline void write_text(const char *file, const char *text)
{
    FILE *f = fopen(file, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

/* Removes the folder dir and all in it (a test's temporary folder): 0 when done, else -1. */
static inline int remove_tree(const char *dir)
{
    char cmd[PATH_MAX_LEN + 16];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

#endif
