/*
 * Fuzz target for the whole drive as the board sees it (libFuzzer entry point): arbitrary
 * serial bytes and CRC-valid request frames through the frame decoder and drive_link_handle,
 * run-time parameter sets, interleaved with control periods that carry arbitrary ADC words,
 * encoder samples, missing conversions and hardware trips, on the drive application and the
 * fixed-point control core over the simulator HAL. After every step:
 *   - the PWM is off in every state but RUN and COMMISSION (a sequence that ends, fails or is
 *     stopped leaves it off);
 *   - FAULT is left only through a clear request, RUN entered only from READY on a run
 *     request, COMMISSION only from READY on a commissioning request, and COMMISSION means
 *     a sequence running;
 *   - every reply encodes, and decodes back to itself;
 *   - the fault log holds at most its size, its records come out in order, each with a
 *     fault bit set and a period not in the future;
 *   - the refusal fields name known reasons;
 *   - an isolated leg stays isolated in the HAL and is never commanded on.
 * A violation aborts (libFuzzer reports it); the sanitizers catch the rest.
 *
 * The first input byte chooses the start: power-up (INIT -> CALIBRATE) or a snapshot taken
 * once after a clean calibration, so short inputs reach READY, RUN and FAULT.
 *
 * Tags 248 and up (the others keep the meaning the committed corpus chose them with) add:
 *   - periods on a plant: the simulator's machine, inverter, ADC and encoder (host_sim)
 *     answering the duties the drive writes, so the commissioning sequence's checks pass
 *     and it advances step by step, RUN turns the motor, and an opened phase or a frozen
 *     converter trips the drive as on the bench;
 *   - capture commands with valid-looking setups (a signal and trigger from small ranges).
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "drive/drive.h"
#include "service/drive_link.h"
#include "hal_board.h"
#include "hal_sim.h"
#include "plant/fault_inject.h"
#include "plant/inverter.h"
#include "plant/plant.h"
#include "plant/sim_adc.h"
#include "plant/sim_encoder.h"
#include "measure/profile.h"
#include "sxlink.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);

typedef struct {
    const unsigned char *p;
    size_t left;
} stream_t;

static uint16_t take8(stream_t *s)
{
    uint16_t v = 0u;
    if (s->left > 0u) {
        v = *s->p;
        s->p++;
        s->left--;
    }
    return v;
}

static uint16_t take16(stream_t *s)
{
    const uint16_t hi = take8(s);
    return (uint16_t)((uint16_t)(hi << 8) | take8(s));
}

static uint32_t take32(stream_t *s)
{
    uint32_t v = 0u;
    int16_t k;
    for (k = 0; k < 4; k++) {
        v = (v << 8) | take8(s);
    }
    return v;
}

static float take_float(stream_t *s)
{
    const uint32_t bits = take32(s);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static drive_t drive;
static sxl_decoder_t rx;
static uint32_t last_record_period; /* records must come out in order */

static void check(int condition)
{
    if (!condition) {
        abort();
    }
}

/* The reply must encode, and the encoded frame decode back to it. */
static void check_reply(const sxl_frame_t *reply)
{
    uint16_t bytes[SXL_MAX_FRAME];
    sxl_decoder_t dec;
    sxl_frame_t back;
    sxl_rx_t r = SXL_RX_NONE;
    uint16_t i;
    const uint16_t n =
        sxl_encode(reply->cmd, reply->payload, reply->len, bytes, (uint16_t)SXL_MAX_FRAME);
    check(n > 0u);
    sxl_decoder_init(&dec);
    for (i = 0u; i < n; i++) {
        r = sxl_decoder_push(&dec, bytes[i], &back);
    }
    check(r == SXL_RX_FRAME && back.cmd == reply->cmd && back.len == reply->len);
    check(memcmp(back.payload, reply->payload, reply->len * sizeof reply->payload[0]) == 0);
}

/* A fault record read over the link: in order, a fault bit set, not from the future. */
static void check_fault_record(const sxl_frame_t *reply)
{
    if (reply->cmd != (SXL_CMD_GET_FAULT_RECORD | SXL_REPLY) || reply->payload[0] != SXL_OK ||
        reply->payload[1u + SXL_FR_PRESENT] == 0u) {
        return;
    }
    {
        const uint32_t period = sxl_get_u32(&reply->payload[1u + SXL_FR_PERIOD]);
        check(sxl_get_u16(&reply->payload[1u + SXL_FR_FAULTS]) != 0u);
        check(period >= last_record_period && period <= drive.protect.period);
        last_record_period = period;
    }
}

static void serve_byte(uint16_t byte)
{
    sxl_frame_t req;
    sxl_frame_t reply;
    if (sxl_decoder_push(&rx, byte, &req) != SXL_RX_FRAME) {
        return;
    }
    drive_link_handle(&drive, &req, &reply, rx.errors);
    check_reply(&reply);
    check_fault_record(&reply);
}

static void serial_noise(stream_t *s)
{
    const uint16_t n = (uint16_t)(take8(s) % 24u + 1u);
    uint16_t i;
    for (i = 0u; i < n; i++) {
        serve_byte(take8(s));
    }
}

/* Arms a session over the link and puts its token in front of the payload (the payload's
 * tail is cut to make room); the new length. */
static uint16_t arm_and_prefix(uint16_t *payload, uint16_t len)
{
    const uint16_t room = (uint16_t)(SXL_MAX_PAYLOAD - SXL_TOKEN_BYTES);
    uint16_t bytes[SXL_MAX_FRAME];
    const uint16_t n = sxl_encode(SXL_CMD_ARM, NULL, 0u, bytes, (uint16_t)SXL_MAX_FRAME);
    uint16_t i;
    for (i = 0u; i < n; i++) {
        serve_byte(bytes[i]);
    }
    len = (len < room) ? len : room;
    for (i = len; i > 0u; i--) {
        payload[i - 1u + SXL_TOKEN_BYTES] = payload[i - 1u];
    }
    sxl_put_u32(payload, drive.link_token);
    return (uint16_t)(len + SXL_TOKEN_BYTES);
}

static void serial_frame(stream_t *s)
{
    static const uint16_t commands[] = {SXL_CMD_PING,
                                        SXL_CMD_GET_STATUS,
                                        SXL_CMD_GET_PROFILE,
                                        SXL_CMD_GET_FAULT_RECORD,
                                        SXL_CMD_SET_SPEED,
                                        SXL_CMD_SET_TORQUE,
                                        SXL_CMD_RUN,
                                        SXL_CMD_STOP,
                                        SXL_CMD_CLEAR_FAULT,
                                        SXL_CMD_SET_CONTROLLER,
                                        SXL_CMD_GET_OPEN_PHASE,
                                        SXL_CMD_SET_OPEN_PHASE_ACTION,
                                        SXL_CMD_ISOLATE_LEG,
                                        SXL_CMD_RESTORE_LEGS};
    /* the commissioning's commands on picks 240..243 and the torque-limited pair on 244..247,
     * so that the picks below keep the commands the committed corpus chose with them */
    static const uint16_t commission[] = {SXL_CMD_COMMISSION_START, SXL_CMD_COMMISSION_STATUS,
                                          SXL_CMD_COMMISSION_RESULT, SXL_CMD_COMMISSION_APPLY};
    static const uint16_t torque_limited[] = {SXL_CMD_SET_TORQUE_LIMITED_ACTION,
                                              SXL_CMD_GET_TORQUE_LIMITED};
    const uint16_t pick = take8(s);
    const uint16_t cmd = (pick < 240u)   ? commands[pick % 14u]
                         : (pick < 244u) ? commission[pick % 4u]
                         : (pick < 248u) ? torque_limited[pick % 2u]
                                         : take8(s);
    uint16_t len = (uint16_t)(take8(s) % (SXL_MAX_PAYLOAD + 1u));
    uint16_t payload[SXL_MAX_PAYLOAD];
    uint16_t bytes[SXL_MAX_FRAME];
    uint16_t i;
    uint16_t n;
    for (i = 0u; i < len; i++) {
        payload[i] = take8(s);
    }
    if (SXL_ARMED_COMMAND(cmd)) { /* as the host tool sends it: ARM, then the token in front */
        len = arm_and_prefix(payload, len);
    }
    n = sxl_encode(cmd, payload, len, bytes, (uint16_t)SXL_MAX_FRAME);
    for (i = 0u; i < n; i++) {
        serve_byte(bytes[i]);
    }
}

static void parameter_set(stream_t *s)
{
    ctl_params_t p = drive.params_bg;
    p.lambda_nm_per_wb = take_float(s);
    p.torque_limit_nm = take_float(s);
    p.sample_time_s = (take8(s) & 1u) ? take_float(s) : p.sample_time_s;
    p.pole_pairs = (int16_t)(take8(s) % 8u);
    p.protect.dc_undervoltage_v = take_float(s);
    p.controller = (ctl_controller_t)(take8(s) % 4u);
    (void)drive_request_params(&drive, &p);
}

/* The ISR's view of one period: ADC words, the encoder and its index, the trip pin. */
static void period_inputs(stream_t *s, uint16_t flags)
{
    hal_adc_sample_t adc;
    hal_encoder_sample_t enc;
    int16_t k;
    for (k = 0; k < HAL_ADC_PHASES; k++) {
        /* quiet: near mid scale as a healthy idle drive reads; else any 12-bit word */
        adc.phase[k] =
            (flags & 8u) ? (uint16_t)(2040u + take8(s) % 16u) : (uint16_t)(take16(s) & 0xFFFu);
    }
    adc.vdc = (flags & 8u) ? (uint16_t)(2700u + take8(s)) : (uint16_t)((take32(s)) & 0xFFFu);
    enc.elec_angle = take32(s);
    enc.mech_speed_q16 = (int32_t)(int16_t)take16(s);
    enc.healthy = (flags & 4u) != 0u;
    enc.position = (int32_t)take32(s);
    enc.index_seen = (flags & 16u) != 0u || enc.healthy;
    hal_sim_post_encoder(&enc);
    if ((flags & 16u) != 0u) {
        hal_sim_post_encoder_index(); /* the index: homed again after an ENCODER clear */
    }
    if ((flags & 1u) != 0u) {
        hal_sim_post_adc(&adc);
    }
    hal_sim_bus.hw_trip = (flags & 2u) != 0u;
}

typedef struct {
    drive_state_t state;
    bool run_asked, clear_asked, comm_asked;
} before_t;

static void before_isr(before_t *b)
{
    b->state = drive.state;
    b->run_asked = drive.run_requested;
    b->clear_asked = drive.clear_requested;
    b->comm_asked = drive.comm.start_requested != 0;
}

/* The invariants after one control period. */
static void check_period(const before_t *b)
{
    check(drive.state == DRIVE_STATE_RUN || drive.state == DRIVE_STATE_COMMISSION ||
          hal_sim_bus.forced_off);
    check(!(drive.state == DRIVE_STATE_COMMISSION && b->state != DRIVE_STATE_COMMISSION) ||
          (b->state == DRIVE_STATE_READY && b->comm_asked));
    check(drive.state != DRIVE_STATE_COMMISSION || drive.comm.state == COMM_STATE_RUNNING);
    check(!(b->state == DRIVE_STATE_FAULT && drive.state != DRIVE_STATE_FAULT) || b->clear_asked);
    check(!(drive.state == DRIVE_STATE_RUN && b->state != DRIVE_STATE_RUN) ||
          (b->state == DRIVE_STATE_READY && b->run_asked));
    check(ctl_protect_log_pending(&drive.protect) <= CTL_PROTECT_LOG_SIZE);
    check(drive.isolated_leg < 0 ||
          ((((unsigned)hal_sim_bus.isolated >> drive.isolated_leg) & 1u) != 0u &&
           (hal_sim_bus.forced_off || hal_sim_bus.duty[drive.isolated_leg] == 0u)));
    check((drive.state == DRIVE_STATE_FAULT) == (drive.fault != DRIVE_FAULT_NONE));
    check((int32_t)drive.run_refusal < DRIVE_RUN_REFUSAL_COUNT);
}

static void control_periods(stream_t *s)
{
    const uint16_t flags = take8(s);
    const uint16_t repeat = (uint16_t)(take8(s) % 16u + 1u);
    uint16_t r;
    period_inputs(s, flags);
    for (r = 0u; r < repeat; r++) {
        before_t b;
        before_isr(&b);
        if (r > 0u && (flags & 1u) != 0u) {
            hal_sim_bus.adc_fresh = true; /* the same words again, freshly converted */
        }
        drive_control_isr(&drive);
        check_period(&b);
    }
}

/* The plant the drive runs on in plant periods: the simulator's default machine (the one the
 * drive's default parameters describe), its inverter, ADC and encoder. */
static struct {
    plant_params_t p;
    plant_state_t x;
    inverter_t inv;
    sim_adc_t adc;
    sim_encoder_t enc;
    sim_fault_state_t fault; /* none: the harness opens phases and freezes words itself */
    hal_adc_sample_t frozen; /* the words a frozen converter keeps returning */
    double t;
    int32_t budget; /* plant periods left in this input (bounds an execution's time) */
    bool on, inv_made;
} plant;

#define PLANT_TS_S (1.0 / HAL_BOARD_PWM_HZ) /* the harness's PWM (power_up) */
/* The ADC's words at rest, from the board's scaling: no current (mid scale), a 540 V DC link. */
#define ADC_ZERO ((uint16_t)HAL_BOARD_CURRENT_ZERO_COUNTS)
#define ADC_VDC_540V ((uint16_t)(540.0 / HAL_BOARD_VDC_V_PER_COUNT + 0.5))
/* Plant periods per input: short inputs (what mutation mostly makes) 25.6 ms of the drive's
 * time, so that the fuzzer keeps its pace (a plant period costs about what a hundred plain
 * ones do under the sanitizers); long ones (first byte bit 1: the seeds that commission)
 * 40 s, the whole sequence with its margins. */
#define PLANT_PERIODS_SHORT 256L
#define PLANT_PERIODS_LONG 400000L

/* Started at an input's first plant period, at standstill; the encoder homed (as the rotor
 * turned past its index before) or not (as commissioning finds it). */
static void plant_start(bool homed)
{
    int16_t k;
    if (plant.inv_made) {
        inverter_free(&plant.inv);
    }
    plant_params_default(&plant.p);
    plant.p.adc_offset_on = false; /* the drive calibrated its offsets on exact mid-scale */
    memset(&plant.x, 0, sizeof plant.x);
    plant_sync_angle(&plant.p, &plant.x);
    inverter_init(&plant.inv, &plant.p, PLANT_TS_S);
    plant.inv_made = true;
    sim_adc_init(&plant.adc, &plant.p, 1u);
    sim_encoder_init(&plant.enc, PLANT_TS_S);
    sim_encoder_power_up(&plant.enc, &plant.p, &plant.x, homed);
    sim_fault_begin(&plant.fault, SIM_FAULT_NONE, 0.0);
    for (k = 0; k < HAL_ADC_PHASES; k++) {
        plant.frozen.phase[k] = ADC_ZERO;
    }
    plant.frozen.vdc = ADC_VDC_540V;
    plant.t = 0.0;
    plant.on = true;
}

/* Phase k (0..5) open or connected again; the open currents commutate off at once. */
static void plant_open(int16_t phase)
{
    int16_t k;
    for (k = 0; k < PLANT_PHASES; k++) {
        plant.p.phase_open[k] = (k == phase);
    }
    if (phase >= 0) {
        plant_open_commutate(&plant.p, &plant.x);
    }
}

#define PLANT_LOAD_NM 3.0 /* a passive load: current flows while the motor turns */

/* One period: sample the plant (or repeat the frozen words), the ISR, the inverter applies
 * the duties it wrote against the load (opposing the motion, proportional below 1 rad/s so
 * that it never drives the rotor). */
static void plant_period(bool frozen, bool loaded)
{
    const double w = plant.x.omega_m;
    const double load = loaded ? PLANT_LOAD_NM * ((w > 1.0) ? 1.0 : ((w < -1.0) ? -1.0 : w)) : 0.0;
    double i[PLANT_PHASES];
    double duty[PLANT_PHASES];
    before_t b;
    int16_t k;
    hal_sim_clock_advance(100000u);
    plant_phase_currents(&plant.p, &plant.x, i);
    if (frozen) {
        hal_sim_post_adc(&plant.frozen);
    } else {
        sim_adc_sample(&plant.adc, &plant.p, i, &plant.fault);
        plant.frozen = hal_sim_bus.adc;
    }
    sim_encoder_sample(&plant.enc, &plant.p, &plant.x, plant.t, PLANT_TS_S, &plant.fault);
    hal_sim_bus.hw_trip = false;
    before_isr(&b);
    drive_control_isr(&drive);
    check_period(&b);
    for (k = 0; k < PLANT_PHASES; k++) {
        duty[k] = hal_sim_duty_fraction(k);
    }
    (void)inverter_run_period(&plant.inv, &plant.p, &plant.x, duty, hal_sim_bus.forced_off, load,
                              false, NULL, 0, NULL, NULL);
    plant.t += PLANT_TS_S;
}

/* Periods on the plant: flags (bits 0..2: phase 0..5 open, 6 or 7 all connected; bit 3: the
 * converter frozen; bit 4: the encoder homed, at the input's first plant period; bit 5: a
 * load on the shaft), then the count in blocks of 32 periods, at most 256 (short, so that
 * mutated inputs stay fast; the seeds that run whole sequences chain tags). */
static void plant_periods(stream_t *s)
{
    const uint16_t flags = take8(s);
    int32_t n = ((int32_t)(take8(s) % 8u) + 1) * 32;
    const int16_t open = (int16_t)(flags & 7u);
    if (!plant.on) {
        plant_start((flags & 16u) != 0u);
    }
    plant_open((open < PLANT_PHASES) ? open : -1);
    n = (n < plant.budget) ? n : plant.budget;
    plant.budget -= n;
    while (n-- > 0) {
        plant_period((flags & 8u) != 0u, (flags & 32u) != 0u);
    }
}

/* A capture command with a setup drawn from small ranges (most of them valid), or its status,
 * read or stop. */
static void capture_command(stream_t *s)
{
    const uint16_t what = take8(s);
    uint16_t payload[SXL_CA_SIZE];
    uint16_t bytes[SXL_MAX_FRAME];
    uint16_t cmd = SXL_CMD_CAPTURE_ARM;
    uint16_t len = SXL_CA_SIZE;
    uint16_t i, n;
    if ((what & 3u) == 0u) {
        const uint16_t chans = (uint16_t)(what >> 2 & 3u) + 1u;
        payload[SXL_CA_CHANNELS] = chans;
        for (i = 0u; i < 4u; i++) {
            payload[SXL_CA_SIGNAL + i] =
                (i < chans) ? (uint16_t)(take8(s) % (CAPTURE_SIGNAL_COUNT + 1u)) : 0xFFu;
        }
        sxl_put_u16(&payload[SXL_CA_LENGTH], (uint16_t)(take8(s) * 4u + (what >> 4 & 1u)));
        sxl_put_u16(&payload[SXL_CA_DECIMATION], (uint16_t)(take8(s) % 5u));
        payload[SXL_CA_TRIGGER] = (uint16_t)(what >> 5 & 3u);
        payload[SXL_CA_TRIG_SIGNAL] = (uint16_t)(take8(s) % CAPTURE_SIGNAL_COUNT);
        sxl_put_u16(&payload[SXL_CA_TRIG_LEVEL], (uint16_t)((int16_t)(int8_t)take8(s) * 64));
        payload[SXL_CA_PRE] = (uint16_t)(take8(s) % 110u);
    } else if ((what & 3u) == 1u) {
        cmd = SXL_CMD_CAPTURE_STATUS;
        len = 0u;
    } else if ((what & 3u) == 2u) {
        cmd = SXL_CMD_CAPTURE_READ;
        payload[0] = (uint16_t)(what >> 2 & 7u);
        sxl_put_u16(&payload[1], (uint16_t)(take8(s) * 8u));
        len = 3u;
    } else {
        cmd = SXL_CMD_CAPTURE_STOP;
        len = 0u;
    }
    n = sxl_encode(cmd, payload, len, bytes, (uint16_t)SXL_MAX_FRAME);
    for (i = 0u; i < n; i++) {
        serve_byte(bytes[i]);
    }
}

static void power_up(void)
{
    ctl_params_t p;
    hal_sim_reset();
    (void)hal_pwm_init(HAL_BOARD_PWM_HZ, HAL_BOARD_DEAD_TIME_NS);
    (void)hal_adc_init();
    (void)hal_encoder_init(HAL_BOARD_ENCODER_LINES, 3u, 0u);
    ctl_params_default(&p);
    drive_init(&drive, &p);
}

/* READY after a clean calibration, taken once and copied for every input that asks. */
static void calibrated_start(void)
{
    static drive_t snapshot;
    static hal_sim_bus_t bus;
    static prof_t profile;
    static bool taken;
    if (!taken) {
        hal_adc_sample_t adc;
        hal_encoder_sample_t enc = {0u, 0, true, 0, true};
        int16_t k;
        int32_t n;
        power_up();
        for (k = 0; k < HAL_ADC_PHASES; k++) {
            adc.phase[k] = ADC_ZERO;
        }
        adc.vdc = ADC_VDC_540V;
        for (n = 0; n < DRIVE_CALIBRATION_SAMPLES; n++) {
            adc.phase[0] = (uint16_t)(ADC_ZERO + (n & 1)); /* a live converter */
            hal_sim_post_adc(&adc);
            hal_sim_post_encoder(&enc);
            drive_control_isr(&drive);
        }
        check(drive.state == DRIVE_STATE_READY);
        snapshot = drive;
        bus = hal_sim_bus;
        profile = drive_profile;
        taken = true;
    }
    drive = snapshot;
    hal_sim_bus = bus;
    drive_profile = profile;
}

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    stream_t s;
    int32_t steps = 0;
    s.p = data;
    s.left = size;
    const uint16_t start = take8(&s);
    if ((start & 1u) != 0u) {
        calibrated_start();
    } else {
        power_up();
    }
    sxl_decoder_init(&rx);
    last_record_period = 0u;
    plant.on = false;
    plant.budget = ((start & 2u) != 0u) ? PLANT_PERIODS_LONG : PLANT_PERIODS_SHORT;
    while (s.left > 0u && steps < 4000) {
        const uint16_t byte = take8(&s);
        const uint16_t tag = (uint16_t)(byte % 6u);
        if (byte >= 248u) {
            if (byte < 250u) {
                plant_periods(&s);
            } else {
                capture_command(&s);
            }
        } else if (tag == 5u) {
            /* the background loop's pass; now and then the open-phase option */
            if ((take8(&s) & 1u) != 0u) {
                (void)drive_set_open_phase_action(&drive, (int16_t)(take8(&s) % 3u),
                                                  (int16_t)(take8(&s) % 3u));
            }
            drive_background(&drive);
        } else if (tag == 0u) {
            serial_noise(&s);
        } else if (tag == 1u) {
            serial_frame(&s);
        } else if (tag == 2u) {
            parameter_set(&s);
        } else {
            control_periods(&s);
        }
        steps++;
    }
    return 0;
}
