/* Metric functions on synthetic signals with known answers. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "record/metrics.h"

#define PI 3.14159265358979323846
#define N 20000

static double x[N], th[N], t[N];

/* 50 Hz fundamental 10 A, 5th 2 A, 7th 1 A, 10 kHz ripple 0.5 A, DC 0.3 A,
 * sampled at 200 kHz over exactly 5 periods. */
static void test_thd_known_mix(void **state)
{
    metrics_thd_t r;
    int i;
    (void)state;
    for (i = 0; i < N; i++) {
        const double ti = (double)i / 200000.0;
        th[i] = 2.0 * PI * 50.0 * ti;
        x[i] = 0.3 + 10.0 * cos(th[i] + 0.4) + 2.0 * cos(5.0 * th[i] - 1.0) +
               1.0 * sin(7.0 * th[i]) + 0.5 * cos(2.0 * PI * 10000.0 * ti);
    }
    assert_int_equal(metrics_thd(x, th, N, &r), 0);
    /* all frequencies: sqrt(2^2 + 1^2 + 0.5^2) / 10; up to 50th: sqrt(5) / 10 */
    assert_true(fabs(r.thd - sqrt(5.25) / 10.0) < 1e-6);
    assert_true(fabs(r.thd_h50 - sqrt(5.0) / 10.0) < 1e-6);
    assert_true(fabs(r.fundamental_rms - 10.0 / sqrt(2.0)) < 1e-9);
}

static void test_thd_pure_sine_and_degenerate(void **state)
{
    metrics_thd_t r;
    int i;
    (void)state;
    for (i = 0; i < 1000; i++) {
        th[i] = 2.0 * PI * (double)i / 100.0; /* 10 periods */
        x[i] = 3.0 * sin(th[i]);
    }
    assert_int_equal(metrics_thd(x, th, 1000, &r), 0);
    assert_true(r.thd < 1e-9 && r.thd_h50 < 1e-9);
    for (i = 0; i < 1000; i++) {
        x[i] = 0.0;
    }
    assert_int_equal(metrics_thd(x, th, 1000, &r), -1);
    assert_int_equal(metrics_thd(x, th, 4, &r), -1);
}

/* A no-load run: ripple over a vanishing fundamental is not a THD of several hundred per
 * cent; it is reported as not meaningful. */
static void test_thd_not_meaningful_without_a_fundamental(void **state)
{
    metrics_thd_t r;
    int i;
    (void)state;
    for (i = 0; i < 1000; i++) {
        th[i] = 2.0 * PI * (double)i / 100.0;
        x[i] = 0.07 * sin(th[i]) + 0.35 * cos(37.0 * th[i]);
    }
    assert_int_equal(metrics_thd(x, th, 1000, &r), -1);
    assert_true(r.thd < 0.0 && r.thd_h50 < 0.0);
    assert_true(fabs(r.fundamental_rms - 0.07 / sqrt(2.0)) < 1e-9);
}

static void test_whole_periods(void **state)
{
    size_t first = 0;
    int i, periods;
    (void)state;
    for (i = 0; i < 1000; i++) {
        th[i] = 2.0 * PI * (double)i / 75.0; /* 75 samples per period, 13.3 periods */
    }
    periods = metrics_whole_periods(th, 1000, 1000, &first);
    assert_int_equal(periods, 13);
    assert_int_equal((int)(1000 - first), 13 * 75);
    periods = metrics_whole_periods(th, 1000, 100, &first);
    assert_int_equal(periods, 1);
    assert_int_equal((int)(1000 - first), 75);
}

static void test_std_pp_rms(void **state)
{
    double y[N];
    int i;
    (void)state;
    for (i = 0; i < 1000; i++) {
        x[i] = 5.0 + 2.0 * sin(2.0 * PI * (double)i / 100.0);
        y[i] = 2.0 * cos(2.0 * PI * (double)i / 100.0);
    }
    assert_true(fabs(metrics_mean(x, 1000) - 5.0) < 1e-9);
    assert_true(fabs(metrics_std(x, 1000) - 2.0 / sqrt(2.0)) < 1e-9);
    assert_true(fabs(metrics_peak_to_peak(x, 1000) - 4.0) < 1e-3);
    for (i = 0; i < 1000; i++) {
        x[i] = 2.0 * sin(2.0 * PI * (double)i / 100.0);
    }
    assert_true(fabs(metrics_rms2(x, y, 1000) - 2.0) < 1e-9);
    assert_true(metrics_std(x, 1) == 0.0);
}

static void test_switching_frequency_count(void **state)
{
    unsigned st[101];
    int i;
    (void)state;
    /* leg A toggles every sample, leg F every other sample, others never:
     * 100 + 50 transitions over 10 ms -> 150 / 2 / 0.01 / 6 = 1250 Hz */
    for (i = 0; i <= 100; i++) {
        st[i] = ((unsigned)(i & 1) << 5) | (unsigned)((i / 2) & 1);
    }
    assert_true(fabs(metrics_switching_freq(st, 101, 0.01) - 1250.0) < 1e-9);
    assert_true(metrics_switching_freq(st, 1, 0.01) == 0.0);
}

static void test_settle_and_reach(void **state)
{
    int i;
    (void)state;
    /* first-order rise to 800 with tau = 30 ms from t = 50 ms */
    for (i = 0; i < 5000; i++) {
        t[i] = (double)i * 1e-4;
        x[i] = (t[i] < 0.05) ? 0.0 : 800.0 * (1.0 - exp(-(t[i] - 0.05) / 0.03));
    }
    {
        const double ts = metrics_settle_time(t, x, 5000, 0.05, 800.0, 16.0);
        /* within 2 %: t - 0.05 = -tau ln(0.02) = 117.4 ms */
        assert_true(fabs(ts - 0.05 - 0.03 * log(50.0)) < 2e-4);
    }
    {
        const double tr = metrics_first_reach(t, x, 5000, 0.05, 720.0);
        assert_true(fabs(tr - 0.05 - 0.03 * log(10.0)) < 2e-4);
    }
    assert_true(metrics_first_reach(t, x, 5000, 0.05, 900.0) < 0.0);
    assert_true(metrics_settle_time(t, x, 5000, 0.05, 1000.0, 1.0) < 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_thd_known_mix),
        cmocka_unit_test(test_thd_pure_sine_and_degenerate),
        cmocka_unit_test(test_thd_not_meaningful_without_a_fundamental),
        cmocka_unit_test(test_whole_periods),
        cmocka_unit_test(test_std_pp_rms),
        cmocka_unit_test(test_switching_frequency_count),
        cmocka_unit_test(test_settle_and_reach),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
