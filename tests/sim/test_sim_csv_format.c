/* The CSV number formatter writes exactly what printf writes: every format the simulator's
 * files use (%.3f .. %.7f, %d) and every precision up to 9, on random values over the whole
 * double range, on exact decimal ties (printf rounds them to even), on carries into a new
 * digit, on negative zero and tiny negatives, and on NaN, infinities and huge values (the
 * formatter hands those to snprintf). */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "record/csv_format.h"

static uint64_t rng_state = 0x1234567887654321ull;

static uint64_t next_u64(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double next_unit(void) { return (double)(next_u64() >> 11) * (1.0 / 9007199254740992.0); }

static long mismatches;

static void check_fixed(double v, int decimals)
{
    char want[CSV_FIXED_MAX_CHARS + 2], got[CSV_FIXED_MAX_CHARS + 2];
    char *end = csv_put_fixed(got, v, decimals);
    *end = '\0';
    (void)snprintf(want, sizeof want, "%.*f", decimals, v);
    if (strcmp(want, got) != 0) {
        if (mismatches < 10) {
            print_error("%.17g with %d decimals: printf '%s', formatter '%s'\n", v, decimals, want,
                        got);
        }
        mismatches++;
    }
}

static void check_all_precisions(double v)
{
    int d;
    for (d = 0; d <= CSV_FIXED_MAX_DECIMALS; d++) {
        check_fixed(v, d);
    }
}

/* The ranges of the simulator's columns: currents, angles, torques, speeds, times. */
static void test_random_values_in_signal_ranges(void **state)
{
    long i;
    (void)state;
    mismatches = 0;
    for (i = 0; i < 300000; i++) {
        const double range = ldexp(1.0, (int)(next_u64() % 24u) - 6); /* 1/64 .. 2^17 */
        const double v = (2.0 * next_unit() - 1.0) * range;
        check_fixed(v, 3 + (int)(next_u64() % 5u)); /* the files' 3..7 decimals */
    }
    assert_int_equal(mismatches, 0);
}

/* Magnitudes from 1e-300 to 1e300 and arbitrary bit patterns (subnormals, NaN, infinities). */
static void test_whole_double_range(void **state)
{
    long i;
    (void)state;
    mismatches = 0;
    for (i = 0; i < 100000; i++) {
        const double mag = pow(10.0, 600.0 * next_unit() - 300.0);
        check_fixed((next_u64() & 1u) ? mag : -mag, (int)(next_u64() % 10u));
    }
    for (i = 0; i < 50000; i++) {
        const uint64_t bits = next_u64();
        double v;
        memcpy(&v, &bits, sizeof v);
        check_fixed(v, (int)(next_u64() % 10u));
    }
    assert_int_equal(mismatches, 0);
}

/* Values exactly halfway between two outputs (dyadic fractions) and their neighbours one ulp
 * away: ties go to even, anything off the tie goes to the nearer side. */
static void test_ties_and_neighbours(void **state)
{
    long i;
    (void)state;
    mismatches = 0;
    for (i = 0; i < 25000; i++) {
        const int bits = 1 + (int)(next_u64() % 12u);
        const double v = (double)(next_u64() % 2000000u) / (double)(1u << bits);
        check_all_precisions(v);
        check_all_precisions(-v);
        check_all_precisions(nextafter(v, INFINITY));
        check_all_precisions(nextafter(v, -INFINITY));
    }
    check_fixed(0.125, 2);
    check_fixed(0.375, 2);
    check_fixed(2.5, 0);
    check_fixed(3.5, 0);
    check_fixed(1.0000005, 6);
    assert_int_equal(mismatches, 0);
}

/* Decimal-looking values (k / 10^d) and the last representable values before a carry. */
static void test_decimal_values_and_carries(void **state)
{
    static const double edges[] = {0.0,
                                   -0.0,
                                   1e-300,
                                   -1e-300,
                                   DBL_MIN,
                                   -DBL_MIN,
                                   4.9e-324,
                                   -4.9e-324,
                                   0.5,
                                   -0.5,
                                   0.05,
                                   0.005,
                                   0.0005,
                                   0.00005,
                                   9.9999995,
                                   9.999995,
                                   99999.5,
                                   0.9999999,
                                   -0.9999999,
                                   999.99995,
                                   1e15,
                                   1e16,
                                   -1e16,
                                   1e22,
                                   1e300,
                                   DBL_MAX,
                                   -DBL_MAX,
                                   INFINITY,
                                   -INFINITY,
                                   NAN,
                                   -NAN,
                                   1125899906842.5,
                                   1125899906842624.0,
                                   1125899906842623.5,
                                   6.2831853071795862,
                                   3.1415926535897931};
    size_t k;
    long i;
    (void)state;
    mismatches = 0;
    for (k = 0; k < sizeof edges / sizeof edges[0]; k++) {
        check_all_precisions(edges[k]);
        check_all_precisions(nextafter(edges[k], 0.0));
    }
    for (i = 0; i < 100000; i++) {
        const int d = (int)(next_u64() % 10u);
        const double v = (double)(int64_t)(next_u64() % 20000001u - 10000000u) / pow(10.0, d);
        check_fixed(v, d);
        check_fixed(v, d > 0 ? d - 1 : 0);
        check_fixed(nextafter(v, 0.0), d);
    }
    assert_int_equal(mismatches, 0);
}

static void test_integers(void **state)
{
    static const int edges[] = {0, 1, -1, 9, 10, 99, 100, -100, 63, INT_MAX, INT_MIN, INT_MIN + 1};
    char want[32], got[32];
    size_t k;
    long i;
    (void)state;
    for (k = 0; k < sizeof edges / sizeof edges[0]; k++) {
        *csv_put_int(got, edges[k]) = '\0';
        (void)snprintf(want, sizeof want, "%d", edges[k]);
        assert_string_equal(got, want);
    }
    for (i = 0; i < 100000; i++) {
        const int v = (int)(int64_t)(next_u64() % 4294967296ull - 2147483648ull);
        *csv_put_int(got, v) = '\0';
        (void)snprintf(want, sizeof want, "%d", v);
        assert_string_equal(got, want);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_values_in_signal_ranges),
        cmocka_unit_test(test_whole_double_range),
        cmocka_unit_test(test_ties_and_neighbours),
        cmocka_unit_test(test_decimal_values_and_carries),
        cmocka_unit_test(test_integers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
