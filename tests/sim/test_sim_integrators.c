/*
 * The exact interval solution (plant_exact.h, the default integrator) against RK4.
 *
 * One interval: at a held speed the exact step and RK4 with 0.05 us sub-steps agree on every
 * current within 1e-6 of the rated current, for active and zero vectors, with and without the
 * PM flux harmonics, at standstill, rated and reversed speed.
 *
 * Carried from period to period: the angle's cos / sin, and the state a period ends in.
 *
 * Whole runs, exact against RK4: test_sim_replay.c.
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

#include "plant/inverter.h"
#include "plant/plant.h"
#include "plant/plant_exact.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_interval_matches_fine_rk4),
        cmocka_unit_test(test_carried_angle_and_written_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
