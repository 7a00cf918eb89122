/* The frames of a PIL session, see pil_session.h. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */

#include "pil_session.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

static long session_ms(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t);
    return (long)t.tv_sec * 1000L + t.tv_nsec / 1000000L;
}

static const char *pil_command_name(uint16_t cmd)
{
#define PIL_SESSION_NAME(name, code, notes)                                                        \
    if (cmd == (uint16_t)(code)) {                                                                 \
        return #name;                                                                              \
    }
    SXL_PIL_COMMAND_LIST(PIL_SESSION_NAME)
#undef PIL_SESSION_NAME
    return "?";
}

/* One request and its reply (the frame whose command is the request's | SXL_REPLY), result ok. */
static int exchange(pil_session_t *s, uint16_t cmd, const uint16_t *payload, uint16_t len,
                    sxl_frame_t *reply)
{
    uint16_t tx[SXL_MAX_FRAME];
    const uint16_t n = sxl_encode(cmd, payload, len, tx, SXL_MAX_FRAME);
    const int limit = (cmd == SXL_CMD_PIL_HELLO) ? PIL_SESSION_HELLO_MS : PIL_SESSION_TIMEOUT_MS;
    const long deadline = session_ms() + limit; /* noise or other frames do not extend it */
    if (n == 0u || pil_port_write(&s->port, tx, n) != 0) {
        (void)snprintf(s->err, sizeof s->err, "PIL: cannot send %s to %.200s",
                       pil_command_name(cmd), s->port.path);
        return -1;
    }
    while (session_ms() < deadline) {
        uint8_t buf[256];
        const int got = pil_port_read(&s->port, buf, sizeof buf, 100);
        int k;
        if (got < 0) {
            (void)snprintf(
                s->err, sizeof s->err, "PIL: the line to %.100s failed during %s%s%.200s",
                s->port.path, pil_command_name(cmd),
                s->port.child_said[0] ? "; the emulator said: " : "", s->port.child_said);
            return -1;
        }
        for (k = 0; k < got; k++) {
            if (sxl_decoder_push(&s->decoder, buf[k], reply) == SXL_RX_FRAME &&
                reply->cmd == (uint16_t)(cmd | SXL_REPLY)) {
                if (reply->len == 0u || reply->payload[0] != SXL_OK) {
                    (void)snprintf(s->err, sizeof s->err, "PIL: the target answered %s with '%s'",
                                   pil_command_name(cmd),
                                   sxl_result_name(reply->len ? reply->payload[0] : 0xFFu));
                    return -1;
                }
                return 0;
            }
        }
    }
    (void)snprintf(s->err, sizeof s->err, "PIL: no answer to %s from %.200s within %d s",
                   pil_command_name(cmd), s->port.path, limit / 1000);
    return -1;
}

int pil_session_open(pil_session_t *s, const char *target, const char *arith)
{
    sxl_frame_t reply;
    memset(s, 0, sizeof *s);
    sxl_decoder_init(&s->decoder);
    if (pil_port_open(&s->port, target, arith, s->err, sizeof s->err) != 0) {
        return -1;
    }
    if (exchange(s, SXL_CMD_PIL_HELLO, NULL, 0u, &reply) != 0) {
        return -1;
    }
    if (reply.len < 1u + SXL_PIL_HELLO_BYTES || reply.payload[1] != SXL_PIL_VERSION) {
        (void)snprintf(s->err, sizeof s->err, "PIL: %s speaks another PIL version (%u, not %u)",
                       target, (unsigned)(reply.len > 1u ? reply.payload[1] : 0u), SXL_PIL_VERSION);
        return -1;
    }
    s->version = reply.payload[1];
    s->arith = reply.payload[2];
    s->target = reply.payload[3];
    s->counter_hz = sxl_get_u32(&reply.payload[4]);
    if ((s->arith == SXL_PIL_ARITH_FLOAT) != (strcmp(arith, "float") == 0)) {
        (void)snprintf(s->err, sizeof s->err,
                       "PIL: the target's image is the %s build, the run asks for --arith %s",
                       (s->arith == SXL_PIL_ARITH_FLOAT) ? "float" : "fixed", arith);
        return -1;
    }
    return 0;
}

int pil_session_init(pil_session_t *s, const sim_ctl_config_t *cfg, const hal_sim_bus_t *bus,
                     int *rc)
{
    uint16_t image[SIM_CTL_CONFIG_IMAGE_BYTES];
    uint16_t payload[SXL_MAX_PAYLOAD];
    sxl_frame_t reply;
    uint16_t at;
    sim_ctl_config_encode(cfg, image);
    for (at = 0u; at < SIM_CTL_CONFIG_IMAGE_BYTES; at = (uint16_t)(at + SXL_PIL_CONFIG_CHUNK)) {
        const uint16_t left = (uint16_t)(SIM_CTL_CONFIG_IMAGE_BYTES - at);
        const uint16_t n = (left < SXL_PIL_CONFIG_CHUNK) ? left : SXL_PIL_CONFIG_CHUNK;
        sxl_put_u16(payload, at);
        memcpy(&payload[2], &image[at], n * sizeof image[0]);
        if (exchange(s, SXL_CMD_PIL_CONFIG, payload, (uint16_t)(2u + n), &reply) != 0) {
            return -1;
        }
    }
    sim_ctl_wire_put_setup(bus, payload);
    if (exchange(s, SXL_CMD_PIL_INIT, payload, SXL_PIL_INIT_BYTES, &reply) != 0) {
        return -1;
    }
    *rc = (reply.len >= 3u) ? (int)sxl_get_i16(&reply.payload[1]) : -1;
    return 0;
}

int pil_session_calls(pil_session_t *s, const uint16_t *calls, uint16_t n)
{
    sxl_frame_t reply;
    uint16_t start = 0u;
    while (start < n) {
        uint16_t end = start;
        while (end < n) { /* whole records up to the payload's size */
            const uint16_t next =
                (uint16_t)(end + 1u + (uint16_t)sim_ctl_wire_call_args(calls[end]));
            if ((uint16_t)(next - start) > SXL_MAX_PAYLOAD) {
                break;
            }
            end = next;
        }
        if (exchange(s, SXL_CMD_PIL_CALLS, &calls[start], (uint16_t)(end - start), &reply) != 0) {
            return -1;
        }
        start = end;
    }
    return 0;
}

int pil_session_step(pil_session_t *s, const hal_sim_bus_t *bus, uint16_t seq,
                     const uint16_t *calls, uint16_t n, sim_ctl_wire_out_t *out)
{
    uint16_t payload[SXL_MAX_PAYLOAD];
    sxl_frame_t reply;
    sim_ctl_wire_put_inputs(bus, seq, payload);
    memcpy(&payload[SXL_PIL_IN_BYTES], calls, n * sizeof calls[0]);
    if (exchange(s, SXL_CMD_PIL_STEP, payload, (uint16_t)(SXL_PIL_IN_BYTES + n), &reply) != 0) {
        return -1;
    }
    if (reply.len != SXL_PIL_OUT_BYTES) {
        (void)snprintf(s->err, sizeof s->err, "PIL: a STEP reply of %u bytes, not %u",
                       (unsigned)reply.len, SXL_PIL_OUT_BYTES);
        return -1;
    }
    sim_ctl_wire_get_outputs(reply.payload, out);
    if (out->seq != seq) {
        (void)snprintf(s->err, sizeof s->err, "PIL: the reply to step %u carries step %u",
                       (unsigned)seq, (unsigned)out->seq);
        return -1;
    }
    return 0;
}

void pil_session_close(pil_session_t *s) { pil_port_close(&s->port); }
