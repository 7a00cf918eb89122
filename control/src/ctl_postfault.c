#include "ctl_postfault.h"

#include "ctl_angle.h"
#include "ctl_ddc_levels.h"
#include "ctl_diag_record.h"
#include "ctl_pulse.h"
#include "ctl_search.h"
#include "ctl_tables.h"
#include "ctl_vectors.h"
#include "ctl_vsd.h"
#include "ctl_qmath.h"

/* The open phase's constraint at one rotor angle: its row c in the rotor frame, the model's
 * one-period response g to a voltage along c (g = (Ts/L_d c_d, Ts/L_q c_q, Ts/L_xy c_x, ..)),
 * and 1 / (c . g), which is at least min(Ts/L_d, Ts/L_q) + Ts/L_xy > 0. */
typedef struct {
    ctl_q cd, cq, cx, cy;
    ctl_q gd, gq, gx, gy;
    ctl_q inv_cg;
} pf_constraint_t;

/* Currents in the rotor (d, q) and stationary x-y frames. */
typedef struct {
    ctl_q d, q, x, y;
} pf_currents_t;

typedef struct {
    const ctl_postfault_config_t *pf; /* the open-phase configuration in force */
    ctl_horizon_t h;                  /* references, angles and the projected k+2 free response */
    ctl_q kd[4]; /* projected forced k+2 i_d per unit of (alpha, beta, x, y) voltage (of Vdc) */
    ctl_q kq[4]; /* and i_q */
    pf_currents_t i1; /* the state at k+1, projected */
} pf_horizon_t;

static void pf_constraint_at(const ctl_model_t *mdl, const ctl_postfault_config_t *pf, ctl_q s,
                             ctl_q co, pf_constraint_t *k)
{
    ctl_q cg;
    ctl_park(pf->c_alpha, pf->c_beta, s, co, &k->cd, &k->cq);
    k->cx = pf->c_x;
    k->cy = pf->c_y;
    /* bounded: a coefficient times a component of the phase's row (at most 1) */
    k->gd = ctl_mul_bnd(mdl->c_d, k->cd);
    k->gq = ctl_mul_bnd(mdl->c_q, k->cq);
    k->gx = ctl_mul_bnd(mdl->c_xy, k->cx);
    k->gy = ctl_mul_bnd(mdl->c_xy, k->cy);
    cg = ctl_add(ctl_mul_add(k->cd, k->gd, k->cq, k->gq), ctl_mul_add(k->cx, k->gx, k->cy, k->gy));
    k->inv_cg = ctl_div(CTL_Q(1.0), cg);
}

/* Removes the open phase's current along g: afterwards c . i = 0 (to the arithmetic's rounding).
 * The projected currents end held to CTL_RANGE_PROJECTED (ctl_range.h), the bound the range
 * analysis takes for them downstream (an oblique projection may magnify; a real one does not). */
static void pf_project(const pf_constraint_t *k, pf_currents_t *i)
{
    const ctl_q lim = CTL_Q(CTL_RANGE_PROJECTED);
    const ctl_q viol =
        ctl_add(ctl_mul_add(k->cd, i->d, k->cq, i->q), ctl_mul_add(k->cx, i->x, k->cy, i->y));
    const ctl_q s = ctl_mul(viol, k->inv_cg);
    i->d = ctl_mul_dec_held(i->d, k->gd, s, lim);
    i->q = ctl_mul_dec_held(i->q, k->gq, s, lim);
    i->x = ctl_mul_dec_held(i->x, k->gx, s, lim);
    i->y = ctl_mul_dec_held(i->y, k->gy, s, lim);
}

void ctl_postfault_project(const ctl_model_t *model, const ctl_postfault_config_t *pf, ctl_q s,
                           ctl_q co, ctl_q *id, ctl_q *iq, ctl_q *ix, ctl_q *iy)
{
    pf_constraint_t k;
    pf_currents_t i;
    i.d = *id;
    i.q = *iq;
    i.x = *ix;
    i.y = *iy;
    pf_constraint_at(model, pf, s, co, &k);
    pf_project(&k, &i);
    *id = i.d;
    *iq = i.q;
    *ix = i.x;
    *iy = i.y;
}

/* The command in force over k -> k+1 (period average, healthy model), then the projection at
 * k+1. Fills the angles of the horizon. */
static void pf_predict_k1(const ctl_t *c, const ctl_config_t *cfg, const ctl_meas_t *m,
                          const pf_currents_t *i0, ctl_q s0, ctl_q c0, pf_horizon_t *p)
{
    const ctl_model_t *mdl = &cfg->model;
    /* a virtual vector still in force when the phase opened (VV-MPTC's last healthy period) */
    const ctl_vsd_t *applied = (c->applied_virtual != CTL_VV_NONE)
                                   ? &ctl_vv_vsd[c->applied_virtual]
                                   : &ctl_vector_vsd[c->applied_vector];
    const ctl_q delta = ctl_mul_bnd(m->omega_e, mdl->ts); /* bounded as the healthy step's */
    const bool mid = cfg->params.mid_period_angle;
    ctl_vsd_t u0 = {CTL_Q(0.0), CTL_Q(0.0), CTL_Q(0.0), CTL_Q(0.0)};
    ctl_q ud0 = CTL_Q(0.0);
    ctl_q uq0 = CTL_Q(0.0);
    pf_constraint_t k1;
    if (c->applied_duty != CTL_Q(0.0)) {
        ctl_q s = s0;
        ctl_q co = c0;
        if (mid) {
            ctl_angle_advance(m->theta_e, s0, c0, ctl_mul(delta, CTL_Q(0.5)), &s, &co);
        }
        ctl_voltage_in_force(applied, c->applied_duty, m->vdc, s, co, &u0, &ud0, &uq0);
    }
    ctl_predict_dq(mdl, i0->d, i0->q, m->omega_e, ud0, uq0, &p->i1.d, &p->i1.q);
    p->i1.x = ctl_predict_xy(mdl, i0->x, u0.x);
    p->i1.y = ctl_predict_xy(mdl, i0->y, u0.y);
    ctl_angle_advance(m->theta_e, s0, c0, delta, &p->h.sin_k1, &p->h.cos_k1);
    if (mid) {
        ctl_angle_advance(m->theta_e, s0, c0, ctl_mul(delta, CTL_Q(1.5)), &p->h.sin1, &p->h.cos1);
    } else {
        p->h.sin1 = p->h.sin_k1;
        p->h.cos1 = p->h.cos_k1;
    }
    pf_constraint_at(mdl, p->pf, p->h.sin_k1, p->h.cos_k1, &k1);
    pf_project(&k1, &p->i1);
}

/* Per-unit-Vdc forced response over k+1 -> k+2 of the healthy model, projected at k+2: the
 * healthy coefficients of ctl_horizon_prepare plus the x-y ones, each less its part along g. */
static void pf_forced_coefficients(pf_horizon_t *p, const pf_constraint_t *k2)
{
    const ctl_model_t *mdl = p->h.model;
    const ctl_q cd = ctl_mul(mdl->c_d, p->h.vdc);
    const ctl_q cq = ctl_mul(mdl->c_q, p->h.vdc);
    const ctl_q cxy = ctl_mul(mdl->c_xy, p->h.vdc);
    const ctl_q fd[2] = {ctl_mul(cd, p->h.cos1), ctl_mul(cd, p->h.sin1)};
    const ctl_q fq[2] = {ctl_sub(CTL_Q(0.0), ctl_mul(cq, p->h.sin1)), ctl_mul(cq, p->h.cos1)};
    const ctl_q cxy_along[2] = {ctl_mul(k2->cx, cxy), ctl_mul(k2->cy, cxy)};
    int16_t j;
    for (j = 0; j < 2; j++) {
        /* c . forced response to voltage component j, over c . g: alpha and beta drive d-q,
         * x and y only x-y (no d-q part to keep) */
        const ctl_q along = ctl_mul(ctl_mul_add(k2->cd, fd[j], k2->cq, fq[j]), k2->inv_cg);
        const ctl_q along_xy = ctl_mul(cxy_along[j], k2->inv_cg);
        p->kd[j] = ctl_mul_dec(fd[j], k2->gd, along);
        p->kq[j] = ctl_mul_dec(fq[j], k2->gq, along);
        p->kd[2 + j] = ctl_mul_dec(CTL_Q(0.0), k2->gd, along_xy);
        p->kq[2 + j] = ctl_mul_dec(CTL_Q(0.0), k2->gq, along_xy);
    }
}

/* The free response k+1 -> k+2 from the projected k+1 state, projected at k+2, and the forced
 * coefficients. */
static void pf_predict_k2(const ctl_config_t *cfg, const ctl_meas_t *m, ctl_q s0, ctl_q c0,
                          pf_horizon_t *p)
{
    const ctl_model_t *mdl = &cfg->model;
    pf_constraint_t k2;
    pf_currents_t i2;
    ctl_q s2;
    ctl_q co2;
    ctl_angle_advance(m->theta_e, s0, c0, ctl_mul(ctl_mul(m->omega_e, mdl->ts), CTL_Q(2.0)), &s2,
                      &co2);
    pf_constraint_at(mdl, p->pf, s2, co2, &k2);
    ctl_predict_dq_free(mdl, p->i1.d, p->i1.q, m->omega_e, &i2.d, &i2.q);
    i2.x = ctl_mul(mdl->a_xy, p->i1.x);
    i2.y = ctl_mul(mdl->a_xy, p->i1.y);
    pf_project(&k2, &i2);
    p->h.id2_free = i2.d;
    p->h.iq2_free = i2.q;
    p->h.model = mdl;
    p->h.vdc = m->vdc;
    p->h.lambda = cfg->lambda;
    pf_forced_coefficients(p, &k2);
}

/* A candidate's projected forced response, held as the projections are (pf_project). */
static inline void pf_forced(const pf_horizon_t *p, const ctl_vsd_t *v, ctl_q *did, ctl_q *diq)
{
    const ctl_q lim = CTL_Q(CTL_RANGE_PROJECTED);
    *did =
        ctl_dot4_held(p->kd[0], v->alpha, p->kd[1], v->beta, p->kd[2], v->x, p->kd[3], v->y, lim);
    *diq =
        ctl_dot4_held(p->kq[0], v->alpha, p->kq[1], v->beta, p->kq[2], v->x, p->kq[3], v->y, lim);
}

/* Index of the free x-y voltage sign the DDC table needs: 1 (negative) while the free x-y
 * current at k+1 is above its reference (free_ref . i_ab, zero for minimum loss). */
static int16_t pf_free_sign(const ctl_postfault_config_t *pf, const pf_horizon_t *p)
{
    ctl_q ia;
    ctl_q ib;
    ctl_park_inverse_bnd(p->i1.d, p->i1.q, p->h.sin_k1, p->h.cos_k1, &ia, &ib);
    {
        const ctl_q free_i = ctl_mul_sub(pf->c_x, p->i1.y, pf->c_y, p->i1.x);
        const ctl_q free_ref = ctl_mul_add(pf->free_ref_alpha, ia, pf->free_ref_beta, ib);
        return (free_i > free_ref) ? 1 : 0;
    }
}

static void pf_select_ddc(const ctl_t *c, const ctl_config_t *cfg, const pf_horizon_t *p,
                          ctl_choice_t *out)
{
    const ctl_model_t *mdl = &cfg->model;
    const ctl_q psi_d1 = ctl_flux_d(mdl, p->i1.d);
    const ctl_q psi_q1 = ctl_flux_q(mdl, p->i1.q);
    const ctl_q flux_ref = p->h.flux_ref;
    ctl_q psi_alpha;
    ctl_q psi_beta;
    ctl_ddc_state_t zero;
    ctl_q did;
    ctl_q diq;
    int16_t vector;
    int16_t sector;
    int16_t half;
    int16_t lower;
    int16_t sign;
    ctl_park_inverse_bnd(psi_d1, psi_q1, p->h.sin_k1, p->h.cos_k1, &psi_alpha, &psi_beta);
    sector = ctl_sector12(psi_beta, psi_alpha);
    zero.torque = ctl_torque_psi(mdl, p->h.id2_free, p->h.iq2_free, &zero.psi_d, &zero.psi_q);
    half = (zero.torque > p->h.torque_ref) ? 1 : 0;
    lower = (ctl_mul_add(psi_d1, psi_d1, psi_q1, psi_q1) >= ctl_mul(flux_ref, flux_ref)) ? 1 : 0;
    sign = pf_free_sign(p->pf, p);
    vector = p->pf->ddc_table[sector][half][lower][sign];
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TABLE);
    /* the healthy search on the projected forced response (the torque guard is always on with
     * an open phase: ctl_config.c) */
    pf_forced(p, &ctl_vector_vsd[vector], &did, &diq);
    ctl_ddc_levels_search(&p->h, &cfg->ctrl.ddc, vector, did, diq, &zero, out);
    out->candidates = cfg->params.duty_levels;
    out->flux_sector = sector;
    out->xy_sector = sign;
    out->braking = half == 1;
}

/* Every candidate held for the whole period (the zero state is placed by pf_command's rule). */
static void pf_select_mptc(const ctl_config_t *cfg, const pf_horizon_t *p, ctl_choice_t *out)
{
    const ctl_postfault_config_t *pf = p->pf;
    const bool all = cfg->params.controller == CTL_CONTROLLER_MPTC49;
    const int16_t *candidates = all ? pf->mptc_all : pf->mptc_large;
    const int16_t count = all ? pf->mptc_all_count : pf->mptc_large_count;
    int16_t i;
    out->cost = CTL_Q_MAX;
    out->vector = 0;
    out->torque = CTL_Q(0.0);
    out->flux = CTL_Q(0.0);
    for (i = 0; i < count; i++) {
        ctl_q did;
        ctl_q diq;
        pf_forced(p, &ctl_vector_vsd[candidates[i]], &did, &diq);
        ctl_choice_consider(&p->h, did, diq, candidates[i], out);
    }
    out->duty = CTL_Q(1.0);
    out->candidates = count;
    out->flux_sector = -1;
    out->xy_sector = -1;
    out->braking = false;
}

/* ctl_pulse_set_difference over a set's healthy legs (mask; the open leg never switches, and
 * with it open the set's zero states are its healthy legs all at 0 or all at 1). */
static int16_t pf_set_difference(ctl_pulse_kind_t kind, bool per_set, int16_t vector,
                                 int16_t edges_before, int16_t mask, int16_t *held)
{
    const int16_t n = ctl_vector_ones(mask);
    const int16_t v = (int16_t)(vector & mask);
    const int16_t at_one = ctl_vector_ones((int16_t)(edges_before & mask));
    if (kind == CTL_PULSE_ZERO || (per_set && (v == 0 || v == mask))) {
        *held = (int16_t)(*held | mask);
        return (int16_t)(n - 2 * at_one);
    }
    if (kind != CTL_PULSE_PART) {
        return 0;
    }
    return (int16_t)(ctl_vector_ones((int16_t)((edges_before ^ vector) & mask)) - at_one + 2 * n -
                     4 * ctl_vector_ones(v));
}

/* ctl_pulse_arrange over the healthy legs (mask): the candidate zero states are those legs all
 * at 0 or all at 1 (by ones: at 1 when most of them are at 1 in the vector), per set each set's
 * healthy legs on their own. */
static void pf_arrange(ctl_pulse_pattern_t pattern, ctl_pulse_kind_t kind, int16_t vector,
                       const ctl_t *c, int16_t mask, ctl_pulse_t *p)
{
    const bool zero = kind == CTL_PULSE_ZERO;
    const int16_t edges_before = (int16_t)(c->applied_edges & mask);
    const int16_t ones = ctl_vector_ones((int16_t)((zero ? c->applied_vector : vector) & mask));
    int16_t held = zero ? mask : 0;
    int16_t z = (2 * ones > ctl_vector_ones(mask)) ? mask : 0;
    if (pattern != CTL_PULSE_BY_ONES) {
        const bool per_set = pattern == CTL_PULSE_FEWEST_PER_SET;
        const int16_t abc_mask = (int16_t)(mask & CTL_PULSE_LEGS_ABC);
        const int16_t def_mask = (int16_t)(mask & CTL_PULSE_LEGS_DEF);
        const int16_t abc = pf_set_difference(kind, per_set, vector, edges_before, abc_mask, &held);
        const int16_t def = pf_set_difference(kind, per_set, vector, edges_before, def_mask, &held);
        const int16_t both = (int16_t)(abc + def);
        int16_t best = (z != 0) ? both : 0;
        if (((z != 0) ? 0 : both) < best) {
            z = (int16_t)(z ^ mask);
            best = (int16_t)(both - best);
        }
        if (per_set && def < best) {
            z = def_mask;
            best = def;
        }
        if (per_set && abc < best) {
            z = abc_mask;
        }
    }
    p->zero = z;
    p->active = (int16_t)((vector & ~held) | (z & held));
}

/* Leg duties of the choice as ctl.c's healthy command (the pulse pattern over the healthy
 * legs), with the open leg always off. */
static void pf_command(ctl_t *c, const ctl_config_t *cfg, const ctl_postfault_config_t *pf,
                       const ctl_choice_t *choice, ctl_cmd_t *cmd)
{
    const int16_t mask = (int16_t)(077 & ~(1 << (5 - pf->open_leg)));
    const int16_t vector = (int16_t)(choice->vector & mask);
    const ctl_q d = ctl_clamp(choice->duty, CTL_Q(0.0), CTL_Q(1.0));
    const ctl_pulse_kind_t kind = (d <= CTL_Q(0.0) || vector == 0 || vector == mask)
                                      ? CTL_PULSE_ZERO
                                      : ((d >= CTL_Q(1.0)) ? CTL_PULSE_FULL : CTL_PULSE_PART);
    const ctl_q rest = ctl_sub(CTL_Q(1.0), d);
    ctl_pulse_t p;
    int16_t leg;
    pf_arrange(cfg->params.pulse_pattern, kind, vector, c, mask, &p);
    for (leg = 0; leg < CTL_PHASES; leg++) {
        /* a set whose healthy legs rest at 1: its legs of the active state on all period, the
         * others high for the rest in the middle; at 0: on for d in the middle, the others off */
        const bool high = (p.zero & ((leg < 3) ? CTL_PULSE_LEGS_ABC : CTL_PULSE_LEGS_DEF)) != 0;
        const ctl_q on = high ? CTL_Q(1.0) : d;
        const ctl_q off = high ? rest : CTL_Q(0.0);
        cmd->leg_duty[leg] = (ctl_vector_leg(p.active, leg) != 0) ? on : off;
    }
    cmd->leg_duty[pf->open_leg] = CTL_Q(0.0);
    cmd->vector = (kind == CTL_PULSE_ZERO) ? p.zero : p.active;
    cmd->duty = (kind == CTL_PULSE_ZERO) ? CTL_Q(0.0) : d;
    cmd->enable = true;
    c->applied_edges = ctl_pulse_edges(kind, &p);
    c->applied_vector = cmd->vector;
    c->applied_duty = cmd->duty;
    c->applied_virtual = CTL_VV_NONE;
}

/* All switches off: no valid parameter set was ever in force. */
static void pf_command_off(ctl_cmd_t *cmd)
{
    int16_t leg;
    for (leg = 0; leg < CTL_PHASES; leg++) {
        cmd->leg_duty[leg] = CTL_Q(0.0);
    }
    cmd->vector = 0;
    cmd->duty = CTL_Q(0.0);
    cmd->enable = false;
}

void ctl_postfault_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd)
{
    const ctl_config_t *cfg = ctl_config(c);
    pf_horizon_t p;
    pf_currents_t i0;
    ctl_choice_t choice;
    ctl_vsd_t vsd;
    ctl_meas_t held;
    ctl_q s0;
    ctl_q c0;
    if (!c->initialised) {
        pf_command_off(cmd);
        return;
    }
    p.pf = ctl_postfault_config(c);
    ctl_vsd_forward_in_range(m->i_phase, &vsd);
    held = *m; /* the speed and DC link of the range analysis' domain, for all but the speed loop */
    ctl_range_clamp(&held.omega_e, &held.vdc, cfg->model.omega_max);
    ctl_sincos_pu(m->theta_e, &s0, &c0);
    ctl_park(vsd.alpha, vsd.beta, s0, c0, &i0.d, &i0.q);
    i0.x = vsd.x;
    i0.y = vsd.y;
    if (c->loop_mode == CTL_LOOP_SPEED) {
        p.h.torque_ref = ctl_speed_pi_run(&c->speed_pi, c->speed_ref, m->omega_e);
    } else {
        p.h.torque_ref = ctl_clamp(c->torque_ref_direct, -cfg->torque_limit, cfg->torque_limit);
    }
    p.h.flux_ref = ctl_flux_ref_run(&cfg->flux_ref, p.h.torque_ref);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TRANSFORMS);
    pf_predict_k1(c, cfg, &held, &i0, s0, c0, &p);
    pf_predict_k2(cfg, &held, s0, c0, &p);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_PREDICT);
    /* FOC-VSD has no five-leg mode: with an open phase it rides through on the post-fault
     * MPTC-13 (the else branch), as the MPTC baselines on theirs */
    if (cfg->params.controller == CTL_CONTROLLER_DDC) {
        pf_select_ddc(c, cfg, &p, &choice);
    } else {
        CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_TABLE);
        pf_select_mptc(cfg, &p, &choice);
    }
    pf_command(c, cfg, p.pf, &choice, cmd);
    ctl_diag_record(&c->diag, i0.d, i0.q, i0.x, i0.y, &p.h, &choice);
    CTL_STAGE_MARK(c->stage_hook, CTL_STAGE_SEARCH);
}
