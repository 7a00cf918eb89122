/* Speed PI with clamping anti-windup; stator flux reference (constant and MTPA). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl_flux_ref.h"
#include "ctl_params.h"
#include "ctl_pu.h"
#include "ctl_speed_pi.h"
#include "test_support.h"

static void test_pi_proportional_and_integral(void **state)
{
    ctl_speed_pi_t pi;
    ctl_q out;
    int16_t k;
    (void)state;
    ctl_speed_pi_init(&pi, CTL_Q(2.0), CTL_Q(0.01), CTL_Q(1.0));
    out = ctl_speed_pi_run(&pi, CTL_Q(0.1), CTL_Q(0.0));
    assert_near((double)ctl_to_float(out), 0.2 + 0.001, 1e-6);
    for (k = 1; k < 10; k++) {
        out = ctl_speed_pi_run(&pi, CTL_Q(0.1), CTL_Q(0.0));
    }
    assert_near((double)ctl_to_float(out), 0.2 + 0.01, 1e-6);
    ctl_speed_pi_reset(&pi);
    out = ctl_speed_pi_run(&pi, CTL_Q(0.0), CTL_Q(0.0));
    assert_near((double)ctl_to_float(out), 0.0, 1e-9);
}

/* Anti-windup: after a long saturation the integrator is bounded, so the output leaves the
 * limit as soon as the error reverses instead of after an unwinding delay. */
static void test_pi_anti_windup(void **state)
{
    ctl_speed_pi_t pi;
    ctl_q out = CTL_Q(0.0);
    int32_t k;
    (void)state;
    ctl_speed_pi_init(&pi, CTL_Q(1.0), CTL_Q(0.05), CTL_Q(0.4));
    for (k = 0; k < 10000; k++) {
        out = ctl_speed_pi_run(&pi, CTL_Q(1.0), CTL_Q(0.0));
    }
    assert_near((double)ctl_to_float(out), 0.4, 1e-7);
    assert_true(pi.integ <= CTL_Q(0.4));
    /* integration stopped once the output saturated: integrator stays below the limit */
    assert_true(pi.integ < CTL_Q(0.4));
    out = ctl_speed_pi_run(&pi, CTL_Q(0.0), CTL_Q(0.1)); /* error -0.1 */
    assert_true(out < CTL_Q(0.4));
    assert_true(out < pi.integ);
    /* negative side is symmetric */
    for (k = 0; k < 10000; k++) {
        out = ctl_speed_pi_run(&pi, CTL_Q(-1.0), CTL_Q(0.0));
    }
    assert_near((double)ctl_to_float(out), -0.4, 1e-7);
    assert_true(pi.integ >= CTL_Q(-0.4));
    out = ctl_speed_pi_run(&pi, CTL_Q(0.1), CTL_Q(0.0));
    assert_true(out > CTL_Q(-0.4));
}

/* Output never exceeds the limit even for extreme inputs (saturating arithmetic). */
static void test_pi_extreme_inputs(void **state)
{
    ctl_speed_pi_t pi;
    ctl_q out;
    (void)state;
    ctl_speed_pi_init(&pi, CTL_Q(50.0), CTL_Q(10.0), CTL_Q(0.5));
    out = ctl_speed_pi_run(&pi, CTL_Q_MAX, CTL_Q_MIN);
    assert_near((double)ctl_to_float(out), 0.5, 1e-9);
    out = ctl_speed_pi_run(&pi, CTL_Q_MIN, CTL_Q_MAX);
    assert_near((double)ctl_to_float(out), -0.5, 1e-9);
}

static const ctl_flux_ref_machine_t reference_machine = {0.035f, 0.055f, 0.225f, 3};

static void test_flux_ref_constant(void **state)
{
    ctl_flux_ref_t f;
    (void)state;
    ctl_flux_ref_init(&f, CTL_FLUX_REF_CONSTANT, 0.26f, &reference_machine, 7.0f, 0.5f, 0);
    assert_near((double)ctl_to_float(ctl_flux_ref_run(&f, CTL_Q(0.3))) * CTL_BASE_FLUX_WB, 0.26,
                1e-6);
}

/* MTPA: for a torque T the reference equals the flux of the smallest current that produces T,
 * found here by brute force over the current angle. */
static double brute_force_mtpa_flux(double torque)
{
    const double ld = 0.035;
    const double lq = 0.055;
    const double psi_f = 0.225;
    double lo = 0.0;
    double hi = 20.0;
    double best_flux = 0.0;
    int32_t it;
    for (it = 0; it < 60; it++) { /* bisect the current magnitude */
        const double i = 0.5 * (lo + hi);
        double tmax = -1.0;
        int32_t k;
        for (k = 0; k <= 9000; k++) {
            const double beta = (double)k / 9000.0 * TEST_PI / 2.0; /* angle from q toward -d */
            const double id = -i * sin(beta);
            const double iq = i * cos(beta);
            const double t = 9.0 * ((ld * id + psi_f) * iq - lq * iq * id);
            if (t > tmax) {
                tmax = t;
                best_flux = hypot(ld * id + psi_f, lq * iq);
            }
        }
        if (tmax < torque) {
            lo = i;
        } else {
            hi = i;
        }
    }
    return best_flux;
}

static void test_flux_ref_mtpa(void **state)
{
    ctl_flux_ref_t f;
    const double torques[] = {0.0, 1.0, 3.5, 5.0, 7.0, -4.0};
    int16_t k;
    (void)state;
    ctl_flux_ref_init(&f, CTL_FLUX_REF_MTPA, 0.26f, &reference_machine, 7.0f, 0.0f, 0);
    for (k = 0; k < 6; k++) {
        const double t = torques[k];
        const double ref = brute_force_mtpa_flux(fabs(t));
        const double got = (double)ctl_to_float(ctl_flux_ref_run(
                               &f, ctl_from_float((float)(t / CTL_BASE_TORQUE_NM)))) *
                           CTL_BASE_FLUX_WB;
        assert_near(got, ref, 0.002); /* 2 mWb: table interpolation and brute-force grid */
    }
    /* beyond the table span the last point holds */
    assert_int_equal(ctl_flux_ref_run(&f, CTL_Q(5.0)), f.table[CTL_FLUX_REF_TABLE_POINTS - 1]);
    /* the MTPA flux grows with torque */
    for (k = 1; k < CTL_FLUX_REF_TABLE_POINTS; k++) {
        assert_true(f.table[k] >= f.table[k - 1]);
    }
}

/* The flux at the point of the circle |i| = floor_a that gives the torque, the d-axis current
 * brute-forced from -floor_a (no torque) toward the MTPA point. */
static double brute_force_floor_flux(double torque, double floor_a)
{
    const double ld = 0.035;
    const double lq = 0.055;
    const double psi_f = 0.225;
    int32_t k;
    for (k = 0; k <= 200000; k++) {
        const double id = -floor_a + floor_a * (double)k / 200000.0;
        const double iq = sqrt(floor_a * floor_a - id * id);
        if (9.0 * iq * (psi_f + (ld - lq) * id) >= torque) {
            return hypot(ld * id + psi_f, lq * iq);
        }
    }
    return -1.0;
}

/* Below the torque the floor current gives on the MTPA curve (2.03 N m at 1 A), the reference is
 * the flux of the floor's circle at that torque: a pure -d current of the floor at no load. */
static void test_flux_ref_light_load_floor(void **state)
{
    ctl_flux_ref_t f;
    const double floor_a = 1.0;
    const double torques[] = {0.0, 0.5, 1.0, -1.5, 1.9};
    int16_t k;
    (void)state;
    ctl_flux_ref_init(&f, CTL_FLUX_REF_MTPA, 0.26f, &reference_machine, 7.0f, (float)floor_a, 0);
    assert_near((double)ctl_to_float(f.table[0]) * CTL_BASE_FLUX_WB, 0.225 - 0.035 * floor_a, 1e-4);
    for (k = 0; k < 5; k++) {
        const double t = torques[k];
        const double got = (double)ctl_to_float(ctl_flux_ref_run(
                               &f, ctl_from_float((float)(t / CTL_BASE_TORQUE_NM)))) *
                           CTL_BASE_FLUX_WB;
        assert_near(got, brute_force_floor_flux(fabs(t), floor_a), 0.002);
    }
    /* above it, plain MTPA */
    assert_near((double)ctl_to_float(
                    ctl_flux_ref_run(&f, ctl_from_float((float)(3.5 / CTL_BASE_TORQUE_NM)))) *
                    CTL_BASE_FLUX_WB,
                brute_force_mtpa_flux(3.5), 0.002);
    for (k = 1; k < CTL_FLUX_REF_TABLE_POINTS; k++) {
        assert_true(f.table[k] >= f.table[k - 1]);
    }
}

/* The light-load current's range: 0 (plain MTPA) up to 1000 A accepted, negative or not a number
 * refused with its own reason. A floor above the current of the table's top (the torque limit's
 * MTPA current, 3.5 A at 7 N m) takes effect as that current: the top stays the plain MTPA
 * point, and the table rises with torque at both ends of the range. */
static void test_light_load_current_range(void **state)
{
    ctl_params_t p;
    ctl_params_t q;
    ctl_flux_ref_t plain;
    const float ends[2] = {0.0f, 1000.0f};
    int k;
    (void)state;
    ctl_params_default(&p);
    ctl_flux_ref_init(&plain, CTL_FLUX_REF_MTPA, 0.26f, &reference_machine, 7.0f, 0.0f, 0);
    for (k = 0; k < 2; k++) {
        ctl_flux_ref_t f;
        int16_t i;
        q = p, q.light_load_current_a = ends[k];
        assert_int_equal(ctl_params_check(&q), CTL_PARAM_OK);
        ctl_flux_ref_init(&f, CTL_FLUX_REF_MTPA, 0.26f, &reference_machine, 7.0f, ends[k], 0);
        for (i = 1; i < CTL_FLUX_REF_TABLE_POINTS; i++) {
            assert_true(f.table[i] >= f.table[i - 1]);
        }
        assert_near((double)ctl_to_float(f.table[CTL_FLUX_REF_TABLE_POINTS - 1]),
                    (double)ctl_to_float(plain.table[CTL_FLUX_REF_TABLE_POINTS - 1]), 1e-4);
    }
    q = p, q.light_load_current_a = 1000.5f;
    assert_int_equal(ctl_params_check(&q), CTL_PARAM_LIGHT_LOAD_CURRENT);
    q = p, q.light_load_current_a = -0.1f;
    assert_int_equal(ctl_params_check(&q), CTL_PARAM_LIGHT_LOAD_CURRENT);
    q = p, q.light_load_current_a = (float)NAN;
    assert_int_equal(ctl_params_check(&q), CTL_PARAM_LIGHT_LOAD_CURRENT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pi_proportional_and_integral),
        cmocka_unit_test(test_pi_anti_windup),
        cmocka_unit_test(test_pi_extreme_inputs),
        cmocka_unit_test(test_flux_ref_constant),
        cmocka_unit_test(test_flux_ref_mtpa),
        cmocka_unit_test(test_flux_ref_light_load_floor),
        cmocka_unit_test(test_light_load_current_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
