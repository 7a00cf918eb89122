/*
 * The simulator's random numbers (host_sim/plant/sim_rng.c): the ziggurat Gaussian against the
 * standard normal distribution on 2 million draws (mean, variance, skew, kurtosis, the
 * probability of each of 12 bins from -3 to +3 sigma and of both tails beyond 3 and 4 sigma,
 * each within 5 standard errors), uniform numbers strictly inside (0, 1) with the right
 * moments, and one stream per seed (same seed, same numbers; another seed, others).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "plant/sim_rng.h"

#define DRAWS 2000000

/* Standard normal CDF. */
static double phi(double x) { return 0.5 * erfc(-x / sqrt(2.0)); }

/* |observed - expected| count of an event of probability p within 5 standard errors. */
static void expect_probability(long count, double p, const char *what)
{
    const double expected = p * DRAWS;
    const double sigma = sqrt(DRAWS * p * (1.0 - p));
    if (fabs((double)count - expected) > 5.0 * sigma + 1.0) {
        print_error("%s: %ld draws, expected %.0f +- %.0f\n", what, count, expected, sigma);
        fail();
    }
}

static void test_gaussian_distribution(void **state)
{
    sim_rng_t r;
    long bins[12] = {0}, tail3 = 0, tail4 = 0;
    double m1 = 0.0, m2 = 0.0, m3 = 0.0, m4 = 0.0;
    long i;
    int b;
    (void)state;
    sim_rng_seed(&r, 7u);
    for (i = 0; i < DRAWS; i++) {
        const double x = sim_rng_gauss(&r);
        m1 += x;
        m2 += x * x;
        m3 += x * x * x;
        m4 += x * x * x * x;
        if (x >= -3.0 && x < 3.0) {
            bins[(int)floor((x + 3.0) * 2.0)]++;
        }
        tail3 += fabs(x) > 3.0;
        tail4 += fabs(x) > 4.0;
    }
    m1 /= DRAWS;
    m2 /= DRAWS;
    m3 /= DRAWS;
    m4 /= DRAWS;
    assert_true(fabs(m1) < 5.0 / sqrt(DRAWS));
    assert_true(fabs(m2 - 1.0) < 5.0 * sqrt(2.0 / DRAWS));
    assert_true(fabs(m3) < 5.0 * sqrt(15.0 / DRAWS));
    assert_true(fabs(m4 - 3.0) < 5.0 * sqrt(96.0 / DRAWS));
    for (b = 0; b < 12; b++) {
        const double lo = -3.0 + 0.5 * b;
        expect_probability(bins[b], phi(lo + 0.5) - phi(lo), "bin");
    }
    expect_probability(tail3, 2.0 * phi(-3.0), "beyond 3 sigma");
    expect_probability(tail4, 2.0 * phi(-4.0), "beyond 4 sigma");
}

static void test_uniform_open_interval_and_moments(void **state)
{
    sim_rng_t r;
    double m1 = 0.0, m2 = 0.0;
    long i;
    (void)state;
    sim_rng_seed(&r, 1u);
    for (i = 0; i < DRAWS; i++) {
        const double u = sim_rng_uniform(&r);
        assert_true(u > 0.0 && u < 1.0);
        m1 += u;
        m2 += u * u;
    }
    assert_true(fabs(m1 / DRAWS - 0.5) < 5.0 * sqrt(1.0 / 12.0 / DRAWS));
    assert_true(fabs(m2 / DRAWS - 1.0 / 3.0) < 5.0 * sqrt(4.0 / 45.0 / DRAWS));
}

static void test_one_stream_per_seed(void **state)
{
    sim_rng_t a, b, c;
    int i, same_other = 0;
    (void)state;
    sim_rng_seed(&a, 42u);
    sim_rng_seed(&b, 42u);
    sim_rng_seed(&c, 43u);
    for (i = 0; i < 1000; i++) {
        const double x = sim_rng_gauss(&a);
        assert_true(x == sim_rng_gauss(&b));
        same_other += (x == sim_rng_gauss(&c));
    }
    assert_int_equal(same_other, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gaussian_distribution),
        cmocka_unit_test(test_uniform_open_interval_and_moments),
        cmocka_unit_test(test_one_stream_per_seed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
