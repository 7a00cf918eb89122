/* Assertions on doubles shared by the tests (include after cmocka.h). Random numbers:
 * test_rng.h. */
#ifndef TEST_SUPPORT_H
#define TEST_SUPPORT_H

#include <math.h>
#include <stdint.h>

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

/* |got - want| <= tol, naming the function and its input when it fails. */
static inline void expect_close(double got, double want, double tol, const char *what, double input)
{
    if (!(fabs(got - want) <= tol)) {
        print_error("%s(%.12g): got %.12g, want %.12g, |err| %.3g > tol %.3g\n", what, input, got,
                    want, fabs(got - want), tol);
        fail();
    }
}

#endif /* TEST_SUPPORT_H */
