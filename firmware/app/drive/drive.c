#include "drive.h"

#include "ctl_pu.h"
#include "drive_capture.h"
#include "drive_commission.h"
#include "drive_open_phase.h"
#include "hal_board.h"
#include "hal_cycles.h"
#include "hal_pwm.h"
#include "measure/profile.h"
#include "sixphase_placement.h"

/* The control core's fault bits are the fault list's (drive_faults.h). */
#define DRIVE_FAULT_BIT_CHECK(name, code, bit_name, bit, text)                                     \
    typedef char                                                                                   \
        drive_fault_bit_check_##name[(CTL_FAULT_##bit_name == (uint16_t)(1u << (bit))) ? 1 : -1];
DRIVE_FAULT_LIST(DRIVE_FAULT_BIT_CHECK)
#undef DRIVE_FAULT_BIT_CHECK

/* Severity order, the list's: the first bit present names the drive fault. */
#define DRIVE_FAULT_MAP_ENTRY(name, code, bit_name, bit, text)                                     \
    {(uint16_t)(1u << (bit)), DRIVE_FAULT_##name},
SIXPHASE_RAMCONST static const struct {
    uint16_t bit;
    drive_fault_t code;
} drive_fault_map[] = {DRIVE_FAULT_LIST(DRIVE_FAULT_MAP_ENTRY)};
#undef DRIVE_FAULT_MAP_ENTRY

#define DRIVE_FAULT_MAP_LEN ((int16_t)(sizeof drive_fault_map / sizeof drive_fault_map[0]))

SIXPHASE_RAMFUNC drive_fault_t drive_fault_from_mask(uint16_t faults)
{
    int16_t i;
    for (i = 0; i < DRIVE_FAULT_MAP_LEN; i++) {
        if ((faults & drive_fault_map[i].bit) != 0u) {
            return drive_fault_map[i].code;
        }
    }
    return DRIVE_FAULT_NONE;
}

uint16_t drive_fault_to_mask(drive_fault_t fault)
{
    int16_t i;
    for (i = 0; i < DRIVE_FAULT_MAP_LEN; i++) {
        if (drive_fault_map[i].code == fault) {
            return drive_fault_map[i].bit;
        }
    }
    return 0u;
}

/* Outputs off first, then the bookkeeping; the first code since the last clear stays. */
static void drive_latch_fault(drive_t *d, drive_fault_t fault)
{
    hal_pwm_force_off();
    comm_abort(&d->comm, COMM_REASON_FAULT); /* a sequence running ends here */
    d->phase_verifying = false;
    if (d->state != DRIVE_STATE_FAULT) {
        d->fault = fault;
        d->state = DRIVE_STATE_FAULT;
    }
    d->run_requested = false;
    if (d->clear_requested) {
        /* a clear pending in a faulty period is refused, and the status says by what */
        d->clear_blocked = d->protect.active | drive_fault_to_mask(fault);
        d->clear_requested = false;
    }
}

/* A fault found outside the protection's periodic check: logged there too. */
static void drive_enter_fault(drive_t *d, drive_fault_t fault)
{
    /* the record's torque from the model in force now: the input's pointer is the last period's,
     * and a buffer switched since may be the background's to rewrite */
    d->protect_in.model = d->ctl.initialised ? &ctl_config(&d->ctl)->model : 0;
    ctl_protect_raise(&d->protect, drive_fault_to_mask(fault), &d->protect_in);
    drive_latch_fault(d, fault);
}

static void drive_init_protection(drive_t *d)
{
    ctl_params_t reference;
    ctl_config_t *fallback = &d->ctl.config[1];
    int16_t i;
    /* Limits and speed scaling for as long as no valid set is in force (a refused init): those
     * of the reference machine, built into the unused half of the controller's buffer. */
    ctl_params_default(&reference);
    (void)ctl_config_build(fallback, &reference);
    d->fallback_limits = fallback->protect;
    d->fallback_omega_pu_per_rev_s = fallback->omega_pu_per_rev_s;
    ctl_protect_init(&d->protect);
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        d->protect_in.i_phase[i] = CTL_Q(0.0);
        d->protect_in.raw_phase[i] = (int16_t)HAL_BOARD_CURRENT_ZERO_COUNTS;
    }
    d->protect_in.vdc = CTL_Q(0.0);
    d->protect_in.theta_e = CTL_Q(0.0);
    d->protect_in.omega_e = CTL_Q(0.0);
    d->protect_in.i_d = CTL_Q(0.0);
    d->protect_in.i_q = CTL_Q(0.0);
    d->protect_in.model = 0;
    d->protect_in.raw_vdc = 0;
    d->protect_in.encoder_healthy = false;
    d->protect_in.overrun = false;
    d->protect_in.hw_trip = false;
    d->protect_in.running = false;
    d->protect_in.currents_calibrated = false;
    d->protect_in.xy_held = false;
}

/* No leg isolated, the build's open-phase option. */
static void drive_init_open_phase(drive_t *d, const ctl_params_t *p)
{
    d->open_phase_action = (int16_t)DRIVE_OPEN_PHASE_DEFAULT;
    d->postfault_strategy = p->postfault_strategy;
    d->isolated_leg = -1;
    d->isolation_cause = (int16_t)DRIVE_ISOLATION_NONE;
    d->isolation_period = 0u;
    d->isolate_request = -1;
    d->restore_request = false;
    d->open_phase_paused = false;
    d->params_bg.open_phase = -1; /* the drive owns it: no leg is isolated at start */
    d->torque_limited_action = (int16_t)DRIVE_TORQUE_LIMITED_DEFAULT;
    d->torque_limited_stop_s = DRIVE_TORQUE_LIMITED_STOP_S;
    d->at_limit = false;
    d->at_limit_since = 0u;
    d->torque_limited = false;
    d->torque_limited_stopped = false;
}

void drive_init(drive_t *d, const ctl_params_t *p)
{
    int16_t i;
    d->state = DRIVE_STATE_INIT;
    d->fault = DRIVE_FAULT_NONE;
    d->run_requested = false;
    d->stop_requested = false;
    d->clear_requested = false;
    d->calibration_samples = 0;
    d->isr_count = 0;
    d->calibrated = false;
    d->run_refused = 0u;
    d->run_refusal = DRIVE_RUN_ACCEPTED;
    d->clear_blocked = 0u;
    d->params_bg = *p;
    drive_init_open_phase(d, p);
    d->speed_ref_rpm = 0.0f;
    d->torque_ref_nm = 0.0f;
    d->link_token = 0u; /* disarmed until the host arms a session */
    d->link_sessions = 0u;
    d->isr_cycles_last = 0u;
    d->isr_cycles_max = 0u;
    comm_init(&d->comm);
    d->phase_check_pending = false;
    d->phase_verifying = false;
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        d->offset_sum[i] = 0;
        d->offset_counts[i] = (int16_t)HAL_BOARD_CURRENT_ZERO_COUNTS;
    }
    /* the board's counts per ampere and volt are exact in binary; one float division each */
    d->current_pu_per_count =
        ctl_from_float((float)HAL_BOARD_CURRENT_A_PER_COUNT / CTL_BASE_CURRENT_A_F);
    d->vdc_pu_per_count = ctl_from_float((float)HAL_BOARD_VDC_V_PER_COUNT / CTL_BASE_VOLTAGE_V_F);
    d->isr_latency_cycles = 0u;
    capture_init(&d->capture);
    prof_init((uint32_t)((float)hal_cycles_per_second() * p->sample_time_s + 0.5f),
              hal_cycles_per_second());
    hal_pwm_force_off();
    drive_init_protection(d);
    if (!ctl_init(&d->ctl, &d->params_bg)) {
        drive_enter_fault(d, DRIVE_FAULT_PARAMS);
        return;
    }
    d->state = DRIVE_STATE_CALIBRATE;
}

SIXPHASE_RAMFUNC static void drive_calibrate(drive_t *d)
{
    int16_t i;
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        d->offset_sum[i] += (int32_t)d->adc.phase[i];
    }
    d->calibration_samples++;
    if (d->calibration_samples < DRIVE_CALIBRATION_SAMPLES) {
        return;
    }
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        const int32_t mean =
            (d->offset_sum[i] + DRIVE_CALIBRATION_SAMPLES / 2) / DRIVE_CALIBRATION_SAMPLES;
        const int32_t dev = mean - (int32_t)HAL_BOARD_CURRENT_ZERO_COUNTS;
        if (dev > DRIVE_OFFSET_TOLERANCE_COUNTS || dev < -DRIVE_OFFSET_TOLERANCE_COUNTS) {
            drive_enter_fault(d, DRIVE_FAULT_ADC_OFFSET);
            return;
        }
        d->offset_counts[i] = (int16_t)mean;
    }
    d->calibrated = true;
    d->state = DRIVE_STATE_READY;
}

SIXPHASE_RAMFUNC static void drive_start_calibration(drive_t *d)
{
    int16_t i;
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        d->offset_sum[i] = 0;
    }
    d->calibration_samples = 0;
    d->state = DRIVE_STATE_CALIBRATE;
}

/* Speed scaling and protection limits of the parameter set in force (they follow every
 * applied set); the reference machine's while no valid set was ever in force. */
SIXPHASE_RAMFUNC static ctl_q drive_omega_scale(const drive_t *d)
{
    return d->ctl.initialised ? ctl_config(&d->ctl)->omega_pu_per_rev_s
                              : d->fallback_omega_pu_per_rev_s;
}

SIXPHASE_RAMFUNC static const ctl_protect_limits_t *drive_limits(const drive_t *d)
{
    return d->ctl.initialised ? &ctl_config(&d->ctl)->protect : &d->fallback_limits;
}

const ctl_protect_limits_t *drive_protect_limits(const drive_t *d) { return drive_limits(d); }

SIXPHASE_RAMFUNC static void drive_scale_measurements(drive_t *d)
{
    int16_t i;
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        const int16_t counts = (int16_t)((int16_t)d->adc.phase[i] - d->offset_counts[i]);
        d->meas.i_phase[i] = ctl_mul_int(d->current_pu_per_count, counts);
    }
    d->meas.vdc = ctl_mul_int(d->vdc_pu_per_count, (int16_t)d->adc.vdc);
    d->meas.theta_e = ctl_from_turn_u32(d->encoder.elec_angle);
    d->meas.omega_e = ctl_mul_q16(d->encoder.mech_speed_q16, drive_omega_scale(d));
}

SIXPHASE_RAMFUNC uint16_t drive_duty_to_hal(ctl_q duty)
{
    const int32_t q15 = ctl_to_qn(duty, 15);
    if (q15 <= 0) {
        return 0u;
    }
    if (q15 >= (int32_t)HAL_PWM_DUTY_ONE) {
        return (uint16_t)HAL_PWM_DUTY_ONE;
    }
    return (uint16_t)q15;
}

SIXPHASE_RAMFUNC static void drive_run_step(drive_t *d)
{
    uint16_t duty[HAL_PWM_LEGS];
    int16_t i;
    prof_mark(PROF_ADC);
    if (!drive_open_phase_gate(d)) {
        return; /* outputs off until the set in force fits the isolated legs */
    }
    ctl_step(&d->ctl, &d->meas, &d->cmd);
    if (!d->cmd.enable) {
        hal_pwm_force_off();
        return;
    }
    for (i = 0; i < HAL_PWM_LEGS; i++) {
        duty[i] = drive_duty_to_hal(d->cmd.leg_duty[i]);
    }
    hal_pwm_write(duty);
    prof_mark(PROF_PWM);
}

void drive_run_period(drive_t *d) { drive_run_step(d); }

static void drive_control_step(drive_t *d);

SIXPHASE_RAMFUNC drive_run_refusal_t drive_run_check(const drive_t *d)
{
    if (d->state != DRIVE_STATE_READY) {
        return DRIVE_RUN_REFUSED_STATE;
    }
    if (!d->encoder.healthy) {
        return DRIVE_RUN_REFUSED_ENCODER;
    }
    if (d->meas.vdc < drive_limits(d)->dc_undervoltage) {
        return DRIVE_RUN_REFUSED_UNDERVOLTAGE;
    }
    return DRIVE_RUN_ACCEPTED;
}

SIXPHASE_RAMFUNC static void drive_refuse_run(drive_t *d, drive_run_refusal_t why)
{
    d->run_refusal = why;
    if (d->run_refused < UINT16_MAX) {
        d->run_refused++;
    }
}

/* READY: a run request starts the drive when nothing stands against it; otherwise a
 * commissioning request may start the sequence. */
SIXPHASE_RAMFUNC static void drive_ready_step(drive_t *d)
{
    drive_run_refusal_t why;
    if (!d->run_requested) {
        drive_commission_begin(d);
        return;
    }
    d->run_requested = false;
    why = drive_run_check(d);
    if (why != DRIVE_RUN_ACCEPTED) {
        drive_refuse_run(d, why);
        return;
    }
    d->stop_requested = false;
    ctl_reset(&d->ctl);
    d->state = DRIVE_STATE_RUN;
    hal_pwm_enable();
    /* after an OPEN_PHASE clear: the phase check first, on six legs (with a leg isolated the
     * open-phase protection watches the five that run; the check waits for the restore) */
    if (d->phase_check_pending && d->isolated_leg < 0) {
        drive_phase_verify_start(d);
        drive_phase_verify_period(d);
        return;
    }
    drive_run_step(d);
}

SIXPHASE_RAMFUNC void drive_control_isr(drive_t *d)
{
    prof_begin(d->isr_latency_cycles);
    drive_control_step(d);
    drive_capture_period(d);
    prof_end();
}

/* Protection inputs of this period: the scaled and raw measurements, the torque the
 * controller estimated last period (the record keeps the command in force). */
SIXPHASE_RAMFUNC static uint16_t drive_protect(drive_t *d, bool running)
{
    ctl_protect_input_t *in = &d->protect_in;
    int16_t i;
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        in->i_phase[i] = d->meas.i_phase[i];
        in->raw_phase[i] = (int16_t)d->adc.phase[i];
    }
    in->vdc = d->meas.vdc;
    in->raw_vdc = (int16_t)d->adc.vdc;
    in->theta_e = d->meas.theta_e;
    in->omega_e = d->meas.omega_e;
    in->i_d = (running && !d->phase_verifying) ? d->ctl.diag.i_d : CTL_Q(0.0);
    in->i_q = (running && !d->phase_verifying) ? d->ctl.diag.i_q : CTL_Q(0.0);
    in->model = d->ctl.initialised ? &ctl_config(&d->ctl)->model : 0;
    in->encoder_healthy = d->encoder.healthy;
    if (d->state == DRIVE_STATE_COMMISSION) {
        /* the sequence may run before the index: only an error after it is unhealthy, and the
         * angle comes from the count, which the index's reset does not make jump */
        in->encoder_healthy = d->encoder.healthy || !d->encoder.index_seen;
        in->theta_e = drive_commission_angle(d);
    }
    in->overrun = false; /* reported by the platform after the ISR (drive_report_overrun) */
    in->hw_trip = hal_pwm_hw_trip_seen();
    in->running = running;
    in->currents_calibrated = d->calibrated;
    /* the DDC's six-leg step runs (not a phase check, whose test current is x-y; not the MPTC
     * baselines, whose cost leaves the x-y currents free; an isolated leg's quiet phases turn the
     * fast check off in the protection) */
    in->xy_held = d->state == DRIVE_STATE_RUN && !d->phase_verifying && d->ctl.xy_held;
    return ctl_protect_check(&d->protect, drive_limits(d), in, d->ctl.diag.torque_ref,
                             d->ctl.applied_vector, d->ctl.applied_duty);
}

SIXPHASE_RAMFUNC uint16_t drive_clear_blockers(const drive_t *d, bool fresh)
{
    const uint16_t latched = d->protect.latched;
    uint16_t blocking = d->protect.active; /* found in this period's check */
    blocking |= latched & (CTL_FAULT_PARAMS | CTL_FAULT_PLATFORM); /* new parameters or a restart */
    if (!fresh) {
        blocking |= CTL_FAULT_ADC_MISSING; /* nothing was evaluated in this period */
    }
    if (hal_pwm_hw_trip_seen()) {
        blocking |= CTL_FAULT_HW_TRIP;
    }
    /* the checks that run only while the motor turns, re-verified at standstill */
    if ((latched & CTL_FAULT_ENCODER) != 0u && !d->encoder.healthy) {
        blocking |= CTL_FAULT_ENCODER;
    }
    if ((latched & CTL_FAULT_DC_UNDERVOLTAGE) != 0u &&
        d->meas.vdc < drive_limits(d)->dc_undervoltage) {
        blocking |= CTL_FAULT_DC_UNDERVOLTAGE;
    }
    if ((latched & CTL_FAULT_ADC_STUCK) != 0u && !ctl_protect_converter_alive(&d->protect)) {
        blocking |= CTL_FAULT_ADC_STUCK;
    }
    return blocking;
}

/* FAULT: a clear request leaves it only when nothing stands against it in this period. */
SIXPHASE_RAMFUNC static void drive_fault_step(drive_t *d, bool fresh)
{
    bool encoder_fault, open_phase;
    hal_pwm_force_off();
    if (!d->clear_requested) {
        return;
    }
    d->clear_requested = false;
    d->clear_blocked = drive_clear_blockers(d, fresh);
    encoder_fault = (d->protect.latched & CTL_FAULT_ENCODER) != 0u;
    open_phase = (d->protect.latched & CTL_FAULT_OPEN_PHASE) != 0u;
    if (d->clear_blocked != 0u || !ctl_protect_clear(&d->protect)) {
        return;
    }
    if (encoder_fault) {
        /* A jump or a stop under torque may have left the count wrong, and a healthy flag at
         * standstill does not say otherwise: the index must be seen again before RUN. */
        hal_encoder_rehome();
        d->encoder.healthy = false;
    }
    if (open_phase) { /* not re-verifiable at standstill: the next run checks the phases */
        d->phase_check_pending = true;
    }
    d->fault = DRIVE_FAULT_NONE;
    if (d->calibrated) {
        d->state = DRIVE_STATE_READY;
    } else {
        drive_start_calibration(d);
    }
}

SIXPHASE_RAMFUNC static void drive_control_step(drive_t *d)
{
    const bool fresh = hal_adc_read(&d->adc);
    uint16_t faults = 0u;
    hal_encoder_read(&d->encoder);
    d->isr_count++;
    if (d->state == DRIVE_STATE_INIT) {
        hal_pwm_force_off();
        return;
    }
    /* a published parameter set takes effect here, at the period start, for everything */
    (void)ctl_config_take(&d->ctl);
    drive_scale_measurements(d);

    drive_open_phase_period(d);
    if (fresh) {
        /* stale words would fake a stuck converter: check fresh conversions only */
        faults =
            drive_protect(d, d->state == DRIVE_STATE_RUN || d->state == DRIVE_STATE_COMMISSION);
        if (faults != 0u) { /* an open phase may be ridden through (drive_open_phase.h) */
            faults = drive_open_phase_faults(d, faults);
        }
    } else {
        /* The ADC converts every period whatever the state (ePWM1 starts it with the outputs
         * off too): a period without a conversion is a fault in READY and FAULT as well, and
         * nothing of it can be checked except the trip pin. */
        drive_enter_fault(d, DRIVE_FAULT_ADC_MISSING);
        if (hal_pwm_hw_trip_seen()) {
            drive_enter_fault(d, DRIVE_FAULT_HW_TRIP);
        }
    }
    if (faults != 0u) {
        drive_latch_fault(d, drive_fault_from_mask(faults));
    }
    if (d->run_requested && d->state != DRIVE_STATE_READY) {
        d->run_requested = false; /* refused, not deferred */
        if (d->state != DRIVE_STATE_RUN) {
            drive_refuse_run(d, DRIVE_RUN_REFUSED_STATE);
        }
    }
    if (d->clear_requested && d->state != DRIVE_STATE_FAULT) {
        d->clear_requested = false; /* never pre-arm the clearing of a later fault */
    }

    switch (d->state) {
    case DRIVE_STATE_CALIBRATE:
        drive_calibrate(d);
        break;
    case DRIVE_STATE_READY:
        drive_ready_step(d);
        break;
    case DRIVE_STATE_RUN:
        if (d->stop_requested) {
            d->stop_requested = false;
            hal_pwm_force_off();
            comm_abort(&d->comm, COMM_REASON_ABORTED); /* a phase check before control */
            d->phase_verifying = false;
            d->state = DRIVE_STATE_READY;
            break;
        }
        if (d->phase_verifying) {
            drive_phase_verify_period(d);
            break;
        }
        drive_run_step(d);
        break;
    case DRIVE_STATE_COMMISSION:
        drive_commission_period(d);
        break;
    case DRIVE_STATE_FAULT:
        drive_fault_step(d, fresh);
        break;
    case DRIVE_STATE_INIT:
    default:
        hal_pwm_force_off();
        break;
    }
}

void drive_request_run(drive_t *d) { d->run_requested = true; }

ctl_param_error_t drive_request_params(drive_t *d, const ctl_params_t *p)
{
    ctl_params_t *q = &d->params_req; /* background only: drive.h */
    ctl_param_error_t e;
    if (q != p) {
        *q = *p;
    }
    /* the open phase is the drive's: the leg it isolated (drive_open_phase.h) */
    q->open_phase = d->isolated_leg;
    q->postfault_strategy = d->postfault_strategy;
    e = ctl_request_params(&d->ctl, q);
    if (e == CTL_PARAM_OK) {
        const bool rescale = q->pole_pairs != d->params_bg.pole_pairs;
        d->params_bg = *q;
        if (rescale && d->ctl.loop_mode == CTL_LOOP_SPEED) {
            drive_set_speed_ref_rpm(d, d->speed_ref_rpm); /* electrical reference follows Pn */
        }
    }
    return e;
}

void drive_trip(drive_t *d, drive_fault_t fault) { drive_enter_fault(d, fault); }

bool drive_read_fault_record(drive_t *d, ctl_fault_record_t *r)
{
    return ctl_protect_read_record(&d->protect, r);
}

uint16_t drive_faults_latched(const drive_t *d) { return d->protect.latched; }

void drive_report_overrun(drive_t *d)
{
    prof_count_overrun();
    drive_trip(d, DRIVE_FAULT_OVERRUN);
}
void drive_request_stop(drive_t *d) { d->stop_requested = true; }
void drive_request_clear_fault(drive_t *d) { d->clear_requested = true; }

bool drive_set_current_span(drive_t *d, float full_span_a)
{
    if (d->state == DRIVE_STATE_RUN || d->state == DRIVE_STATE_COMMISSION ||
        !(full_span_a >= DRIVE_CURRENT_SPAN_MIN_A && full_span_a <= DRIVE_CURRENT_SPAN_MAX_A)) {
        return false;
    }
    d->current_pu_per_count =
        ctl_from_float(full_span_a / (float)(HAL_ADC_FULL_SCALE + 1u) / CTL_BASE_CURRENT_A_F);
    return true;
}

void drive_set_speed_ref_rpm(drive_t *d, float rpm)
{
    const float omega_e = rpm * (CTL_TWO_PI_F / 60.0f) * (float)d->params_bg.pole_pairs;
    d->speed_ref_rpm = rpm;
    ctl_set_loop_mode(&d->ctl, CTL_LOOP_SPEED);
    ctl_set_speed_ref(&d->ctl, ctl_from_float(omega_e / CTL_BASE_OMEGA_RAD_S_F));
}

void drive_set_torque_ref_nm(drive_t *d, float torque_nm)
{
    d->torque_ref_nm = torque_nm;
    ctl_set_loop_mode(&d->ctl, CTL_LOOP_TORQUE);
    ctl_set_torque_ref(&d->ctl, ctl_from_float(torque_nm / CTL_BASE_TORQUE_NM_F));
}
