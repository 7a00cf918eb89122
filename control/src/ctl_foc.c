#include "ctl_foc.h"

#include "ctl_angle.h"
#include "ctl_qmath.h"

/* i_d by the flux reference's interpolation (ctl_flux_ref_run) over the table's every fourth
 * point, i_q from the torque equation Te = Pn i_q (psi_f + (L_d - L_q) i_d) (one division; the
 * bracket, at least psi_f for an MTPA point, held above a quarter of it). */
void ctl_foc_current_ref(const ctl_foc_config_t *f, const ctl_flux_ref_t *span,
                         const ctl_model_t *model, ctl_q torque_ref, ctl_q *id_ref, ctl_q *iq_ref)
{
    const ctl_q pos =
        ctl_mul(ctl_mul(ctl_min(ctl_abs(torque_ref), span->torque_max), span->points_per_torque),
                CTL_Q(0.25)); /* 1 / CTL_FOC_REF_STRIDE */
    ctl_q id;
    ctl_q bracket;
    if (!(pos < CTL_Q(CTL_FOC_REF_POINTS - 1))) { /* at or past the end, or NaN */
        id = f->id_ref[CTL_FOC_REF_POINTS - 1];
    } else if (!(pos > CTL_Q(0.0))) {
        id = f->id_ref[0];
    } else {
#if CTL_MATH_FLOAT
        const int16_t k = (int16_t)pos; /* defined: 0 < pos < points - 1 */
        const ctl_q frac = pos - (float)k;
#else
        const int16_t k = (int16_t)(pos >> CTL_Q_FRAC_BITS);
        const ctl_q frac = pos & (CTL_Q_ONE - 1);
#endif
        id = ctl_add(f->id_ref[k], ctl_mul(frac, ctl_sub(f->id_ref[k + 1], f->id_ref[k])));
    }
    bracket = ctl_mul_acc(model->psi_f, ctl_sub(model->ld, model->lq), id);
    bracket = ctl_max(bracket, ctl_mul(model->psi_f, CTL_Q(0.25)));
    *id_ref = id;
    *iq_ref = ctl_div(torque_ref, ctl_mul_int(bracket, model->pole_pairs));
}

/* The spread of one three-phase set's phase voltages (legs first..first+2) and its middle: the
 * set's own zero sequence is the min-max one, which centres the spread between the rails. */
static ctl_q set_spread(const ctl_q *v, int16_t first, ctl_q *mid)
{
    const ctl_q hi = ctl_max(ctl_max(v[first], v[first + 1]), v[first + 2]);
    const ctl_q lo = ctl_min(ctl_min(v[first], v[first + 1]), v[first + 2]);
    *mid = ctl_mul(ctl_add(hi, lo), CTL_Q(0.5));
    return ctl_sub(hi, lo);
}

int16_t ctl_foc_modulate(const ctl_vsd_t *v, ctl_q vdc, ctl_q duty[6], ctl_vsd_t *realised)
{
    ctl_q phase[6];
    ctl_q mid[2];
    ctl_vsd_t r;
    /* 1 / Vdc once per period (the DC link at least a quarter of its base: below that the duties
     * clamp anyway) */
    const ctl_q vdc_floor = ctl_max(vdc, CTL_Q(0.25));
    const ctl_q inv_vdc = ctl_div(CTL_Q(1.0), vdc_floor);
    ctl_q gain = inv_vdc;
    ctl_q spread;
    int16_t edges = 0;
    int16_t k;
    ctl_vsd_inverse(v, phase);
    spread =
        ctl_mul(ctl_max(set_spread(phase, 0, &mid[0]), set_spread(phase, 3, &mid[1])), inv_vdc);
    if (spread > CTL_Q(1.0)) { /* beyond the linear range: the whole request scaled to fit */
        gain = ctl_mul(inv_vdc, ctl_div(CTL_Q(1.0), spread));
    }
    for (k = 0; k < 6; k++) {
        const ctl_q d = ctl_mul_acc(CTL_Q(0.5), ctl_sub(phase[k], mid[k / 3]), gain);
        duty[k] = ctl_clamp(d, CTL_Q(0.0), CTL_Q(1.0));
        if (duty[k] >= CTL_Q(1.0)) {
            edges = (int16_t)(edges | (1 << (5 - k)));
        }
    }
    /* The set's common mode drops out of the VSD rows: the duties' VSD times Vdc is the period
     * average the legs apply. */
    ctl_vsd_forward(duty, &r);
    realised->alpha = ctl_mul(r.alpha, vdc_floor);
    realised->beta = ctl_mul(r.beta, vdc_floor);
    realised->x = ctl_mul(r.x, vdc_floor);
    realised->y = ctl_mul(r.y, vdc_floor);
    return edges;
}

/* The period's working values. */
typedef struct {
    ctl_q id1, iq1, ix1, iy1; /* predicted at k+1 */
    ctl_q id_ref, iq_ref;     /* references */
    ctl_q ed, eq, ex, ey;     /* errors at k+1 */
    ctl_q vd, vq;             /* requested, rotor frame */
    ctl_q s_cmd, c_cmd;       /* the command's angle: k + 1.5 periods */
    ctl_vsd_t v;              /* requested */
    ctl_vsd_t realised;
    ctl_foc_gains_t g;
} foc_work_t;

/* k -> k+1 under the voltage in force, rotated at the sample angle as the MPC's prediction. */
static void foc_predict(const ctl_foc_state_t *s, const ctl_model_t *model, const ctl_vsd_t *i,
                        ctl_q id, ctl_q iq, ctl_q w, ctl_q s0, ctl_q c0, foc_work_t *fw)
{
    const ctl_vsd_t *u = &s->v_in_force;
    const ctl_q ud = ctl_mul_add(u->alpha, c0, u->beta, s0);
    const ctl_q uq = ctl_mul_sub(u->beta, c0, u->alpha, s0);
    ctl_predict_dq(model, id, iq, w, ud, uq, &fw->id1, &fw->iq1);
    fw->ix1 = ctl_predict_xy(model, i->x, u->x);
    fw->iy1 = ctl_predict_xy(model, i->y, u->y);
}

/* The four PIs and the decoupling. */
static void foc_pis(const ctl_foc_state_t *s, const ctl_config_t *cfg, ctl_q w, foc_work_t *fw)
{
    const ctl_foc_gains_t *f = &fw->g;
    fw->ed = ctl_sub(fw->id_ref, fw->id1);
    fw->eq = ctl_sub(fw->iq_ref, fw->iq1);
    fw->ex = -fw->ix1;
    fw->ey = -fw->iy1;
    /* v_d = PI - w L_q i_q, v_q = PI + w (L_d i_d + psi_f) */
    fw->vd =
        ctl_mul_dec(ctl_foc_pi(f->kp_d, s->integ_d, fw->ed), w, ctl_flux_q(&cfg->model, fw->iq1));
    fw->vq =
        ctl_mul_acc(ctl_foc_pi(f->kp_q, s->integ_q, fw->eq), w, ctl_flux_d(&cfg->model, fw->id1));
    fw->v.x = ctl_foc_pi(f->kp_xy, s->integ_x, fw->ex);
    fw->v.y = ctl_foc_pi(f->kp_xy, s->integ_y, fw->ey);
}

/* The integrators after the modulator: back-calculation against the realised voltage, the d-q
 * part turned back at the command's angle. */
static void foc_integrate(ctl_foc_state_t *s, const foc_work_t *fw)
{
    const ctl_foc_gains_t *f = &fw->g;
    ctl_q rd;
    ctl_q rq;
    ctl_park(fw->realised.alpha, fw->realised.beta, fw->s_cmd, fw->c_cmd, &rd, &rq);
    s->integ_d =
        ctl_foc_integrate(s->integ_d, f->ki_ts, f->kt_d, fw->ed, fw->vd, rd, CTL_FOC_INTEG_LIMIT);
    s->integ_q =
        ctl_foc_integrate(s->integ_q, f->ki_ts, f->kt_q, fw->eq, fw->vq, rq, CTL_FOC_INTEG_LIMIT);
    s->integ_x = ctl_foc_integrate(s->integ_x, f->ki_ts, f->kt_xy, fw->ex, fw->v.x, fw->realised.x,
                                   CTL_FOC_INTEG_LIMIT);
    s->integ_y = ctl_foc_integrate(s->integ_y, f->ki_ts, f->kt_xy, fw->ey, fw->v.y, fw->realised.y,
                                   CTL_FOC_INTEG_LIMIT);
    s->v_in_force = fw->realised;
}

/* What the period leaves in the diagnostics: the measured state as the other controllers',
 * the references' torque as the prediction. */
static void foc_diag(ctl_t *c, const ctl_config_t *cfg, const ctl_vsd_t *i, ctl_q id, ctl_q iq,
                     ctl_q torque_ref, ctl_q flux_ref, const foc_work_t *fw)
{
    ctl_diag_t *dg = &c->diag;
    dg->i_d = id;
    dg->i_q = iq;
    dg->i_x = i->x;
    dg->i_y = i->y;
    dg->torque_ref = torque_ref;
    dg->flux_ref = flux_ref;
    /* the references' torque (held: a reference beyond 40 A is one no PI reaches) */
    dg->torque_pred = ctl_torque_held(&cfg->model, fw->id_ref, fw->iq_ref);
    dg->flux_pred = flux_ref;
    dg->cost = CTL_Q(0.0);
    dg->flux_sector = -1;
    dg->xy_sector = -1;
    dg->candidates = 0;
    dg->braking = false;
}

void ctl_foc_healthy_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd)
{
    const ctl_config_t *cfg = &c->config[c->config_active];
    ctl_foc_state_t *s = &c->foc;
    foc_work_t fw;
    ctl_vsd_t i;
    ctl_q s0;
    ctl_q c0;
    ctl_q id;
    ctl_q iq;
    ctl_q torque_ref;
    ctl_q flux_ref;
    ctl_meas_t held;

    /* Measured state at k and references, as the predictive controllers'. */
    ctl_vsd_forward_in_range(m->i_phase, &i);
    held = *m; /* the speed and DC link of the range analysis' domain, for all but the speed loop */
    ctl_range_clamp(&held.omega_e, &held.vdc, cfg->model.omega_max);
    ctl_sincos_pu(m->theta_e, &s0, &c0);
    ctl_park(i.alpha, i.beta, s0, c0, &id, &iq);
    if (c->loop_mode == CTL_LOOP_SPEED) {
        torque_ref = ctl_speed_pi_run(&c->speed_pi, c->speed_ref, m->omega_e); /* as measured */
    } else {
        torque_ref = ctl_clamp(c->torque_ref_direct, -cfg->torque_limit, cfg->torque_limit);
    }
    flux_ref = ctl_flux_ref_run(&cfg->flux_ref, torque_ref);
    ctl_foc_current_ref(&cfg->ctrl.foc, &cfg->flux_ref, &cfg->model, torque_ref, &fw.id_ref,
                        &fw.iq_ref);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TRANSFORMS);

    foc_predict(s, &cfg->model, &i, id, iq, held.omega_e, s0, c0, &fw);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_PREDICT);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TABLE); /* no tables: the stage is empty */

    ctl_foc_gains(&cfg->ctrl.foc, &cfg->model, &fw.g);
    foc_pis(s, cfg, held.omega_e, &fw);
    ctl_angle_advance(m->theta_e, s0, c0, ctl_mul(held.omega_e, ctl_mul(cfg->model.ts, CTL_Q(1.5))),
                      &fw.s_cmd, &fw.c_cmd);
    ctl_park_inverse(fw.vd, fw.vq, fw.s_cmd, fw.c_cmd, &fw.v.alpha, &fw.v.beta);
    c->applied_edges = ctl_foc_modulate(&fw.v, held.vdc, cmd->leg_duty, &fw.realised);
    foc_integrate(s, &fw);
    /* no one switching state stands for a carrier-PWM command: the predictive controllers, should
     * the next set be one of them, see a zero vector in force, and no virtual vector */
    cmd->vector = 0;
    cmd->duty = CTL_Q(0.0);
    cmd->enable = true;
    c->applied_vector = 0;
    c->applied_duty = CTL_Q(0.0);
    c->applied_virtual = CTL_VV_NONE;
    foc_diag(c, cfg, &i, id, iq, torque_ref, flux_ref, &fw);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_SEARCH);
}
