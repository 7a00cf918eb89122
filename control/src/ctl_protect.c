#include "ctl_protect.h"

#include "ctl_barrier.h"
#include "ctl_constants.h"
#include "ctl_pu.h"
#include "ctl_placement.h"
#include "ctl_vsd.h"
#include "ctl_qmath.h"

static void open_phase_restart(ctl_protect_t *p);
static void open_phase_fast_reset(ctl_protect_t *p);

void ctl_protect_settings_default(ctl_protect_settings_t *s)
{
    s->overcurrent_a = 15.0f; /* hardware trip is the first line */
    s->overcurrent_periods = 1;
    s->dc_overvoltage_v = 720.0f;
    s->dc_overvoltage_periods = 3;
    s->dc_undervoltage_v = 350.0f;
    s->dc_undervoltage_periods = 10;
    s->overspeed_rpm = 2000.0f;
    s->overspeed_periods = 5;
    s->current_sum_a = 2.0f;
    s->current_sum_periods = 5;
    s->adc_rail_low_counts = 2;
    s->adc_rail_high_counts = 4093;
    s->adc_rail_periods = 3;
    s->adc_stuck_periods = 50; /* 5 ms: switching ripple moves every word each period */
    s->stuck_min_current_a = 1.0f;
    s->encoder_torque_nm = 1.0f;
    s->encoder_expected_turns = 0.25f;
    s->encoder_jump_turns = 0.05f;
    s->open_phase_min_current_a = 0.1f;
    s->open_phase_ratio = 0.2f;
    s->open_phase_fast_min_a = 0.1f;
    s->open_phase_fast_ratio = 0.2f;
}

static bool periods_valid(int16_t n) { return n >= 1 && n <= 10000; }

bool ctl_protect_settings_valid(const ctl_protect_settings_t *s)
{
    const float big = 1.0e6f;
    const bool thresholds = ctl_float_in_range(s->overcurrent_a, 0.01f, big) &&
                            ctl_float_in_range(s->dc_overvoltage_v, 1.0f, big) &&
                            ctl_float_in_range(s->dc_undervoltage_v, 0.0f, big) &&
                            s->dc_undervoltage_v < s->dc_overvoltage_v &&
                            ctl_float_in_range(s->overspeed_rpm, 1.0f, big) &&
                            ctl_float_in_range(s->current_sum_a, 0.01f, big) &&
                            ctl_float_in_range(s->stuck_min_current_a, 0.0f, big) &&
                            ctl_float_in_range(s->encoder_torque_nm, 0.0f, big) &&
                            ctl_float_in_range(s->encoder_expected_turns, 0.01f, big) &&
                            ctl_float_in_range(s->encoder_jump_turns, 0.001f, big) &&
                            ctl_float_in_range(s->open_phase_min_current_a, 0.0f, big) &&
                            ctl_float_in_range(s->open_phase_ratio, 0.0f, 1.0f) &&
                            ctl_float_in_range(s->open_phase_fast_min_a, 0.0f, big) &&
                            ctl_float_in_range(s->open_phase_fast_ratio, 0.0f, 1.0f);
    const bool filters =
        periods_valid(s->overcurrent_periods) && periods_valid(s->dc_overvoltage_periods) &&
        periods_valid(s->dc_undervoltage_periods) && periods_valid(s->overspeed_periods) &&
        periods_valid(s->current_sum_periods) && periods_valid(s->adc_rail_periods) &&
        periods_valid(s->adc_stuck_periods);
    const bool rails =
        s->adc_rail_low_counts >= -1 && s->adc_rail_low_counts < s->adc_rail_high_counts;
    return thresholds && filters && rails;
}

void ctl_protect_limits_build(ctl_protect_limits_t *l, const ctl_protect_settings_t *s,
                              float sample_time_s, int16_t pole_pairs, float inertia_kg_m2)
{
    const float ib = CTL_BASE_CURRENT_A_F;
    const float vb = CTL_BASE_VOLTAGE_V_F;
    const float wb = CTL_BASE_OMEGA_RAD_S_F;
    const float pp = (float)pole_pairs;
    l->overcurrent = ctl_from_float(s->overcurrent_a / ib);
    l->overcurrent_periods = s->overcurrent_periods;
    l->dc_overvoltage = ctl_from_float(s->dc_overvoltage_v / vb);
    l->dc_overvoltage_periods = s->dc_overvoltage_periods;
    l->dc_undervoltage = ctl_from_float(s->dc_undervoltage_v / vb);
    l->dc_undervoltage_periods = s->dc_undervoltage_periods;
    l->overspeed = ctl_from_float(s->overspeed_rpm * (CTL_TWO_PI_F / 60.0f) * pp / wb);
    l->overspeed_periods = s->overspeed_periods;
    l->current_sum = ctl_from_float(s->current_sum_a / ib);
    l->current_sum_periods = s->current_sum_periods;
    l->adc_rail_low = s->adc_rail_low_counts;
    l->adc_rail_high = s->adc_rail_high_counts;
    l->adc_rail_periods = s->adc_rail_periods;
    l->adc_stuck_periods = s->adc_stuck_periods;
    l->stuck_min_current = ctl_from_float(s->stuck_min_current_a / ib);
    l->encoder_torque = ctl_from_float(s->encoder_torque_nm / CTL_BASE_TORQUE_NM_F);
    l->encoder_expected_turn = ctl_from_float(s->encoder_expected_turns);
    l->encoder_jump = ctl_from_float(s->encoder_jump_turns);
    l->torque_to_dspeed =
        ctl_from_float(CTL_BASE_TORQUE_NM_F * pp * sample_time_s / (inertia_kg_m2 * wb));
    l->ts_turns = ctl_from_float(sample_time_s * wb / CTL_TWO_PI_F);
    l->open_phase_min_mean = ctl_from_float(s->open_phase_min_current_a / ib);
    l->open_phase_ratio = ctl_from_float(s->open_phase_ratio);
    l->open_phase_fast_ratio = ctl_from_float(s->open_phase_fast_ratio);
    /* compared with a window's deficit: ratio times the expected current, summed */
    l->open_phase_fast_min =
        ctl_from_float(s->open_phase_fast_min_a / ib * s->open_phase_fast_ratio *
                       (float)CTL_PROTECT_OPEN_PHASE_FAST_WINDOW);
    l->open_phase_fast_keep =
        ctl_from_float(-4.0f * s->open_phase_fast_min_a / ib * s->open_phase_fast_ratio *
                       (float)CTL_PROTECT_OPEN_PHASE_FAST_WINDOW);
}

static void reset_filters(ctl_protect_t *p)
{
    int16_t k;
    p->n_overcurrent = 0;
    p->n_overvoltage = 0;
    p->n_undervoltage = 0;
    p->n_overspeed = 0;
    p->n_sum = 0;
    p->n_rail = 0;
    /* The converter's history (last_raw, word_age, stuck_latched_at) survives: a clear
     * that forgot it would count the frozen word as a fresh change and pass a dead ADC. */
    for (k = 0; k < 7; k++) {
        p->n_stuck[k] = 0;
    }
    p->expected_speed = CTL_Q(0.0);
    p->expected_angle = CTL_Q(0.0);
    p->have_last = false;
    p->last_theta = CTL_Q(0.0);
    open_phase_restart(p);
    open_phase_fast_reset(p);
}

void ctl_protect_init(ctl_protect_t *p)
{
    int16_t k;
    p->latched = 0u;
    p->active = 0u;
    p->period = 0u;
    p->log_write = 0u;
    p->log_read = 0u;
    p->log_dropped = 0u;
    p->episode_recorded = false;
    p->quiet = 0u;
    p->inv_judged = CTL_K_ONE_SIXTH;
    p->open_phase = -1;
    for (k = 0; k < 7; k++) {
        p->last_raw[k] = -1;
    }
    for (k = 0; k < 6; k++) {
        p->word_age[k] = 0;
    }
    p->stuck_latched_at = 0u;
    reset_filters(p);
}

/* New faults (not latched yet) are about to latch: a stuck converter must show every word
 * change after this period before a clear (ctl_protect_converter_alive). Off the normal path:
 * only in the period that latches something new. */
static void note_new_faults(ctl_protect_t *p, uint16_t faults)
{
    if ((faults & CTL_FAULT_ADC_STUCK) != 0u && (p->latched & CTL_FAULT_ADC_STUCK) == 0u) {
        p->stuck_latched_at = p->period;
    }
}

/* Count consecutive periods a condition holds; true once it held for `periods`. */
SIXPHASE_RAMFUNC static bool filtered(bool condition, int16_t *count, int16_t periods)
{
    if (!condition) {
        *count = 0;
        return false;
    }
    if (*count < periods) {
        (*count)++;
    }
    return *count >= periods;
}

SIXPHASE_RAMFUNC static bool any_nan(const ctl_protect_input_t *in)
{
#if CTL_MATH_FLOAT
    int16_t k;
    bool nan = !(in->vdc == in->vdc) || !(in->theta_e == in->theta_e) ||
               !(in->omega_e == in->omega_e) || !(in->i_d == in->i_d) || !(in->i_q == in->i_q);
    for (k = 0; k < 6; k++) {
        nan = nan || !(in->i_phase[k] == in->i_phase[k]);
    }
    return nan;
#else
    (void)in;
    return false;
#endif
}

/* Signed angle difference in turns, in [-0.5, 0.5). */
SIXPHASE_RAMFUNC static ctl_q turn_difference(ctl_q a, ctl_q b)
{
    return ctl_sub(ctl_wrap_turn(ctl_add(ctl_sub(a, b), CTL_Q(0.5))), CTL_Q(0.5));
}

/* Te from the input's measured currents with its model; 0 without a model. */
SIXPHASE_RAMFUNC static ctl_q protect_torque(const ctl_protect_input_t *in)
{
    return (in->model == 0) ? CTL_Q(0.0) : ctl_torque_held(in->model, in->i_d, in->i_q);
}

/* No count this period: while torque acts, the motion a free rotor would have made since the
 * last count (speed grows linearly, angle with its sum). The torque is estimated here, the only
 * period work that needs it (issue 28: the step no longer does). */
SIXPHASE_RAMFUNC static void expect_motion(ctl_protect_t *p, const ctl_protect_limits_t *l,
                                           const ctl_protect_input_t *in, uint16_t *f)
{
    const ctl_q torque = protect_torque(in);
    if (ctl_abs(torque) <= l->encoder_torque) {
        return;
    }
    p->expected_speed = ctl_add(p->expected_speed, ctl_abs(ctl_mul(torque, l->torque_to_dspeed)));
    p->expected_angle = ctl_add(p->expected_angle, ctl_mul(p->expected_speed, l->ts_turns));
    if (p->expected_angle > l->encoder_expected_turn) {
        *f |= CTL_FAULT_ENCODER;
    }
}

SIXPHASE_RAMFUNC static uint16_t check_encoder(ctl_protect_t *p, const ctl_protect_limits_t *l,
                                               const ctl_protect_input_t *in)
{
    uint16_t f = 0u;
    if (!in->running) {
        /* at standstill the index may not have been seen yet: the drive refuses to start
         * instead (an unhealthy encoder only faults while the drive runs) */
        p->have_last = false;
        p->expected_speed = CTL_Q(0.0);
        p->expected_angle = CTL_Q(0.0);
        return 0u;
    }
    if (!in->encoder_healthy) {
        f |= CTL_FAULT_ENCODER;
    }
    if (p->have_last) {
        const ctl_q step = turn_difference(in->theta_e, p->last_theta);
        const ctl_q predicted = ctl_mul(in->omega_e, l->ts_turns);
        if (ctl_abs(ctl_sub(step, predicted)) > l->encoder_jump) {
            f |= CTL_FAULT_ENCODER;
        }
        if (step != CTL_Q(0.0)) {
            p->expected_speed = CTL_Q(0.0);
            p->expected_angle = CTL_Q(0.0);
        } else {
            expect_motion(p, l, in, &f);
        }
    }
    p->last_theta = in->theta_e;
    p->have_last = true;
    return f;
}

/* Phases whose three-phase set had an active state for a real part of the period before this
 * one (its legs not all equal, for at least CTL_PROTECT_DRIVEN_DUTY): every one of its windings
 * then saw at least a third of the DC link, so its current moves by many counts whatever the
 * converter reads (bit k: phase k, A..F). */
SIXPHASE_RAMFUNC static uint16_t driven_phases(int16_t vector, ctl_q duty)
{
    const uint16_t set_abc = ((uint16_t)vector >> 3) & 7u;
    const uint16_t set_def = (uint16_t)vector & 7u;
    uint16_t m = 0u;
    if (vector < 0 || vector > 077 || duty < CTL_PROTECT_DRIVEN_DUTY) {
        return 0u;
    }
    if (set_abc != 0u && set_abc != 7u) {
        m |= 0x07u;
    }
    if (set_def != 0u && set_def != 7u) {
        m |= 0x38u;
    }
    return m;
}

SIXPHASE_RAMFUNC static uint16_t check_adc(ctl_protect_t *p, const ctl_protect_limits_t *l,
                                           const ctl_protect_input_t *in, uint16_t driven)
{
    uint16_t judged;
    uint16_t f = 0u;
    bool rail = false;
    bool flowing = false;
    int16_t k;
    for (k = 0; k < 6; k++) {
        rail = rail || in->raw_phase[k] <= l->adc_rail_low || in->raw_phase[k] >= l->adc_rail_high;
        flowing = flowing || ctl_abs(in->i_phase[k]) > l->stuck_min_current;
    }
    /* The DC link's channel is unipolar: 0 counts is 0 V, a link that is off (bring-up, a
     * drive waiting for its supply), which the under-voltage check judges. Only its top
     * rail means the sensor chain left its range. */
    rail = rail || in->raw_vdc >= l->adc_rail_high;
    if (filtered(rail, &p->n_rail, l->adc_rail_periods)) {
        f |= CTL_FAULT_ADC_RAIL;
    }
    /* Phase currents ripple every period while the inverter switches: a frozen word is a
     * dead converter or multiplexer. Not so a phase that carries no current by design (an
     * isolated leg): a quiet sensor may read one word for good. Judged while current is
     * measured to flow, and - since a converter frozen at idle reads no current at all - on
     * the phases an active state drove in the last period. */
    judged = in->running ? (uint16_t)(~p->quiet & (flowing ? 0x3Fu : driven)) : 0u;
    for (k = 0; k < 6; k++) {
        const bool unchanged = in->raw_phase[k] == p->last_raw[k];
        const bool same = unchanged && (((unsigned)judged >> k) & 1u) != 0u;
        if (filtered(same, &p->n_stuck[k], l->adc_stuck_periods)) {
            f |= CTL_FAULT_ADC_STUCK;
        }
        if (!unchanged) {
            p->word_age[k] = 0;
        } else if (p->word_age[k] < INT16_MAX) {
            p->word_age[k]++;
        }
        p->last_raw[k] = in->raw_phase[k];
    }
    return f;
}

/* x / 64 of a non-negative x: a shift in Q24 instead of a multiply (every period, six times) */
static inline ctl_q sixty_fourth(ctl_q x)
{
#if CTL_MATH_FLOAT
    return x * 0.015625f;
#else
    return x >> 6;
#endif
}

/* The window's verdict: the mean |i| of the judged phases, and every judged phase below the
 * ratio of it is open; the one found is remembered (-1 for several). Starts the next window. */
SIXPHASE_RAMFUNC static uint16_t open_phase_verdict(ctl_protect_t *p, const ctl_protect_limits_t *l)
{
    ctl_q mean = CTL_Q(0.0);
    int16_t found = 0;
    int16_t k;
    for (k = 0; k < 6; k++) {
        if ((((unsigned)p->quiet >> k) & 1u) == 0u) {
            mean = ctl_add(mean, ctl_mul(p->open_sum[k], p->inv_judged));
        }
    }
    if (mean > ctl_mul_int(ctl_mul(l->open_phase_min_mean, CTL_Q(0.015625)), p->open_count)) {
        const ctl_q floor = ctl_mul(mean, l->open_phase_ratio);
        for (k = 0; k < 6; k++) {
            if ((((unsigned)p->quiet >> k) & 1u) == 0u && p->open_sum[k] < floor) {
                p->open_phase = (found == 0) ? k : -1;
                found++;
            }
        }
    }
    open_phase_restart(p);
    return (found > 0) ? CTL_FAULT_OPEN_PHASE : 0u;
}

SIXPHASE_RAMFUNC static void open_phase_restart(ctl_protect_t *p)
{
    int16_t k;
    for (k = 0; k < 6; k++) {
        p->open_sum[k] = CTL_Q(0.0);
    }
    p->open_count = 0;
    p->open_turns = CTL_Q(0.0);
}

/* Mean |i| per phase over a window of at least CTL_PROTECT_OPEN_PHASE_WINDOW periods that also
 * spans one electrical turn made while current flows (six phases' |i| summing to at least three
 * times the minimum mean): a healthy phase then carries current for part of it whatever the
 * current vector's angle, while near standstill (a reversal's zero crossing) one phase may
 * rightly carry none for a long time. A window that reaches 4 times its length without a turn
 * (below about 125 r/min at 10 kHz, 3 pole pairs) is dropped unjudged. Phases that carry no
 * current by design (ctl_protect_quiet: an isolated leg) are neither judged nor in the mean. */
SIXPHASE_RAMFUNC static uint16_t check_open_phase(ctl_protect_t *p, const ctl_protect_limits_t *l,
                                                  const ctl_protect_input_t *in)
{
    int16_t k;
    ctl_q flowing = CTL_Q(0.0);
    if (!in->running) {
        open_phase_restart(p);
        return 0u;
    }
    for (k = 0; k < 6; k++) { /* sums of |i| / 64: 1,600 periods at 3 pu stay in range */
        const ctl_q a = sixty_fourth(ctl_abs(in->i_phase[k]));
        p->open_sum[k] = ctl_add(p->open_sum[k], a);
        flowing = ctl_add(flowing, a);
    }
    /* the turn counts only while current flows: a vector that stops (the current switched off
     * while the rotor coasts on) turns no longer, and a phase's share from before would be
     * judged against a turn it did not make (commissioning's mechanics step: OPEN_PHASE) */
    if (flowing >= ctl_mul(l->open_phase_min_mean, CTL_Q(0.046875))) { /* 3 x min / 64 */
        p->open_turns = ctl_add(p->open_turns, ctl_abs(ctl_mul(in->omega_e, l->ts_turns)));
    }
    p->open_count++;
    if (p->open_count < CTL_PROTECT_OPEN_PHASE_WINDOW || p->open_turns < CTL_Q(1.0)) {
        if (p->open_count >= 4 * CTL_PROTECT_OPEN_PHASE_WINDOW) {
            open_phase_restart(p);
        }
        return 0u;
    }
    return open_phase_verdict(p, l);
}

SIXPHASE_RAMFUNC static void open_phase_fast_restart(ctl_protect_t *p)
{
    int16_t k;
    for (k = 0; k < 6; k++) {
        p->fast_deficit[k] = CTL_Q(0.0);
    }
    p->fast_count = 0;
}

/* The fast check starts over: no window in progress, no suspect. */
SIXPHASE_RAMFUNC static void open_phase_fast_reset(ctl_protect_t *p)
{
    open_phase_fast_restart(p);
    p->fast_suspect = -1;
    p->fast_strikes = 0;
}

/* The fast window's verdict: the phase with the largest deficit, if above the minimum, is the
 * suspect; open when the same phase is so in consecutive windows (a start's x-y transient may
 * hold one phase low for a window or two). A window that judges no phase keeps the suspect unless
 * its deficit fell below minus four times the minimum, as a healthy phase's does (an open phase's
 * share may be too small to judge for a window near its zero crossing, while the open connection's
 * leakage still flows). Starts the next window. */
SIXPHASE_RAMFUNC static uint16_t open_phase_fast_verdict(ctl_protect_t *p,
                                                         const ctl_protect_limits_t *l)
{
    int16_t worst = -1;
    int16_t k;
    bool keep;
    for (k = 0; k < 6; k++) {
        if (p->fast_deficit[k] > l->open_phase_fast_min &&
            (worst < 0 || p->fast_deficit[k] > p->fast_deficit[worst])) {
            worst = k;
        }
    }
    keep = worst < 0 && p->fast_suspect >= 0 &&
           p->fast_deficit[p->fast_suspect] > l->open_phase_fast_keep;
    open_phase_fast_restart(p);
    if (keep) {
        return 0u;
    }
    if (worst < 0 || worst != p->fast_suspect) {
        p->fast_suspect = worst;
        p->fast_strikes = 1; /* counts only while there is a suspect */
        return 0u;
    }
    p->fast_strikes++;
    if (p->fast_strikes < CTL_PROTECT_OPEN_PHASE_FAST_WINDOWS) {
        return 0u;
    }
    p->open_phase = worst;
    return CTL_FAULT_OPEN_PHASE;
}

/* The fast check, on the x-y residual (docs/faults.md, "Two open-phase checks"): while the DDC's
 * six-leg step holds the x-y currents near zero, each phase carries its share of the alpha-beta
 * current, be the machine motoring, braking or at a standstill. An open phase carries nothing
 * whatever its share. Each phase's deficit sums ratio * |share| - |i| over a short window: a
 * healthy phase's stays below zero (it carries its share), an open phase's grows with its share;
 * above the minimum (ratio times the expected current that makes a phase judged) it is open.
 * Needs no turn of the rotor. */
SIXPHASE_RAMFUNC static uint16_t check_open_phase_fast(ctl_protect_t *p,
                                                       const ctl_protect_limits_t *l,
                                                       const ctl_protect_input_t *in)
{
    ctl_vsd_t v;
    ctl_q share[6];
    int16_t k;
    if (!in->running || !in->xy_held || p->quiet != 0u) {
        open_phase_fast_reset(p);
        return 0u;
    }
    ctl_vsd_forward(in->i_phase, &v);
    ctl_vsd_alpha_beta_phases(ctl_mul(v.alpha, l->open_phase_fast_ratio),
                              ctl_mul(v.beta, l->open_phase_fast_ratio), share);
    for (k = 0; k < 6; k++) {
        /* both magnitudes are non-negative: their difference cannot overflow; the sum saturates */
        p->fast_deficit[k] =
            ctl_add(p->fast_deficit[k], ctl_abs(share[k]) - ctl_abs(in->i_phase[k]));
    }
    p->fast_count++;
    if (p->fast_count < CTL_PROTECT_OPEN_PHASE_FAST_WINDOW) {
        return 0u;
    }
    return open_phase_fast_verdict(p, l);
}

static void drop_one(ctl_protect_t *p)
{
    if (p->log_dropped < UINT16_MAX) {
        p->log_dropped++;
    }
}

static void fill_record(ctl_fault_record_t *r, const ctl_protect_t *p, uint16_t faults,
                        const ctl_protect_input_t *in, ctl_q torque_ref, int16_t vector, ctl_q duty)
{
    int16_t k;
    r->faults = faults;
    r->period = p->period;
    for (k = 0; k < 6; k++) {
        r->i_phase[k] = in->i_phase[k];
    }
    r->vdc = in->vdc;
    r->theta_e = in->theta_e;
    r->omega_e = in->omega_e;
    r->torque_est = protect_torque(in);
    r->torque_ref = torque_ref;
    r->vector = vector;
    r->duty = duty;
}

static void record(ctl_protect_t *p, uint16_t faults, const ctl_protect_input_t *in,
                   ctl_q torque_ref, int16_t vector, ctl_q duty)
{
    const uint16_t w = p->log_write;
    const bool full = (uint16_t)(w - p->log_read) >= (uint16_t)CTL_PROTECT_LOG_SIZE;
    if (full && p->episode_recorded) {
        drop_one(p); /* keep the oldest: the first fault of this episode is recorded */
        return;
    }
    if (full) {
        /* A new root cause since the last clear: it replaces the newest record. The reader
         * copies the oldest, eight slots away, so the slot is the ISR's alone. */
        drop_one(p);
        fill_record(&p->log[(uint16_t)(w - 1u) % (uint16_t)CTL_PROTECT_LOG_SIZE], p, faults, in,
                    torque_ref, vector, duty);
        p->episode_recorded = true;
        return;
    }
    fill_record(&p->log[w % (uint16_t)CTL_PROTECT_LOG_SIZE], p, faults, in, torque_ref, vector,
                duty);
    p->episode_recorded = true;
    CTL_COMPILER_BARRIER();            /* the record is complete ... */
    p->log_write = (uint16_t)(w + 1u); /* ... before it is published */
}

SIXPHASE_RAMFUNC uint16_t ctl_protect_check(ctl_protect_t *p, const ctl_protect_limits_t *l,
                                            const ctl_protect_input_t *in, ctl_q torque_ref,
                                            int16_t vector, ctl_q duty)
{
    uint16_t f = 0u;
    bool over = false;
    int16_t k;
    p->period++;
    if (any_nan(in)) {
        f |= CTL_FAULT_MEASUREMENT;
    }
    for (k = 0; k < 6; k++) {
        over = over || ctl_abs(in->i_phase[k]) > l->overcurrent;
    }
    if (filtered(over, &p->n_overcurrent, l->overcurrent_periods)) {
        f |= CTL_FAULT_OVERCURRENT;
    }
    if (filtered(in->vdc > l->dc_overvoltage, &p->n_overvoltage, l->dc_overvoltage_periods)) {
        f |= CTL_FAULT_DC_OVERVOLTAGE;
    }
    if (filtered(in->running && in->vdc < l->dc_undervoltage, &p->n_undervoltage,
                 l->dc_undervoltage_periods)) {
        f |= CTL_FAULT_DC_UNDERVOLTAGE;
    }
    if (filtered(ctl_abs(in->omega_e) > l->overspeed, &p->n_overspeed, l->overspeed_periods)) {
        f |= CTL_FAULT_OVERSPEED;
    }
    {
        const ctl_q sum1 = ctl_add(ctl_add(in->i_phase[0], in->i_phase[1]), in->i_phase[2]);
        const ctl_q sum2 = ctl_add(ctl_add(in->i_phase[3], in->i_phase[4]), in->i_phase[5]);
        const bool bad = in->currents_calibrated &&
                         (ctl_abs(sum1) > l->current_sum || ctl_abs(sum2) > l->current_sum);
        if (filtered(bad, &p->n_sum, l->current_sum_periods)) {
            f |= CTL_FAULT_CURRENT_SUM;
        }
    }
    if (in->overrun) {
        f |= CTL_FAULT_OVERRUN;
    }
    if (in->hw_trip) {
        f |= CTL_FAULT_HW_TRIP;
    }
    f |= check_encoder(p, l, in);
    f |= check_adc(p, l, in, driven_phases(vector, duty));
    f |= check_open_phase(p, l, in);
    f |= check_open_phase_fast(p, l, in);

    p->active = f;
    if ((f & (uint16_t)~p->latched) != 0u) {
        note_new_faults(p, f);
        record(p, f, in, torque_ref, vector, duty);
    }
    p->latched |= f;
    return f;
}

void ctl_protect_raise(ctl_protect_t *p, uint16_t faults, const ctl_protect_input_t *in)
{
    if ((faults & (uint16_t)~p->latched) != 0u) {
        note_new_faults(p, faults);
        record(p, faults, in, CTL_Q(0.0), 0, CTL_Q(0.0));
    }
    p->latched |= faults;
}

void ctl_protect_quiet(ctl_protect_t *p, uint16_t quiet)
{
    int16_t judged = 0;
    int16_t k;
    quiet &= 0x3Fu;
    if (quiet == p->quiet) {
        return;
    }
    for (k = 0; k < 6; k++) {
        judged = (int16_t)(judged + (((((unsigned)quiet >> k) & 1u) == 0u) ? 1 : 0));
    }
    p->quiet = quiet;
    open_phase_fast_reset(p);
    /* no phase judged: the mean stays 0 and nothing is ever below it */
    p->inv_judged = (judged == 6)  ? CTL_K_ONE_SIXTH
                    : (judged > 0) ? ctl_div(CTL_Q(1.0), ctl_mul_int(CTL_Q(1.0), judged))
                                   : CTL_Q(0.0);
    open_phase_restart(p);
}

int16_t ctl_protect_open_phase(const ctl_protect_t *p) { return p->open_phase; }

void ctl_protect_accept(ctl_protect_t *p, uint16_t faults)
{
    p->latched &= (uint16_t)~faults;
    p->episode_recorded = false;
}

bool ctl_protect_clear(ctl_protect_t *p)
{
    if (p->active != 0u) {
        return false;
    }
    p->latched = 0u;
    p->episode_recorded = false;
    reset_filters(p);
    return true;
}

bool ctl_protect_read_record(ctl_protect_t *p, ctl_fault_record_t *r)
{
    const uint16_t rd = p->log_read;
    if (rd == p->log_write) {
        return false;
    }
    CTL_COMPILER_BARRIER(); /* nothing of the record is read before the index */
    *r = p->log[rd % (uint16_t)CTL_PROTECT_LOG_SIZE];
    CTL_COMPILER_BARRIER();            /* the copy is complete ... */
    p->log_read = (uint16_t)(rd + 1u); /* ... before the slot is freed */
    return true;
}

uint16_t ctl_protect_log_pending(const ctl_protect_t *p)
{
    return (uint16_t)(p->log_write - p->log_read);
}

SIXPHASE_RAMFUNC bool ctl_protect_converter_alive(const ctl_protect_t *p)
{
    /* a word changed after the latch: its age is below the periods since (an age that
     * saturated is above CTL_PROTECT_ALIVE_PERIODS anyway) */
    const uint32_t since_stuck = p->period - p->stuck_latched_at;
    int16_t k;
    for (k = 0; k < 6; k++) {
        if ((((unsigned)p->quiet >> k) & 1u) == 0u &&
            (p->word_age[k] >= CTL_PROTECT_ALIVE_PERIODS ||
             (uint32_t)p->word_age[k] >= since_stuck)) {
            return false;
        }
    }
    return true;
}
