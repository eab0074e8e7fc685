/* Test helpers on top of cmocka: comparisons in double precision (cmocka 1.1 compares floats). */
#ifndef FATHOM_TEST_CHECK_H
#define FATHOM_TEST_CHECK_H

#include <math.h>

#define assert_near(a, b, tol)                                                                      \
    do {                                                                                            \
        double a_ = (double)(a), b_ = (double)(b);                                                  \
        if (!(fabs(a_ - b_) <= (double)(tol)))                                                      \
            fail_msg("%s = %.9g, expected %.9g within %g", #a, a_, b_, (double)(tol));              \
    } while (0)

#endif
