#include "drive_link.h"

#include "ctl_pu.h"
#include "hal_pwm.h"
#include "profile.h"

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

void drive_link_status(const drive_t *d, uint16_t rx_errors, uint16_t *out)
{
    const ctl_diag_t *diag = ctl_diag(&d->ctl);
    const float torque_scale = (float)(CTL_BASE_TORQUE_NM * 1000.0);
    uint16_t flags = 0u;
    /* rev/s Q16 -> 0.1 r/min: * 600 / 65536 */
    const int64_t speed_01rpm = ((int64_t)d->encoder.mech_speed_q16 * 600) / 65536;

    if (d->encoder.healthy) {
        flags |= SXL_FLAG_ENCODER_OK;
    }
    if (hal_pwm_is_off()) {
        flags |= SXL_FLAG_PWM_OFF;
    }
    if (d->ctl.shadow_pending) {
        flags |= SXL_FLAG_PARAMS_PENDING;
    }
    out[SXL_ST_STATE] = (uint16_t)((uint16_t)d->state & 0xFFu);
    out[SXL_ST_FAULT] = (uint16_t)((uint16_t)d->fault & 0xFFu);
    out[SXL_ST_FLAGS] = flags;
    out[SXL_ST_CONTROLLER] = (uint16_t)((uint16_t)d->ctl.params.controller & 0xFFu);
    sxl_put_i32(&out[SXL_ST_SPEED], (int32_t)speed_01rpm);
    sxl_put_i32(&out[SXL_ST_SPEED_REF], float_to_i32(d->speed_ref_rpm * 10.0f));
    sxl_put_i32(&out[SXL_ST_TORQUE], float_to_i32(ctl_to_float(diag->torque_est) * torque_scale));
    sxl_put_i32(&out[SXL_ST_TORQUE_REF],
                float_to_i32(ctl_to_float(diag->torque_ref) * torque_scale));
    sxl_put_u32(&out[SXL_ST_LAMBDA],
                (uint32_t)float_to_i32(d->ctl.params.lambda_nm_per_wb * 1000.0f));
    sxl_put_u32(&out[SXL_ST_ISR_COUNT], d->isr_count);
    sxl_put_u32(&out[SXL_ST_ISR_MAX], d->isr_cycles_max);
    sxl_put_u16(&out[SXL_ST_RX_ERRORS], rx_errors);
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
    ctl_params_t p;
    uint32_t lambda_milli;
    if (req->len != 5u) {
        return SXL_ERR_LENGTH;
    }
    lambda_milli = sxl_get_u32(&req->payload[1]);
    if (req->payload[0] > SXL_CONTROLLER_MPTC13 || lambda_milli > DRIVE_LINK_MAX_LAMBDA_MILLI) {
        return SXL_ERR_VALUE;
    }
    p = d->params_bg;
    p.controller = (ctl_controller_t)req->payload[0];
    p.lambda_nm_per_wb = (float)lambda_milli * 0.001f;
    return drive_request_params(d, &p) ? SXL_OK : SXL_ERR_VALUE;
}

void drive_link_handle(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply, uint16_t rx_errors)
{
    uint16_t result = SXL_OK;
    reply->cmd = (uint16_t)((req->cmd | SXL_REPLY) & 0xFFu);
    reply->len = 1u;

    switch (req->cmd) {
    case SXL_CMD_PING:
        if (req->len != 0u) {
            result = SXL_ERR_LENGTH;
            break;
        }
        reply->payload[1] = SXL_VERSION;
        reply->len = 2u;
        break;
    case SXL_CMD_GET_STATUS:
        if (req->len != 0u) {
            result = SXL_ERR_LENGTH;
            break;
        }
        drive_link_status(d, rx_errors, &reply->payload[1]);
        reply->len = (uint16_t)(1u + SXL_ST_SIZE);
        break;
    case SXL_CMD_GET_PROFILE:
        if (req->len != 1u) {
            result = SXL_ERR_LENGTH;
        } else if (req->payload[0] >= (uint16_t)PROF_STAGES) {
            result = SXL_ERR_VALUE;
        } else {
            drive_link_profile(req->payload[0], &reply->payload[1]);
            reply->len = (uint16_t)(1u + SXL_PF_SIZE);
        }
        break;
    case SXL_CMD_SET_SPEED: {
        int32_t v;
        if (req->len != 4u) {
            result = SXL_ERR_LENGTH;
            break;
        }
        v = sxl_get_i32(req->payload);
        if (v > DRIVE_LINK_MAX_SPEED_01RPM || v < -DRIVE_LINK_MAX_SPEED_01RPM) {
            result = SXL_ERR_VALUE;
            break;
        }
        drive_set_speed_ref_rpm(d, (float)v * 0.1f);
        break;
    }
    case SXL_CMD_SET_TORQUE: {
        int32_t v;
        if (req->len != 4u) {
            result = SXL_ERR_LENGTH;
            break;
        }
        v = sxl_get_i32(req->payload);
        if (v > DRIVE_LINK_MAX_TORQUE_MNM || v < -DRIVE_LINK_MAX_TORQUE_MNM) {
            result = SXL_ERR_VALUE;
            break;
        }
        drive_set_torque_ref_nm(d, (float)v * 0.001f);
        break;
    }
    case SXL_CMD_RUN:
        if (req->len != 0u) {
            result = SXL_ERR_LENGTH;
        } else if (d->state != DRIVE_STATE_READY || !d->encoder.healthy) {
            result = SXL_ERR_REFUSED;
        } else {
            drive_request_run(d);
        }
        break;
    case SXL_CMD_STOP:
        if (req->len != 0u) {
            result = SXL_ERR_LENGTH;
        } else {
            drive_request_stop(d);
        }
        break;
    case SXL_CMD_CLEAR_FAULT:
        if (req->len != 0u) {
            result = SXL_ERR_LENGTH;
        } else if (d->state != DRIVE_STATE_FAULT) {
            result = SXL_ERR_REFUSED;
        } else {
            drive_request_clear_fault(d);
        }
        break;
    case SXL_CMD_SET_CONTROLLER:
        result = handle_set_controller(d, req);
        break;
    default:
        result = SXL_ERR_UNKNOWN;
        break;
    }
    reply->payload[0] = result;
    if (result != SXL_OK) {
        reply->len = 1u;
    }
}
