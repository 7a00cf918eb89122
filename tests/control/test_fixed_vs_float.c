/*
 * Fixed-point build against the float build on many random operating points, both driven
 * through the public control-step API. Counts how often the chosen vector/duty differ and,
 * when they do, how much worse the fixed choice is under an independent double-precision
 * evaluation of the paper's cost (two-step Euler prediction, J = |Te - Tref| + lambda
 * |psi - psi_ref|). The figures are recorded in docs/design.md.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdbool.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl_params.h"
#include "fvf.h"
#include "test_rng.h"
#include "test_support.h"
#include "vsd_reference.h"

#define R_OHM 2.0
#define LD_H 0.035
#define LQ_H 0.055
#define PSI_F 0.225
#define TS_S 1.0e-4
#define POINTS 20000

/* alpha-beta voltage of a switching state per unit of Vdc, from the phase-voltage formula. */
static void state_voltage(int16_t v, double *ua, double *ub)
{
    double s[6];
    double m1;
    double m2;
    int16_t k;
    for (k = 0; k < 6; k++) {
        s[k] = (double)((v >> (5 - k)) & 1);
    }
    m1 = (s[0] + s[1] + s[2]) / 3.0;
    m2 = (s[3] + s[4] + s[5]) / 3.0;
    *ua = 0.0;
    *ub = 0.0;
    for (k = 0; k < 6; k++) {
        const double ph = s[k] - (k < 3 ? m1 : m2);
        *ua += ph * cos(vsd_ref_phase_deg[k] * TEST_PI / 180.0) / 3.0;
        *ub += ph * sin(vsd_ref_phase_deg[k] * TEST_PI / 180.0) / 3.0;
    }
}

static void euler(double *id, double *iq, double w, double ud, double uq)
{
    const double d = *id + TS_S * (ud - R_OHM * *id + w * LQ_H * *iq) / LD_H;
    const double q = *iq + TS_S * (uq - R_OHM * *iq - w * LD_H * *id - w * PSI_F) / LQ_H;
    *id = d;
    *iq = q;
}

static void rotate(double ua, double ub, double theta_turn, double *ud, double *uq)
{
    const double a = 2.0 * TEST_PI * theta_turn;
    *ud = ua * cos(a) + ub * sin(a);
    *uq = -ua * sin(a) + ub * cos(a);
}

static double reference_cost(const fvf_point_t *p, double flux_ref, int16_t v, double d)
{
    double id = p->id;
    double iq = p->iq;
    double ua;
    double ub;
    double ud;
    double uq;
    double te;
    double psi;
    state_voltage(p->vector_in_force, &ua, &ub);
    rotate(p->duty_in_force * p->vdc * ua, p->duty_in_force * p->vdc * ub, p->theta, &ud, &uq);
    euler(&id, &iq, p->omega, ud, uq);
    state_voltage(v, &ua, &ub);
    rotate(d * p->vdc * ua, d * p->vdc * ub, p->theta + p->omega * TS_S / (2.0 * TEST_PI), &ud,
           &uq);
    euler(&id, &iq, p->omega, ud, uq);
    te = 9.0 * ((LD_H * id + PSI_F) * iq - LQ_H * iq * id);
    psi = hypot(LD_H * id + PSI_F, LQ_H * iq);
    return fabs(te - p->torque_ref) + p->lambda * fabs(psi - flux_ref);
}

/* The fraction of a choice's state voltage applied over the period: its duty, or for a virtual
 * vector of VV-MPTC (reported as its large state, duty 1) the virtual vector's magnitude over
 * the large state's, 4 sqrt(3) - 6 (the same direction; the x-y part is zero and does not enter
 * the cost). */
static double applied_share(int16_t controller, int16_t v, double d)
{
    if (controller == (int16_t)CTL_CONTROLLER_VVMPTC && v != 0 && v != 077 && d > 0.0) {
        return 4.0 * sqrt(3.0) - 6.0;
    }
    return d;
}

static uint32_t rng = 99u;
static double uniform(double lo, double hi) { return test_lcg_range(&rng, lo, hi); }

/* A random operating point, drawn in this order: currents, angle, speed, DC link, the state in
 * force; then the caller's duty in force; then random_torque_ref near the currents' torque. */
static void random_point(fvf_point_t *p, int16_t controller, double lambda)
{
    p->controller = controller;
    p->lambda = lambda;
    p->id = uniform(-2.0, 0.5);
    p->iq = uniform(-4.0, 4.0);
    p->ix = uniform(-0.5, 0.5);
    p->iy = uniform(-0.5, 0.5);
    p->theta = uniform(0.0, 1.0);
    p->omega = uniform(-1.0, 1.0) * 1600.0 * TEST_PI / 30.0 * 3.0;
    p->vdc = uniform(510.0, 570.0);
    p->vector_in_force = (int16_t)(uniform(0.0, 64.0));
}

static void random_torque_ref(fvf_point_t *p)
{
    const double te = 9.0 * ((LD_H * p->id + PSI_F) * p->iq - LQ_H * p->iq * p->id);
    p->torque_ref = fmax(-7.0, fmin(7.0, te + uniform(-1.0, 1.0)));
}

static void compare(int16_t controller, double max_mismatch_fraction, double max_cost_excess)
{
    static const double lambdas[3] = {20.0, 100.0, 200.0};
    int32_t n;
    int32_t mismatches = 0;
    int32_t vector_mismatches = 0;
    double excess_sum = 0.0;
    double excess_max = 0.0;
    double cost_sum = 0.0;
    for (n = 0; n < POINTS; n++) {
        fvf_point_t p;
        fvf_result_t fx;
        fvf_result_t fl;
        random_point(&p, controller, lambdas[n % 3]);
        p.duty_in_force = controller == 0 ? (double)(int32_t)uniform(0.0, 6.0) / 5.0 : 1.0;
        random_torque_ref(&p);
        fvf_evaluate(&p, &fx);
        flt_fvf_evaluate(&p, &fl);
        assert_true(fx.vector >= 0 && fl.vector >= 0);
        cost_sum += reference_cost(&p, fl.flux_ref, fl.vector,
                                   applied_share(controller, fl.vector, fl.duty));
        if (fx.vector != fl.vector || fabs(fx.duty - fl.duty) > 1e-6) {
            /* u00 and u77 are the same voltage: not a different choice */
            const bool both_zero = (fx.vector == 0 || fx.vector == 077 || fx.duty == 0.0) &&
                                   (fl.vector == 0 || fl.vector == 077 || fl.duty == 0.0);
            if (!both_zero) {
                const double excess =
                    reference_cost(&p, fl.flux_ref, fx.vector,
                                   applied_share(controller, fx.vector, fx.duty)) -
                    reference_cost(&p, fl.flux_ref, fl.vector,
                                   applied_share(controller, fl.vector, fl.duty));
                mismatches++;
                vector_mismatches += (fx.vector != fl.vector) ? 1 : 0;
                excess_sum += excess;
                excess_max = fmax(excess_max, excess);
            }
        }
    }
    print_message("controller %d: %d points, choice differs in %d (%.3f %%; vector differs in %d), "
                  "mean cost %.4f, cost excess of the fixed choice when different: mean %.5f, "
                  "max %.5f (cost units N*m)\n",
                  controller, POINTS, mismatches, 100.0 * mismatches / POINTS, vector_mismatches,
                  cost_sum / POINTS, mismatches ? excess_sum / mismatches : 0.0, excess_max);
    assert_true((double)mismatches / POINTS <= max_mismatch_fraction);
    assert_true(excess_max <= max_cost_excess);
}

static void test_ddc(void **state)
{
    (void)state;
    compare(0, 0.01, 0.02);
}

static void test_mptc49(void **state)
{
    (void)state;
    compare(1, 0.01, 0.02);
}

static void test_mptc13(void **state)
{
    (void)state;
    compare(2, 0.01, 0.02);
}

static void test_vvmptc(void **state)
{
    (void)state;
    compare((int16_t)CTL_CONTROLLER_VVMPTC, 0.01, 0.02);
}

/* FOC-VSD has no choice to differ: its command is six continuous duties. Both builds on the same
 * random points (the voltage in force a random state's at a random duty): the duties agree to
 * within a few Q24 roundings amplified by the PI gains. */
static void test_foc(void **state)
{
    int32_t n;
    double diff_max = 0.0;
    double diff_sum = 0.0;
    (void)state;
    for (n = 0; n < POINTS; n++) {
        fvf_point_t p;
        fvf_result_t fx;
        fvf_result_t fl;
        int16_t k;
        random_point(&p, (int16_t)CTL_CONTROLLER_FOC, 100.0);
        p.duty_in_force = uniform(0.0, 1.0);
        random_torque_ref(&p);
        fvf_evaluate(&p, &fx);
        flt_fvf_evaluate(&p, &fl);
        assert_true(fx.vector == 0 && fl.vector == 0);
        for (k = 0; k < 6; k++) {
            const double d = fabs(fx.leg_duty[k] - fl.leg_duty[k]);
            diff_max = fmax(diff_max, d);
            diff_sum += d;
        }
    }
    print_message("controller 3 (FOC-VSD): %d points, leg duty fixed - float: mean %.2e, max "
                  "%.2e\n",
                  POINTS, diff_sum / (6.0 * POINTS), diff_max);
    assert_true(diff_max < 1e-4); /* 10 ns of a 100 us period */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ddc),    cmocka_unit_test(test_mptc49), cmocka_unit_test(test_mptc13),
        cmocka_unit_test(test_vvmptc), cmocka_unit_test(test_foc),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
