#include "ctl.h"

#include "ctl_barrier.h"
#include "ctl_constants.h"
#include "ctl_ddc.h"
#include "ctl_diag_record.h"
#include "ctl_mptc.h"
#include "ctl_pulse.h"
#include "ctl_search.h"
#include "ctl_vectors.h"
#include "ctl_vsd.h"
#include "ctl_vvmptc.h"
#include "ctl_placement.h"
#include "ctl_qmath.h"

SIXPHASE_RAMFUNC void ctl_reset(ctl_t *c)
{
    ctl_speed_pi_reset(&c->speed_pi);
    ctl_reset_command(c);
}

SIXPHASE_RAMFUNC void ctl_reset_command(ctl_t *c)
{
    c->applied_vector = 0;
    c->applied_duty = CTL_Q(0.0);
    c->applied_edges = 0;
    c->applied_virtual = CTL_VV_NONE;
    ctl_foc_reset(&c->foc); /* its integrators hold voltages no longer applied */
}

/* The speed loop's gains follow the configuration in force; its integrator is kept across a
 * change, held inside the new torque limit. */
SIXPHASE_RAMFUNC static void use_config(ctl_t *c, const ctl_config_t *cfg)
{
    c->speed_pi.kp = cfg->speed_kp;
    c->speed_pi.ki_ts = cfg->speed_ki_ts;
    c->speed_pi.limit = cfg->torque_limit;
    c->speed_pi.integ = ctl_clamp(c->speed_pi.integ, -cfg->torque_limit, cfg->torque_limit);
    c->initialised = true;
    c->healthy_step = c->postfault[c->config_active].open_leg == CTL_POSTFAULT_NO_LEG;
    c->xy_held = c->healthy_step && cfg->params.controller == CTL_CONTROLLER_DDC;
    c->foc_step = c->healthy_step && cfg->params.controller == CTL_CONTROLLER_FOC;
}

/* The open-phase part of a configuration (ctl_postfault_config.h), beside it. */
static void build_postfault(ctl_t *c, int16_t buffer, const ctl_params_t *p)
{
    ctl_postfault_config_build(&c->postfault[buffer], p->open_phase,
                               (ctl_postfault_strategy_t)p->postfault_strategy, p->ld_h, p->lq_h,
                               p->l_xy_h);
}

bool ctl_init(ctl_t *c, const ctl_params_t *p)
{
    ctl_diag_t zero_diag = {0};
    c->initialised = false;
    c->healthy_step = false;
    c->xy_held = false;
    c->foc_step = false;
    c->config_active = 0;
    c->config_ready = 0;
    c->params_rejected = 0u;
    c->diag = zero_diag;
    c->loop_mode = CTL_LOOP_SPEED;
    c->speed_ref = CTL_Q(0.0);
    c->torque_ref_direct = CTL_Q(0.0);
    c->speed_pi.integ = CTL_Q(0.0);
    c->stage_hook = 0;
    ctl_reset(c);
    c->params_last_error = ctl_config_build(&c->config[0], p);
    if (c->params_last_error != CTL_PARAM_OK) {
        return false;
    }
    build_postfault(c, 0, p);
    use_config(c, &c->config[0]);
    return true;
}

ctl_param_error_t ctl_request_params(ctl_t *c, const ctl_params_t *p)
{
    ctl_param_error_t e;
    if (c->config_ready != 0) {
        return CTL_PARAM_BUSY; /* the standby buffer is published: not ours to write */
    }
    e = ctl_config_build(&c->config[1 - c->config_active], p);
    if (e != CTL_PARAM_OK) {
        if (c->params_rejected < UINT16_MAX) {
            c->params_rejected++;
        }
        c->params_last_error = e;
        return e;
    }
    build_postfault(c, (int16_t)(1 - c->config_active), p);
    CTL_COMPILER_BARRIER(); /* the whole buffer is written before it is published */
    c->config_ready = 1;
    return CTL_PARAM_OK;
}

SIXPHASE_RAMFUNC bool ctl_config_take(ctl_t *c)
{
    if (c->config_ready == 0) {
        return false;
    }
    CTL_COMPILER_BARRIER(); /* nothing of the new buffer is read before the flag */
    if (c->config[1 - c->config_active].params.controller !=
        c->config[c->config_active].params.controller) {
        ctl_foc_reset(&c->foc); /* FOC-VSD starts from a clean state after another controller */
    }
    c->config_active = (int16_t)(1 - c->config_active);
    use_config(c, &c->config[c->config_active]);
    CTL_COMPILER_BARRIER(); /* done with the old buffer before the background may reuse it */
    c->config_ready = 0;
    return true;
}

SIXPHASE_RAMFUNC const ctl_config_t *ctl_config(const ctl_t *c)
{
    return &c->config[c->config_active];
}
const ctl_params_t *ctl_params(const ctl_t *c) { return &ctl_config(c)->params; }
SIXPHASE_RAMFUNC const ctl_postfault_config_t *ctl_postfault_config(const ctl_t *c)
{
    return &c->postfault[c->config_active];
}
bool ctl_config_pending(const ctl_t *c) { return c->config_ready != 0; }

void ctl_set_loop_mode(ctl_t *c, ctl_loop_mode_t mode) { c->loop_mode = mode; }
void ctl_set_speed_ref(ctl_t *c, ctl_q omega_e_pu) { c->speed_ref = omega_e_pu; }
void ctl_set_torque_ref(ctl_t *c, ctl_q torque_pu) { c->torque_ref_direct = torque_pu; }
const ctl_diag_t *ctl_diag(const ctl_t *c) { return &c->diag; }
SIXPHASE_RAMFUNC ctl_q ctl_torque_estimate(const ctl_t *c, ctl_q i_d, ctl_q i_q)
{
    return ctl_torque_held(&ctl_config(c)->model, i_d, i_q);
}
SIXPHASE_RAMFUNC ctl_q ctl_diag_torque_est(const ctl_t *c)
{
    return ctl_torque_estimate(c, c->diag.i_d, c->diag.i_q);
}
SIXPHASE_RAMFUNC ctl_q ctl_diag_flux_est(const ctl_t *c)
{
    return ctl_flux_held(&ctl_config(c)->model, c->diag.i_d, c->diag.i_q);
}
void ctl_set_stage_hook(ctl_t *c, ctl_stage_hook_t hook) { c->stage_hook = hook; }

/* Leg duties of the choice, the zero vector arranged as ctl_pulse.h says, and the legs'
 * states at the period boundary. */
SIXPHASE_RAMFUNC static void command_from_choice(int16_t vector, ctl_q duty, const ctl_t *c,
                                                 ctl_pulse_pattern_t pattern, ctl_cmd_t *cmd,
                                                 int16_t *edges)
{
    int16_t leg;
    const ctl_q d = ctl_clamp(duty, CTL_Q(0.0), CTL_Q(1.0));
    const ctl_pulse_kind_t kind = (d <= CTL_Q(0.0) || vector == 0 || vector == 077)
                                      ? CTL_PULSE_ZERO
                                      : ((d >= CTL_Q(1.0)) ? CTL_PULSE_FULL : CTL_PULSE_PART);
    const ctl_q rest = ctl_sub(CTL_Q(1.0), d);
    ctl_pulse_t p;
    ctl_pulse_arrange(pattern, kind, vector, c->applied_vector, c->applied_edges, &p);
    for (leg = 0; leg < CTL_PHASES; leg += 3) {
        /* a set with zero state 111: its legs of the active state on all period, the others
         * high for the rest in the middle; with 000: on for d in the middle, the others off */
        const bool high = ctl_vector_leg(p.zero, leg) != 0;
        const ctl_q on = high ? CTL_Q(1.0) : d;
        const ctl_q off = high ? rest : CTL_Q(0.0);
        cmd->leg_duty[leg] = (ctl_vector_leg(p.active, leg) != 0) ? on : off;
        cmd->leg_duty[leg + 1] = (ctl_vector_leg(p.active, (int16_t)(leg + 1)) != 0) ? on : off;
        cmd->leg_duty[leg + 2] = (ctl_vector_leg(p.active, (int16_t)(leg + 2)) != 0) ? on : off;
    }
    cmd->vector = (kind == CTL_PULSE_ZERO) ? p.zero : p.active;
    cmd->duty = (kind == CTL_PULSE_ZERO) ? CTL_Q(0.0) : d;
    cmd->enable = true;
    *edges = ctl_pulse_edges(kind, &p);
}

/* A virtual vector's command (ctl_vvmptc.h): each leg on for its share of the two states, the
 * large state's for CTL_K_VV_LARGE_SHARE of the period and the medium-large state's for the
 * rest, one pulse centred in the period. Within each three-phase set the two states' legs are
 * nested (the one set's legs on in one state are on in the other), so each set applies its part
 * of the one state in the middle and of the other at the edges, for exactly its share; the period
 * average is the virtual vector's, x-y zero. The legs' states at the period boundary: those on
 * in both states. VV-MPTC is a comparison: in the Q24 image this runs from flash beside
 * ctl_vvmptc_select (tools/flash_on_purpose.txt), leaving RAM to the product's period. */
CTL_RAMFUNC_FLOAT SIXPHASE_NOINLINE static void command_from_virtual(int16_t k, ctl_cmd_t *cmd,
                                                                     int16_t *edges)
{
    int16_t leg;
    const int16_t large = ctl_vv_states[k][0];
    const int16_t medium = ctl_vv_states[k][1];
    const ctl_q medium_share = ctl_sub(CTL_Q(1.0), CTL_K_VV_LARGE_SHARE);
    for (leg = 0; leg < CTL_PHASES; leg++) {
        const ctl_q on = (ctl_vector_leg(large, leg) != 0) ? CTL_K_VV_LARGE_SHARE : CTL_Q(0.0);
        cmd->leg_duty[leg] = (ctl_vector_leg(medium, leg) != 0) ? ctl_add(on, medium_share) : on;
    }
    cmd->vector = large;
    cmd->duty = CTL_Q(1.0);
    cmd->enable = true;
    *edges = (int16_t)(large & medium);
}

/* The sample angle advanced by delta (rad). For |delta| <= 0.5 rad (7 times rated speed at
 * 10 kHz) rotate its sine and cosine by short series of sin/cos delta (error < 2e-5 there,
 * < 1e-8 at rated speed); beyond that look the angle up again. */
SIXPHASE_RAMFUNC static inline void advance_angle(ctl_q theta_e, ctl_q s0, ctl_q c0, ctl_q delta,
                                                  ctl_q *s, ctl_q *c)
{
    if (ctl_abs(delta) <= CTL_Q(0.5)) { /* bounded: every term below 1.1 */
        const ctl_q d2 = ctl_mul_bnd(delta, delta);
        const ctl_q sd = ctl_mul_bnd(delta, ctl_mul_dec_bnd(CTL_Q(1.0), d2, CTL_K_ONE_SIXTH));
        const ctl_q cd = ctl_mul_dec_bnd(CTL_Q(1.0), ctl_mul_bnd(d2, CTL_Q(0.5)),
                                         ctl_mul_dec_bnd(CTL_Q(1.0), d2, CTL_K_ONE_TWELFTH));
        *s = ctl_mul_add_bnd(s0, cd, c0, sd);
        *c = ctl_mul_sub_bnd(c0, cd, s0, sd);
    } else {
        ctl_sincos_pu(ctl_add(theta_e, ctl_mul(delta, CTL_K_INV_TWO_PI)), s, c);
    }
}

/* Measured currents at k in the rotor and x-y frames; with the speed and the DC link, held in
 * the range analysis' domain (ctl_range_clamp). */
typedef struct {
    ctl_vsd_t vsd;
    ctl_q s0, c0; /* sine and cosine of the sample angle */
    ctl_q id, iq;
    ctl_q omega_e, vdc;
} ctl_sample_t;

/* The option ctl_params_t.mid_period_angle: each period's voltage enters the prediction at
 * the rotor angle of the period's middle, for the command in force (k -> k+1) and for the
 * candidates (k+1 -> k+2). Off the default path. */
SIXPHASE_RAMFUNC static void mid_period_angles(const ctl_meas_t *m, const ctl_sample_t *smp,
                                               ctl_q delta, ctl_q *s_in_force, ctl_q *c_in_force,
                                               ctl_horizon_t *h)
{
    advance_angle(m->theta_e, smp->s0, smp->c0, ctl_mul_bnd(delta, CTL_Q(0.5)), s_in_force,
                  c_in_force);
    advance_angle(m->theta_e, smp->s0, smp->c0, ctl_mul_bnd(delta, CTL_Q(1.5)), &h->sin1, &h->cos1);
}

/* Delay compensation k -> k+1 under the command already in force (period average), then the
 * horizon k+1 -> k+2 up to the free response. Fills the x-y currents at k+1. */
SIXPHASE_RAMFUNC static void predict(const ctl_t *c, const ctl_config_t *cfg, const ctl_meas_t *m,
                                     const ctl_sample_t *smp, ctl_horizon_t *h, ctl_q *ix1,
                                     ctl_q *iy1, ctl_q *id1, ctl_q *iq1)
{
    const ctl_vsd_t *applied = (c->applied_virtual != CTL_VV_NONE)
                                   ? &ctl_vv_vsd[c->applied_virtual]
                                   : &ctl_vector_vsd[c->applied_vector];
    const ctl_q delta = ctl_mul_bnd(smp->omega_e, cfg->model.ts); /* rotation over one period */
    ctl_vsd_t u0 = {CTL_Q(0.0), CTL_Q(0.0), CTL_Q(0.0), CTL_Q(0.0)};
    ctl_q ud0 = CTL_Q(0.0);
    ctl_q uq0 = CTL_Q(0.0);
    ctl_q s_in_force = smp->s0; /* the angle at which the command in force enters: k */
    ctl_q c_in_force = smp->c0;
    advance_angle(m->theta_e, smp->s0, smp->c0, delta, &h->sin_k1, &h->cos_k1);
    h->sin1 = h->sin_k1; /* the candidates' voltage enters at k+1 */
    h->cos1 = h->cos_k1;
    if (cfg->params.mid_period_angle) {
        mid_period_angles(m, smp, delta, &s_in_force, &c_in_force, h);
    }
    if (c->applied_duty > CTL_Q(0.0)) { /* a zero vector in force (duty 0) applies no voltage */
        ctl_voltage_in_force(applied, c->applied_duty, smp->vdc, s_in_force, c_in_force, &u0, &ud0,
                             &uq0);
    }
    ctl_predict_dq(&cfg->model, smp->id, smp->iq, smp->omega_e, ud0, uq0, id1, iq1);
    *ix1 = ctl_predict_xy(&cfg->model, smp->vsd.x, u0.x);
    *iy1 = ctl_predict_xy(&cfg->model, smp->vsd.y, u0.y);
    h->model = &cfg->model;
    ctl_predict_dq_free(&cfg->model, *id1, *iq1, smp->omega_e, &h->id2_free, &h->iq2_free);
    h->vdc = smp->vdc;
    h->lambda = cfg->lambda;
    ctl_horizon_prepare(h);
}

SIXPHASE_RAMFUNC static void select_ddc(const ctl_t *c, const ctl_config_t *cfg,
                                        const ctl_horizon_t *h, ctl_q id1, ctl_q iq1, ctl_q ix1,
                                        ctl_q iy1, ctl_choice_t *choice)
{
    ctl_ddc_flux_t f;
    const ctl_q psi_d1 = ctl_flux_d(&cfg->model, id1);
    const ctl_q psi_q1 = ctl_flux_q(&cfg->model, iq1);
    ctl_park_inverse_bnd(psi_d1, psi_q1, h->sin_k1, h->cos_k1, &f.psi_alpha, &f.psi_beta);
    f.psi_mag_sq = ctl_mul_add(psi_d1, psi_d1, psi_q1, psi_q1);
    f.psi_x = ctl_mul_bnd(cfg->model.lxy, ix1); /* bounded: ctl_model_init */
    f.psi_y = ctl_mul_bnd(cfg->model.lxy, iy1);
#if CTL_PROFILE
    ctl_ddc_select(h, &f, &cfg->ctrl.ddc, c->stage_hook, choice);
#else
    (void)c;
    ctl_ddc_select(h, &f, &cfg->ctrl.ddc, 0, choice);
#endif
}

/* ctl_step's healthy branch (ctl_step.c). */
SIXPHASE_RAMFUNC void ctl_healthy_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd)
{
    const ctl_config_t *cfg = &c->config[c->config_active];
    ctl_sample_t smp;
    ctl_horizon_t h;
    ctl_choice_t choice;
    int16_t virtual_vector;
    ctl_q id1;
    ctl_q iq1;
    ctl_q ix1;
    ctl_q iy1;

    /* Measured state at k, references. */
    ctl_vsd_forward_in_range(m->i_phase, &smp.vsd);
    smp.omega_e = m->omega_e;
    smp.vdc = m->vdc;
    ctl_range_clamp(&smp.omega_e, &smp.vdc, cfg->model.omega_max);
    ctl_sincos_pu(m->theta_e, &smp.s0, &smp.c0);
    ctl_park(smp.vsd.alpha, smp.vsd.beta, smp.s0, smp.c0, &smp.id, &smp.iq);
    if (c->loop_mode == CTL_LOOP_SPEED) {
        /* the speed as measured: the domain's clamp is the prediction's, not the speed loop's */
        h.torque_ref = ctl_speed_pi_run(&c->speed_pi, c->speed_ref, m->omega_e);
    } else {
        h.torque_ref = ctl_clamp(c->torque_ref_direct, -cfg->torque_limit, cfg->torque_limit);
    }
    h.flux_ref = ctl_flux_ref_run(&cfg->flux_ref, h.torque_ref);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TRANSFORMS);

    predict(c, cfg, m, &smp, &h, &ix1, &iy1, &id1, &iq1);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_PREDICT);

    virtual_vector = CTL_VV_NONE;
    if (cfg->params.controller == CTL_CONTROLLER_DDC) {
        select_ddc(c, cfg, &h, id1, iq1, ix1, iy1, &choice);
    } else if (cfg->params.controller == CTL_CONTROLLER_VVMPTC) {
        CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TABLE); /* no tables: the stage is empty */
        virtual_vector = ctl_vvmptc_select(&h, c->applied_vector, &choice);
    } else {
        const bool all = cfg->params.controller == CTL_CONTROLLER_MPTC49;
        CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TABLE); /* no tables: the stage is empty */
        ctl_mptc_select(&h, all ? ctl_mptc49_vectors : ctl_mptc13_vectors,
                        all ? CTL_MPTC49_CANDIDATES : CTL_MPTC13_CANDIDATES, c->applied_vector,
                        &choice);
    }

    if (virtual_vector != CTL_VV_NONE) {
        command_from_virtual(virtual_vector, cmd, &c->applied_edges);
    } else {
        command_from_choice(choice.vector, choice.duty, c, cfg->params.pulse_pattern, cmd,
                            &c->applied_edges);
    }
    c->applied_virtual = virtual_vector;
    c->applied_vector = cmd->vector;
    c->applied_duty = cmd->duty;
    ctl_diag_record(&c->diag, smp.id, smp.iq, smp.vsd.x, smp.vsd.y, &h, &choice);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_SEARCH);
}
