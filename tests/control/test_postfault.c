/* Open-phase operation in the control core: the post-fault geometry, derating and tables
 * (recomputed here in double from the phase angles), the projection, and the post-fault step's
 * commands. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl.h"
#include "ctl_postfault.h"
#include "ctl_pu.h"
#include "ctl_vectors.h"
#include "q24_exact.h" /* test_rng_q */
#include "test_rng.h"
#include "test_support.h"
#include "vsd_reference.h"

/* c_k = (cos th, sin th, cos 5th, sin 5th) */
static void row(int k, double c[4])
{
    const double th = vsd_ref_phase_deg[k] * TEST_PI / 180.0;
    c[0] = cos(th);
    c[1] = sin(th);
    c[2] = cos(5.0 * th);
    c[3] = sin(5.0 * th);
}

/* VSD voltage of a state per unit of Vdc from the phase voltages (two isolated neutrals). */
static void state_voltage(int s, double u[4])
{
    double v[6];
    int k;
    int j;
    for (k = 0; k < 6; k++) {
        const int set = (k < 3) ? 0 : 3;
        double mean = 0.0;
        for (j = set; j < set + 3; j++) {
            mean += (double)((s >> (5 - j)) & 1) / 3.0;
        }
        v[k] = (double)((s >> (5 - k)) & 1) - mean;
    }
    for (j = 0; j < 4; j++) {
        u[j] = 0.0;
    }
    for (k = 0; k < 6; k++) {
        double c[4];
        row(k, c);
        for (j = 0; j < 4; j++) {
            u[j] += c[j] * v[k] / 3.0;
        }
    }
}

/* The effective voltage with phase k open: u less its part along c in the M^-1 metric. */
static void effective(int s, int k, double l_ab, double l_xy, double e[4])
{
    double c[4];
    double u[4];
    double wu;
    double wc;
    int j;
    row(k, c);
    state_voltage(s, u);
    wu = (c[0] * u[0] + c[1] * u[1]) / l_ab + (c[2] * u[2] + c[3] * u[3]) / l_xy;
    wc = 1.0 / l_ab + 1.0 / l_xy;
    for (j = 0; j < 4; j++) {
        e[j] = u[j] - c[j] * wu / wc;
    }
}

static void build(int leg, ctl_postfault_strategy_t s, ctl_postfault_config_t *pf)
{
    ctl_params_t p;
    ctl_params_default(&p);
    ctl_postfault_config_build(pf, (int16_t)leg, s, p.ld_h, p.lq_h, p.l_xy_h);
}

/* Che et al.'s two-isolated-neutral figures: per unit of alpha-beta current the healthy phases
 * peak at sqrt(13)/2 = 1.803 with minimum loss and sqrt(3) = 1.732 with maximum torque; the
 * speed loop's torque limit shrinks by that ratio. */
static void test_peak_ratio_and_torque_derating(void **state)
{
    int k;
    (void)state;
    for (k = 0; k < 6; k++) {
        ctl_params_t p;
        ctl_config_t cfg;
        assert_near((double)ctl_postfault_peak_ratio((int16_t)k, CTL_POSTFAULT_MIN_LOSS),
                    sqrt(13.0) / 2.0, 1e-4);
        assert_near((double)ctl_postfault_peak_ratio((int16_t)k, CTL_POSTFAULT_MAX_TORQUE),
                    sqrt(3.0), 1e-4);
        ctl_params_default(&p);
        p.open_phase = (int16_t)k;
        assert_int_equal(ctl_config_build(&cfg, &p), CTL_PARAM_OK);
        assert_near((double)ctl_to_float(cfg.torque_limit) * CTL_BASE_TORQUE_NM,
                    7.0 / (sqrt(13.0) / 2.0), 1e-4);
    }
    assert_near((double)ctl_postfault_peak_ratio(CTL_POSTFAULT_NO_LEG, CTL_POSTFAULT_MIN_LOSS), 1.0,
                0.0);
}

/* i_xy = forced part + free reference along c_xy turned by 90 deg keeps the open phase (and with
 * maximum torque its partner) at zero for any alpha-beta current; minimum loss has no free part. */
static void test_strategy_currents(void **state)
{
    static const int partner[6] = {5, 3, 4, 1, 2, 0}; /* MT's zero phase: A-F, B-D, C-E */
    test_rng_t rng = {12345u};
    int k;
    int s;
    (void)state;
    for (k = 0; k < 6; k++) {
        for (s = 0; s < 2; s++) {
            ctl_postfault_config_t pf;
            double c[4];
            int n;
            build(k, (ctl_postfault_strategy_t)s, &pf);
            row(k, c);
            assert_int_equal(pf.open_leg, k);
            assert_int_equal(pf.zero_leg, (s == 0) ? CTL_POSTFAULT_NO_LEG : partner[k]);
            assert_int_equal(pf.quiet, (1u << k) | ((s == 0) ? 0u : (1u << partner[k])));
            if (s == 0) {
                assert_true(pf.free_ref_alpha == CTL_Q(0.0) && pf.free_ref_beta == CTL_Q(0.0));
            }
            for (n = 0; n < 20; n++) {
                const double ia = test_rng_range(&rng, -1.0, 1.0);
                const double ib = test_rng_range(&rng, -1.0, 1.0);
                const double forced = -(c[0] * ia + c[1] * ib);
                const double free = (double)ctl_to_float(pf.free_ref_alpha) * ia +
                                    (double)ctl_to_float(pf.free_ref_beta) * ib;
                const double ix = forced * c[2] - free * c[3];
                const double iy = forced * c[3] + free * c[2];
                int j;
                for (j = 0; j < 6; j++) {
                    double cj[4];
                    row(j, cj);
                    if ((((unsigned)pf.quiet >> j) & 1u) != 0u) {
                        assert_near(cj[0] * ia + cj[1] * ib + cj[2] * ix + cj[3] * iy, 0.0, 1e-5);
                    }
                }
            }
        }
    }
}

/* A state and the same state with the open leg's bit flipped move the currents alike, and an
 * effective voltage moves no current into the open phase. */
static void test_effective_voltage(void **state)
{
    int k;
    int s;
    (void)state;
    for (k = 0; k < 6; k++) {
        const int bit = 1 << (5 - k);
        double c[4];
        row(k, c);
        for (s = 0; s < 64; s++) {
            float e[4];
            float f[4];
            double ref[4];
            int j;
            ctl_postfault_effective_voltage((int16_t)s, (int16_t)k, 0.045f, 0.010f, e);
            ctl_postfault_effective_voltage((int16_t)(s ^ bit), (int16_t)k, 0.045f, 0.010f, f);
            effective(s, k, 0.045, 0.010, ref);
            for (j = 0; j < 4; j++) {
                assert_near((double)e[j], (double)f[j], 1e-6);
                assert_near((double)e[j], ref[j], 1e-6);
            }
            assert_near((c[0] * (double)e[0] + c[1] * (double)e[1]) / 0.045 +
                            (c[2] * (double)e[2] + c[3] * (double)e[3]) / 0.010,
                        0.0, 1e-4);
        }
    }
}

/* Every DDC entry: a state of the healthy legs, the largest effective alpha-beta voltage along
 * its direction among the states whose free x-y voltage has the entry's sign. */
static void test_ddc_table(void **state)
{
    const double l_ab = 0.5 * (0.035 + 0.055);
    int k;
    (void)state;
    for (k = 0; k < 6; k++) {
        ctl_postfault_config_t pf;
        double c[4];
        int sec;
        int h;
        int f;
        int sign;
        build(k, CTL_POSTFAULT_MIN_LOSS, &pf);
        row(k, c);
        for (sec = 0; sec < 12; sec++) {
            for (h = 0; h < 2; h++) {
                for (f = 0; f < 2; f++) {
                    const double off = (f == 0) ? 75.0 : 105.0;
                    const double deg = 30.0 * sec + ((h == 0) ? off : -off);
                    const double dx = cos(deg * TEST_PI / 180.0);
                    const double dy = sin(deg * TEST_PI / 180.0);
                    for (sign = 0; sign < 2; sign++) {
                        const int v = pf.ddc_table[sec][h][f][sign];
                        double e[4];
                        double best = 0.0;
                        int s;
                        assert_int_equal(v & (1 << (5 - k)), 0);
                        effective(v, k, l_ab, 0.010, e);
                        assert_true(e[0] * dx + e[1] * dy > 0.1);
                        assert_true(((-c[3] * e[2] + c[2] * e[3]) < 0.0) == (sign == 1));
                        for (s = 0; s < 64; s++) {
                            double o[4];
                            effective(s, k, l_ab, 0.010, o);
                            if (((-c[3] * o[2] + c[2] * o[3]) < -1e-3) == (sign == 1) &&
                                fabs(-c[3] * o[2] + c[2] * o[3]) > 1e-3) {
                                best = fmax(best, o[0] * dx + o[1] * dy);
                            }
                        }
                        assert_near(e[0] * dx + e[1] * dy, best, 1e-4);
                    }
                }
            }
        }
    }
}

/* MPTC: the zero state, then one state per distinct non-zero effective voltage: with isolated
 * neutrals the open phase's set contributes 0 or +-its other phase's voltage (3 values) and the
 * healthy set 7: 21 candidates. The large set: magnitudes at or above the twelfth largest. */
static void test_mptc_sets(void **state)
{
    const double l_ab = 0.5 * (0.035 + 0.055);
    int k;
    (void)state;
    for (k = 0; k < 6; k++) {
        ctl_postfault_config_t pf;
        double mags[32];
        double twelfth;
        int i;
        int j;
        build(k, CTL_POSTFAULT_MIN_LOSS, &pf);
        assert_int_equal(pf.mptc_all_count, 21);
        assert_int_equal(pf.mptc_all[0], 0);
        assert_int_equal(pf.mptc_large[0], 0);
        for (i = 1; i < pf.mptc_all_count; i++) {
            double e[4];
            assert_int_equal(pf.mptc_all[i] & (1 << (5 - k)), 0);
            effective(pf.mptc_all[i], k, l_ab, 0.010, e);
            mags[i] = hypot(e[0], e[1]);
            assert_true(fabs(e[0]) + fabs(e[1]) + fabs(e[2]) + fabs(e[3]) > 1e-3);
            for (j = 1; j < i; j++) {
                double o[4];
                effective(pf.mptc_all[j], k, l_ab, 0.010, o);
                assert_true(fabs(e[0] - o[0]) + fabs(e[1] - o[1]) + fabs(e[2] - o[2]) +
                                fabs(e[3] - o[3]) >
                            1e-3);
            }
        }
        twelfth = 0.0;
        for (i = 1; i < pf.mptc_all_count; i++) {
            int larger = 0;
            for (j = 1; j < pf.mptc_all_count; j++) {
                larger += mags[j] > mags[i] + 1e-4;
            }
            if (larger < 12 && (twelfth == 0.0 || mags[i] < twelfth)) {
                twelfth = mags[i];
            }
        }
        assert_true(pf.mptc_large_count >= 13);
        for (i = 1, j = 1; i < pf.mptc_all_count; i++) {
            if (mags[i] > twelfth - 1e-4) {
                assert_int_equal(pf.mptc_large[j], pf.mptc_all[i]);
                j++;
            }
        }
        assert_int_equal(j, pf.mptc_large_count);
    }
}

/* After the projection the open phase carries no current at that angle, and what moved, moved
 * along M^-1 c (the direction the open terminal's voltage acts in). */
static void test_projection(void **state)
{
    test_rng_t rng = {777u};
    ctl_params_t p;
    ctl_config_t cfg;
    int n;
    (void)state;
    ctl_params_default(&p);
    assert_int_equal(ctl_config_build(&cfg, &p), CTL_PARAM_OK);
    for (n = 0; n < 600; n++) {
        const int k = n % 6;
        const double th = test_rng_range(&rng, 0.0, 2.0 * TEST_PI);
        const double i0[4] = {test_rng_range(&rng, -0.5, 0.5), test_rng_range(&rng, -0.5, 0.5),
                              test_rng_range(&rng, -0.2, 0.2), test_rng_range(&rng, -0.2, 0.2)};
        ctl_postfault_config_t pf;
        ctl_q id = ctl_from_float((float)i0[0]);
        ctl_q iq = ctl_from_float((float)i0[1]);
        ctl_q ix = ctl_from_float((float)i0[2]);
        ctl_q iy = ctl_from_float((float)i0[3]);
        double c[4];
        double cd;
        double cq;
        double g[4];
        double di[4];
        double t;
        build(k, CTL_POSTFAULT_MIN_LOSS, &pf);
        row(k, c);
        cd = c[0] * cos(th) + c[1] * sin(th);
        cq = c[1] * cos(th) - c[0] * sin(th);
        ctl_postfault_project(&cfg.model, &pf, ctl_from_float((float)sin(th)),
                              ctl_from_float((float)cos(th)), &id, &iq, &ix, &iy);
        assert_near(cd * (double)ctl_to_float(id) + cq * (double)ctl_to_float(iq) +
                        c[2] * (double)ctl_to_float(ix) + c[3] * (double)ctl_to_float(iy),
                    0.0, 2e-5);
        g[0] = cd / 0.035;
        g[1] = cq / 0.055;
        g[2] = c[2] / 0.010;
        g[3] = c[3] / 0.010;
        di[0] = (double)ctl_to_float(id) - i0[0];
        di[1] = (double)ctl_to_float(iq) - i0[1];
        di[2] = (double)ctl_to_float(ix) - i0[2];
        di[3] = (double)ctl_to_float(iy) - i0[3];
        t = (di[0] * g[0] + di[1] * g[1] + di[2] * g[2] + di[3] * g[3]) /
            (g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + g[3] * g[3]);
        for (int j = 0; j < 4; j++) {
            assert_near(di[j], t * g[j], 5e-5);
        }
    }
}

/* Within each three-phase set the healthy legs' duties differ as the command's state and
 * duty say (their common part, the set's zero state, applies no voltage): d * (S_i - S_j). */
static void assert_realises_command(const ctl_cmd_t *cmd, int open)
{
    int i;
    int j;
    for (i = 0; i < 6; i++) {
        for (j = 0; j < 6; j++) {
            if (i != open && j != open && i / 3 == j / 3) {
                const int si = (cmd->vector >> (5 - i)) & 1;
                const int sj = (cmd->vector >> (5 - j)) & 1;
                const double want = (double)ctl_to_float(cmd->duty) * (double)(si - sj);
                const double di = (double)ctl_to_float(cmd->leg_duty[i]);
                const double dj = (double)ctl_to_float(cmd->leg_duty[j]);
                assert_true(fabs(di - dj - want) < 1e-6);
            }
        }
    }
}

/* Whatever the input, the post-fault step keeps the open leg's switches off and returns a
 * command of the healthy legs: duties in [0, 1], the open leg's bit clear in the vector, the
 * duties realising the state and duty under every pulse pattern. */
static void test_step_never_drives_the_open_leg(void **state)
{
    test_rng_t rng = {99u};
    int k;
    int ctl;
    (void)state;
    for (k = 0; k < 6; k++) {
        for (ctl = 0; ctl < 9; ctl++) {
            ctl_params_t p;
            ctl_t c;
            int n;
            ctl_params_default(&p);
            p.open_phase = (int16_t)k;
            p.pulse_pattern = (ctl_pulse_pattern_t)(ctl / 3);
            p.controller = (ctl_controller_t)(ctl % 3);
            p.postfault_strategy = (int16_t)(ctl % 3 == 1 ? CTL_POSTFAULT_MAX_TORQUE : 0);
            assert_true(ctl_init(&c, &p));
            assert_int_equal(ctl_postfault_config(&c)->open_leg, k);
            for (n = 0; n < 500; n++) {
                ctl_meas_t m;
                ctl_cmd_t cmd;
                int j;
                for (j = 0; j < 6; j++) {
                    m.i_phase[j] =
                        (n % 50 == 0) ? ctl_from_float(100.0f) : test_rng_q(&rng, -2.0, 2.0);
                }
                m.vdc = test_rng_q(&rng, -0.5, 1.5);
                m.theta_e = test_rng_q(&rng, -3.0, 3.0);
                m.omega_e = test_rng_q(&rng, -4.0, 4.0);
                ctl_set_torque_ref(&c, test_rng_q(&rng, -1.0, 1.0));
                if (n % 2 == 0) {
                    ctl_set_speed_ref(&c, test_rng_q(&rng, -1.0, 1.0));
                }
                ctl_step(&c, &m, &cmd);
                assert_true(cmd.enable);
                assert_int_equal(cmd.vector & (1 << (5 - k)), 0);
                assert_true(cmd.leg_duty[k] == CTL_Q(0.0));
                for (j = 0; j < 6; j++) {
                    assert_true(cmd.leg_duty[j] >= CTL_Q(0.0) && cmd.leg_duty[j] <= CTL_Q(1.0));
                }
                assert_true(cmd.duty >= CTL_Q(0.0) && cmd.duty <= CTL_Q(1.0));
                assert_realises_command(&cmd, k);
            }
        }
    }
}

/* The hand-off switches between the healthy and the post-fault step like any other set; the
 * torque limit in force follows (the speed loop is held within the derated limit). */
static void test_handoff_between_healthy_and_postfault(void **state)
{
    ctl_params_t p;
    ctl_t c;
    (void)state;
    ctl_params_default(&p);
    assert_true(ctl_init(&c, &p));
    assert_int_equal(ctl_postfault_config(&c)->open_leg, CTL_POSTFAULT_NO_LEG);
    assert_true(c.healthy_step);
    p.open_phase = 2;
    assert_int_equal(ctl_request_params(&c, &p), CTL_PARAM_OK);
    assert_int_equal(ctl_postfault_config(&c)->open_leg, CTL_POSTFAULT_NO_LEG); /* not yet */
    assert_true(ctl_config_take(&c));
    assert_int_equal(ctl_postfault_config(&c)->open_leg, 2);
    assert_false(c.healthy_step);
    assert_near((double)ctl_to_float(c.speed_pi.limit) * CTL_BASE_TORQUE_NM,
                7.0 / (sqrt(13.0) / 2.0), 1e-4);
    p.open_phase = CTL_POSTFAULT_NO_LEG;
    assert_int_equal(ctl_request_params(&c, &p), CTL_PARAM_OK);
    assert_true(ctl_config_take(&c));
    assert_true(c.healthy_step);
    assert_near((double)ctl_to_float(c.speed_pi.limit) * CTL_BASE_TORQUE_NM, 7.0, 1e-4);
}

static void test_open_phase_parameters_are_checked(void **state)
{
    ctl_params_t p;
    ctl_params_t bad;
    (void)state;
    ctl_params_default(&p);
    assert_int_equal(p.open_phase, CTL_POSTFAULT_NO_LEG);
    bad = p, bad.open_phase = 6;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_OPEN_PHASE);
    bad = p, bad.open_phase = -2;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_OPEN_PHASE);
    bad = p, bad.postfault_strategy = 2;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_OPEN_PHASE);
    bad = p, bad.open_phase = 5, bad.postfault_strategy = (int16_t)CTL_POSTFAULT_MAX_TORQUE;
    assert_int_equal(ctl_params_check(&bad), CTL_PARAM_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_peak_ratio_and_torque_derating),
        cmocka_unit_test(test_strategy_currents),
        cmocka_unit_test(test_effective_voltage),
        cmocka_unit_test(test_ddc_table),
        cmocka_unit_test(test_mptc_sets),
        cmocka_unit_test(test_projection),
        cmocka_unit_test(test_step_never_drives_the_open_leg),
        cmocka_unit_test(test_handoff_between_healthy_and_postfault),
        cmocka_unit_test(test_open_phase_parameters_are_checked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
