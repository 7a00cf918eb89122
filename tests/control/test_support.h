/* Small helpers shared by the control-core tests (include after cmocka.h). */
#ifndef TEST_SUPPORT_H
#define TEST_SUPPORT_H

#include <math.h>

#define TEST_PI 3.14159265358979323846

/* |a - b| <= tol in double, printing both values when it fails. */
#define assert_near(a, b, tol)                                                                     \
    do {                                                                                           \
        const double assert_near_a_ = (a);                                                         \
        const double assert_near_b_ = (b);                                                         \
        if (!(fabs(assert_near_a_ - assert_near_b_) <= (tol))) {                                   \
            print_error("%s = %.9g, %s = %.9g, tolerance %.3g\n", #a, assert_near_a_, #b,          \
                        assert_near_b_, (double)(tol));                                            \
            fail();                                                                                \
        }                                                                                          \
    } while (0)

#endif /* TEST_SUPPORT_H */
