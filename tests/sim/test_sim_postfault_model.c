/*
 * The control core's open-phase prediction against the plant: from a state that carries no
 * current in the open phase, one control period under a held switching state, the plant's exact
 * open-phase model (plant_params_t.phase_open, RK4 with small steps) against the core's healthy
 * forward-Euler step followed by its projection (ctl_postfault_project at the period's end
 * angle). The projected prediction must match the plant about as well as the healthy model
 * matches a healthy machine, and far better than the unprojected step.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl.h"
#include "ctl_postfault.h"
#include "ctl_pu.h"
#include "plant/plant.h"
#include "test_rng.h"

#define PI 3.14159265358979323846
#define TS 1e-4

typedef struct {
    double err_projected; /* |prediction - plant| of the four currents, A */
    double err_healthy;   /* the same without the projection */
    double change;        /* |plant(k+1) - plant(k)|, A */
} model_err_t;

static double norm4(double a, double b, double c, double d)
{
    return sqrt(a * a + b * b + c * c + d * d);
}

/* One period from s (on the constraint) under state `vector`; the plant and both predictions. */
static model_err_t one_period(const ctl_config_t *cfg, const plant_params_t *p, int leg,
                              plant_state_t s, unsigned vector)
{
    const double ib = CTL_BASE_CURRENT_A;
    const double we = (double)p->pole_pairs * s.omega_m;
    const double th = (double)p->pole_pairs * s.theta_m;
    ctl_postfault_config_t pf;
    plant_state_t s1 = s;
    double u[4];
    ctl_q ud;
    ctl_q uq;
    ctl_q id;
    ctl_q iq;
    ctl_q ix;
    ctl_q iy;
    ctl_q sn;
    ctl_q co;
    model_err_t e;
    ctl_postfault_config_build(&pf, (int16_t)leg, CTL_POSTFAULT_MIN_LOSS, 0.035f, 0.055f, 0.010f);
    plant_vector_voltage(vector, p->vdc_v, u);
    (void)plant_integrate(p, &s1, u, 0.0, true, TS);
    /* the core's step in per unit, the voltage at the period start's angle (its default) */
    ctl_park(ctl_from_float((float)(u[0] / CTL_BASE_VOLTAGE_V)),
             ctl_from_float((float)(u[1] / CTL_BASE_VOLTAGE_V)), ctl_from_float((float)sin(th)),
             ctl_from_float((float)cos(th)), &ud, &uq);
    ctl_predict_dq(&cfg->model, ctl_from_float((float)(s.i_d / ib)),
                   ctl_from_float((float)(s.i_q / ib)),
                   ctl_from_float((float)(we / CTL_BASE_OMEGA_RAD_S)), ud, uq, &id, &iq);
    ix = ctl_predict_xy(&cfg->model, ctl_from_float((float)(s.i_x / ib)),
                        ctl_from_float((float)(u[2] / CTL_BASE_VOLTAGE_V)));
    iy = ctl_predict_xy(&cfg->model, ctl_from_float((float)(s.i_y / ib)),
                        ctl_from_float((float)(u[3] / CTL_BASE_VOLTAGE_V)));
    e.err_healthy =
        norm4((double)ctl_to_float(id) * ib - s1.i_d, (double)ctl_to_float(iq) * ib - s1.i_q,
              (double)ctl_to_float(ix) * ib - s1.i_x, (double)ctl_to_float(iy) * ib - s1.i_y);
    sn = ctl_from_float((float)sin(th + we * TS));
    co = ctl_from_float((float)cos(th + we * TS));
    ctl_postfault_project(&cfg->model, &pf, sn, co, &id, &iq, &ix, &iy);
    e.err_projected =
        norm4((double)ctl_to_float(id) * ib - s1.i_d, (double)ctl_to_float(iq) * ib - s1.i_q,
              (double)ctl_to_float(ix) * ib - s1.i_x, (double)ctl_to_float(iy) * ib - s1.i_y);
    e.change = norm4(s1.i_d - s.i_d, s1.i_q - s.i_q, s1.i_x - s.i_x, s1.i_y - s.i_y);
    return e;
}

static void test_projection_against_the_plant(void **state)
{
    ctl_params_t cp;
    ctl_config_t cfg;
    uint32_t rng = 4242u;
    int leg;
    (void)state;
    ctl_params_default(&cp);
    assert_int_equal(ctl_config_build(&cfg, &cp), CTL_PARAM_OK);
    for (leg = 0; leg < 6; leg++) {
        plant_params_t p;
        double sum_p = 0.0;
        double sum_h = 0.0;
        double sum_c = 0.0;
        double worst = 0.0;
        int n;
        plant_params_default(&p);
        p.harmonics_on = false;
        p.integrator = PLANT_INTEGRATOR_RK4;
        p.max_step_s = 1e-6;
        p.phase_open[leg] = true;
        for (n = 0; n < 200; n++) {
            plant_state_t s = {0};
            model_err_t e;
            s.i_d = test_lcg_range(&rng, -2.0, 2.0);
            s.i_q = test_lcg_range(&rng, -4.0, 4.0);
            s.i_x = 0.3 * s.i_q;
            s.theta_m = 2.0 * PI * (double)n / 200.0 / 3.0;
            s.omega_m = 157.0 * ((n % 3) - 1); /* -1500, 0, +1500 r/min */
            plant_sync_angle(&p, &s);
            plant_open_commutate(&p, &s);
            e = one_period(&cfg, &p, leg, s, (rng >> 10) & 077u);
            sum_p += e.err_projected;
            sum_h += e.err_healthy;
            sum_c += e.change;
            worst = fmax(worst, e.err_projected / fmax(e.change, 0.05));
        }
        print_message("open %c: mean error projected %.4f A, healthy model %.4f A, mean change "
                      "%.3f A, worst projected / change %.3f\n",
                      'A' + leg, sum_p / 200.0, sum_h / 200.0, sum_c / 200.0, worst);
        assert_true(sum_p < 0.05 * sum_c);
        assert_true(sum_p < 0.1 * sum_h);
        assert_true(worst < 0.15);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_projection_against_the_plant),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
