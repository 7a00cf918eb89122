#include "pil_target.h"

#include "hal_cycles.h"
#include "hal_serial.h"
#include "hal_sim.h"
#include "measure/profile.h"

void pil_target_init(pil_target_t *t, const sim_ctl_ops_t *ops, uint16_t arith, uint16_t target)
{
    uint16_t k;
    t->ops = ops;
    t->arith = arith;
    t->target = target;
    sxl_decoder_init(&t->decoder);
    for (k = 0u; k < SIM_CTL_CONFIG_IMAGE_BYTES; k++) {
        t->image[k] = 0u;
    }
    t->initialised = false;
    t->steps = 0u;
    hal_sim_reset();
}

/* Call records (SXL_PIL_CALL_LIST) are checked whole before any runs: a bad list changes
 * nothing. */
static bool calls_valid(const uint16_t *p, uint16_t n)
{
    uint16_t pos = 0u;
    while (pos < n) {
        const int16_t args = sim_ctl_wire_call_args(p[pos]);
        if (args < 0 || (uint16_t)(pos + 1u + (uint16_t)args) > n) {
            return false;
        }
        pos = (uint16_t)(pos + 1u + (uint16_t)args);
    }
    return true;
}

static void call_run(const sim_ctl_ops_t *ops, uint16_t code, const uint16_t *a)
{
    unsigned applied;
    double gains[2];
    sim_fault_record_t record;
    switch (code) {
    case SXL_PIL_CALL_RUN:
        ops->request_run();
        break;
    case SXL_PIL_CALL_CLEAR:
        ops->request_clear();
        break;
    case SXL_PIL_CALL_SET_SPEED:
        ops->set_speed_rpm(sim_ctl_wire_real_of(sxl_get_u32(a)));
        break;
    case SXL_PIL_CALL_SET_TORQUE:
        ops->set_torque_nm(sim_ctl_wire_real_of(sxl_get_u32(a)));
        break;
    case SXL_PIL_CALL_OVERRUN:
        ops->report_overrun();
        break;
    case SXL_PIL_CALL_BACKGROUND:
        ops->background();
        break;
    case SXL_PIL_CALL_ISOLATE_LEG:
        (void)ops->isolate_leg((int)a[0]);
        break;
    case SXL_PIL_CALL_COMMISSION_START:
        (void)ops->commission_start((unsigned)sxl_get_u16(a), (unsigned)sxl_get_u16(&a[2]));
        break;
    case SXL_PIL_CALL_COMMISSION_APPLY:
        (void)ops->commission_apply(&applied, gains);
        break;
    case SXL_PIL_CALL_READ_FAULT_RECORD:
        (void)ops->read_fault_record(&record);
        break;
    default:
        break; /* not reached: calls_valid */
    }
}

static void calls_run(const sim_ctl_ops_t *ops, const uint16_t *p, uint16_t n)
{
    uint16_t pos = 0u;
    while (pos < n) {
        const uint16_t args = (uint16_t)sim_ctl_wire_call_args(p[pos]);
        call_run(ops, p[pos], &p[pos + 1u]);
        pos = (uint16_t)(pos + 1u + args);
    }
}

static uint16_t on_hello(const pil_target_t *t, sxl_frame_t *reply)
{
    reply->payload[1] = SXL_PIL_VERSION;
    reply->payload[2] = t->arith;
    reply->payload[3] = t->target;
    sxl_put_u32(&reply->payload[4], hal_cycles_per_second());
    reply->len = 1u + SXL_PIL_HELLO_BYTES;
    return SXL_OK;
}

static uint16_t on_config(pil_target_t *t, const sxl_frame_t *req)
{
    uint16_t offset;
    uint16_t k;
    if (req->len < 2u) {
        return SXL_ERR_LENGTH;
    }
    offset = sxl_get_u16(req->payload);
    if (req->len - 2u > SIM_CTL_CONFIG_IMAGE_BYTES ||
        offset > SIM_CTL_CONFIG_IMAGE_BYTES - (req->len - 2u)) {
        return SXL_ERR_VALUE;
    }
    for (k = 0u; k < req->len - 2u; k++) {
        t->image[offset + k] = req->payload[2u + k];
    }
    t->initialised = false; /* a changed image needs an INIT */
    return SXL_OK;
}

static uint16_t on_init(pil_target_t *t, const sxl_frame_t *req, sxl_frame_t *reply)
{
    sim_ctl_config_t cfg;
    const char *why = "";
    int rc;
    if (req->len != SXL_PIL_INIT_BYTES) {
        return SXL_ERR_LENGTH;
    }
    t->initialised = false;
    if (!sim_ctl_wire_apply_setup(req->payload)) {
        return SXL_ERR_VALUE;
    }
    sim_ctl_config_decode(t->image, &cfg);
    rc = t->ops->init(&cfg, &why);
    t->ops->profile();
    t->initialised = rc != 1; /* 2: configured, the drive in FAULT (as on the host) */
    t->steps = 0u;
    sxl_put_i16(&reply->payload[1], (int16_t)rc);
    reply->len = 3u;
    return SXL_OK;
}

/* The profile's stages this ISR ran (prof_stage_t ADC .. PWM; one it did not run, 0: its count
 * did not move) and its TOTAL. */
static void step_cycles(const uint32_t *counts_before, sim_ctl_wire_out_t *out)
{
    uint16_t k;
    for (k = 0u; k < SXL_PIL_OUT_STAGE_COUNT; k++) {
        const prof_stat_t *s = &drive_profile.stage[PROF_ADC + k];
        out->stage[k] = (s->count != counts_before[k]) ? s->last : 0u;
    }
    out->cycles = drive_profile.stage[PROF_TOTAL].last;
}

static uint16_t on_step(pil_target_t *t, const sxl_frame_t *req, sxl_frame_t *reply)
{
    sim_ctl_wire_out_t out;
    sim_ctl_status_t st;
    uint32_t counts[SXL_PIL_OUT_STAGE_COUNT];
    uint16_t k;
    if (!t->initialised) {
        return SXL_ERR_REFUSED;
    }
    if (req->len < SXL_PIL_IN_BYTES) {
        return SXL_ERR_LENGTH;
    }
    if (!calls_valid(&req->payload[SXL_PIL_IN_BYTES], (uint16_t)(req->len - SXL_PIL_IN_BYTES))) {
        return SXL_ERR_VALUE;
    }
    calls_run(t->ops, &req->payload[SXL_PIL_IN_BYTES], (uint16_t)(req->len - SXL_PIL_IN_BYTES));
    out.seq = sim_ctl_wire_take_inputs(req->payload, &hal_sim_bus);
    for (k = 0u; k < SXL_PIL_OUT_STAGE_COUNT; k++) {
        counts[k] = drive_profile.stage[PROF_ADC + k].count;
    }
    t->ops->isr();
    t->steps++;
    sim_ctl_wire_outputs_of_bus(&hal_sim_bus, &out);
    t->ops->status(&st); /* outside the ISR's count: the faults latched, not only the code */
    out.state = (uint16_t)st.state;
    out.faults = (uint16_t)st.faults_latched;
    step_cycles(counts, &out);
    sim_ctl_wire_put_outputs(&out, reply->payload);
    reply->len = SXL_PIL_OUT_BYTES;
    return SXL_OK;
}

static uint16_t on_calls(const pil_target_t *t, const sxl_frame_t *req)
{
    if (!t->initialised) {
        return SXL_ERR_REFUSED;
    }
    if (!calls_valid(req->payload, req->len)) {
        return SXL_ERR_VALUE;
    }
    calls_run(t->ops, req->payload, req->len);
    return SXL_OK;
}

void pil_target_handle(pil_target_t *t, const sxl_frame_t *req)
{
    sxl_frame_t *reply = &t->reply;
    uint16_t result;
    reply->cmd = (uint16_t)(req->cmd | SXL_REPLY);
    reply->len = 1u;
    switch (req->cmd) {
    case SXL_CMD_PIL_HELLO:
        result = on_hello(t, reply);
        break;
    case SXL_CMD_PIL_CONFIG:
        result = on_config(t, req);
        break;
    case SXL_CMD_PIL_INIT:
        result = on_init(t, req, reply);
        break;
    case SXL_CMD_PIL_CALLS:
        result = on_calls(t, req);
        break;
    case SXL_CMD_PIL_STEP:
        result = on_step(t, req, reply);
        break;
    default:
        result = SXL_ERR_UNKNOWN;
        break;
    }
    if (result != SXL_OK) {
        reply->len = 1u;
    }
    reply->payload[0] = result;
}

static void send_reply(pil_target_t *t)
{
    const uint16_t n =
        sxl_encode(t->reply.cmd, t->reply.payload, t->reply.len, t->tx, SXL_MAX_FRAME);
    uint16_t k;
    for (k = 0u; k < n; k++) {
        while (!hal_serial_write(t->tx[k])) {
            /* the transmitter drains by itself */
        }
    }
}

void pil_target_poll(pil_target_t *t)
{
    uint16_t byte;
    while (hal_serial_read(&byte)) {
        if (sxl_decoder_push(&t->decoder, byte, &t->request) == SXL_RX_FRAME) {
            pil_target_handle(t, &t->request);
            send_reply(t);
        }
    }
}
