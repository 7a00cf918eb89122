/* The drive's side of commissioning, see drive_commission.h. */
#include "drive_commission.h"

#include "ctl_pu.h"
#include "hal_board.h"
#include "hal_encoder.h"
#include "hal_pwm.h"
#include "ctl_qmath.h"

/* An encoder that saw its index and then went unhealthy has a counter or signal error; one
 * that has not seen its index yet is what the sequence turns the rotor for. */
static bool drive_encoder_error(const drive_t *d)
{
    return d->encoder.index_seen && !d->encoder.healthy;
}

/* A rotor still coasting (after a STOP, or turned by hand or by a load) faster than the
 * encoder step's spin, one electrical turn per second: the alignment would drag it and the
 * sequence would blame a load, so the start is refused. */
static bool drive_rotor_turning(const drive_t *d)
{
    const int32_t speed = d->encoder.mech_speed_q16; /* 65536 = 1 rev/s */
    const int32_t limit = (int32_t)65536 / (int32_t)ctl_params(&d->ctl)->pole_pairs;
    return speed > limit || speed < -limit;
}

static int16_t drive_comm_refusal(const drive_t *d)
{
    if (d->state != DRIVE_STATE_READY) {
        return COMM_REASON_NOT_READY;
    }
    if (d->meas.vdc < drive_protect_limits(d)->dc_undervoltage) {
        return COMM_REASON_UNDERVOLTAGE;
    }
    if (drive_encoder_error(d)) {
        return COMM_REASON_ENCODER_ERROR;
    }
    if (d->isolated_leg >= 0) { /* five legs (drive_open_phase.h): restore them first */
        return COMM_REASON_OPEN_PHASE;
    }
    if (drive_rotor_turning(d)) {
        return COMM_REASON_ROTOR_TURNING;
    }
    return COMM_REASON_NONE;
}

drive_comm_result_t drive_request_commission(drive_t *d, uint16_t mask, uint16_t permille)
{
    int16_t why;
    if (!comm_mask_valid(mask) || !comm_current_valid(permille)) {
        return DRIVE_COMM_INVALID;
    }
    why = drive_comm_refusal(d);
    if (why != COMM_REASON_NONE) {
        d->comm.reason = why;
        return DRIVE_COMM_REFUSED;
    }
    comm_request(&d->comm, mask, permille);
    return DRIVE_COMM_OK;
}

/* The board's tolerances as standard uncertainties (an error anywhere within +-t: t / sqrt 3):
 * each current channel's gain; the DC link's gain and, at the link's voltage, its offset. */
static void drive_commission_tolerances(ident_machine_t *m)
{
    const float inv_sqrt3 = 0.57735027f;
    const float gain = (float)HAL_BOARD_ADC_GAIN_TOLERANCE;
    const float offset_v =
        (float)HAL_BOARD_ADC_OFFSET_TOLERANCE_COUNTS * (float)HAL_BOARD_VDC_V_PER_COUNT;
    const float offset = offset_v / ((m->vdc > offset_v) ? m->vdc : offset_v);
    m->u_current = gain * inv_sqrt3;
    m->u_vdc = ctl_sqrtf(gain * gain + offset * offset) * inv_sqrt3;
}

void drive_commission_machine(const drive_t *d, ident_machine_t *m)
{
    const ctl_params_t *p = ctl_params(&d->ctl);
    const float pn = (float)p->pole_pairs;
    m->ts = p->sample_time_s;
    m->r = p->resistance_ohm;
    m->ld = p->ld_h;
    m->lq = p->lq_h;
    m->lxy = p->l_xy_h;
    m->psi_f = p->pm_flux_wb;
    m->inertia = p->inertia_kg_m2;
    m->pole_pairs = p->pole_pairs;
    m->rated_a = p->torque_limit_nm / (3.0f * pn * p->pm_flux_wb);
    m->trip_a = p->protect.overcurrent_a;
    m->counts_per_turn = (float)hal_encoder_counts_per_turn();
    m->overspeed_e = p->protect.overspeed_rpm * (CTL_TWO_PI_F / 60.0f) * pn;
    m->open_ratio = p->protect.open_phase_ratio;
    m->hal_offset = hal_encoder_offset();
    m->vdc = ctl_to_float(d->meas.vdc) * CTL_BASE_VOLTAGE_V_F;
    m->dead_time_s = (float)HAL_BOARD_DEAD_TIME_NS * 1.0e-9f;
    drive_commission_tolerances(m);
}

/* This period's measurements as the identification takes them (SI). */
static void drive_commission_input(const drive_t *d, ident_input_t *in)
{
    int16_t k;
    for (k = 0; k < IDENT_PHASES; k++) {
        in->i_phase[k] = ctl_to_float(d->meas.i_phase[k]) * CTL_BASE_CURRENT_A_F;
    }
    in->vdc = ctl_to_float(d->meas.vdc) * CTL_BASE_VOLTAGE_V_F;
    in->elec_angle = d->encoder.elec_angle;
    in->position = d->encoder.position;
    in->index_seen = d->encoder.index_seen;
    in->mech_rev_s = (float)d->encoder.mech_speed_q16 * (1.0f / 65536.0f);
}

/* One period of the sequence: the duties, or false once it ended. */
static bool drive_commission_output(drive_t *d)
{
    ident_input_t in;
    float u[4];
    uint16_t duty[IDENT_PHASES];
    drive_commission_input(d, &in);
    if (!comm_period(&d->comm, &in, u)) {
        hal_pwm_force_off();
        return false;
    }
    ident_modulate(u, in.vdc, duty);
    hal_pwm_write(duty);
    return true;
}

void drive_commission_begin(drive_t *d)
{
    ident_machine_t m;
    int16_t why;
    if (d->comm.start_requested == 0) {
        return;
    }
    d->comm.start_requested = 0;
    why = drive_comm_refusal(d);
    if (why != COMM_REASON_NONE) { /* conditions changed since the request: IDLE, and why */
        d->comm.state = COMM_STATE_IDLE;
        d->comm.reason = why;
        return;
    }
    drive_commission_machine(d, &m);
    comm_start(&d->comm, &m, d->comm.req_mask, d->comm.req_permille);
    d->stop_requested = false;
    d->state = DRIVE_STATE_COMMISSION;
    hal_pwm_enable();
    drive_commission_period(d);
}

void drive_commission_period(drive_t *d)
{
    if (d->stop_requested) {
        d->stop_requested = false;
        comm_abort(&d->comm, COMM_REASON_ABORTED);
        hal_pwm_force_off();
        d->state = DRIVE_STATE_READY;
        return;
    }
    if (!drive_commission_output(d)) {
        d->state = DRIVE_STATE_READY;
    }
}

void drive_phase_verify_start(drive_t *d)
{
    ident_machine_t m;
    drive_commission_machine(d, &m);
    comm_start(&d->comm, &m, (uint16_t)(1u << COMM_STEP_PHASES), DRIVE_PHASE_VERIFY_PERMILLE);
    d->phase_verifying = true;
}

void drive_phase_verify_period(drive_t *d)
{
    if (drive_commission_output(d)) {
        return;
    }
    d->phase_verifying = false;
    if (d->comm.state == COMM_STATE_DONE &&
        d->comm.x.result[COMM_Q_PHASES].quality == COMM_QUALITY_OK) {
        d->phase_check_pending = false;
        ctl_reset(&d->ctl);
        hal_pwm_enable();
        drive_run_period(d);
        return;
    }
    drive_trip(d, DRIVE_FAULT_OPEN_PHASE);
}

ctl_q drive_commission_angle(const drive_t *d)
{
    const int32_t cpr = (int32_t)hal_encoder_counts_per_turn();
    int32_t in_turn;
    float turns;
    if (cpr <= 0) {
        return CTL_Q(0.0);
    }
    in_turn = d->encoder.position % cpr;
    if (in_turn < 0) {
        in_turn += cpr;
    }
    turns = (float)in_turn * (float)ctl_params(&d->ctl)->pole_pairs / (float)cpr;
    return ctl_from_float(turns - (float)(int32_t)turns);
}

/* An OK inertia into p, and the speed loop's gains designed for it (ctl_params.h); its bit.
 * The friction is reported, not applied: the control core has no term for it. */
static uint16_t drive_comm_take_mechanics(const comm_t *c, ctl_params_t *p)
{
    const ident_result_t *j = &c->x.result[COMM_Q_INERTIA];
    if (j->quality != COMM_QUALITY_OK) {
        return 0u;
    }
    p->inertia_kg_m2 = j->value;
    ctl_speed_gains_from_inertia(p);
    return (uint16_t)(1u << COMM_Q_INERTIA);
}

/* The quantities whose quality is OK into p; their bits. */
static uint16_t drive_comm_take(const comm_t *c, ctl_params_t *p)
{
    const ident_result_t *r = c->x.result;
    uint16_t got = 0u;
    if (r[COMM_Q_R].quality == COMM_QUALITY_OK) {
        p->resistance_ohm = r[COMM_Q_R].value;
        got |= (uint16_t)(1u << COMM_Q_R);
    }
    if (r[COMM_Q_LD].quality == COMM_QUALITY_OK) {
        p->ld_h = r[COMM_Q_LD].value;
        got |= (uint16_t)(1u << COMM_Q_LD);
    }
    if (r[COMM_Q_LQ].quality == COMM_QUALITY_OK) {
        p->lq_h = r[COMM_Q_LQ].value;
        got |= (uint16_t)(1u << COMM_Q_LQ);
    }
    if (r[COMM_Q_LXY].quality == COMM_QUALITY_OK) {
        p->l_xy_h = r[COMM_Q_LXY].value;
        got |= (uint16_t)(1u << COMM_Q_LXY);
    }
    if (r[COMM_Q_PSI_F].quality == COMM_QUALITY_OK) {
        p->pm_flux_wb = r[COMM_Q_PSI_F].value;
        got |= (uint16_t)(1u << COMM_Q_PSI_F);
    }
    return got;
}

/* The rule of commission_lists.h (COMM_KEPT_CONTRADICTS, COMM_FLUX_GROUP;
 * docs/commissioning.md section 3.1): true when taking the quantities got into the set p would
 * keep a value its measurement contradicts, or take part of the flux group while another
 * member was selected and has no number. */
static bool drive_comm_mixed(const comm_t *c, const ctl_params_t *p, uint16_t got)
{
    /* the model's quantities R, L_d, L_q, L_xy, psi_f are numbers COMM_Q_R.. in this order */
    const float kept[5] = {p->resistance_ohm, p->ld_h, p->lq_h, p->l_xy_h, p->pm_flux_wb};
    const ident_result_t *r = c->x.result;
    uint16_t selected = 0u, unconfirmed = 0u;
    int16_t k;
    for (k = 0; k < (int16_t)COMM_STEP_END; k++) {
        selected =
            (uint16_t)(selected | (((c->mask & (1u << k)) != 0u) ? comm_step_quantities(k) : 0u));
    }
    selected &= (uint16_t)(COMM_MODEL_QUANTITIES & ~got);
    for (k = 0; k < 5; k++) {
        const int16_t q = (int16_t)(COMM_Q_R + k);
        if ((selected & (1u << q)) == 0u) {
            continue; /* taken, or not selected */
        }
        if (r[q].quality != COMM_QUALITY_POOR) {
            unconfirmed = (uint16_t)(unconfirmed | (1u << q)); /* failed or skipped: no number */
        } else if (COMM_KEPT_CONTRADICTS(r[q].value, r[q].sigma, kept[k])) {
            return true;
        }
    }
    return (got & COMM_FLUX_GROUP) != 0u && (unconfirmed & COMM_FLUX_GROUP) != 0u;
}

drive_comm_result_t drive_commission_apply(drive_t *d, uint16_t *applied)
{
    const comm_t *c = &d->comm;
    const bool offset = c->x.result[COMM_Q_OFFSET].quality == COMM_QUALITY_OK;
    ctl_params_t *p = &d->params_req; /* the drive's staging set, off the stack (drive.h) */
    uint16_t got;
    *applied = 0u;
    if (d->state != DRIVE_STATE_READY || c->state == COMM_STATE_IDLE ||
        c->state == COMM_STATE_RUNNING) {
        return DRIVE_COMM_REFUSED;
    }
    if (c->state == COMM_STATE_FAILED && c->reason == COMM_REASON_OPEN_PHASE) {
        return DRIVE_COMM_REFUSED; /* when the phase opened is unknown: no result is trusted */
    }
    *p = d->params_bg;
    got = (uint16_t)(drive_comm_take(c, p) | drive_comm_take_mechanics(c, p));
    if (got == 0u && !offset) {
        return DRIVE_COMM_REFUSED;
    }
    if (drive_comm_mixed(c, &d->params_bg, got)) {
        d->comm.reason = COMM_REASON_MIXED_SET; /* the last refusal (COMMISSION_STATUS) */
        return DRIVE_COMM_REFUSED;
    }
    if (got != 0u) {
        const ctl_param_error_t e = drive_request_params(d, p);
        if (e == CTL_PARAM_BUSY) {
            return DRIVE_COMM_BUSY;
        }
        if (e != CTL_PARAM_OK) {
            return DRIVE_COMM_REJECTED;
        }
    }
    if (offset) {
        hal_encoder_set_offset(c->x.offset_abs);
        got |= (uint16_t)(1u << COMM_Q_OFFSET);
    }
    *applied = got;
    return DRIVE_COMM_OK;
}
