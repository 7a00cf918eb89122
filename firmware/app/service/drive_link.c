#include "drive_link.h"

#include "ctl_barrier.h"
#include "ctl_pu.h"
#include "drive/drive_commission.h"
#include "drive/drive_open_phase.h"
#include "hal_pwm.h"
#include "measure/profile.h"
#include "measure/stack_watch.h"

/* The link's numbers that are the drive's own, checked where both are visible (C99 has no
 * static_assert; a false condition gives an array of size -1). States, refusals and faults
 * come from the application's lists (drive_states.h, drive_faults.h), which the link maps. */
#define DRIVE_LINK_ASSERT(name, cond) typedef char drive_link_assert_##name[(cond) ? 1 : -1]
DRIVE_LINK_ASSERT(stack_not_measured, SXL_STACK_NOT_MEASURED == 0u); /* stack_watch.h's size 0 */
/* the torque-limited action goes over the link as the drive's own number */
DRIVE_LINK_ASSERT(tl_continue, (int32_t)SXL_TL_CONTINUE == (int32_t)DRIVE_TORQUE_LIMITED_CONTINUE);
DRIVE_LINK_ASSERT(tl_stop, (int32_t)SXL_TL_STOP == (int32_t)DRIVE_TORQUE_LIMITED_STOP);

/* x rounded to the nearest integer and saturated to int32. */
static int32_t float_to_i32(float x)
{
    if (!(x == x)) {
        return 0;
    }
    if (x >= 2147483520.0f) {
        return INT32_MAX;
    }
    if (x <= -2147483520.0f) {
        return -INT32_MAX;
    }
    return (int32_t)((x >= 0.0f) ? (x + 0.5f) : (x - 0.5f));
}

/* x rounded and saturated to int16 (NaN: 0), for the record's 16-bit fields. */
static int16_t float_to_i16(float x)
{
    const int32_t v = float_to_i32(x);
    if (v > (int32_t)INT16_MAX) {
        return INT16_MAX;
    }
    if (v < -(int32_t)INT16_MAX) {
        return -INT16_MAX;
    }
    return (int16_t)v;
}

void drive_link_status(const drive_t *d, uint16_t rx_errors, uint16_t *out)
{
    const ctl_diag_t *diag = ctl_diag(&d->ctl);
    const float torque_scale = CTL_BASE_TORQUE_NM_F * 1000.0f;
    uint16_t flags = 0u;
    /* rev/s Q16 -> 0.1 r/min: * 600 / 65536 */
    const int64_t speed_01rpm = ((int64_t)d->encoder.mech_speed_q16 * 600) / 65536;

    if (d->encoder.healthy) {
        flags |= SXL_FLAG_ENCODER_OK;
    }
    if (hal_pwm_is_off()) {
        flags |= SXL_FLAG_PWM_OFF;
    }
    if (ctl_config_pending(&d->ctl)) {
        flags |= SXL_FLAG_PARAMS_PENDING;
    }
    if (d->isolated_leg >= 0) {
        flags |= SXL_FLAG_LEG_ISOLATED;
    }
    if (d->torque_limited) {
        flags |= SXL_FLAG_TORQUE_LIMITED;
    }
    out[SXL_ST_STATE] = (uint16_t)((uint16_t)d->state & 0xFFu);
    out[SXL_ST_FAULT] = (uint16_t)((uint16_t)d->fault & 0xFFu);
    out[SXL_ST_FLAGS] = flags;
    out[SXL_ST_CONTROLLER] = (uint16_t)((uint16_t)ctl_params(&d->ctl)->controller & 0xFFu);
    sxl_put_i32(&out[SXL_ST_SPEED], (int32_t)speed_01rpm);
    sxl_put_i32(&out[SXL_ST_SPEED_REF], float_to_i32(d->speed_ref_rpm * 10.0f));
    sxl_put_i32(&out[SXL_ST_TORQUE],
                float_to_i32(ctl_to_float(ctl_diag_torque_est(&d->ctl)) * torque_scale));
    sxl_put_i32(&out[SXL_ST_TORQUE_REF],
                float_to_i32(ctl_to_float(diag->torque_ref) * torque_scale));
    sxl_put_u32(&out[SXL_ST_LAMBDA],
                (uint32_t)float_to_i32(ctl_params(&d->ctl)->lambda_nm_per_wb * 1000.0f));
    sxl_put_u32(&out[SXL_ST_ISR_COUNT], d->isr_count);
    sxl_put_u32(&out[SXL_ST_ISR_MAX], d->isr_cycles_max);
    sxl_put_u16(&out[SXL_ST_RX_ERRORS], rx_errors);
    sxl_put_u16(&out[SXL_ST_FAULTS], drive_faults_latched(d));
    sxl_put_u16(&out[SXL_ST_RECORDS], ctl_protect_log_pending(&d->protect));
    out[SXL_ST_RUN_REFUSAL] = (uint16_t)((uint16_t)d->run_refusal & 0xFFu);
    sxl_put_u16(&out[SXL_ST_CLEAR_BLOCKED], d->clear_blocked);
    /* the scan (at most the stack's size in reads) runs here, in the background */
    sxl_put_u16(&out[SXL_ST_STACK_USED], stack_watch_scan(&drive_stack));
    sxl_put_u16(&out[SXL_ST_STACK_WORDS], drive_stack.words); /* 0 unpainted: not measured */
}

uint16_t drive_link_fault_record(drive_t *d, uint16_t *out)
{
    ctl_fault_record_t r;
    const bool present = drive_read_fault_record(d, &r);
    /* counts after the read, so PENDING 0 tells the host it has everything */
    out[SXL_FR_PRESENT] = present ? 1u : 0u;
    sxl_put_u16(&out[SXL_FR_PENDING], ctl_protect_log_pending(&d->protect));
    sxl_put_u16(&out[SXL_FR_DROPPED], d->protect.log_dropped);
    if (!present) {
        return SXL_FR_HEADER_SIZE;
    }
    {
        const float amp_10ma = CTL_BASE_CURRENT_A_F * 100.0f;
        const float volt_01 = CTL_BASE_VOLTAGE_V_F * 10.0f;
        const float torque_mnm = CTL_BASE_TORQUE_NM_F * 1000.0f;
        /* electrical per unit -> mechanical 0.1 r/min; a set without pole pairs reads as 1 */
        const int16_t pole_pairs = (d->params_bg.pole_pairs > 0) ? d->params_bg.pole_pairs : 1;
        const float speed_01rpm =
            (CTL_BASE_OMEGA_RAD_S_F * 600.0f / CTL_TWO_PI_F) / (float)pole_pairs;
        /* turns -> 1/65536 turn, wrapped: the low 16 bits of the saturated count */
        const int32_t theta = float_to_i32(ctl_to_float(r.theta_e) * 65536.0f);
        uint16_t k;
        sxl_put_u16(&out[SXL_FR_FAULTS], r.faults);
        sxl_put_u32(&out[SXL_FR_PERIOD], r.period);
        for (k = 0u; k < SXL_FR_PHASES; k++) {
            sxl_put_i16(&out[SXL_FR_I_PHASE + 2u * k],
                        float_to_i16(ctl_to_float(r.i_phase[k]) * amp_10ma));
        }
        sxl_put_i16(&out[SXL_FR_VDC], float_to_i16(ctl_to_float(r.vdc) * volt_01));
        sxl_put_u16(&out[SXL_FR_THETA], (uint16_t)((uint32_t)theta & 0xFFFFu));
        sxl_put_i32(&out[SXL_FR_SPEED], float_to_i32(ctl_to_float(r.omega_e) * speed_01rpm));
        sxl_put_i32(&out[SXL_FR_TORQUE], float_to_i32(ctl_to_float(r.torque_est) * torque_mnm));
        sxl_put_i32(&out[SXL_FR_TORQUE_REF], float_to_i32(ctl_to_float(r.torque_ref) * torque_mnm));
        sxl_put_i16(&out[SXL_FR_VECTOR], r.vector);
        sxl_put_u16(&out[SXL_FR_DUTY], drive_duty_to_hal(r.duty));
    }
    return SXL_FR_SIZE;
}

void drive_link_open_phase(const drive_t *d, uint16_t *out)
{
    const int16_t leg = d->isolated_leg;
    out[SXL_OP_ACTION] = (uint16_t)((uint16_t)d->open_phase_action & 0xFFu);
    out[SXL_OP_STRATEGY] = (uint16_t)((uint16_t)d->postfault_strategy & 0xFFu);
    out[SXL_OP_LEG] = (leg >= 0) ? (uint16_t)leg : 0xFFu;
    out[SXL_OP_CAUSE] = (uint16_t)((uint16_t)d->isolation_cause & 0xFFu);
    out[SXL_OP_IN_FORCE] = drive_open_phase_in_force(d) ? 1u : 0u;
    sxl_put_i32(&out[SXL_OP_TORQUE_LIMIT],
                float_to_i32(ctl_to_float(ctl_config(&d->ctl)->torque_limit) *
                             CTL_BASE_TORQUE_NM_F * 1000.0f));
    sxl_put_u32(&out[SXL_OP_PERIOD], d->isolation_period);
}

void drive_link_profile(uint16_t stage, uint16_t *out)
{
    const prof_t *p = &drive_profile;
    const prof_stat_t *st = &p->stage[stage % (uint16_t)PROF_STAGES];
    out[SXL_PF_STAGE] = (uint16_t)(stage & 0xFFu);
    sxl_put_u32(&out[SXL_PF_LAST], st->last);
    sxl_put_u32(&out[SXL_PF_MIN], st->min);
    sxl_put_u32(&out[SXL_PF_MAX], st->max);
    sxl_put_u32(&out[SXL_PF_MEAN], prof_mean(st));
    sxl_put_u32(&out[SXL_PF_PERIOD], p->period_cycles);
    sxl_put_u32(&out[SXL_PF_READ_COST], p->read_cost);
    sxl_put_u16(&out[SXL_PF_CYCLES_PER_US], (uint16_t)p->cycles_per_us);
    sxl_put_u16(&out[SXL_PF_LOAD_LAST], p->load_permille_last);
    sxl_put_u16(&out[SXL_PF_LOAD_MAX], p->load_permille_max);
    sxl_put_u32(&out[SXL_PF_OVERRUNS], p->overruns);
}

static uint16_t handle_set_controller(drive_t *d, const sxl_frame_t *req)
{
    ctl_params_t *p = &d->params_req; /* the drive's staging set, off the stack (drive.h) */
    const uint32_t lambda_milli = sxl_get_u32(&req->payload[SXL_SC_LAMBDA]);
    if (req->payload[SXL_SC_CONTROLLER] >= (uint16_t)CTL_CONTROLLER_COUNT ||
        lambda_milli > DRIVE_LINK_MAX_LAMBDA_MILLI) {
        return SXL_ERR_VALUE;
    }
    *p = d->params_bg;
    p->controller = (ctl_controller_t)req->payload[SXL_SC_CONTROLLER];
    p->lambda_nm_per_wb = (float)lambda_milli * 0.001f;
    switch (drive_request_params(d, p)) {
    case CTL_PARAM_OK:
        return SXL_OK;
    case CTL_PARAM_BUSY:
        return SXL_ERR_BUSY;
    default:
        return SXL_ERR_VALUE;
    }
}

/* One command each: the request's length is checked by the table below; the handler fills the
 * reply's payload after the result byte, sets its length, and returns the result. */
typedef uint16_t (*link_handler_t)(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                   uint16_t rx_errors);

static uint16_t on_ping(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply, uint16_t rx_errors)
{
    (void)d;
    (void)req;
    (void)rx_errors;
    reply->payload[1u + SXL_PG_VERSION] = SXL_VERSION;
    reply->len = (uint16_t)(1u + SXL_PG_SIZE);
    return SXL_OK;
}

static uint16_t on_get_status(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                              uint16_t rx_errors)
{
    (void)req;
    drive_link_status(d, rx_errors, &reply->payload[1]);
    reply->len = (uint16_t)(1u + SXL_ST_SIZE);
    return SXL_OK;
}

static uint16_t on_get_profile(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                               uint16_t rx_errors)
{
    (void)d;
    (void)rx_errors;
    if (req->payload[SXL_PQ_STAGE] >= (uint16_t)PROF_STAGES) {
        return SXL_ERR_VALUE;
    }
    drive_link_profile(req->payload[SXL_PQ_STAGE], &reply->payload[1]);
    reply->len = (uint16_t)(1u + SXL_PF_SIZE);
    return SXL_OK;
}

static uint16_t on_get_fault_record(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                    uint16_t rx_errors)
{
    (void)req;
    (void)rx_errors;
    reply->len = (uint16_t)(1u + drive_link_fault_record(d, &reply->payload[1]));
    return SXL_OK;
}

static uint16_t on_set_speed(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                             uint16_t rx_errors)
{
    const int32_t v = sxl_get_i32(&req->payload[SXL_SPEED_REF]);
    (void)reply;
    (void)rx_errors;
    if (v > DRIVE_LINK_MAX_SPEED_01RPM || v < -DRIVE_LINK_MAX_SPEED_01RPM) {
        return SXL_ERR_VALUE;
    }
    drive_set_speed_ref_rpm(d, (float)v * 0.1f);
    return SXL_OK;
}

static uint16_t on_set_torque(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                              uint16_t rx_errors)
{
    const int32_t v = sxl_get_i32(&req->payload[SXL_TORQUE_REF]);
    (void)reply;
    (void)rx_errors;
    if (v > DRIVE_LINK_MAX_TORQUE_MNM || v < -DRIVE_LINK_MAX_TORQUE_MNM) {
        return SXL_ERR_VALUE;
    }
    drive_set_torque_ref_nm(d, (float)v * 0.001f);
    return SXL_OK;
}

static uint16_t on_run(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply, uint16_t rx_errors)
{
    const drive_run_refusal_t why = drive_run_check(d);
    (void)req;
    (void)reply;
    (void)rx_errors;
    if (why != DRIVE_RUN_ACCEPTED) {
        d->run_refusal = why; /* the status says why */
        return SXL_ERR_REFUSED;
    }
    drive_request_run(d);
    return SXL_OK;
}

static uint16_t on_stop(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply, uint16_t rx_errors)
{
    (void)req;
    (void)reply;
    (void)rx_errors;
    drive_request_stop(d);
    return SXL_OK;
}

static uint16_t on_clear_fault(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                               uint16_t rx_errors)
{
    (void)req;
    (void)reply;
    (void)rx_errors;
    if (d->state != DRIVE_STATE_FAULT) {
        return SXL_ERR_REFUSED;
    }
    drive_request_clear_fault(d);
    return SXL_OK;
}

static uint16_t on_set_controller(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                  uint16_t rx_errors)
{
    (void)reply;
    (void)rx_errors;
    return handle_set_controller(d, req);
}

static uint16_t on_capture_arm(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                               uint16_t rx_errors)
{
    const uint16_t *p = req->payload;
    capture_setup_t s;
    int16_t k;
    (void)reply;
    (void)rx_errors;
    s.n_channels = (int16_t)p[SXL_CA_CHANNELS];
    for (k = 0; k < CAPTURE_CHANNELS; k++) {
        s.signal[k] = (int16_t)p[SXL_CA_SIGNAL + (uint16_t)k];
    }
    s.length = sxl_get_u16(&p[SXL_CA_LENGTH]);
    s.decimation = sxl_get_u16(&p[SXL_CA_DECIMATION]);
    s.trigger = (capture_trigger_t)p[SXL_CA_TRIGGER];
    s.trigger_signal = (int16_t)p[SXL_CA_TRIG_SIGNAL];
    s.trigger_level = sxl_get_i16(&p[SXL_CA_TRIG_LEVEL]);
    s.pre_percent = p[SXL_CA_PRE];
    switch (capture_arm(&d->capture, &s)) {
    case CAPTURE_OK:
        return SXL_OK;
    case CAPTURE_ERR_NO_ROOM:
        return SXL_ERR_NO_ROOM;
    case CAPTURE_ERR_BUSY:
        return SXL_ERR_REFUSED;
    default:
        return SXL_ERR_VALUE;
    }
}

static uint16_t on_capture_status(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                  uint16_t rx_errors)
{
    const capture_t *c = &d->capture;
    uint16_t *out = &reply->payload[1];
    int16_t k;
    (void)req;
    (void)rx_errors;
    out[SXL_CS_STATE] = (uint16_t)c->state;
    CTL_COMPILER_BARRIER(); /* the fields after the state: never older than it */
    out[SXL_CS_CHANNELS] = (uint16_t)c->setup.n_channels;
    for (k = 0; k < CAPTURE_CHANNELS; k++) {
        out[SXL_CS_SIGNAL + (uint16_t)k] =
            (k < c->setup.n_channels) ? (uint16_t)c->setup.signal[k] : 0xFFu;
    }
    sxl_put_u16(&out[SXL_CS_LENGTH], c->setup.length);
    sxl_put_u16(&out[SXL_CS_DECIMATION], c->setup.decimation);
    sxl_put_u16(&out[SXL_CS_COUNT], c->count);
    sxl_put_u16(&out[SXL_CS_TRIGGER], c->trigger_index);
    sxl_put_u32(&out[SXL_CS_PERIOD], c->first_period);
    sxl_put_u32(&out[SXL_CS_TS_NS], (uint32_t)(d->params_bg.sample_time_s * 1.0e9f + 0.5f));
    reply->len = (uint16_t)(1u + SXL_CS_SIZE);
    return SXL_OK;
}

static uint16_t on_capture_read(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                uint16_t rx_errors)
{
    const int16_t ch = (int16_t)req->payload[SXL_CQ_CHANNEL];
    const uint16_t first = sxl_get_u16(&req->payload[SXL_CQ_FIRST]);
    uint16_t n = 0u;
    (void)rx_errors;
    if (ch >= d->capture.setup.n_channels) {
        return SXL_ERR_VALUE;
    }
    while (n < SXL_CR_MAX && (uint32_t)first + n < d->capture.count) {
        sxl_put_u16(&reply->payload[1 + SXL_CR_SAMPLES + 2u * n],
                    (uint16_t)capture_read(&d->capture, ch, (uint16_t)(first + n)));
        n++;
    }
    reply->payload[1 + SXL_CR_COUNT] = n;
    reply->len = (uint16_t)(1u + SXL_CR_SAMPLES + 2u * n);
    return SXL_OK;
}

static uint16_t on_capture_stop(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                uint16_t rx_errors)
{
    (void)req;
    (void)reply;
    (void)rx_errors;
    capture_stop(&d->capture);
    return SXL_OK;
}

/* Commissioning (commission_lists.h, on the wire as sxlink_commission.h maps it): each quantity's
 * scales. */
#define LINK_COMM_SCALE(id, number, name, step, unit, scale, xscale, extra)                        \
    CTL_FLOAT_LITERAL(scale),
#define LINK_COMM_XSCALE(id, number, name, step, unit, scale, xscale, extra)                       \
    CTL_FLOAT_LITERAL(xscale),
static const float link_comm_scale[COMM_Q_COUNT] = {SXL_COMM_QUANTITY_LIST(LINK_COMM_SCALE)};
static const float link_comm_xscale[COMM_Q_COUNT] = {SXL_COMM_QUANTITY_LIST(LINK_COMM_XSCALE)};
#undef LINK_COMM_SCALE
#undef LINK_COMM_XSCALE

static uint16_t on_commission_start(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                    uint16_t rx_errors)
{
    (void)reply;
    (void)rx_errors;
    switch (drive_request_commission(d, req->payload[SXL_CC_MASK],
                                     sxl_get_u16(&req->payload[SXL_CC_CURRENT]))) {
    case DRIVE_COMM_OK:
        return SXL_OK;
    case DRIVE_COMM_INVALID:
        return SXL_ERR_VALUE;
    default:
        return SXL_ERR_REFUSED; /* the status says why */
    }
}

static uint16_t on_commission_status(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                     uint16_t rx_errors)
{
    const comm_t *c = &d->comm;
    uint16_t *out = &reply->payload[1];
    (void)req;
    (void)rx_errors;
    out[SXL_CT_STATE] = (uint16_t)((uint16_t)c->state & 0xFFu);
    out[SXL_CT_STEP] = (uint16_t)((uint16_t)c->step & 0xFFu);
    out[SXL_CT_PROGRESS] = (uint16_t)(comm_progress_percent(c) & 0xFFu);
    out[SXL_CT_REASON] = (uint16_t)((uint16_t)c->reason & 0xFFu);
    out[SXL_CT_MASK] = (uint16_t)(c->mask & 0xFFu);
    sxl_put_u16(&out[SXL_CT_CURRENT], c->permille);
    sxl_put_u32(&out[SXL_CT_PERIODS], c->periods);
    reply->len = (uint16_t)(1u + SXL_CT_SIZE);
    return SXL_OK;
}

static uint16_t on_commission_result(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                     uint16_t rx_errors)
{
    const uint16_t q = req->payload[SXL_CQ2_QUANTITY];
    uint16_t *out = &reply->payload[1];
    const ident_result_t *r;
    (void)rx_errors;
    if (q >= (uint16_t)COMM_Q_COUNT) {
        return SXL_ERR_VALUE;
    }
    r = &d->comm.x.result[q];
    out[SXL_CR2_QUANTITY] = q;
    out[SXL_CR2_QUALITY] = (uint16_t)((uint16_t)r->quality & 0xFFu);
    out[SXL_CR2_REASON] = (uint16_t)((uint16_t)r->reason & 0xFFu);
    sxl_put_i32(&out[SXL_CR2_VALUE], float_to_i32(r->value * link_comm_scale[q]));
    sxl_put_i32(&out[SXL_CR2_SIGMA], float_to_i32(r->sigma * link_comm_scale[q]));
    sxl_put_i32(&out[SXL_CR2_EXTRA], float_to_i32(r->extra * link_comm_xscale[q]));
    reply->len = (uint16_t)(1u + SXL_CR2_SIZE);
    return SXL_OK;
}

static uint16_t on_commission_apply(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                    uint16_t rx_errors)
{
    uint16_t applied = 0u;
    (void)req;
    (void)rx_errors;
    switch (drive_commission_apply(d, &applied)) {
    case DRIVE_COMM_OK:
        sxl_put_u16(&reply->payload[1 + SXL_CA2_APPLIED], applied);
        reply->len = (uint16_t)(1u + SXL_CA2_SIZE);
        return SXL_OK;
    case DRIVE_COMM_BUSY:
        return SXL_ERR_BUSY;
    case DRIVE_COMM_REJECTED:
        return SXL_ERR_VALUE;
    default:
        return SXL_ERR_REFUSED;
    }
}

static uint16_t on_get_open_phase(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                  uint16_t rx_errors)
{
    (void)req;
    (void)rx_errors;
    drive_link_open_phase(d, &reply->payload[1]);
    reply->len = (uint16_t)(1u + SXL_OP_SIZE);
    return SXL_OK;
}

static uint16_t on_set_open_phase_action(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                         uint16_t rx_errors)
{
    (void)reply;
    (void)rx_errors;
    return drive_set_open_phase_action(d, (int16_t)req->payload[SXL_OA_ACTION],
                                       (int16_t)req->payload[SXL_OA_STRATEGY])
               ? SXL_OK
               : SXL_ERR_VALUE;
}

/* The time goes to the drive in seconds, and the drive's range check is the only one: the
 * wire's 1..60000 ms is what it accepts (0 ms is 0 s, refused; above 60000, above 60 s). A
 * division, not a multiplication by 0.001f, so that 60000 ms is exactly the drive's 60 s. */
static uint16_t on_set_torque_limited_action(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                             uint16_t rx_errors)
{
    const uint16_t stop_ms = sxl_get_u16(&req->payload[SXL_TL_STOP_MS]);
    (void)reply;
    (void)rx_errors;
    return drive_set_torque_limited_action(d, (int16_t)req->payload[SXL_TL_ACTION],
                                           (float)stop_ms / 1000.0f)
               ? SXL_OK
               : SXL_ERR_VALUE;
}

static uint16_t on_get_torque_limited(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                      uint16_t rx_errors)
{
    uint16_t *out = &reply->payload[1];
    (void)req;
    (void)rx_errors;
    out[SXL_TL_ACTION] = (uint16_t)((uint16_t)d->torque_limited_action & 0xFFu);
    /* at most 60 s (the setter's range): 60000 ms fits */
    sxl_put_u16(&out[SXL_TL_STOP_MS], (uint16_t)float_to_i32(d->torque_limited_stop_s * 1000.0f));
    out[SXL_TL_STOPPED] = d->torque_limited_stopped ? 1u : 0u;
    reply->len = (uint16_t)(1u + SXL_TL_SIZE);
    return SXL_OK;
}

static uint16_t on_isolate_leg(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                               uint16_t rx_errors)
{
    (void)reply;
    (void)rx_errors;
    if (req->payload[SXL_IL_LEG] > 5u) {
        return SXL_ERR_VALUE;
    }
    return drive_request_isolate_leg(d, (int16_t)req->payload[SXL_IL_LEG]) ? SXL_OK
                                                                           : SXL_ERR_REFUSED;
}

static uint16_t on_restore_legs(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                                uint16_t rx_errors)
{
    (void)req;
    (void)reply;
    (void)rx_errors;
    return drive_request_restore_legs(d) ? SXL_OK : SXL_ERR_REFUSED;
}

/* A session token no noise frame can be expected to carry: a 32-bit mix (murmur3's finaliser)
 * of the session count and the control period, never 0 (0 is "disarmed"). */
static uint32_t session_token(const drive_t *d)
{
    uint32_t x = (d->link_sessions * 0x9E3779B9u) ^ d->isr_count;
    x ^= x >> 16;
    x *= 0x85EBCA6Bu;
    x ^= x >> 13;
    x *= 0xC2B2AE35u;
    x ^= x >> 16;
    return (x != 0u) ? x : 1u;
}

static uint16_t on_arm(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply, uint16_t rx_errors)
{
    (void)req;
    (void)rx_errors;
    d->link_sessions++;
    d->link_token = session_token(d);
    sxl_put_u32(&reply->payload[1u + SXL_AR_TOKEN], d->link_token);
    reply->len = (uint16_t)(1u + SXL_AR_SIZE);
    return SXL_OK;
}

static uint16_t on_disarm(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                          uint16_t rx_errors)
{
    (void)req;
    (void)reply;
    (void)rx_errors;
    d->link_token = 0u;
    return SXL_OK;
}

/* A command that moves the motor: its payload starts with the armed session's token, which is
 * taken off here (in place) so that its handler sees its own payload. */
static bool take_token(const drive_t *d, sxl_frame_t *req)
{
    uint16_t i;
    if (req->len < SXL_TOKEN_BYTES || d->link_token == 0u ||
        sxl_get_u32(req->payload) != d->link_token) {
        return false;
    }
    req->len = (uint16_t)(req->len - SXL_TOKEN_BYTES);
    for (i = 0u; i < req->len; i++) {
        req->payload[i] = req->payload[i + SXL_TOKEN_BYTES];
    }
    return true;
}

/* indirect-call: drive_link_handle -> prefix on_ (the handlers of link_commands;
 * tools/stack_depth.py) */

#ifdef DRIVE_LINK_EXTRA_HANDLERS_HEADER
#include DRIVE_LINK_EXTRA_HANDLERS_HEADER /* a test build's handlers of SXL_EXTRA_COMMANDS */
#endif

/* The command list (sxlink_commands.h): code, request length, token, handler. */
#define LINK_COMMAND_ROW(name, code, handler, armed, request, reply, notes)                        \
    {SXL_CMD_##name, (uint16_t)request##_SIZE, (armed) != 0, on_##handler},
static const struct {
    uint16_t cmd, len;
    bool armed;
    link_handler_t handler;
} link_commands[SXL_COMMAND_COUNT] = {SXL_COMMAND_LIST(LINK_COMMAND_ROW)};
#undef LINK_COMMAND_ROW

void drive_link_handle(drive_t *d, sxl_frame_t *req, sxl_frame_t *reply, uint16_t rx_errors)
{
    uint16_t result = SXL_ERR_UNKNOWN;
    uint16_t k;
    reply->cmd = (uint16_t)((req->cmd | SXL_REPLY) & 0xFFu);
    reply->len = 1u;
    for (k = 0u; k < (uint16_t)(sizeof link_commands / sizeof link_commands[0]); k++) {
        if (link_commands[k].cmd == req->cmd && link_commands[k].armed && !take_token(d, req)) {
            result = SXL_ERR_NOT_ARMED;
            break;
        }
        if (link_commands[k].cmd == req->cmd) {
            result = (req->len != link_commands[k].len)
                         ? SXL_ERR_LENGTH
                         : link_commands[k].handler(d, req, reply, rx_errors);
            break;
        }
    }
    reply->payload[0] = result;
    if (result != SXL_OK) {
        reply->len = 1u;
    }
}
