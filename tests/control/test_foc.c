/*
 * FOC-VSD (ctl_foc.h): gains from the machine, current references at the flux reference's
 * operating points, the modulator (each set's own zero sequence, duties in range, the voltage
 * it realises), the back-calculation anti-windup, and the current loops through ctl_step on a
 * model of the machine (d-q and x-y currents settle on their references; the decoupling holds
 * them there at speed).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "ctl.h"
#include "ctl_foc.h"
#include "ctl_machine.h"
#include "ctl_pu.h"
#include "test_rng.h"
#include "test_support.h"

#define PU_L(h) ((h) / CTL_BASE_INDUCTANCE_H)

static ctl_t ctl;

static ctl_params_t foc_params(void)
{
    ctl_params_t p;
    ctl_params_default(&p);
    p.controller = CTL_CONTROLLER_FOC;
    return p;
}

static double f(ctl_q x) { return (double)ctl_to_float(x); }

/* Kp = L w_c, Ki Ts = R w_c Ts, tracking R Ts / L with w_c = 2 pi fs / 20 (500 Hz at 10 kHz),
 * per unit. */
static void test_gains_from_machine(void **state)
{
    const ctl_params_t p = foc_params();
    const ctl_config_t *cfg;
    ctl_foc_gains_t g;
    const double wc = 2.0 * TEST_PI * (1.0 / (double)p.sample_time_s) / 20.0 / CTL_BASE_OMEGA_RAD_S;
    const double ts = (double)p.sample_time_s / CTL_BASE_TIME_S;
    (void)state;
    assert_true(ctl_init(&ctl, &p));
    cfg = ctl_config(&ctl);
    assert_near(wc * CTL_BASE_OMEGA_RAD_S, 2.0 * TEST_PI * 500.0, 1e-3);
    ctl_foc_gains(&cfg->ctrl.foc, &cfg->model, &g);
    assert_near(f(g.kp_d), PU_L(CTL_MACHINE_LD_H) * wc, 1e-5);
    assert_near(f(g.kp_q), PU_L(CTL_MACHINE_LQ_H) * wc, 1e-5);
    assert_near(f(g.kp_xy), PU_L(CTL_MACHINE_LXY_H) * wc, 1e-5);
    assert_near(f(g.ki_ts), CTL_MACHINE_R_OHM / CTL_BASE_IMPEDANCE_OHM * wc * ts, 1e-6);
    assert_near(f(g.kt_d), CTL_MACHINE_R_OHM / CTL_BASE_IMPEDANCE_OHM * ts / PU_L(CTL_MACHINE_LD_H),
                1e-6);
}

/* Torque and flux of the references: the torque asked, the MTPA flux the predictive
 * controllers are given (ctl_flux_ref_run); constant-flux mode i_d = 0. */
static void test_current_references(void **state)
{
    ctl_params_t p = foc_params();
    const ctl_config_t *cfg;
    int16_t k;
    (void)state;
    p.light_load_current_a = 0.0f;
    assert_true(ctl_init(&ctl, &p));
    cfg = ctl_config(&ctl);
    for (k = -20; k <= 20; k++) {
        const double t_nm = 7.0 * (double)k / 20.0;
        const ctl_q t = ctl_from_float((float)(t_nm / CTL_BASE_TORQUE_NM));
        ctl_q id;
        ctl_q iq;
        double psi_d, psi_q;
        ctl_foc_current_ref(&cfg->ctrl.foc, &cfg->flux_ref, &cfg->model, t, &id, &iq);
        psi_d = CTL_MACHINE_PSI_F_WB + CTL_MACHINE_LD_H * f(id) * CTL_BASE_CURRENT_A;
        psi_q = CTL_MACHINE_LQ_H * f(iq) * CTL_BASE_CURRENT_A;
        assert_near(3.0 * 3.0 * (psi_d * f(iq) - psi_q * f(id)) * CTL_BASE_CURRENT_A, t_nm, 0.01);
        assert_near(sqrt(psi_d * psi_d + psi_q * psi_q),
                    f(ctl_flux_ref_run(&cfg->flux_ref, t)) * CTL_BASE_FLUX_WB, 1e-3);
        assert_true(f(id) <= 1e-7); /* MTPA of L_d < L_q: i_d <= 0 */
    }
    p.flux_ref_mode = CTL_FLUX_REF_CONSTANT;
    assert_true(ctl_init(&ctl, &p));
    cfg = ctl_config(&ctl);
    for (k = -4; k <= 4; k++) {
        const double t_nm = 1.75 * (double)k;
        ctl_q id;
        ctl_q iq;
        ctl_foc_current_ref(&cfg->ctrl.foc, &cfg->flux_ref, &cfg->model,
                            ctl_from_float((float)(t_nm / CTL_BASE_TORQUE_NM)), &id, &iq);
        assert_near(f(id), 0.0, 1e-7);
        assert_near(f(iq) * CTL_BASE_CURRENT_A, t_nm / (3.0 * 3.0 * CTL_MACHINE_PSI_F_WB), 1e-3);
    }
}

/* Phase voltages of the duties with isolated neutrals: Vdc (d_k - mean of the set). */
static void set_voltages(const ctl_q duty[6], double vdc, double v[6])
{
    int16_t s;
    int16_t k;
    for (s = 0; s < 6; s += 3) {
        const double mean = (f(duty[s]) + f(duty[s + 1]) + f(duty[s + 2])) / 3.0;
        for (k = s; k < s + 3; k++) {
            v[k] = vdc * (f(duty[k]) - mean);
        }
    }
}

/* Within the linear range the duties realise the request exactly, each set centred by its own
 * min-max zero sequence (its highest and lowest duty symmetric about one half); beyond it the
 * duties clamp to [0, 1] and the realised voltage says what was applied. */
static void test_modulator(void **state)
{
    test_rng_t rng = {12345u};
    int32_t n;
    (void)state;
    for (n = 0; n < 5000; n++) {
        const double scale = (n % 2 == 0) ? 0.5 : 1.2; /* inside, or partly beyond, the range */
        const double vdc = test_rng_range(&rng, 0.9, 1.1);
        ctl_vsd_t v;
        ctl_vsd_t r;
        ctl_q duty[6];
        double phase[6];
        double want[6];
        bool inside = true;
        int16_t s;
        int16_t k;
        v.alpha = ctl_from_float((float)(scale * test_rng_range(&rng, -1.0, 1.0)));
        v.beta = ctl_from_float((float)(scale * test_rng_range(&rng, -1.0, 1.0)));
        v.x = ctl_from_float((float)(0.2 * scale * test_rng_range(&rng, -1.0, 1.0)));
        v.y = ctl_from_float((float)(0.2 * scale * test_rng_range(&rng, -1.0, 1.0)));
        (void)ctl_foc_modulate(&v, ctl_from_float((float)vdc), duty, &r);
        set_voltages(duty, vdc, phase);
        for (k = 0; k < 6; k++) {
            const double th = (double)((int16_t[]){0, 120, 240, 30, 150, 270})[k] * TEST_PI / 180.0;
            want[k] = f(v.alpha) * cos(th) + f(v.beta) * sin(th) + f(v.x) * cos(5.0 * th) +
                      f(v.y) * sin(5.0 * th);
            assert_true(duty[k] >= CTL_Q(0.0) && duty[k] <= CTL_Q(1.0));
        }
        for (s = 0; s < 6; s += 3) { /* centred, and within the range by the request's spread */
            const double hi = fmax(fmax(f(duty[s]), f(duty[s + 1])), f(duty[s + 2]));
            const double lo = fmin(fmin(f(duty[s]), f(duty[s + 1])), f(duty[s + 2]));
            const double whi = fmax(fmax(want[s], want[s + 1]), want[s + 2]);
            const double wlo = fmin(fmin(want[s], want[s + 1]), want[s + 2]);
            assert_near(hi + lo, 1.0, 1e-5);
            inside = inside && whi - wlo < vdc * (1.0 - 1e-4);
        }
        if (!inside) {
            continue;
        }
        for (k = 0; k < 6; k++) {
            assert_near(phase[k], want[k], 1e-5);
        }
        assert_near(f(r.alpha), f(v.alpha), 1e-5);
        assert_near(f(r.beta), f(v.beta), 1e-5);
        assert_near(f(r.x), f(v.x), 1e-5);
        assert_near(f(r.y), f(v.y), 1e-5);
    }
}

/* Back-calculation (tracking time constant T_i): held in saturation, the integrator settles at
 * the realised voltage, where its output with the error gone would ask for just what the
 * modulator applies, not at its bound; the output leaves the limit as soon as the error turns.
 * Plain integration would have run to the bound. */
static void test_anti_windup(void **state)
{
    const ctl_q kp = CTL_Q(2.0);
    const ctl_q ki = CTL_Q(0.0125);
    const ctl_q kt = CTL_Q(0.0125 / 2.0);
    const ctl_q limit = CTL_Q(2.0);
    const ctl_q realised_max = CTL_Q(0.5);
    ctl_q integ = CTL_Q(0.0);
    ctl_q out = CTL_Q(0.0);
    int32_t k;
    (void)state;
    for (k = 0; k < 20000; k++) {
        const ctl_q err = CTL_Q(0.25);
        const ctl_q requested = ctl_foc_pi(kp, integ, err);
        const ctl_q realised = ctl_min(requested, realised_max);
        integ = ctl_foc_integrate(integ, ki, kt, err, requested, realised, limit);
        out = realised;
    }
    assert_near(f(out), 0.5, 1e-6);
    assert_near(f(integ), 0.5, 1e-4);
    out = ctl_foc_pi(kp, integ, CTL_Q(-0.0078125)); /* the error turns: out of saturation at once */
    assert_true(out < realised_max);
    for (k = 0; k < 20000; k++) { /* the bound holds whatever is asked */
        integ =
            ctl_foc_integrate(integ, CTL_Q(1.0), kt, CTL_Q(100.0), CTL_Q(0.0), CTL_Q(0.0), limit);
    }
    assert_true(integ == limit);
}

/* Beyond the linear range the request is scaled as a whole: the realised voltage keeps the
 * direction of each plane, and the wider set spans the full duty range. */
static void test_modulator_overrange(void **state)
{
    ctl_vsd_t v = {CTL_Q(0.75), CTL_Q(0.5), CTL_Q(0.0625), CTL_Q(-0.03125)};
    ctl_vsd_t r;
    ctl_q duty[6];
    double k;
    int16_t n;
    (void)state;
    (void)ctl_foc_modulate(&v, CTL_Q(1.0), duty, &r);
    k = f(r.alpha) / f(v.alpha);
    assert_true(k < 0.8 && k > 0.5);
    assert_near(f(r.beta), k * f(v.beta), 1e-5);
    assert_near(f(r.x), k * f(v.x), 1e-5);
    assert_near(f(r.y), k * f(v.y), 1e-5);
    for (n = 0; n < 6; n += 3) {
        const double hi = fmax(fmax(f(duty[n]), f(duty[n + 1])), f(duty[n + 2]));
        const double lo = fmin(fmin(f(duty[n]), f(duty[n + 1])), f(duty[n + 2]));
        assert_true(hi - lo <= 1.0 + 1e-6);
        assert_near(hi + lo, 1.0, 1e-5);
    }
}

/* The machine's continuous model (method notes section 2, no PM harmonics), per unit, over one
 * period of the leg duties' average voltages: 50 Euler sub-steps, the rotor turning at w. */
typedef struct {
    double id, iq, ix, iy, theta; /* theta in turns */
} plant_t;

static void plant_period(plant_t *x, const ctl_q duty[6], double vdc, double w)
{
    static const double deg[6] = {0, 120, 240, 30, 150, 270};
    const double ld = PU_L(CTL_MACHINE_LD_H), lq = PU_L(CTL_MACHINE_LQ_H);
    const double lxy = PU_L(CTL_MACHINE_LXY_H), r = CTL_MACHINE_R_OHM / CTL_BASE_IMPEDANCE_OHM;
    const double psi_f = CTL_MACHINE_PSI_F_WB / CTL_BASE_FLUX_WB;
    const double h = 1e-4 / CTL_BASE_TIME_S / 50.0;
    double v[6];
    double ua = 0.0, ub = 0.0, ux = 0.0, uy = 0.0;
    int16_t k;
    set_voltages(duty, vdc, v);
    for (k = 0; k < 6; k++) {
        const double th = deg[k] * TEST_PI / 180.0;
        ua += v[k] * cos(th) / 3.0;
        ub += v[k] * sin(th) / 3.0;
        ux += v[k] * cos(5.0 * th) / 3.0;
        uy += v[k] * sin(5.0 * th) / 3.0;
    }
    for (k = 0; k < 50; k++) {
        const double c = cos(2.0 * TEST_PI * x->theta), s = sin(2.0 * TEST_PI * x->theta);
        const double ud = ua * c + ub * s, uq = ub * c - ua * s;
        const double did = (ud - r * x->id + w * lq * x->iq) / ld;
        const double diq = (uq - r * x->iq - w * (ld * x->id + psi_f)) / lq;
        x->id += h * did;
        x->iq += h * diq;
        x->ix += h * (ux - r * x->ix) / lxy;
        x->iy += h * (uy - r * x->iy) / lxy;
        x->theta += h * w / (2.0 * TEST_PI);
    }
}

static void measure(const plant_t *x, double w, ctl_meas_t *m)
{
    static const double deg[6] = {0, 120, 240, 30, 150, 270};
    const double c = cos(2.0 * TEST_PI * x->theta), s = sin(2.0 * TEST_PI * x->theta);
    const double ia = x->id * c - x->iq * s, ib = x->id * s + x->iq * c;
    int16_t k;
    for (k = 0; k < 6; k++) {
        const double th = deg[k] * TEST_PI / 180.0;
        m->i_phase[k] = ctl_from_float(
            (float)(ia * cos(th) + ib * sin(th) + x->ix * cos(5.0 * th) + x->iy * sin(5.0 * th)));
    }
    m->vdc = CTL_Q(1.0);
    m->theta_e = ctl_from_float((float)(x->theta - floor(x->theta)));
    m->omega_e = ctl_from_float((float)w);
}

/* Torque mode at rated torque and 1500 r/min from a standstill current with x-y current: the
 * d-q currents settle on the MTPA references and the x-y currents die out within the
 * bandwidth's few time constants (w_c = 3142 rad/s: 0.3 ms), and stay there; every command is
 * six duties in [0, 1] with no single vector named. */
static void test_current_loops_on_the_model(void **state)
{
    const ctl_params_t p = foc_params();
    const double w = 1500.0 / 60.0 * 3.0 * 2.0 * TEST_PI / CTL_BASE_OMEGA_RAD_S;
    const ctl_q t_ref = ctl_from_float((float)(7.0 / CTL_BASE_TORQUE_NM));
    plant_t x = {0.0, 0.0, 0.03, -0.02, 0.1};
    ctl_q id_ref;
    ctl_q iq_ref;
    int16_t n;
    (void)state;
    assert_true(ctl_init(&ctl, &p));
    ctl_set_loop_mode(&ctl, CTL_LOOP_TORQUE);
    ctl_set_torque_ref(&ctl, t_ref);
    ctl_foc_current_ref(&ctl_config(&ctl)->ctrl.foc, &ctl_config(&ctl)->flux_ref,
                        &ctl_config(&ctl)->model, t_ref, &id_ref, &iq_ref);
    for (n = 0; n < 300; n++) {
        ctl_meas_t m;
        ctl_cmd_t cmd;
        int16_t k;
        measure(&x, w, &m);
        ctl_step(&ctl, &m, &cmd);
        assert_true(cmd.enable);
        assert_int_equal(cmd.vector, 0);
        assert_true(cmd.duty == CTL_Q(0.0));
        for (k = 0; k < 6; k++) {
            assert_true(cmd.leg_duty[k] >= CTL_Q(0.0) && cmd.leg_duty[k] <= CTL_Q(1.0));
        }
        plant_period(&x, cmd.leg_duty, 1.0, w);
        if (n >= 30) { /* 3 ms: settled */
            assert_near(x.id, f(id_ref), 0.02 * f(iq_ref));
            assert_near(x.iq, f(iq_ref), 0.02 * f(iq_ref));
            assert_true(fabs(x.ix) < 2e-3 && fabs(x.iy) < 2e-3); /* 0.02 A */
        }
    }
    assert_near(f(ctl_diag_torque_est(&ctl)), f(t_ref), 0.02 * f(t_ref));
}

/* Another controller's set and back: FOC starts from a clean state (integrators and the voltage
 * in force cleared when the controller changes). */
static void test_controller_change_resets(void **state)
{
    ctl_params_t p = foc_params();
    ctl_meas_t m;
    ctl_cmd_t cmd;
    plant_t x = {0.0, 0.1, 0.0, 0.0, 0.0};
    (void)state;
    assert_true(ctl_init(&ctl, &p));
    ctl_set_loop_mode(&ctl, CTL_LOOP_TORQUE);
    ctl_set_torque_ref(&ctl, CTL_Q(0.2));
    measure(&x, 0.5, &m);
    ctl_step(&ctl, &m, &cmd);
    assert_true(ctl.foc.integ_q != CTL_Q(0.0));
    p.controller = CTL_CONTROLLER_DDC;
    assert_int_equal(ctl_request_params(&ctl, &p), CTL_PARAM_OK);
    ctl_step(&ctl, &m, &cmd);
    assert_int_equal(ctl_config(&ctl)->params.controller, CTL_CONTROLLER_DDC);
    assert_true(ctl.foc.integ_q == CTL_Q(0.0) && ctl.foc.v_in_force.alpha == CTL_Q(0.0));
    p.controller = CTL_CONTROLLER_FOC;
    assert_int_equal(ctl_request_params(&ctl, &p), CTL_PARAM_OK);
    ctl_step(&ctl, &m, &cmd);
    assert_int_equal(ctl_config(&ctl)->params.controller, CTL_CONTROLLER_FOC);
    assert_int_equal(ctl.applied_vector, 0);
    assert_true(ctl.applied_duty == CTL_Q(0.0));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gains_from_machine),
        cmocka_unit_test(test_current_references),
        cmocka_unit_test(test_modulator),
        cmocka_unit_test(test_modulator_overrange),
        cmocka_unit_test(test_anti_windup),
        cmocka_unit_test(test_current_loops_on_the_model),
        cmocka_unit_test(test_controller_change_resets),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
