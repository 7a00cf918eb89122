#include "ctl.h"

#include "ctl_ddc.h"
#include "ctl_machine.h"
#include "ctl_mptc.h"
#include "ctl_pu.h"
#include "ctl_search.h"
#include "ctl_vectors.h"
#include "ctl_vsd.h"

void ctl_params_default(ctl_params_t *p)
{
    p->resistance_ohm = (float)CTL_MACHINE_R_OHM;
    p->ld_h = (float)CTL_MACHINE_LD_H;
    p->lq_h = (float)CTL_MACHINE_LQ_H;
    p->l_xy_h = (float)CTL_MACHINE_LXY_H;
    p->pm_flux_wb = (float)CTL_MACHINE_PSI_F_WB;
    p->pole_pairs = CTL_MACHINE_POLE_PAIRS;
    p->inertia_kg_m2 = (float)CTL_MACHINE_INERTIA_KG_M2;
    p->sample_time_s = 1.0e-4f;
    p->controller = CTL_CONTROLLER_DDC;
    p->lambda_nm_per_wb = 100.0f;
    p->duty_levels = 6;
    p->ddc_direction = CTL_DDC_DIRECTION_FLUX_ERROR;
    p->ddc_torque_guard = true; /* improvement (docs/improvements.md); false = the paper */
    p->flux_ref_mode = CTL_FLUX_REF_MTPA;
    p->flux_ref_wb = 0.26f;
    p->speed_kp_nm_per_rad_s = 1.5f;
    p->speed_ki_nm_per_rad = 60.0f;
    p->torque_limit_nm = 7.0f;
}

/* Speed-loop gains to per unit: torque per unit per electrical per-unit speed. */
static float speed_gain_pu(float gain_si, int16_t pole_pairs)
{
    return gain_si * (float)CTL_BASE_OMEGA_RAD_S / ((float)pole_pairs * (float)CTL_BASE_TORQUE_NM);
}

/* Builds everything derived from p into c; leaves c untouched and returns false if p is
 * unusable. */
static bool ctl_apply_params(ctl_t *c, const ctl_params_t *p)
{
    ctl_model_t model;
    ctl_flux_ref_t flux_ref;
    float kp;
    float ki_ts;
    float limit;
    int16_t k;
    if (!(p->controller == CTL_CONTROLLER_DDC || p->controller == CTL_CONTROLLER_MPTC49 ||
          p->controller == CTL_CONTROLLER_MPTC13)) {
        return false;
    }
    if (!(p->ddc_direction == CTL_DDC_DIRECTION_FLUX_ERROR ||
          p->ddc_direction == CTL_DDC_DIRECTION_XY_TABLE)) {
        return false;
    }
    if (p->duty_levels < 2 || p->duty_levels > CTL_DUTY_LEVELS_MAX) {
        return false;
    }
    if (!(p->lambda_nm_per_wb >= 0.0f && p->lambda_nm_per_wb <= 2000.0f)) {
        return false;
    }
    if (!(p->inertia_kg_m2 > 0.0f && p->inertia_kg_m2 < 1000.0f)) {
        return false;
    }
    if (!(p->torque_limit_nm > 0.0f && p->torque_limit_nm < 500.0f)) {
        return false;
    }
    if (!(p->speed_kp_nm_per_rad_s >= 0.0f && p->speed_ki_nm_per_rad >= 0.0f)) {
        return false;
    }
    if (!ctl_model_init(&model, p->resistance_ohm, p->ld_h, p->lq_h, p->l_xy_h, p->pm_flux_wb,
                        p->pole_pairs, p->sample_time_s)) {
        return false;
    }
    if (!ctl_flux_ref_init(&flux_ref, p->flux_ref_mode, p->flux_ref_wb, p->ld_h, p->lq_h,
                           p->pm_flux_wb, p->pole_pairs, p->torque_limit_nm)) {
        return false;
    }
    kp = speed_gain_pu(p->speed_kp_nm_per_rad_s, p->pole_pairs);
    /* Integrator gain per step: ki in N*m per mechanical rad, so ki * Ts per (rad/s). */
    ki_ts = speed_gain_pu(p->speed_ki_nm_per_rad, p->pole_pairs) * p->sample_time_s;
    limit = p->torque_limit_nm / (float)CTL_BASE_TORQUE_NM;
    if (!(kp < 100.0f && ki_ts < 100.0f && limit < 100.0f)) {
        return false;
    }
    c->params = *p;
    c->model = model;
    c->flux_ref = flux_ref;
    c->lambda_pu =
        ctl_from_float(p->lambda_nm_per_wb * (float)(CTL_BASE_FLUX_WB / CTL_BASE_TORQUE_NM));
    c->torque_limit_pu = ctl_from_float(limit);
    /* Keep the integrator across a run-time change; only the gains move. */
    c->speed_pi.kp = ctl_from_float(kp);
    c->speed_pi.ki_ts = ctl_from_float(ki_ts);
    c->speed_pi.limit = c->torque_limit_pu;
    c->speed_pi.integ = ctl_clamp(c->speed_pi.integ, -c->torque_limit_pu, c->torque_limit_pu);
    /* Duty levels 1, (n-2)/(n-1), ..., 0: the paper's {1, 0.8, 0.6, 0.4, 0.2, 0} for n = 6. */
    for (k = 0; k < CTL_DUTY_LEVELS_MAX; k++) {
        c->duty_level[k] = CTL_Q(0.0);
    }
    for (k = 0; k < p->duty_levels; k++) {
        c->duty_level[k] =
            ctl_from_float((float)(p->duty_levels - 1 - k) / (float)(p->duty_levels - 1));
    }
    return true;
}

bool ctl_params_valid(const ctl_params_t *p)
{
    ctl_t scratch;
    scratch.speed_pi.integ = CTL_Q(0.0);
    return ctl_apply_params(&scratch, p);
}

void ctl_reset(ctl_t *c)
{
    ctl_speed_pi_reset(&c->speed_pi);
    c->applied_vector = 0;
    c->applied_duty = CTL_Q(0.0);
}

bool ctl_init(ctl_t *c, const ctl_params_t *p)
{
    ctl_diag_t zero_diag = {0};
    c->initialised = false;
    c->shadow_pending = false;
    c->diag = zero_diag;
    c->loop_mode = CTL_LOOP_SPEED;
    c->speed_ref = CTL_Q(0.0);
    c->torque_ref_direct = CTL_Q(0.0);
    c->speed_pi.integ = CTL_Q(0.0);
    c->stage_hook = 0;
    ctl_reset(c);
    if (!ctl_apply_params(c, p)) {
        return false;
    }
    c->initialised = true;
    return true;
}

void ctl_request_params(ctl_t *c, const ctl_params_t *p)
{
    /* The flag is raised after the copy so a step never sees a half-written shadow. */
    c->shadow_pending = false;
    c->shadow = *p;
    c->shadow_pending = true;
}

void ctl_set_loop_mode(ctl_t *c, ctl_loop_mode_t mode) { c->loop_mode = mode; }
void ctl_set_speed_ref(ctl_t *c, ctl_q omega_e_pu) { c->speed_ref = omega_e_pu; }
void ctl_set_torque_ref(ctl_t *c, ctl_q torque_pu) { c->torque_ref_direct = torque_pu; }
const ctl_diag_t *ctl_diag(const ctl_t *c) { return &c->diag; }
void ctl_set_stage_hook(ctl_t *c, ctl_stage_hook_t hook) { c->stage_hook = hook; }

static void command_off(ctl_cmd_t *cmd)
{
    int16_t leg;
    for (leg = 0; leg < CTL_PHASES; leg++) {
        cmd->leg_duty[leg] = CTL_Q(0.0);
    }
    cmd->vector = 0;
    cmd->duty = CTL_Q(0.0);
    cmd->enable = false;
}

/* Leg duties of "vector for duty d, zero vector for the rest", centred pulses. With three
 * or fewer upper switches on, u00 fills the edges (v in the middle); otherwise u77 fills the
 * middle (v at the edges): either way each leg of v switches at most twice per period. */
static void command_from_choice(int16_t vector, ctl_q duty, int16_t vector_in_force, ctl_cmd_t *cmd)
{
    int16_t leg;
    const bool zero = (duty <= CTL_Q(0.0)) || vector == 0 || vector == 077;
    const bool high_zero =
        zero ? (ctl_vector_ones(vector_in_force) > 3) : (ctl_vector_ones(vector) > 3);
    const ctl_q d = ctl_clamp(duty, CTL_Q(0.0), CTL_Q(1.0));
    for (leg = 0; leg < CTL_PHASES; leg++) {
        const bool on = ctl_vector_leg(vector, leg) != 0;
        if (zero) {
            cmd->leg_duty[leg] = high_zero ? CTL_Q(1.0) : CTL_Q(0.0);
        } else if (high_zero) {
            cmd->leg_duty[leg] = on ? CTL_Q(1.0) : ctl_sub(CTL_Q(1.0), d);
        } else {
            cmd->leg_duty[leg] = on ? d : CTL_Q(0.0);
        }
    }
    cmd->vector = zero ? (high_zero ? 077 : 0) : vector;
    cmd->duty = zero ? CTL_Q(0.0) : d;
    cmd->enable = true;
}

void ctl_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd)
{
    ctl_vsd_t i_vsd;
    ctl_q s0;
    ctl_q c0;
    ctl_q id;
    ctl_q iq;
    ctl_q torque_ref;
    ctl_q flux_ref;
    ctl_vsd_t u0;
    ctl_q ud0;
    ctl_q uq0;
    ctl_q id1;
    ctl_q iq1;
    ctl_q ix1;
    ctl_q iy1;
    ctl_q delta;
    ctl_horizon_t h = {0};
    ctl_choice_t choice;
    const ctl_vsd_t *applied;
    ctl_q applied_scale;

    if (c->shadow_pending) {
        if (!ctl_apply_params(c, &c->shadow)) {
            c->diag.params_rejected++;
        }
        c->shadow_pending = false;
    }
    if (!c->initialised) {
        command_off(cmd);
        return;
    }

    /* Measured state at k. */
    ctl_vsd_forward(m->i_phase, &i_vsd);
    ctl_sincos_pu(m->theta_e, &s0, &c0);
    ctl_park(i_vsd.alpha, i_vsd.beta, s0, c0, &id, &iq);

    /* References. */
    if (c->loop_mode == CTL_LOOP_SPEED) {
        torque_ref = ctl_speed_pi_run(&c->speed_pi, c->speed_ref, m->omega_e);
    } else {
        torque_ref = ctl_clamp(c->torque_ref_direct, -c->torque_limit_pu, c->torque_limit_pu);
    }
    flux_ref = ctl_flux_ref_run(&c->flux_ref, torque_ref);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TRANSFORMS);

    /* Delay compensation: k -> k+1 under the command already in force (period average). */
    applied = &ctl_vector_vsd[c->applied_vector];
    applied_scale = ctl_mul(c->applied_duty, m->vdc);
    u0.alpha = ctl_mul(applied->alpha, applied_scale);
    u0.beta = ctl_mul(applied->beta, applied_scale);
    u0.x = ctl_mul(applied->x, applied_scale);
    u0.y = ctl_mul(applied->y, applied_scale);
    ctl_park(u0.alpha, u0.beta, s0, c0, &ud0, &uq0);
    ctl_predict_dq(&c->model, id, iq, m->omega_e, ud0, uq0, &id1, &iq1);
    ix1 = ctl_predict_xy(&c->model, i_vsd.x, u0.x);
    iy1 = ctl_predict_xy(&c->model, i_vsd.y, u0.y);

    /* Horizon k+1 -> k+2: rotor angle advanced by one period, delta = omega Ts (rad). For
     * |delta| <= 0.5 rad (7 times rated speed at 10 kHz) rotate the sample angle's sine and
     * cosine by short series of sin/cos delta (error < 2e-5 there, < 1e-8 at rated speed);
     * beyond that look the angle up again. */
    delta = ctl_mul(m->omega_e, c->model.ts);
    h.model = &c->model;
    if (ctl_abs(delta) <= CTL_Q(0.5)) {
        const ctl_q d2 = ctl_mul(delta, delta);
        const ctl_q sd = ctl_mul(delta, ctl_sub(CTL_Q(1.0), ctl_mul(d2, CTL_Q(1.0 / 6.0))));
        const ctl_q cd =
            ctl_sub(CTL_Q(1.0), ctl_mul(ctl_mul(d2, CTL_Q(0.5)),
                                        ctl_sub(CTL_Q(1.0), ctl_mul(d2, CTL_Q(1.0 / 12.0)))));
        h.sin1 = ctl_add(ctl_mul(s0, cd), ctl_mul(c0, sd));
        h.cos1 = ctl_sub(ctl_mul(c0, cd), ctl_mul(s0, sd));
    } else {
        ctl_sincos_pu(ctl_add(m->theta_e, ctl_mul(delta, CTL_Q(1.0 / CTL_TWO_PI))), &h.sin1,
                      &h.cos1);
    }
    ctl_predict_dq(&c->model, id1, iq1, m->omega_e, CTL_Q(0.0), CTL_Q(0.0), &h.id2_free,
                   &h.iq2_free);
    h.vdc = m->vdc;
    h.torque_ref = torque_ref;
    h.flux_ref = flux_ref;
    h.lambda = c->lambda_pu;
    ctl_horizon_prepare(&h);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_PREDICT);

    if (c->params.controller == CTL_CONTROLLER_DDC) {
        ctl_ddc_flux_t f;
        const ctl_q psi_d1 = ctl_flux_d(&c->model, id1);
        const ctl_q psi_q1 = ctl_flux_q(&c->model, iq1);
        ctl_park_inverse(psi_d1, psi_q1, h.sin1, h.cos1, &f.psi_alpha, &f.psi_beta);
        f.psi_mag_sq = ctl_add(ctl_mul(psi_d1, psi_d1), ctl_mul(psi_q1, psi_q1));
        f.psi_x = ctl_mul(c->model.lxy, ix1);
        f.psi_y = ctl_mul(c->model.lxy, iy1);
        ctl_ddc_config_t cfg;
        cfg.direction = (int16_t)c->params.ddc_direction;
        cfg.levels = c->duty_level;
        cfg.n_levels = c->params.duty_levels;
        cfg.torque_guard = c->params.ddc_torque_guard;
#if CTL_PROFILE
        cfg.stage_hook = c->stage_hook;
#else
        cfg.stage_hook = 0;
#endif
        ctl_ddc_select(&h, &f, &cfg, &choice);
    } else {
        const bool all = c->params.controller == CTL_CONTROLLER_MPTC49;
        CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TABLE); /* no tables: the stage is empty */
        ctl_mptc_select(&h, all ? ctl_mptc49_vectors : ctl_mptc13_vectors,
                        all ? CTL_MPTC49_CANDIDATES : CTL_MPTC13_CANDIDATES, c->applied_vector,
                        &choice);
    }

    command_from_choice(choice.vector, choice.duty, c->applied_vector, cmd);
    c->applied_vector = cmd->vector;
    c->applied_duty = cmd->duty;

    c->diag.i_d = id;
    c->diag.i_q = iq;
    c->diag.i_x = i_vsd.x;
    c->diag.i_y = i_vsd.y;
    ctl_torque_flux(&c->model, id, iq, &c->diag.torque_est, &c->diag.flux_est);
    c->diag.torque_ref = torque_ref;
    c->diag.flux_ref = flux_ref;
    c->diag.torque_pred = choice.torque;
    c->diag.flux_pred = choice.flux;
    c->diag.cost = choice.cost;
    c->diag.flux_sector = choice.flux_sector;
    c->diag.xy_sector = choice.xy_sector;
    c->diag.candidates = choice.candidates;
    c->diag.braking = choice.braking;
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_SEARCH);
}
