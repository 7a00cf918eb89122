/* Inverter: period-average voltage, dead-time sign rule, short pulses,
 * switching-transition count. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "plant/inverter.h"
#include "plant/plant.h"

/* Locked rotor at theta = 0, R = 0, no harmonics: the current change over one
 * period measures the period-average voltage exactly. */
static void test_average_voltage_without_dead_time(void **state)
{
    plant_params_t p;
    plant_state_t s = {0};
    inverter_t inv;
    const double ts = 100e-6;
    const double duty[6] = {0.7, 0.2, 0.45, 0.9, 0.1, 0.55};
    double v[6], exp_u[4] = {0, 0, 0, 0};
    int k;
    (void)state;
    plant_params_default(&p);
    p.r_ohm = 0.0;
    p.harmonics_on = false;
    p.dead_time_on = false;
    plant_sync_angle(&p, &s);
    inverter_init(&inv, &p, ts);
    /* first period: legs start from the all-off state; use the second */
    (void)inverter_run_period(&inv, &p, &s, duty, false, 0.0, true, NULL, 0, NULL, NULL);
    {
        const plant_state_t s0 = s;
        (void)inverter_run_period(&inv, &p, &s, duty, false, 0.0, true, NULL, 0, NULL, NULL);
        for (k = 0; k < 6; k++) {
            const double g =
                (k < 3) ? (duty[0] + duty[1] + duty[2]) / 3.0 : (duty[3] + duty[4] + duty[5]) / 3.0;
            v[k] = p.vdc_v * (duty[k] - g);
            exp_u[0] += v[k] * cos(plant_phase_angle_rad[k]) / 3.0;
            exp_u[1] += v[k] * sin(plant_phase_angle_rad[k]) / 3.0;
            exp_u[2] += v[k] * cos(5.0 * plant_phase_angle_rad[k]) / 3.0;
            exp_u[3] += v[k] * sin(5.0 * plant_phase_angle_rad[k]) / 3.0;
        }
        assert_true(fabs((s.i_d - s0.i_d) * p.ld_h / ts - exp_u[0]) < 1e-6);
        assert_true(fabs((s.i_q - s0.i_q) * p.lq_h / ts - exp_u[1]) < 1e-6);
        assert_true(fabs((s.i_x - s0.i_x) * p.lxy_h / ts - exp_u[2]) < 1e-6);
        assert_true(fabs((s.i_y - s0.i_y) * p.lxy_h / ts - exp_u[3]) < 1e-6);
    }
    inverter_free(&inv);
}

typedef struct {
    double on[6];
    int n;
} leg_avg_t;

static void leg_cb(void *ctx, double t_rel, const plant_state_t *s, unsigned legs)
{
    leg_avg_t *a = (leg_avg_t *)ctx;
    int k;
    (void)t_rel;
    (void)s;
    for (k = 0; k < 6; k++) {
        a->on[k] += (double)((legs >> (5 - k)) & 1u);
    }
    a->n++;
}

/* Dead time: the leg follows the current during the dead interval, so the
 * effective on-time is d*Ts - Td for i > 0 and d*Ts + Td for i < 0. Huge
 * inductances keep the current signs fixed. */
static void test_dead_time_follows_current_sign(void **state)
{
    plant_params_t p;
    plant_state_t s = {0};
    inverter_t inv;
    const double ts = 100e-6;
    const double duty[6] = {0.5, 0.5, 0.3, 0.6, 0.4, 0.7};
    double iph[6], smp[2000];
    leg_avg_t a = {{0, 0, 0, 0, 0, 0}, 0};
    int k;
    (void)state;
    plant_params_default(&p);
    p.harmonics_on = false;
    p.ld_h = p.lq_h = p.lxy_h = 9.0;
    s.i_d = 5.0;
    s.i_q = 2.0;
    s.i_x = 0.3;
    s.i_y = -0.2;
    plant_sync_angle(&p, &s);
    plant_phase_currents(&p, &s, iph);
    for (k = 0; k < 2000; k++) {
        smp[k] = ts * ((double)k + 0.5) / 2000.0;
    }
    inverter_init(&inv, &p, ts);
    (void)inverter_run_period(&inv, &p, &s, duty, false, 0.0, true, NULL, 0, NULL, NULL);
    (void)inverter_run_period(&inv, &p, &s, duty, false, 0.0, true, smp, 2000, leg_cb, &a);
    assert_int_equal(a.n, 2000);
    for (k = 0; k < 6; k++) {
        const double expect = duty[k] + ((iph[k] > 0.0) ? -1.0 : 1.0) * p.dead_time_s / ts;
        const double got = a.on[k] / (double)a.n;
        print_message("leg %d: i = %+.3f A, duty %.2f -> effective %.4f (expected %.4f)\n", k,
                      iph[k], duty[k], got, expect);
        assert_true(fabs(iph[k]) > 0.1);
        assert_true(fabs(got - expect) < 1.0e-3);
    }
    inverter_free(&inv);
}

/* A pulse shorter than the dead time vanishes for i > 0 and is stretched by
 * Td for i < 0. */
static void test_short_pulse(void **state)
{
    plant_params_t p;
    plant_state_t s = {0};
    inverter_t inv;
    const double ts = 100e-6;
    const double duty[6] = {0.01, 0.01, 0.0, 0.0, 0.0, 0.0};
    double iph[6], smp[4000];
    leg_avg_t a = {{0, 0, 0, 0, 0, 0}, 0};
    int k;
    (void)state;
    plant_params_default(&p);
    p.harmonics_on = false;
    p.ld_h = p.lq_h = p.lxy_h = 9.0;
    s.i_d = 3.0; /* i_A = 3 > 0, i_B = -1.5 < 0 */
    plant_sync_angle(&p, &s);
    plant_phase_currents(&p, &s, iph);
    for (k = 0; k < 4000; k++) {
        smp[k] = ts * ((double)k + 0.5) / 4000.0;
    }
    inverter_init(&inv, &p, ts);
    (void)inverter_run_period(&inv, &p, &s, duty, false, 0.0, true, NULL, 0, NULL, NULL);
    inv.counting = true;
    (void)inverter_run_period(&inv, &p, &s, duty, false, 0.0, true, smp, 4000, leg_cb, &a);
    assert_true(iph[0] > 0.0 && iph[1] < 0.0);
    assert_true(a.on[0] == 0.0);
    assert_true(fabs(a.on[1] / 4000.0 - (0.01 + p.dead_time_s / ts)) < 1e-3);
    assert_int_equal((int)inv.transitions, 2); /* only leg B switches */
    inverter_free(&inv);
}

/* Transition count: duty 0.5 on every leg switches each leg twice a period. */
static void test_switching_count(void **state)
{
    plant_params_t p;
    plant_state_t s = {0};
    inverter_t inv;
    const double ts = 100e-6;
    const double half[6] = {0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
    const double one[6] = {1, 1, 1, 0, 0, 0};
    const double zero[6] = {0, 0, 0, 1, 1, 1};
    int k;
    (void)state;
    plant_params_default(&p);
    plant_sync_angle(&p, &s);
    inverter_init(&inv, &p, ts);
    (void)inverter_run_period(&inv, &p, &s, half, false, 0.0, true, NULL, 0, NULL, NULL);
    inv.counting = true;
    for (k = 0; k < 10; k++) {
        (void)inverter_run_period(&inv, &p, &s, half, false, 0.0, true, NULL, 0, NULL, NULL);
    }
    assert_int_equal((int)inv.transitions, 120); /* f_sw = 120 / 2 / 6 / 1 ms = 10 kHz = fs */
    inv.transitions = 0;
    for (k = 0; k < 10;
         k++) { /* full-period vectors alternating: one transition per leg per period */
        (void)inverter_run_period(&inv, &p, &s, (k % 2) ? one : zero, false, 0.0, true, NULL, 0,
                                  NULL, NULL);
    }
    assert_int_equal((int)inv.transitions,
                     6 * 10 - 3); /* the first switch of D-F already matches */
    assert_true(isfinite(s.i_d) && isfinite(s.i_x));
    inverter_free(&inv);
}

/* Forced off: currents are zero and nothing switches. */
static void test_forced_off(void **state)
{
    plant_params_t p;
    plant_state_t s = {0};
    inverter_t inv;
    const double duty[6] = {0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
    (void)state;
    plant_params_default(&p);
    s.i_d = 2.0;
    s.omega_m = 10.0;
    plant_sync_angle(&p, &s);
    inverter_init(&inv, &p, 100e-6);
    inv.counting = true;
    assert_true(inverter_run_period(&inv, &p, &s, duty, true, 0.0, false, NULL, 0, NULL, NULL) ==
                0.0);
    assert_true(s.i_d == 0.0 && s.i_q == 0.0 && s.i_x == 0.0 && s.i_y == 0.0);
    assert_true(s.omega_m < 10.0 && s.omega_m > 9.99);
    assert_int_equal((int)inv.transitions, 0);
    inverter_free(&inv);
}

/* Every sample the callback saw, to compare two runs. */
typedef struct {
    double v[8192];
    int n;
} sample_log_t;

static void log_cb(void *ctx, double t_rel, const plant_state_t *s, unsigned legs)
{
    sample_log_t *l = (sample_log_t *)ctx;
    if (l->n + 4 <= 8192) {
        l->v[l->n++] = t_rel;
        l->v[l->n++] = s->i_d;
        l->v[l->n++] = s->i_x;
        l->v[l->n++] = (double)legs;
    }
}

/* The switching programs kept from earlier periods (inverter_program.h) change nothing: an
 * inverter that builds every period as it runs and one that reuses programs give the same bits
 * over 3,000 periods of duty patterns drawn from a small set, with pulses short enough to vanish,
 * dead intervals that run into the next period, equal duties, forced-off periods, new sample
 * instants and a plant parameter changed on the way. */
static void test_program_cache_changes_nothing(void **state)
{
    static const double patterns[8][6] = {
        {0.5, 0.5, 0.5, 0.5, 0.5, 0.5},          {1.0, 0.0, 0.0, 1.0, 1.0, 0.0},
        {0.7, 0.2, 0.45, 0.9, 0.1, 0.55},        {0.99, 0.995, 0.0, 0.01, 1.0, 0.98},
        {0.3125, 0.3125, 0.0, 0.3125, 0.0, 0.0}, {0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
        {0.015, 1.0, 0.985, 0.5, 0.25, 0.75},    {0.6, 0.6, 0.6, 0.0, 1.0, 0.0}};
    static sample_log_t log_a, log_b;
    double t_ten[10], t_seven[7];
    plant_params_t p, p_changed;
    plant_state_t sa = {0}, sb;
    inverter_t a, b;
    unsigned long lcg = 12345u;
    int k;
    (void)state;
    plant_params_default(&p);
    p_changed = p;
    p_changed.r_ohm = 2.5;
    sa.i_d = -1.0;
    sa.i_q = 6.0;
    sa.i_x = 0.2;
    sa.omega_m = 150.0;
    plant_sync_angle(&p, &sa);
    sb = sa;
    for (k = 0; k < 10; k++) {
        t_ten[k] = 1e-5 * (double)k;
    }
    for (k = 0; k < 7; k++) {
        t_seven[k] = 1e-4 * (double)k / 7.0;
    }
    inverter_init(&a, &p, 1e-4);
    inverter_init(&b, &p, 1e-4);
    b.cache.off = true;
    a.counting = b.counting = true;
    log_a.n = log_b.n = 0;
    for (k = 0; k < 3000; k++) {
        const plant_params_t *pk = (k >= 2000) ? &p_changed : &p;
        const double *samples = (k < 1000) ? NULL : ((k < 2500) ? t_ten : t_seven);
        const int n = (k < 1000) ? 0 : ((k < 2500) ? 10 : 7);
        const bool off = (k % 997) == 500;
        double ta, tb;
        lcg = lcg * 1103515245u + 12345u;
        ta = inverter_run_period(&a, pk, &sa, patterns[(lcg >> 16) % 8u], off, 1.0, false, samples,
                                 n, (k % 50 == 0) ? log_cb : NULL, &log_a);
        tb = inverter_run_period(&b, pk, &sb, patterns[(lcg >> 16) % 8u], off, 1.0, false, samples,
                                 n, (k % 50 == 0) ? log_cb : NULL, &log_b);
        assert_memory_equal(&ta, &tb, sizeof ta);
        assert_memory_equal(&sa, &sb, sizeof sa);
    }
    assert_true(a.transitions == b.transitions && a.transitions > 10000u);
    assert_int_equal(log_a.n, log_b.n);
    assert_memory_equal(log_a.v, log_b.v, (size_t)log_a.n * sizeof(double));
    print_message("programs reused %lu times, built %lu\n", a.cache.hits, a.cache.built);
    assert_true(a.cache.hits > 2000u && b.cache.hits == 0u);
    inverter_free(&a);
    inverter_free(&b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_average_voltage_without_dead_time),
        cmocka_unit_test(test_dead_time_follows_current_sign),
        cmocka_unit_test(test_short_pulse),
        cmocka_unit_test(test_switching_count),
        cmocka_unit_test(test_forced_off),
        cmocka_unit_test(test_program_cache_changes_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
