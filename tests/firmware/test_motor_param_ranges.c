/*
 * The motor parameter file's ranges (MOTOR_PARAM_LIST, firmware/tools/motor_params_file.h, which
 * the host tools check: sixphase-link identify before it writes, the reader) are the control
 * core's (ctl_params_check): at each bound both accept the value, just outside both refuse it,
 * the core with that quantity's own error. The two lists can then not drift apart unnoticed.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl_params.h"
#include "motor_params_file.h"

#define RANGE_LO(id, name, text, unit, lo, hi, integer) lo,
#define RANGE_HI(id, name, text, unit, lo, hi, integer) hi,
static const double range_lo[] = {MOTOR_PARAM_LIST(RANGE_LO)};
static const double range_hi[] = {MOTOR_PARAM_LIST(RANGE_HI)};
#undef RANGE_LO
#undef RANGE_HI

/* The core's verdict on the default set with quantity id at v: 1 when it refuses it with the
 * quantity's own error (the model check may refuse an extreme but valid value for its own
 * reason), 0 otherwise. */
static int core_refuses(motor_param_t id, double v)
{
    ctl_params_t p;
    ctl_param_error_t own = CTL_PARAM_OK;
    ctl_params_default(&p);
    switch (id) {
    case MOTOR_PARAM_R:
        p.resistance_ohm = (float)v;
        own = CTL_PARAM_RESISTANCE;
        break;
    case MOTOR_PARAM_LD:
        p.ld_h = (float)v;
        own = CTL_PARAM_INDUCTANCE;
        break;
    case MOTOR_PARAM_LQ:
        p.lq_h = (float)v;
        own = CTL_PARAM_INDUCTANCE;
        break;
    case MOTOR_PARAM_LXY:
        p.l_xy_h = (float)v;
        own = CTL_PARAM_INDUCTANCE;
        break;
    case MOTOR_PARAM_PSI_F:
        p.pm_flux_wb = (float)v;
        own = CTL_PARAM_PM_FLUX;
        break;
    case MOTOR_PARAM_INERTIA:
        p.inertia_kg_m2 = (float)v;
        own = CTL_PARAM_INERTIA;
        break;
    default:
        p.pole_pairs = (int16_t)v;
        own = CTL_PARAM_POLE_PAIRS;
        break;
    }
    return ctl_params_check(&p) == own;
}

static int file_refuses(motor_param_t id, double v)
{
    motor_params_t m;
    char err[200];
    motor_params_clear(&m);
    motor_params_set(&m, id, v, 0.0, NULL);
    return motor_params_check(&m, err, sizeof err) != 0;
}

/* The machine's entries and the inertia; not the offset (the HAL's), the friction (no term in
 * the core) nor the speed gains (the core's per-unit bound on them depends on the pole pairs:
 * the file holds the SI range, the gains ctl_speed_gains_from_inertia designs stay inside). */
static void test_ranges_agree(void **state)
{
    int k;
    (void)state;
    for (k = 0; k <= (int)MOTOR_PARAM_ENCODER_OFFSET; k++) {
        const int id = (k == (int)MOTOR_PARAM_ENCODER_OFFSET) ? (int)MOTOR_PARAM_INERTIA : k;
        const motor_param_t q = (motor_param_t)id;
        const double lo = range_lo[id], hi = range_hi[id];
        const double step = (q == MOTOR_PARAM_POLE_PAIRS) ? 1.0 : ((lo > 0.0) ? 1e-3 * lo : 1e-3);
        const double below = lo - step,
                     above = hi + ((q == MOTOR_PARAM_POLE_PAIRS) ? 1.0 : 1e-3 * hi);
        print_message("%d: %g..%g, refused %g and %g\n", id, lo, hi, below, above);
        assert_false(core_refuses(q, lo));
        assert_false(file_refuses(q, lo));
        assert_false(core_refuses(q, hi));
        assert_false(file_refuses(q, hi));
        assert_true(core_refuses(q, below));
        assert_true(file_refuses(q, below));
        assert_true(core_refuses(q, above));
        assert_true(file_refuses(q, above));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_ranges_agree)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
