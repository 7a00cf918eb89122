/* Two-step predictor against an accurate solution of the continuous model. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "ctl_predict.h"
#include "ctl_pu.h"
#include "test_rng.h"
#include "test_support.h"

#define R_OHM 2.0
#define LD_H 0.035
#define LQ_H 0.055
#define LXY_H 0.010
#define PSI_F 0.225

typedef struct {
    double id, iq, ix;
} state_t;

/* Continuous rotor-frame model at constant speed and voltage, RK4 with fine steps. */
static void derivative(const state_t *s, double w, double ud, double uq, double ux, state_t *ds)
{
    ds->id = (ud - R_OHM * s->id + w * LQ_H * s->iq) / LD_H;
    ds->iq = (uq - R_OHM * s->iq - w * LD_H * s->id - w * PSI_F) / LQ_H;
    ds->ix = (ux - R_OHM * s->ix) / LXY_H;
}

static state_t exact_step(state_t s, double w, double ud, double uq, double ux, double ts)
{
    const int32_t n = 2000;
    const double h = ts / (double)n;
    int32_t k;
    for (k = 0; k < n; k++) {
        state_t k1, k2, k3, k4, t;
        derivative(&s, w, ud, uq, ux, &k1);
        t = (state_t){s.id + 0.5 * h * k1.id, s.iq + 0.5 * h * k1.iq, s.ix + 0.5 * h * k1.ix};
        derivative(&t, w, ud, uq, ux, &k2);
        t = (state_t){s.id + 0.5 * h * k2.id, s.iq + 0.5 * h * k2.iq, s.ix + 0.5 * h * k2.ix};
        derivative(&t, w, ud, uq, ux, &k3);
        t = (state_t){s.id + h * k3.id, s.iq + h * k3.iq, s.ix + h * k3.ix};
        derivative(&t, w, ud, uq, ux, &k4);
        s.id += h / 6.0 * (k1.id + 2.0 * k2.id + 2.0 * k3.id + k4.id);
        s.iq += h / 6.0 * (k1.iq + 2.0 * k2.iq + 2.0 * k3.iq + k4.iq);
        s.ix += h / 6.0 * (k1.ix + 2.0 * k2.ix + 2.0 * k3.ix + k4.ix);
    }
    return s;
}

static ctl_q pu(double si, double base) { return ctl_from_float((float)(si / base)); }

/* Largest one-step error of the Euler predictor over random operating points at rated
 * conditions (|u| up to 0.644 * 540 V, speed up to 1600 r/min). */
static double worst_error(double ts, uint32_t seed)
{
    ctl_model_t m;
    double worst = 0.0;
    int32_t n;
    assert_true(ctl_model_init(&m, (float)R_OHM, (float)LD_H, (float)LQ_H, (float)LXY_H,
                               (float)PSI_F, 3, (float)ts));
    for (n = 0; n < 300; n++) {
        const state_t s0 = {test_lcg_range(&seed, -4.0, 2.0), test_lcg_range(&seed, -4.0, 4.0),
                            test_lcg_range(&seed, -2.0, 2.0)};
        const double w = test_lcg_range(&seed, -1.0, 1.0) * 1600.0 * TEST_PI / 30.0 * 3.0;
        const double ud = test_lcg_range(&seed, -348.0, 348.0);
        const double uq = test_lcg_range(&seed, -348.0, 348.0);
        const double ux = test_lcg_range(&seed, -348.0, 348.0);
        const state_t ref = exact_step(s0, w, ud, uq, ux, ts);
        ctl_q id1;
        ctl_q iq1;
        ctl_q ix1;
        double e;
        ctl_predict_dq(&m, pu(s0.id, CTL_BASE_CURRENT_A), pu(s0.iq, CTL_BASE_CURRENT_A),
                       pu(w, CTL_BASE_OMEGA_RAD_S), pu(ud, CTL_BASE_VOLTAGE_V),
                       pu(uq, CTL_BASE_VOLTAGE_V), &id1, &iq1);
        ix1 = ctl_predict_xy(&m, pu(s0.ix, CTL_BASE_CURRENT_A), pu(ux, CTL_BASE_VOLTAGE_V));
        e = fabs((double)ctl_to_float(id1) * CTL_BASE_CURRENT_A - ref.id);
        e = fmax(e, fabs((double)ctl_to_float(iq1) * CTL_BASE_CURRENT_A - ref.iq));
        e = fmax(e, fabs((double)ctl_to_float(ix1) * CTL_BASE_CURRENT_A - ref.ix));
        worst = fmax(worst, e);
    }
    return worst;
}

/* Stated bound: at Ts = 100 us the one-step error of the forward-Euler predictor stays below
 * 0.06 A (Ts^2/2 * max|d2i/dt2|: the x-y circuit, 348 V over 10 mH, dominates), i.e. under
 * 2 % of rated current. */
static void test_euler_error_bound_at_10khz(void **state)
{
    (void)state;
    const double e = worst_error(1.0e-4, 12345u);
    print_message("predictor worst one-step error at 10 kHz: %.4f A\n", e);
    assert_true(e < 0.06);
}

/* Forward Euler is first order per step overall, second order locally: halving Ts must cut
 * the one-step error by about four (3..5 allowing for fixed-point resolution). */
static void test_euler_error_is_second_order_locally(void **state)
{
    (void)state;
    const double e1 = worst_error(1.0e-4, 777u);
    const double e2 = worst_error(0.5e-4, 777u);
    print_message("error ratio Ts/(Ts/2): %.2f\n", e1 / e2);
    assert_true(e1 / e2 > 3.0 && e1 / e2 < 5.0);
}

static void test_model_rejects_bad_parameters(void **state)
{
    ctl_model_t m;
    (void)state;
    assert_false(ctl_model_init(&m, 2.0f, 0.0f, 0.055f, 0.01f, 0.225f, 3, 1e-4f));
    assert_false(ctl_model_init(&m, 2.0f, 0.035f, -0.055f, 0.01f, 0.225f, 3, 1e-4f));
    assert_false(ctl_model_init(&m, 2.0f, 0.035f, 0.055f, 0.0f, 0.225f, 3, 1e-4f));
    assert_false(ctl_model_init(&m, 2.0f, 0.035f, 0.055f, 0.01f, 0.225f, 0, 1e-4f));
    assert_false(ctl_model_init(&m, 2.0f, 0.035f, 0.055f, 0.01f, 0.225f, 3, 0.0f));
    assert_false(ctl_model_init(&m, -1.0f, 0.035f, 0.055f, 0.01f, 0.225f, 3, 1e-4f));
    /* a step longer than the R/L time constant makes Euler unstable: refused */
    assert_false(ctl_model_init(&m, 2.0f, 0.035f, 0.055f, 0.001f, 0.225f, 3, 1e-3f));
    assert_true(ctl_model_init(&m, 2.0f, 0.035f, 0.055f, 0.01f, 0.225f, 3, 1e-4f));
}

/* Torque and flux from currents: Te = 3 Pn (psi_d iq - psi_q id), brief Eq. 6. */
static void test_torque_and_flux_match_formula(void **state)
{
    ctl_model_t m;
    const double id = -0.8;
    const double iq = 3.2;
    const double te = 3.0 * 3.0 * ((LD_H * id + PSI_F) * iq - LQ_H * iq * id);
    const double psi = hypot(LD_H * id + PSI_F, LQ_H * iq);
    ctl_q torque;
    ctl_q flux;
    (void)state;
    assert_true(ctl_model_init(&m, 2.0f, 0.035f, 0.055f, 0.01f, 0.225f, 3, 1e-4f));
    ctl_torque_flux(&m, pu(id, CTL_BASE_CURRENT_A), pu(iq, CTL_BASE_CURRENT_A), &torque, &flux);
    assert_near((double)ctl_to_float(torque) * CTL_BASE_TORQUE_NM, te, 1e-3);
    assert_near((double)ctl_to_float(flux) * CTL_BASE_FLUX_WB, psi, 1e-5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_euler_error_bound_at_10khz),
        cmocka_unit_test(test_euler_error_is_second_order_locally),
        cmocka_unit_test(test_model_rejects_bad_parameters),
        cmocka_unit_test(test_torque_and_flux_match_formula),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
