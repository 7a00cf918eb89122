/* One operating point through the public control-step API of this arithmetic build. */
#include "ctl.h"
#include "ctl_pu.h"
#include "ctl_vectors.h"
#include "ctl_vsd.h"
#include "fvf.h"
#include "ctl_qmath.h"

static ctl_q pu(double si, double base) { return ctl_from_float((float)(si / base)); }

/* Initialising a controller tabulates MTPA; keep one per (controller, lambda) seen. */
#define FVF_CACHE 16
static ctl_t cache[FVF_CACHE];
static fvf_point_t cache_key[FVF_CACHE];
static int16_t cache_used;

static ctl_t *controller_for(const fvf_point_t *p)
{
    ctl_params_t params;
    int16_t k;
    for (k = 0; k < cache_used; k++) {
        if (cache_key[k].controller == p->controller && cache_key[k].lambda == p->lambda) {
            return &cache[k];
        }
    }
    if (cache_used == FVF_CACHE) {
        return 0;
    }
    ctl_params_default(&params);
    params.controller = (ctl_controller_t)p->controller;
    params.lambda_nm_per_wb = (float)p->lambda;
    if (!ctl_init(&cache[cache_used], &params)) {
        return 0;
    }
    cache_key[cache_used] = *p;
    return &cache[cache_used++];
}

void fvf_evaluate(const fvf_point_t *p, fvf_result_t *r)
{
    ctl_t *c = controller_for(p);
    ctl_meas_t m;
    ctl_cmd_t cmd;
    ctl_vsd_t v;
    ctl_q s;
    ctl_q co;
    if (c == 0) {
        r->vector = -1;
        return;
    }
    ctl_reset(c);
    ctl_set_loop_mode(c, CTL_LOOP_TORQUE);
    ctl_set_torque_ref(c, pu(p->torque_ref, CTL_BASE_TORQUE_NM));
    c->applied_vector = p->vector_in_force;
    c->applied_duty = pu(p->duty_in_force, 1.0);
    if (p->controller == CTL_CONTROLLER_FOC) { /* FOC-VSD: the same voltage in force */
        const ctl_vsd_t *u = &ctl_vector_vsd[p->vector_in_force];
        const ctl_q scale = ctl_mul(c->applied_duty, pu(p->vdc, CTL_BASE_VOLTAGE_V));
        c->foc.v_in_force.alpha = ctl_mul(u->alpha, scale);
        c->foc.v_in_force.beta = ctl_mul(u->beta, scale);
        c->foc.v_in_force.x = ctl_mul(u->x, scale);
        c->foc.v_in_force.y = ctl_mul(u->y, scale);
    }
    m.theta_e = pu(p->theta, 1.0);
    m.omega_e = pu(p->omega, CTL_BASE_OMEGA_RAD_S);
    m.vdc = pu(p->vdc, CTL_BASE_VOLTAGE_V);
    ctl_sincos_pu(m.theta_e, &s, &co);
    ctl_park_inverse(pu(p->id, CTL_BASE_CURRENT_A), pu(p->iq, CTL_BASE_CURRENT_A), s, co, &v.alpha,
                     &v.beta);
    v.x = pu(p->ix, CTL_BASE_CURRENT_A);
    v.y = pu(p->iy, CTL_BASE_CURRENT_A);
    ctl_vsd_inverse(&v, m.i_phase);
    ctl_step(c, &m, &cmd);
    r->vector = cmd.vector;
    r->duty = (double)ctl_to_float(cmd.duty);
    r->flux_ref = (double)ctl_to_float(ctl_diag(c)->flux_ref) * CTL_BASE_FLUX_WB;
    {
        int16_t k;
        for (k = 0; k < 6; k++) {
            r->leg_duty[k] = (double)ctl_to_float(cmd.leg_duty[k]);
        }
    }
}
