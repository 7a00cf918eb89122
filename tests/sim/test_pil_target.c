/*
 * Processor-in-the-loop, the parts that need no target: the configuration's byte image (every
 * field of the list, an INT held to int16), a period's inputs and outputs through their frames,
 * the call records' lengths, the comparison (fixed: nothing may differ; float: a duty within
 * tolerance) and its first difference; and the target's service on this host (firmware/pil's
 * pil_target.c over the fixed bridge): HELLO, refusals (STEP before INIT, a bad length, an
 * image past its end, an unknown call, which runs none of the calls before it), INIT, STEP
 * with its inputs taken and its sequence echoed.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "bridge/sim_ctl_wire.h"
#include "hal_sim.h"
#include "pil/pil_stats.h"
#include "pil_target.h"
#include "run/sim_config.h"
#include "run/sim_run_state.h"

static void test_config_image_round_trip(void **state)
{
    sim_ctl_config_t a;
    sim_ctl_config_t b;
    uint16_t image[SIM_CTL_CONFIG_IMAGE_BYTES];
    int n = 0;
    (void)state;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    /* a value of its own in every field: a swapped or shifted field shows */
#define FILL_INT(name) a.name = -(++n);
#define FILL_REAL(name) a.name = 0.25 + (double)(++n);
#define FILL_BOOL(name) a.name = ((++n) % 2) == 0;
#define FILL(kind, name) FILL_##kind(name)
    SIM_CTL_CONFIG_FIELDS(FILL)
    a.pole_pairs = 100000; /* beyond int16: held */
    sim_ctl_config_encode(&a, image);
    sim_ctl_config_decode(image, &b);
#define CHECK(kind, name)                                                                          \
    if (strcmp(#name, "pole_pairs") != 0) {                                                        \
        assert_true(a.name == b.name);                                                             \
    }
    SIM_CTL_CONFIG_FIELDS(CHECK)
    assert_int_equal(b.pole_pairs, INT16_MAX);
    a.lambda = 0.1; /* not a single: rounded */
    sim_ctl_config_encode(&a, image);
    sim_ctl_config_decode(image, &b);
    assert_true(b.lambda == (double)(float)0.1);
}

static void test_inputs_and_outputs_round_trip(void **state)
{
    hal_sim_bus_t in;
    hal_sim_bus_t got;
    uint16_t payload[SXL_MAX_PAYLOAD];
    sim_ctl_wire_out_t o;
    sim_ctl_wire_out_t back;
    int k;
    (void)state;
    memset(&back, 0, sizeof back); /* the padding too: the structs are compared whole */
    memset(&in, 0, sizeof in);
    memset(&got, 0, sizeof got);
    for (k = 0; k < 6; k++) {
        in.adc.phase[k] = (uint16_t)(100 * k + 4095 * (k == 5));
    }
    in.adc.vdc = 3071u;
    in.encoder.elec_angle = 0xDEADBEEFu;
    in.encoder.mech_speed_q16 = -123456;
    in.encoder.position = INT32_MIN + 5;
    in.encoder.healthy = true;
    in.adc_fresh = true;
    in.forced_off = true;
    sim_ctl_wire_put_inputs(&in, 0xBEEFu, payload);
    assert_int_equal(sim_ctl_wire_take_inputs(payload, &got), 0xBEEF);
    assert_memory_equal(&got.adc, &in.adc, sizeof in.adc);
    assert_int_equal(got.encoder.elec_angle, in.encoder.elec_angle);
    assert_int_equal(got.encoder.mech_speed_q16, in.encoder.mech_speed_q16);
    assert_int_equal(got.encoder.position, in.encoder.position);
    assert_true(got.encoder.healthy && !got.encoder.index_seen && got.adc_fresh && got.forced_off &&
                !got.hw_trip && !got.encoder_homing_lost);
    memset(&o, 0, sizeof o);
    o.seq = 7u;
    o.duty[3] = 32768u;
    o.flags = SXL_PIL_OUT_FORCED_OFF | SXL_PIL_OUT_HOMING_LOST;
    o.isolated = 0x04u;
    o.encoder_offset = 0x80000001u;
    o.state = 3u;
    o.faults = 15u;
    o.cycles = 123456789u;
    o.stage[0] = 0xFFFFFFu + 5u; /* beyond 24 bits: held */
    o.stage[5] = 42u;
    sim_ctl_wire_put_outputs(&o, payload);
    sim_ctl_wire_get_outputs(payload, &back);
    o.stage[0] = 0xFFFFFFu;
    assert_memory_equal(&o, &back, sizeof o);
}

static void test_call_lengths(void **state)
{
    (void)state;
    assert_int_equal(sim_ctl_wire_call_args(SXL_PIL_CALL_RUN), 0);
    assert_int_equal(sim_ctl_wire_call_args(SXL_PIL_CALL_SET_SPEED), 4);
    assert_int_equal(sim_ctl_wire_call_args(SXL_PIL_CALL_ISOLATE_LEG), 1);
    assert_int_equal(sim_ctl_wire_call_args(SXL_PIL_CALL_COMMISSION_START), 4);
    assert_int_equal(sim_ctl_wire_call_args(SXL_PIL_CALL_COUNT), -1);
}

static void test_comparison(void **state)
{
    sim_ctl_wire_out_t a;
    sim_ctl_wire_out_t b;
    unsigned diff = 99u;
    pil_stats_t st;
    hal_sim_bus_t in;
    sim_pil_summary_t s;
    char err[64];
    (void)state;
    memset(&a, 0, sizeof a);
    memset(&in, 0, sizeof in);
    b = a;
    assert_true(pil_outputs_agree(&a, &b, 0u, &diff));
    assert_int_equal(diff, 0);
    b.duty[2] = 1u;
    assert_false(pil_outputs_agree(&a, &b, 0u, &diff)); /* fixed: one count is a difference */
    assert_true(pil_outputs_agree(&a, &b, SIM_PIL_FLOAT_DUTY_TOL, &diff));
    assert_int_equal(diff, 1);
    b.duty[2] = 0u;
    b.state = 4u;
    assert_false(pil_outputs_agree(&a, &b, 1000u, &diff)); /* a state never within tolerance */
    assert_int_equal(pil_stats_open(&st, NULL, err, sizeof err), 0);
    pil_stats_add(&st, &in, &a, &a, 0.0);
    pil_stats_add(&st, &in, &a, &b, 0.0001);
    pil_stats_add(&st, &in, &a, &b, 0.0002);
    pil_stats_close(&st, 1.0, &s);
    assert_int_equal(s.steps, 3);
    assert_int_equal(s.differing, 2);
    assert_int_equal(s.first_diff, 1);
    assert_non_null(strstr(s.first_diff_text, "period 1 "));
    assert_non_null(strstr(s.first_diff_text, "state 4"));
}

/* The reference machine's DDC as the simulator configures it for a run at 10 kHz. */
static void reference_config(sim_ctl_config_t *cc)
{
    sim_config_t c;
    sim_config_default(&c);
    c.controller = 0;
    sim_controller_config(&c, &c.plant, 1e-4, 0.0, cc);
}

/* The fixed bridge with its background share and run request counted: which calls ran. */
static sim_ctl_ops_t recording;
static int backgrounds, run_requests;
static void count_background(void)
{
    backgrounds++;
    sim_ctl_ops_fixed.background();
}
static void count_run(void)
{
    run_requests++;
    sim_ctl_ops_fixed.request_run();
}

/* A request answered by the service; its result byte. */
static uint16_t ask(pil_target_t *t, uint16_t cmd, const uint16_t *payload, uint16_t len)
{
    sxl_frame_t req;
    req.cmd = cmd;
    req.len = len;
    if (len) {
        memcpy(req.payload, payload, len * sizeof payload[0]);
    }
    pil_target_handle(t, &req);
    assert_int_equal(t->reply.cmd, cmd | SXL_REPLY);
    return t->reply.payload[0];
}

static void test_target_service(void **state)
{
    static pil_target_t t;
    uint16_t p[SXL_MAX_PAYLOAD];
    uint16_t image[SIM_CTL_CONFIG_IMAGE_BYTES];
    sim_ctl_config_t cc;
    hal_sim_bus_t setup;
    uint16_t at;
    (void)state;
    recording = sim_ctl_ops_fixed;
    recording.background = count_background;
    recording.request_run = count_run;
    pil_target_init(&t, &recording, SXL_PIL_ARITH_FIXED, SXL_PIL_TARGET_MPS2);
    assert_int_equal(ask(&t, SXL_CMD_PIL_HELLO, NULL, 0u), SXL_OK);
    assert_int_equal(t.reply.payload[1], SXL_PIL_VERSION);
    assert_int_equal(t.reply.payload[3], SXL_PIL_TARGET_MPS2);
    assert_int_equal(ask(&t, 0x01u, NULL, 0u), SXL_ERR_UNKNOWN); /* a product command */
    memset(p, 0, sizeof p);
    assert_int_equal(ask(&t, SXL_CMD_PIL_STEP, p, SXL_PIL_IN_BYTES), SXL_ERR_REFUSED);
    reference_config(&cc);
    sim_ctl_config_encode(&cc, image);
    for (at = 0u; at < SIM_CTL_CONFIG_IMAGE_BYTES; at = (uint16_t)(at + SXL_PIL_CONFIG_CHUNK)) {
        const unsigned left = (unsigned)SIM_CTL_CONFIG_IMAGE_BYTES - at;
        const uint16_t n = (uint16_t)((left < SXL_PIL_CONFIG_CHUNK) ? left : SXL_PIL_CONFIG_CHUNK);
        sxl_put_u16(p, at);
        memcpy(&p[2], &image[at], n * sizeof image[0]);
        assert_int_equal(ask(&t, SXL_CMD_PIL_CONFIG, p, (uint16_t)(2u + n)), SXL_OK);
    }
    sxl_put_u16(p, (uint16_t)(SIM_CTL_CONFIG_IMAGE_BYTES - 1u));
    assert_int_equal(ask(&t, SXL_CMD_PIL_CONFIG, p, 4u), SXL_ERR_VALUE); /* past the end */
    sxl_put_u16(p, 0u);
    memcpy(&p[2], image, 2u * sizeof image[0]);
    assert_int_equal(ask(&t, SXL_CMD_PIL_CONFIG, p, 4u), SXL_OK); /* the image unchanged */
    memset(&setup, 0, sizeof setup);
    setup.carrier_hz = 10000u;
    setup.encoder_lines = 2500u;
    setup.encoder_pole_pairs = (uint16_t)cc.pole_pairs;
    sim_ctl_wire_put_setup(&setup, p);
    assert_int_equal(ask(&t, SXL_CMD_PIL_INIT, p, SXL_PIL_INIT_BYTES - 1u), SXL_ERR_LENGTH);
    assert_int_equal(ask(&t, SXL_CMD_PIL_INIT, p, SXL_PIL_INIT_BYTES), SXL_OK);
    assert_int_equal(sxl_get_i16(&t.reply.payload[1]), 0);
    assert_int_equal(hal_sim_bus.carrier_hz, 10000u);
    /* a STEP whose calls end in an unknown code: refused, none of them run, no period */
    memset(p, 0, sizeof p);
    p[SXL_PIL_IN_BYTES] = SXL_PIL_CALL_BACKGROUND;
    p[SXL_PIL_IN_BYTES + 1u] = SXL_PIL_CALL_RUN;
    p[SXL_PIL_IN_BYTES + 2u] = SXL_PIL_CALL_COUNT;
    assert_int_equal(ask(&t, SXL_CMD_PIL_STEP, p, SXL_PIL_IN_BYTES + 3u), SXL_ERR_VALUE);
    assert_int_equal(t.steps, 0u);
    assert_int_equal(backgrounds, 0);
    assert_int_equal(run_requests, 0);
    assert_int_equal(ask(&t, SXL_CMD_PIL_CALLS, &p[SXL_PIL_IN_BYTES], 3u), SXL_ERR_VALUE);
    assert_int_equal(backgrounds + run_requests, 0);
    p[SXL_PIL_IN_BYTES] = SXL_PIL_CALL_SET_SPEED; /* its REAL cut short */
    assert_int_equal(ask(&t, SXL_CMD_PIL_STEP, p, SXL_PIL_IN_BYTES + 3u), SXL_ERR_VALUE);
    assert_int_equal(ask(&t, SXL_CMD_PIL_STEP, p, SXL_PIL_IN_BYTES - 1u), SXL_ERR_LENGTH);
    /* a period with a fresh conversion at mid scale */
    hal_sim_bus.adc.vdc = 2000u;
    for (at = 0u; at < 6u; at++) {
        hal_sim_bus.adc.phase[at] = 2048u;
    }
    hal_sim_bus.adc_fresh = true;
    sim_ctl_wire_put_inputs(&hal_sim_bus, 0x1234u, p);
    p[SXL_PIL_IN_BYTES] = SXL_PIL_CALL_BACKGROUND;
    assert_int_equal(ask(&t, SXL_CMD_PIL_STEP, p, SXL_PIL_IN_BYTES + 1u), SXL_OK);
    assert_int_equal(t.reply.len, SXL_PIL_OUT_BYTES);
    assert_int_equal(sxl_get_u16(&t.reply.payload[SXL_PIL_OUT_SEQ]), 0x1234);
    assert_int_equal(t.steps, 1u);
    assert_int_equal(backgrounds, 1);    /* the call ran, once, before the period */
    assert_false(hal_sim_bus.adc_fresh); /* the period read it */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_config_image_round_trip),
        cmocka_unit_test(test_inputs_and_outputs_round_trip),
        cmocka_unit_test(test_call_lengths),
        cmocka_unit_test(test_comparison),
        cmocka_unit_test(test_target_service),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
