/*
 * Fuzz target for the control step (libFuzzer entry point). The input is a stream of
 * records: a tag word chooses between a parameter change (through the shadow copy, with
 * arbitrary values, valid or not), a reference change, or a control step with arbitrary
 * measurement words (any int32 in the fixed build; any float bit pattern, NaN and infinity
 * included, in the float build). After every step the command must be valid:
 * duties in [0, 1], the vector a 6-bit state, leg duties realising "vector for d, zero vector
 * for the rest", and the protection check must not misbehave on the same inputs.
 *
 * Built with clang -fsanitize=fuzzer,address,undefined (preset `fuzz`), or with any compiler
 * and tests/fuzz/replay_main.c, which runs the committed corpus as a regression test.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ctl.h"
#include "ctl_protect.h"
#include "ctl_vectors.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);

typedef struct {
    const unsigned char *p;
    size_t left;
} stream_t;

static uint32_t take32(stream_t *s)
{
    uint32_t v = 0u;
    int16_t k;
    for (k = 0; k < 4; k++) {
        v = (v << 8) | ((s->left > 0u) ? (uint32_t)*s->p : 0u);
        if (s->left > 0u) {
            s->p++;
            s->left--;
        }
    }
    return v;
}

static ctl_q take_q(stream_t *s)
{
    const uint32_t bits = take32(s);
#if CTL_MATH_FLOAT
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
#else
    return (ctl_q)bits;
#endif
}

static float take_float(stream_t *s)
{
    const uint32_t bits = take32(s);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* The expected duty of a leg at 1 or 0 in the active state and in the zero state. */
static ctl_q leg_duty(bool active, bool zero, ctl_q d)
{
    if (active == zero) {
        return zero ? CTL_Q(1.0) : CTL_Q(0.0);
    }
    return active ? d : ctl_sub(CTL_Q(1.0), d);
}

/* One three-phase set realises "active state for d, its zero state 000 or 111 for the rest"
 * (ctl_pulse.h); a zero command (duty 0) holds a zero state. With an open phase in the set its
 * healthy legs do so (the open leg is checked by the caller). */
static bool set_realised(const ctl_cmd_t *cmd, int16_t set, int16_t open_leg)
{
    const int16_t open = (int16_t)(open_leg - 3 * set);
    const int16_t healthy = (int16_t)((open >= 0 && open < 3) ? (07 & ~(1 << (2 - open))) : 07);
    const int16_t bits = (int16_t)((cmd->vector >> (3 - 3 * set)) & healthy);
    int16_t zero;
    if (cmd->duty == CTL_Q(0.0) && bits != 0 && bits != healthy) {
        return false;
    }
    for (zero = 0; zero < 2; zero++) {
        const bool z = (cmd->duty == CTL_Q(0.0)) ? bits != 0 : zero != 0;
        bool matched = true;
        int16_t leg;
        for (leg = (int16_t)(3 * set); leg < 3 * set + 3; leg++) {
            matched =
                matched && (leg == open_leg ||
                            cmd->leg_duty[leg] ==
                                leg_duty(ctl_vector_leg(cmd->vector, leg) != 0, z, cmd->duty));
        }
        if (matched) {
            return true;
        }
    }
    return false;
}

/* With an open phase (open_leg >= 0) its leg is never on and the vector never names it; the
 * other legs follow the same arrangement rules. A carrier-PWM command (FOC-VSD, carrier) names
 * no vector: six duties in [0, 1], vector and duty 0. */
static void check_command(const ctl_cmd_t *cmd, int16_t open_leg, bool carrier)
{
    const int16_t mask = (int16_t)((open_leg >= 0) ? (077 & ~(1 << (5 - open_leg))) : 077);
    int16_t leg;
    if (!cmd->enable) {
        for (leg = 0; leg < CTL_PHASES; leg++) {
            if (cmd->leg_duty[leg] != CTL_Q(0.0)) {
                abort();
            }
        }
        return;
    }
    if (cmd->vector < 0 || cmd->vector > 63) {
        abort();
    }
    if (!(cmd->duty >= CTL_Q(0.0) && cmd->duty <= CTL_Q(1.0))) {
        abort();
    }
    for (leg = 0; leg < CTL_PHASES; leg++) {
        if (!(cmd->leg_duty[leg] >= CTL_Q(0.0) && cmd->leg_duty[leg] <= CTL_Q(1.0))) {
            abort();
        }
    }
    if (carrier) {
        if (cmd->vector != 0 || cmd->duty != CTL_Q(0.0) || open_leg >= 0) {
            abort();
        }
        return;
    }
    if ((cmd->vector & ~mask) != 0 || (open_leg >= 0 && cmd->leg_duty[open_leg] != CTL_Q(0.0))) {
        abort();
    }
    if (!set_realised(cmd, 0, open_leg) || !set_realised(cmd, 1, open_leg)) {
        abort();
    }
}

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    static ctl_t c;
    static ctl_protect_t prot;
    stream_t s;
    ctl_params_t p;
    int32_t steps = 0;
    s.p = data;
    s.left = size;
    ctl_params_default(&p);
    if (!ctl_init(&c, &p)) {
        abort(); /* the defaults must always be valid */
    }
    ctl_protect_init(&prot);
    while (s.left > 0u && steps < 2000) {
        const uint32_t tag = take32(&s) % 8u;
        if (tag == 0u) {
            ctl_params_t q = p;
            q.controller = (ctl_controller_t)(take32(&s) % 4u); /* 3: FOC-VSD */
            q.lambda_nm_per_wb = take_float(&s);
            q.duty_levels = (int16_t)(take32(&s) % 16u);
            q.ddc_direction = (ctl_ddc_direction_t)(take32(&s) % 3u);
            q.ddc_torque_guard = (take32(&s) & 1u) != 0u;
            q.ddc_flux_tie_band = take_float(&s);
            q.torque_limit_nm = take_float(&s);
            q.speed_kp_nm_per_rad_s = take_float(&s);
            q.lq_h = take_float(&s);
            q.pulse_pattern = (ctl_pulse_pattern_t)(take32(&s) % 4u); /* 3: refused */
            q.open_phase = (int16_t)((int32_t)(take32(&s) % 9u) - 2); /* -2..6: 2 refused */
            q.postfault_strategy = (int16_t)(take32(&s) % 3u);        /* 2 refused */
            (void)ctl_request_params(&c, &q);
        } else if (tag == 1u) {
            ctl_set_loop_mode(&c, (take32(&s) & 1u) ? CTL_LOOP_TORQUE : CTL_LOOP_SPEED);
            ctl_set_speed_ref(&c, take_q(&s));
            ctl_set_torque_ref(&c, take_q(&s));
        } else {
            ctl_meas_t m;
            ctl_cmd_t cmd;
            ctl_protect_input_t in;
            int16_t k;
            for (k = 0; k < CTL_PHASES; k++) {
                m.i_phase[k] = take_q(&s);
                in.i_phase[k] = m.i_phase[k];
                in.raw_phase[k] = (int16_t)(take32(&s) % 4096u);
            }
            m.vdc = take_q(&s);
            m.theta_e = take_q(&s);
            m.omega_e = take_q(&s);
            ctl_step(&c, &m, &cmd);
            check_command(&cmd, ctl_postfault_config(&c)->open_leg, c.foc_step);
            in.vdc = m.vdc;
            in.theta_e = m.theta_e;
            in.omega_e = m.omega_e;
            in.i_d = ctl_diag(&c)->i_d;
            in.i_q = ctl_diag(&c)->i_q;
            in.model = &ctl_config(&c)->model;
            in.raw_vdc = (int16_t)(take32(&s) % 4096u);
            in.encoder_healthy = (tag & 1u) != 0u;
            in.overrun = false;
            in.hw_trip = false;
            in.running = true;
            in.currents_calibrated = (tag & 2u) != 0u;
            in.xy_held = (tag & 4u) != 0u;
            (void)ctl_protect_check(&prot, &ctl_config(&c)->protect, &in, ctl_diag(&c)->torque_ref,
                                    cmd.vector, cmd.duty);
            if ((prot.latched & (uint16_t)~0x3FFFu) != 0u ||
                ctl_protect_log_pending(&prot) > CTL_PROTECT_LOG_SIZE) {
                abort();
            }
            steps++;
        }
    }
    return 0;
}
