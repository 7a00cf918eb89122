#include "drive.h"

#include "ctl_pu.h"
#include "hal_board.h"
#include "hal_cycles.h"
#include "hal_pwm.h"
#include "profile.h"

static void drive_enter_fault(drive_t *d, drive_fault_t fault)
{
    hal_pwm_force_off();
    d->fault = fault;
    d->state = DRIVE_STATE_FAULT;
    d->run_requested = false;
    d->clear_requested = false;
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
    d->params_bg = *p;
    d->speed_ref_rpm = 0.0f;
    d->torque_ref_nm = 0.0f;
    d->isr_cycles_last = 0u;
    d->isr_cycles_max = 0u;
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        d->offset_sum[i] = 0;
        d->offset_counts[i] = (int16_t)HAL_BOARD_CURRENT_ZERO_COUNTS;
    }
    d->current_pu_per_count =
        ctl_from_float((float)(HAL_BOARD_CURRENT_A_PER_COUNT / CTL_BASE_CURRENT_A));
    d->vdc_pu_per_count = ctl_from_float((float)(HAL_BOARD_VDC_V_PER_COUNT / CTL_BASE_VOLTAGE_V));
    d->omega_pu_per_rev_s =
        ctl_from_float((float)(CTL_TWO_PI / CTL_BASE_OMEGA_RAD_S) * (float)p->pole_pairs);
    d->isr_latency_cycles = 0u;
    prof_init((uint32_t)((float)hal_cycles_per_second() * p->sample_time_s + 0.5f),
              hal_cycles_per_second());
    hal_pwm_force_off();
    if (!ctl_init(&d->ctl, p)) {
        drive_enter_fault(d, DRIVE_FAULT_PARAMS);
        return;
    }
    d->state = DRIVE_STATE_CALIBRATE;
}

static void drive_calibrate(drive_t *d)
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

static void drive_start_calibration(drive_t *d)
{
    int16_t i;
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        d->offset_sum[i] = 0;
    }
    d->calibration_samples = 0;
    d->state = DRIVE_STATE_CALIBRATE;
}

static void drive_scale_measurements(drive_t *d)
{
    int16_t i;
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        const int16_t counts = (int16_t)((int16_t)d->adc.phase[i] - d->offset_counts[i]);
        d->meas.i_phase[i] = ctl_mul_int(d->current_pu_per_count, counts);
    }
    d->meas.vdc = ctl_mul_int(d->vdc_pu_per_count, (int16_t)d->adc.vdc);
    d->meas.theta_e = ctl_from_turn_u32(d->encoder.elec_angle);
    d->meas.omega_e = ctl_mul_q16(d->encoder.mech_speed_q16, d->omega_pu_per_rev_s);
}

uint16_t drive_duty_to_hal(ctl_q duty)
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

static void drive_run_step(drive_t *d)
{
    uint16_t duty[HAL_PWM_LEGS];
    int16_t i;
    prof_mark(PROF_ADC);
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

static void drive_control_step(drive_t *d);

void drive_control_isr(drive_t *d)
{
    prof_begin(d->isr_latency_cycles);
    drive_control_step(d);
    prof_end();
}

static void drive_control_step(drive_t *d)
{
    const bool fresh = hal_adc_read(&d->adc);
    hal_encoder_read(&d->encoder);
    d->isr_count++;

    if (hal_pwm_hw_trip_seen() && d->state != DRIVE_STATE_FAULT) {
        drive_enter_fault(d, DRIVE_FAULT_HW_TRIP);
    }
    if (!fresh && (d->state == DRIVE_STATE_RUN || d->state == DRIVE_STATE_CALIBRATE)) {
        drive_enter_fault(d, DRIVE_FAULT_ADC_MISSING);
    }
    if (d->state == DRIVE_STATE_RUN && !d->encoder.healthy) {
        drive_enter_fault(d, DRIVE_FAULT_ENCODER);
    }
    if (d->run_requested && d->state != DRIVE_STATE_READY) {
        d->run_requested = false; /* refused, not deferred */
        if (d->state != DRIVE_STATE_RUN) {
            d->run_refused++;
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
        if (d->run_requested && !d->encoder.healthy) {
            d->run_requested = false;
            d->run_refused++;
        }
        if (d->run_requested) {
            d->run_requested = false;
            d->stop_requested = false;
            ctl_reset(&d->ctl);
            drive_scale_measurements(d);
            d->state = DRIVE_STATE_RUN;
            hal_pwm_enable();
            drive_run_step(d);
        }
        break;
    case DRIVE_STATE_RUN:
        if (d->stop_requested) {
            d->stop_requested = false;
            hal_pwm_force_off();
            d->state = DRIVE_STATE_READY;
            break;
        }
        drive_scale_measurements(d);
        drive_run_step(d);
        break;
    case DRIVE_STATE_FAULT:
        hal_pwm_force_off();
        if (d->clear_requested) {
            d->clear_requested = false;
            /* healthy: parameters usable, no trip input active, encoder fine
             * if that was the cause */
            if (d->fault != DRIVE_FAULT_PARAMS && d->fault != DRIVE_FAULT_STARTUP &&
                !hal_pwm_hw_trip_seen() &&
                (d->fault != DRIVE_FAULT_ENCODER || d->encoder.healthy)) {
                d->fault = DRIVE_FAULT_NONE;
                if (d->calibrated) {
                    d->state = DRIVE_STATE_READY;
                } else {
                    drive_start_calibration(d);
                }
            }
        }
        break;
    case DRIVE_STATE_INIT:
    default:
        hal_pwm_force_off();
        break;
    }
}

void drive_request_run(drive_t *d) { d->run_requested = true; }

bool drive_request_params(drive_t *d, const ctl_params_t *p)
{
    if (!ctl_params_valid(p)) {
        return false;
    }
    d->params_bg = *p;
    ctl_request_params(&d->ctl, &d->params_bg);
    return true;
}

void drive_trip(drive_t *d, drive_fault_t fault)
{
    if (d->state != DRIVE_STATE_FAULT) {
        drive_enter_fault(d, fault);
    } else {
        hal_pwm_force_off(); /* first fault code kept */
    }
}

void drive_report_overrun(drive_t *d)
{
    prof_count_overrun();
    drive_trip(d, DRIVE_FAULT_OVERRUN);
}
void drive_request_stop(drive_t *d) { d->stop_requested = true; }
void drive_request_clear_fault(drive_t *d) { d->clear_requested = true; }

void drive_set_speed_ref_rpm(drive_t *d, float rpm)
{
    const float omega_e = rpm * (float)(CTL_TWO_PI / 60.0) * (float)d->params_bg.pole_pairs;
    d->speed_ref_rpm = rpm;
    ctl_set_loop_mode(&d->ctl, CTL_LOOP_SPEED);
    ctl_set_speed_ref(&d->ctl, ctl_from_float(omega_e / (float)CTL_BASE_OMEGA_RAD_S));
}

void drive_set_torque_ref_nm(drive_t *d, float torque_nm)
{
    d->torque_ref_nm = torque_nm;
    ctl_set_loop_mode(&d->ctl, CTL_LOOP_TORQUE);
    ctl_set_torque_ref(&d->ctl, ctl_from_float(torque_nm / (float)CTL_BASE_TORQUE_NM));
}
