/*
 * Executable portability proxy: replays a stream of input records through the control core
 * (ctl_step, ctl_request_params, ctl_protect_check, ...) and emits every command and the key
 * diagnostics in a fixed little-endian byte encoding. The same source runs
 *   - on an 8-bit AVR (16-bit int, 32-bit double, avr-gcc) under simavr: bytes come from
 *     and go to unused I/O registers that the harness (harness.c) answers;
 *   - on the host (32-bit int, 64-bit double): bytes come from stdin and go to stdout.
 * Only the port layer below differs. tools/avr_proxy/run.sh compares the two outputs.
 *
 * Wire format (all multi-byte values little-endian, written byte by byte):
 *   q    a ctl_q as its 32-bit pattern: the Q24 int32 (fixed build) or the IEEE single bits
 *        (float build); the input generator writes the pattern of the build it feeds
 *   f32  IEEE single bits of a float (parameters are float in both builds)
 *   i16/u16/u32, u8
 * Input records (tag byte, then the payload):
 *   'N' params   ctl_init + ctl_protect_init          -> 'N' ok u8, last_error u8, config
 *                                                          (only when ok)
 *   'Q' params   ctl_request_params                   -> 'Q' result u8, rejected u16,
 *                                                          last_error u8, pending u8, config
 *                                                          (the standby buffer when accepted)
 *   'M' u8       ctl_set_loop_mode (0 speed, 1 torque) -> nothing
 *   'R'          ctl_reset                            -> nothing
 *   'K'          ctl_protect_clear                    -> 'K' ok u8, latched u16, active u16
 *   'L'          drain the fault log                  -> 'L' n u8, then n records
 *   'S' step     see read_step                        -> 'S' step output (emit_step)
 *   'Z' u8       ctl_protect_quiet (bit k: phase k)   -> 'Z' inv_judged q
 *   'E'          end                                  -> 'E' steps u32, then the done mark
 * params: controller u8, ddc_direction u8, improvement flags u8 (bit 0 torque guard, 1
 *   mid-period angle, 2 fewest transitions, 3 flux tie band off), flux_ref_mode u8, duty_levels
 *   i16, lambda f32, torque_limit f32, speed_kp f32, speed_ki f32, flux_ref_wb f32, sample_time
 *   f32, overcurrent_a f32, overspeed_rpm f32, dc_overvoltage_v f32, open phase + 1 u8 (0:
 *   none), post-fault strategy u8 (the rest: ctl_params_default).
 * config: the derived configuration's fields, then the open-phase part built with it
 *   (emit_postfault).
 */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "ctl.h"
#include "ctl_protect.h"

/* ---- port layer ------------------------------------------------------------------------ */
#if defined(__AVR__)
/* General-purpose I/O registers of the ATmega1284P (data-space addresses): unused by the core,
 * answered by the simavr harness. */
#define PORT_IN (*(volatile uint8_t *)0x3Eu)   /* GPIOR0: read = next input byte */
#define PORT_OUT (*(volatile uint8_t *)0x4Au)  /* GPIOR1: write = one output byte */
#define PORT_MARK (*(volatile uint8_t *)0x4Bu) /* GPIOR2: write = timing mark / done */
static uint8_t port_read(void) { return PORT_IN; }
static void port_write(uint8_t b) { PORT_OUT = b; }
static void port_mark(uint8_t m) { PORT_MARK = m; }
static bool port_eof(void) { return false; } /* the harness fails a read past the end */
#else
#include <stdio.h>
static bool eof_seen;
static uint8_t port_read(void)
{
    const int ch = getchar();
    if (ch == EOF) {
        eof_seen = true;
        return (uint8_t)'E';
    }
    return (uint8_t)ch;
}
static void port_write(uint8_t b) { (void)putchar(b); }
static void port_mark(uint8_t m) { (void)m; }
static bool port_eof(void) { return eof_seen; }
#endif

/* Marks: 1/2 around ctl_step, 3/4 around ctl_protect_check, 5/6 around ctl_request_params,
 * 0xFF: done, 0xFE: an unknown record tag (stops). */
#define MARK_STEP_BEGIN 1u
#define MARK_STEP_END 2u
#define MARK_PROT_BEGIN 3u
#define MARK_PROT_END 4u
#define MARK_PARAM_BEGIN 5u
#define MARK_PARAM_END 6u
#define MARK_DONE 0xFFu
#define MARK_BAD_INPUT 0xFEu

/* ---- encoding -------------------------------------------------------------------------- */
typedef union {
    uint32_t u;
    float f;
} bits32_t;

static uint16_t rd_u16(void)
{
    const uint16_t lo = port_read();
    const uint16_t hi = port_read();
    return (uint16_t)(lo | (uint16_t)(hi << 8));
}
static int16_t rd_i16(void) { return (int16_t)rd_u16(); }
static uint32_t rd_u32(void)
{
    const uint32_t lo = rd_u16();
    const uint32_t hi = rd_u16();
    return lo | (hi << 16);
}
static float rd_f32(void)
{
    bits32_t b;
    b.u = rd_u32();
    return b.f;
}
static ctl_q rd_q(void)
{
#if CTL_MATH_FLOAT
    return rd_f32();
#else
    return (ctl_q)(int32_t)rd_u32();
#endif
}

static void wr_u8(uint8_t v) { port_write(v); }
static void wr_u16(uint16_t v)
{
    port_write((uint8_t)(v & 0xFFu));
    port_write((uint8_t)(v >> 8));
}
static void wr_i16(int16_t v) { wr_u16((uint16_t)v); }
static void wr_u32(uint32_t v)
{
    wr_u16((uint16_t)(v & 0xFFFFu));
    wr_u16((uint16_t)(v >> 16));
}
static void wr_q(ctl_q v)
{
#if CTL_MATH_FLOAT
    bits32_t b;
    b.f = v;
    wr_u32(b.u);
#else
    wr_u32((uint32_t)v);
#endif
}
static void wr_bool(bool v) { port_write(v ? 1u : 0u); }

/* ---- state ----------------------------------------------------------------------------- */
static ctl_t ctl_state;
static ctl_protect_t prot_state;
static ctl_params_t params_buf;
static ctl_protect_input_t prot_in;
static ctl_meas_t meas;
static ctl_cmd_t cmd;
static uint32_t steps;

static void read_params(ctl_params_t *p)
{
    ctl_params_default(p);
    p->controller = (ctl_controller_t)port_read();
    p->ddc_direction = (ctl_ddc_direction_t)port_read();
    {
        /* bit 0 guard, 1 mid, 2 fewest transitions, 3 tie band off, 4 per set (with bit 2) */
        const uint16_t flags = port_read();
        p->ddc_torque_guard = (flags & 1u) != 0u;
        p->mid_period_angle = (flags & 2u) != 0u;
        p->pulse_pattern = ((flags & 4u) == 0u)    ? CTL_PULSE_BY_ONES
                           : ((flags & 16u) != 0u) ? CTL_PULSE_FEWEST_PER_SET
                                                   : CTL_PULSE_FEWEST_TRANSITIONS;
        if ((flags & 8u) != 0u) {
            p->ddc_flux_tie_band = 0.0f;
        }
    }
    p->flux_ref_mode = (ctl_flux_ref_mode_t)port_read();
    p->duty_levels = rd_i16();
    p->lambda_nm_per_wb = rd_f32();
    p->torque_limit_nm = rd_f32();
    p->speed_kp_nm_per_rad_s = rd_f32();
    p->speed_ki_nm_per_rad = rd_f32();
    p->flux_ref_wb = rd_f32();
    p->sample_time_s = rd_f32();
    p->protect.overcurrent_a = rd_f32();
    p->protect.overspeed_rpm = rd_f32();
    p->protect.dc_overvoltage_v = rd_f32();
    p->open_phase = (int16_t)((int16_t)port_read() - 1);
    p->postfault_strategy = (int16_t)port_read();
}

/* The open-phase part of a configuration: geometry, references, tables and sets. */
static void emit_postfault(const ctl_postfault_config_t *pf)
{
    bits32_t ratio;
    int16_t s;
    int16_t h;
    int16_t f;
    wr_i16(pf->open_leg);
    if (pf->open_leg < 0) {
        return;
    }
    wr_i16(pf->zero_leg);
    wr_u16(pf->quiet);
    wr_q(pf->c_alpha);
    wr_q(pf->c_beta);
    wr_q(pf->c_x);
    wr_q(pf->c_y);
    wr_q(pf->free_ref_alpha);
    wr_q(pf->free_ref_beta);
    ratio.f = pf->peak_ratio;
    wr_u32(ratio.u);
    for (s = 0; s < CTL_SECTORS; s++) {
        for (h = 0; h < 2; h++) {
            for (f = 0; f < 2; f++) {
                wr_i16(pf->ddc_table[s][h][f][0]);
                wr_i16(pf->ddc_table[s][h][f][1]);
            }
        }
    }
    wr_i16(pf->mptc_all_count);
    for (s = 0; s < pf->mptc_all_count; s++) {
        wr_i16(pf->mptc_all[s]);
    }
    wr_i16(pf->mptc_large_count);
    for (s = 0; s < pf->mptc_large_count; s++) {
        wr_i16(pf->mptc_large[s]);
    }
}

/* The derived configuration, so that a difference in the background's float arithmetic shows
 * where it starts rather than as a command difference later. */
static void emit_config(const ctl_config_t *c)
{
    const ctl_model_t *m = &c->model;
    const ctl_protect_limits_t *l = &c->protect;
    int16_t i;
    wr_q(m->a_d);
    wr_q(m->b_d);
    wr_q(m->c_d);
    wr_q(m->a_q);
    wr_q(m->b_q);
    wr_q(m->e_q);
    wr_q(m->c_q);
    wr_q(m->a_xy);
    wr_q(m->c_xy);
    wr_q(m->ld);
    wr_q(m->lq);
    wr_q(m->lxy);
    wr_q(m->psi_f);
    wr_q(m->ts);
    wr_q(m->omega_max);
    wr_i16(m->pole_pairs);
    wr_q(c->lambda);
    wr_q(c->torque_limit);
    wr_q(c->speed_kp);
    wr_q(c->speed_ki_ts);
    if (c->params.controller == CTL_CONTROLLER_FOC) { /* the place the DDC's settings share */
        wr_q(c->ctrl.foc.wc);                         /* the same 12 fields: w_c, i_d, 0, 0 */
        for (i = 0; i < CTL_FOC_REF_POINTS; i++) {
            wr_q(c->ctrl.foc.id_ref[i]);
        }
        for (i = CTL_FOC_REF_POINTS + 1; i < CTL_DUTY_LEVELS_MAX + 1; i++) {
            wr_q(CTL_Q(0.0));
        }
    } else {
        for (i = 0; i < CTL_DUTY_LEVELS_MAX; i++) {
            wr_q(c->ctrl.ddc.levels[i]);
        }
        wr_q(c->ctrl.ddc.tie_per_span);
    }
    wr_q(c->omega_pu_per_rev_s);
    wr_u8((uint8_t)c->flux_ref.mode);
    wr_q(c->flux_ref.constant);
    wr_q(c->flux_ref.torque_max);
    wr_q(c->flux_ref.points_per_torque);
    for (i = 0; i < CTL_FLUX_REF_TABLE_POINTS; i++) {
        wr_q(c->flux_ref.table[i]);
    }
    wr_q(l->overcurrent);
    wr_i16(l->overcurrent_periods);
    wr_q(l->dc_overvoltage);
    wr_i16(l->dc_overvoltage_periods);
    wr_q(l->dc_undervoltage);
    wr_i16(l->dc_undervoltage_periods);
    wr_q(l->overspeed);
    wr_i16(l->overspeed_periods);
    wr_q(l->current_sum);
    wr_i16(l->current_sum_periods);
    wr_i16(l->adc_rail_low);
    wr_i16(l->adc_rail_high);
    wr_i16(l->adc_rail_periods);
    wr_i16(l->adc_stuck_periods);
    wr_q(l->stuck_min_current);
    wr_q(l->encoder_torque);
    wr_q(l->encoder_expected_turn);
    wr_q(l->encoder_jump);
    wr_q(l->torque_to_dspeed);
    wr_q(l->ts_turns);
    wr_q(l->open_phase_min_mean);
    wr_q(l->open_phase_ratio);
    wr_q(l->open_phase_fast_ratio);
    wr_q(l->open_phase_fast_min);
    wr_q(l->open_phase_fast_keep);
}

static void do_init(void)
{
    bool ok;
    read_params(&params_buf);
    ok = ctl_init(&ctl_state, &params_buf);
    ctl_protect_init(&prot_state);
    wr_u8((uint8_t)'N');
    wr_bool(ok);
    wr_u8((uint8_t)ctl_state.params_last_error);
    if (ok) { /* a refused set leaves the buffer partly written: nothing to show */
        emit_config(&ctl_state.config[ctl_state.config_active]);
        emit_postfault(&ctl_state.postfault[ctl_state.config_active]);
    }
}

static void do_request(void)
{
    ctl_param_error_t e;
    read_params(&params_buf);
    port_mark(MARK_PARAM_BEGIN);
    e = ctl_request_params(&ctl_state, &params_buf);
    port_mark(MARK_PARAM_END);
    wr_u8((uint8_t)'Q');
    wr_u8((uint8_t)e);
    wr_u16(ctl_state.params_rejected);
    wr_u8((uint8_t)ctl_state.params_last_error);
    wr_bool(ctl_config_pending(&ctl_state));
    /* accepted: the set just built (standby buffer); otherwise the one in force */
    emit_config(&ctl_state.config[(e == CTL_PARAM_OK) ? (1 - ctl_state.config_active)
                                                      : ctl_state.config_active]);
    if (e == CTL_PARAM_OK) {
        emit_postfault(&ctl_state.postfault[1 - ctl_state.config_active]);
    }
}

static void do_quiet(void)
{
    ctl_protect_quiet(&prot_state, (uint16_t)port_read());
    wr_u8((uint8_t)'Z');
    wr_q(prot_state.inv_judged);
}

static void do_clear(void)
{
    const bool ok = ctl_protect_clear(&prot_state);
    wr_u8((uint8_t)'K');
    wr_bool(ok);
    wr_u16(prot_state.latched);
    wr_u16(prot_state.active);
}

static void do_log(void)
{
    ctl_fault_record_t r;
    const uint16_t pending = ctl_protect_log_pending(&prot_state);
    uint8_t n = (uint8_t)((pending > 255u) ? 255u : pending);
    uint8_t k;
    int16_t i;
    wr_u8((uint8_t)'L');
    wr_u8(n);
    for (k = 0; k < n; k++) {
        const bool ok = ctl_protect_read_record(&prot_state, &r);
        wr_bool(ok);
        wr_u16(r.faults);
        wr_u32(r.period);
        for (i = 0; i < 6; i++) {
            wr_q(r.i_phase[i]);
        }
        wr_q(r.vdc);
        wr_q(r.theta_e);
        wr_q(r.omega_e);
        wr_q(r.torque_est);
        wr_q(r.torque_ref);
        wr_i16(r.vector);
        wr_q(r.duty);
    }
    wr_u16(prot_state.log_dropped);
}

/* Step record: flags u8 (bit0 run the protection check, bit1 encoder healthy, bit2 overrun,
 * bit3 hw trip, bit4 running, bit5 currents calibrated), ref q (speed or torque, per the loop
 * mode), i_phase[6] q, vdc q, theta_e q, omega_e q, raw_phase[6] i16, raw_vdc i16. */
static uint8_t read_step(ctl_q *ref)
{
    const uint8_t flags = port_read();
    int16_t i;
    *ref = rd_q();
    for (i = 0; i < CTL_PHASES; i++) {
        meas.i_phase[i] = rd_q();
    }
    meas.vdc = rd_q();
    meas.theta_e = rd_q();
    meas.omega_e = rd_q();
    for (i = 0; i < 6; i++) {
        prot_in.raw_phase[i] = rd_i16();
    }
    prot_in.raw_vdc = rd_i16();
    return flags;
}

static void emit_step(uint16_t faults)
{
    const ctl_diag_t *d = ctl_diag(&ctl_state);
    int16_t i;
    wr_u8((uint8_t)'S');
    /* command */
    wr_i16(cmd.vector);
    wr_q(cmd.duty);
    for (i = 0; i < CTL_PHASES; i++) {
        wr_q(cmd.leg_duty[i]);
    }
    wr_bool(cmd.enable);
    /* protection */
    wr_u16(faults);
    wr_u16(prot_state.latched);
    wr_u16(prot_state.active);
    wr_u16(prot_state.log_write);
    /* diagnostics */
    wr_i16(d->flux_sector);
    wr_i16(d->xy_sector);
    wr_i16(d->candidates);
    wr_bool(d->braking);
    wr_q(d->i_d);
    wr_q(d->i_q);
    wr_q(d->i_x);
    wr_q(d->i_y);
    wr_q(ctl_diag_torque_est(&ctl_state));
    wr_q(ctl_diag_flux_est(&ctl_state));
    wr_q(d->torque_ref);
    wr_q(d->flux_ref);
    wr_q(d->torque_pred);
    wr_q(d->flux_pred);
    wr_q(d->cost);
    wr_q(ctl_state.speed_pi.integ);
}

static void do_step(void)
{
    ctl_q ref;
    uint16_t faults = 0u;
    const uint8_t flags = read_step(&ref);
    int16_t i;
    if (ctl_state.loop_mode == CTL_LOOP_SPEED) {
        ctl_set_speed_ref(&ctl_state, ref);
    } else {
        ctl_set_torque_ref(&ctl_state, ref);
    }
    if ((flags & 1u) != 0u) {
        /* as the drive does: this period's measurements, last period's estimate and the
         * command in force */
        for (i = 0; i < 6; i++) {
            prot_in.i_phase[i] = meas.i_phase[i];
        }
        prot_in.vdc = meas.vdc;
        prot_in.theta_e = meas.theta_e;
        prot_in.omega_e = meas.omega_e;
        prot_in.encoder_healthy = (flags & 2u) != 0u;
        prot_in.overrun = (flags & 4u) != 0u;
        prot_in.hw_trip = (flags & 8u) != 0u;
        prot_in.running = (flags & 16u) != 0u;
        prot_in.currents_calibrated = (flags & 32u) != 0u;
        prot_in.xy_held = prot_in.running && ctl_state.xy_held;
        prot_in.i_d = prot_in.running ? ctl_state.diag.i_d : CTL_Q(0.0);
        prot_in.i_q = prot_in.running ? ctl_state.diag.i_q : CTL_Q(0.0);
        prot_in.model = &ctl_config(&ctl_state)->model;
        port_mark(MARK_PROT_BEGIN);
        faults = ctl_protect_check(&prot_state, &ctl_config(&ctl_state)->protect, &prot_in,
                                   ctl_state.diag.torque_ref, ctl_state.applied_vector,
                                   ctl_state.applied_duty);
        port_mark(MARK_PROT_END);
    }
    port_mark(MARK_STEP_BEGIN);
    ctl_step(&ctl_state, &meas, &cmd);
    port_mark(MARK_STEP_END);
    steps++;
    emit_step(faults);
}

int main(void)
{
    for (;;) {
        const uint8_t tag = port_read();
        if (port_eof() || tag == (uint8_t)'E') {
            break;
        }
        switch (tag) {
        case 'N':
            do_init();
            break;
        case 'Q':
            do_request();
            break;
        case 'M':
            ctl_set_loop_mode(&ctl_state, (port_read() != 0u) ? CTL_LOOP_TORQUE : CTL_LOOP_SPEED);
            break;
        case 'R':
            ctl_reset(&ctl_state);
            break;
        case 'K':
            do_clear();
            break;
        case 'L':
            do_log();
            break;
        case 'S':
            do_step();
            break;
        case 'Z':
            do_quiet();
            break;
        default:
            wr_u8((uint8_t)'?');
            wr_u8(tag);
            port_mark(MARK_BAD_INPUT);
            return 2;
        }
    }
    wr_u8((uint8_t)'E');
    wr_u32(steps);
    port_mark(MARK_DONE);
#if defined(__AVR__)
    for (;;) {
    }
#else
    return 0;
#endif
}
