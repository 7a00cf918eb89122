/*
 * The exact interval solution (plant_exact.h, the default integrator) against RK4.
 *
 * One interval: at a held speed the exact step and RK4 with 0.05 us sub-steps agree on every
 * current within 1e-6 of the rated current, for active and zero vectors, with and without the
 * PM flux harmonics, at standstill, rated and reversed speed.
 *
 * A whole analysis window: the commands a closed-loop run applied (DDC at lambda 20, 100, 200
 * and MPTC-49, rated load, 1500 r/min) are replayed open loop through two plants from the same
 * state, one integrated exactly, one with the RK4 of the simulator before the exact solution
 * (50 us sub-steps, free mechanics). Bands (issue 12): the six phase currents differ by at most
 * 0.1 % of their RMS value, the six-phase mean THD by at most 0.1 percentage points.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "inverter.h"
#include "metrics.h"
#include "plant.h"
#include "plant_exact.h"
#include "sim.h"

#define FINE_PER_PERIOD 10
#define MAX_SAMPLES 40000
#define RPM_TO_RAD_S (3.14159265358979323846 / 30.0)

static void rk4_fine(const plant_params_t *p, plant_state_t *s, const double u[4], double h)
{
    plant_params_t fine = *p;
    fine.max_step_s = 5e-8;
    (void)plant_integrate(&fine, s, u, 0.0, true, h);
}

static void check_one_interval(double rpm, unsigned vector, bool harmonics)
{
    plant_params_t p;
    plant_state_t a, b;
    plant_exact_t e;
    plant_exact_point_t pt;
    plant_exact_span_t sp;
    double u[4];
    plant_params_default(&p);
    p.harmonics_on = harmonics;
    memset(&a, 0, sizeof a);
    a.i_d = -2.0;
    a.i_q = 9.0;
    a.i_x = 0.7;
    a.i_y = -0.4;
    a.omega_m = rpm * RPM_TO_RAD_S;
    a.theta_m = 0.37;
    plant_sync_angle(&p, &a);
    b = a;
    plant_vector_voltage(vector, p.vdc_v, u);
    plant_exact_init(&e, &p);
    plant_exact_set_speed(&e, a.omega_m);
    plant_exact_point(&e, &a, &pt);
    plant_exact_span(&e, 73e-6, &sp);
    (void)plant_exact_step(&e, &a, u, 73e-6, &sp, &pt);
    rk4_fine(&p, &b, u, 73e-6);
    assert_true(fabs(a.i_d - b.i_d) < 1e-5);
    assert_true(fabs(a.i_q - b.i_q) < 1e-5);
    assert_true(fabs(a.i_x - b.i_x) < 1e-5);
    assert_true(fabs(a.i_y - b.i_y) < 1e-5);
    assert_true(fabs(a.cos_e - b.cos_e) < 1e-9 && fabs(a.sin_e - b.sin_e) < 1e-9);
}

static void test_one_interval_matches_fine_rk4(void **state)
{
    static const double speeds[] = {0.0, 1500.0, -800.0, 3000.0};
    static const unsigned vectors[] = {0u, 63u, 0x31u, 0x0Eu, 0x2Cu};
    size_t i, j;
    (void)state;
    for (i = 0; i < sizeof speeds / sizeof speeds[0]; i++) {
        for (j = 0; j < sizeof vectors / sizeof vectors[0]; j++) {
            check_one_interval(speeds[i], vectors[j], true);
            check_one_interval(speeds[i], vectors[j], false);
        }
    }
}

/* The exact method carries cos / sin of the angle from period to period (no libm per period) and
 * reuses the last period's end point: after 20,000 periods (2 s at 1500 r/min) they agree with
 * the true angle to 1e-11 and have unit length to 1e-15; a state written between periods is
 * noticed (the period then equals one started from scratch, bit for bit). */
static void test_carried_angle_and_written_state(void **state)
{
    static const double duty[6] = {0.7, 0.2, 0.45, 0.9, 0.1, 0.55};
    plant_params_t p;
    plant_state_t a, b;
    inverter_t inv_a, inv_b;
    int k;
    (void)state;
    plant_params_default(&p);
    memset(&a, 0, sizeof a);
    a.omega_m = 1500.0 * RPM_TO_RAD_S;
    plant_sync_angle(&p, &a);
    inverter_init(&inv_a, &p, 1e-4);
    for (k = 0; k < 20000; k++) {
        (void)inverter_run_period(&inv_a, &p, &a, duty, false, 0.0, true, NULL, 0, NULL, NULL);
    }
    {
        /* the true angle: 2 s at the held speed (theta_m, a sum of 130,000 interval increments,
         * is off by about 5e-9 rad by then) */
        const double th = (double)p.pole_pairs * 1500.0 * RPM_TO_RAD_S * 2.0;
        assert_true(fabs(a.cos_e - cos(th)) < 1e-11 && fabs(a.sin_e - sin(th)) < 1e-11);
        assert_true(fabs(a.cos_e * a.cos_e + a.sin_e * a.sin_e - 1.0) < 1e-15);
    }
    b = a;
    inv_b = inv_a;
    inv_b.cache.slot = NULL; /* its own programs */
    inv_b.cache.sample_t = NULL;
    inv_b.cache.n_samples = 0;
    a.i_x = b.i_x = 1.5;
    a.theta_m = b.theta_m = 0.25;
    plant_sync_angle(&p, &a);
    plant_sync_angle(&p, &b);
    inv_b.stepper.point_known = false; /* b starts the period from scratch */
    {
        const double ta =
            inverter_run_period(&inv_a, &p, &a, duty, false, 0.0, true, NULL, 0, NULL, NULL);
        const double tb =
            inverter_run_period(&inv_b, &p, &b, duty, false, 0.0, true, NULL, 0, NULL, NULL);
        assert_memory_equal(&ta, &tb, sizeof ta);
        assert_memory_equal(&a, &b, sizeof a);
    }
    inverter_free(&inv_a);
    inverter_free(&inv_b);
}

/* One plant replaying the commands, with its fine samples. */
typedef struct {
    plant_params_t p;
    plant_state_t x;
    inverter_t inv;
    size_t n;
    double *iph[6], *theta;
} replay_plant_t;

typedef struct {
    replay_plant_t plant[2]; /* exact, rk4 */
    double window_start_s, sample_t[FINE_PER_PERIOD];
    bool started;
} replay_t;

static void replay_sample(void *ctx, double t_rel, const plant_state_t *s, unsigned legs)
{
    replay_plant_t *rp = (replay_plant_t *)ctx;
    double iph[6];
    int k;
    (void)t_rel;
    (void)legs;
    if (rp->n >= MAX_SAMPLES) {
        return;
    }
    plant_phase_currents(&rp->p, s, iph);
    for (k = 0; k < 6; k++) {
        rp->iph[k][rp->n] = iph[k];
    }
    rp->theta[rp->n] = (double)rp->p.pole_pairs * s->theta_m;
    rp->n++;
}

static void replay_start(replay_t *rep, const sim_trace_row_t *row)
{
    int m;
    for (m = 0; m < 2; m++) {
        replay_plant_t *rp = &rep->plant[m];
        plant_params_default(&rp->p);
        rp->p.integrator = (m == 0) ? PLANT_INTEGRATOR_EXACT : PLANT_INTEGRATOR_RK4;
        memset(&rp->x, 0, sizeof rp->x);
        rp->x.i_d = row->i_d;
        rp->x.i_q = row->i_q;
        rp->x.i_x = row->i_x;
        rp->x.i_y = row->i_y;
        rp->x.omega_m = row->speed_rpm * RPM_TO_RAD_S;
        rp->x.theta_m = row->theta_e / (double)rp->p.pole_pairs;
        plant_sync_angle(&rp->p, &rp->x);
        inverter_init(&rp->inv, &rp->p, 1e-4);
    }
    rep->started = true;
}

static void replay_period(void *ctx, const sim_trace_row_t *row, const sim_period_input_t *in)
{
    replay_t *rep = (replay_t *)ctx;
    int m;
    if (row->t < rep->window_start_s - 1e-9) {
        return;
    }
    if (!rep->started) {
        replay_start(rep, row);
    }
    for (m = 0; m < 2; m++) {
        replay_plant_t *rp = &rep->plant[m];
        (void)inverter_run_period(&rp->inv, &rp->p, &rp->x, in->duty, in->forced_off, in->t_load_nm,
                                  false, rep->sample_t, FINE_PER_PERIOD, replay_sample, rp);
    }
}

static double six_phase_thd(const replay_plant_t *rp, size_t first, size_t n)
{
    static const double each[6][METRICS_MAX_CHANNELS] = {{1, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0},
                                                         {0, 0, 1, 0, 0, 0}, {0, 0, 0, 1, 0, 0},
                                                         {0, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 0, 1}};
    const double *ph[6];
    metrics_thd_t th[6];
    double sum = 0.0;
    int k;
    for (k = 0; k < 6; k++) {
        ph[k] = rp->iph[k] + first;
    }
    assert_int_equal(metrics_thd_combined(ph, 6, each, 6, rp->theta + first, n, th), 6);
    for (k = 0; k < 6; k++) {
        sum += th[k].thd;
    }
    return 100.0 * sum / 6.0;
}

static void compare_replays(const replay_t *rep, const char *name)
{
    const replay_plant_t *ex = &rep->plant[0], *rk = &rep->plant[1];
    double err2 = 0.0, ref2 = 0.0, thd_ex, thd_rk, rel;
    size_t first, i, n = ex->n;
    int k, periods;
    assert_int_equal(ex->n, rk->n);
    for (k = 0; k < 6; k++) {
        for (i = 0; i < n; i++) {
            const double d = ex->iph[k][i] - rk->iph[k][i];
            err2 += d * d;
            ref2 += rk->iph[k][i] * rk->iph[k][i];
        }
    }
    rel = sqrt(err2 / ref2);
    periods = metrics_whole_periods(rk->theta, n, n, &first);
    assert_true(periods >= 5);
    thd_ex = six_phase_thd(ex, first, n - first);
    thd_rk = six_phase_thd(rk, first, n - first);
    print_message(
        "%-10s currents differ by %.4f %% rms; THD %.3f %% exact, %.3f %% RK4 (%+.3f pp)\n", name,
        100.0 * rel, thd_ex, thd_rk, thd_ex - thd_rk);
    assert_true(rel <= 1e-3);
    assert_true(fabs(thd_ex - thd_rk) <= 0.1);
}

static void replay_case(int controller, double lambda, const char *name)
{
    static replay_t rep;
    char err[200] = "";
    sim_observer_t obs = {&rep, replay_period, NULL};
    sim_config_t c;
    sim_result_t r;
    int m, k;
    memset(&rep, 0, sizeof rep);
    for (m = 0; m < 2; m++) {
        for (k = 0; k < 6; k++) {
            rep.plant[m].iph[k] = calloc(MAX_SAMPLES, sizeof(double));
            assert_non_null(rep.plant[m].iph[k]);
        }
        rep.plant[m].theta = calloc(MAX_SAMPLES, sizeof(double));
        assert_non_null(rep.plant[m].theta);
    }
    for (k = 0; k < FINE_PER_PERIOD; k++) {
        rep.sample_t[k] = 1e-4 * (double)k / FINE_PER_PERIOD;
    }
    sim_config_default(&c);
    c.controller = controller;
    c.lambda = lambda;
    c.protect = (controller != 1);
    c.observer = &obs;
    rep.window_start_s = 0.3;
    assert_int_equal(sim_run(&c, &r, err, sizeof err), 0);
    compare_replays(&rep, name);
    for (m = 0; m < 2; m++) {
        inverter_free(&rep.plant[m].inv);
        for (k = 0; k < 6; k++) {
            free(rep.plant[m].iph[k]);
        }
        free(rep.plant[m].theta);
    }
}

static void test_window_replay_ddc(void **state)
{
    (void)state;
    replay_case(0, 20.0, "DDC l=20");
    replay_case(0, 100.0, "DDC l=100");
    replay_case(0, 200.0, "DDC l=200");
}

static void test_window_replay_mptc49(void **state)
{
    (void)state;
    replay_case(1, 100.0, "MPTC-49");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_interval_matches_fine_rk4),
        cmocka_unit_test(test_carried_angle_and_written_state),
        cmocka_unit_test(test_window_replay_ddc),
        cmocka_unit_test(test_window_replay_mptc49),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
