/* Simulator HAL, its peripheral bus (PWM, ADC, encoder): see hal_sim.h. Free of the host: a
 * processor-in-the-loop target links this file as its peripherals (firmware/pil); the
 * serial port and the clock are in hal_sim_serial.c and hal_sim_clock.c. */
#include "hal_sim.h"

#include <string.h>

#include "hal_board.h"

hal_sim_bus_t hal_sim_bus;

void hal_sim_reset(void)
{
    memset(&hal_sim_bus, 0, sizeof hal_sim_bus);
    hal_sim_bus.forced_off = true;
}

void hal_sim_post_adc(const hal_adc_sample_t *s)
{
    hal_sim_bus.adc = *s;
    hal_sim_bus.adc_fresh = true;
}

void hal_sim_post_encoder(const hal_encoder_sample_t *s) { hal_sim_bus.encoder = *s; }

void hal_sim_post_encoder_index(void) { hal_sim_bus.encoder_homing_lost = false; }

/* ---- hal_pwm.h ---- */

bool hal_pwm_init(uint32_t carrier_hz, uint32_t dead_time_ns)
{
    int i;
    if (carrier_hz == 0u) {
        return false;
    }
    hal_sim_bus.carrier_hz = carrier_hz;
    hal_sim_bus.dead_time_ns = dead_time_ns;
    for (i = 0; i < HAL_PWM_LEGS; i++) {
        hal_sim_bus.duty[i] = 0u;
    }
    hal_sim_bus.writes = 0u;
    hal_sim_bus.forced_off = true;
    hal_sim_bus.hw_trip = false;
    hal_sim_bus.isolated = 0u;
    hal_sim_bus.pwm_initialised = true;
    return true;
}

void hal_pwm_write(const uint16_t duty[HAL_PWM_LEGS])
{
    int i;
    for (i = 0; i < HAL_PWM_LEGS; i++) {
        hal_sim_bus.duty[i] = (duty[i] > HAL_PWM_DUTY_ONE) ? (uint16_t)HAL_PWM_DUTY_ONE : duty[i];
    }
    hal_sim_bus.writes++;
}

void hal_pwm_force_off(void) { hal_sim_bus.forced_off = true; }

void hal_pwm_enable(void)
{
    if (!hal_sim_bus.hw_trip) {
        hal_sim_bus.forced_off = false;
    }
}

bool hal_pwm_is_off(void) { return hal_sim_bus.forced_off; }

bool hal_pwm_hw_trip_seen(void) { return hal_sim_bus.hw_trip; }

bool hal_pwm_isolate_leg(int16_t leg)
{
    if (leg < 0 || leg >= HAL_PWM_LEGS) {
        return false;
    }
    hal_sim_bus.isolated |= (uint16_t)(1u << leg);
    return true;
}

uint16_t hal_pwm_isolated_legs(void) { return hal_sim_bus.isolated; }

void hal_pwm_restore_legs(void) { hal_sim_bus.isolated = 0u; }

/* ---- hal_adc.h ---- */

bool hal_adc_init(void)
{
    hal_sim_bus.adc_fresh = false;
    hal_sim_bus.adc_initialised = true;
    return true;
}

bool hal_adc_read(hal_adc_sample_t *s)
{
    const bool fresh = hal_sim_bus.adc_fresh;
    *s = hal_sim_bus.adc;
    hal_sim_bus.adc_fresh = false;
    return fresh;
}

/* ---- hal_encoder.h ---- */

bool hal_encoder_init(uint32_t lines, uint16_t pole_pairs, uint32_t elec_offset)
{
    if (lines == 0u || pole_pairs == 0u) {
        return false;
    }
    hal_sim_bus.encoder_lines = lines;
    hal_sim_bus.encoder_pole_pairs = pole_pairs;
    hal_sim_bus.encoder_elec_offset = elec_offset;
    hal_sim_bus.encoder_initialised = true;
    return true;
}

void hal_encoder_read(hal_encoder_sample_t *s)
{
    *s = hal_sim_bus.encoder;
    if (hal_sim_bus.encoder_homing_lost) {
        s->healthy = false; /* the eQEP's FIMF cleared: neither healthy nor homed */
        s->index_seen = false;
    }
}

void hal_encoder_rehome(void) { hal_sim_bus.encoder_homing_lost = true; }

uint32_t hal_encoder_counts_per_turn(void)
{
    return hal_sim_bus.encoder_initialised ? 4u * hal_sim_bus.encoder_lines : 0u;
}

uint32_t hal_encoder_offset(void) { return hal_sim_bus.encoder_elec_offset; }

/* The plant's encoder model computes the angle with the bus's offset
 * (host_sim/plant/sim_encoder.c), so a new offset shows from the next period's sample on, as on
 * the eQEP. */
void hal_encoder_set_offset(uint32_t elec_offset) { hal_sim_bus.encoder_elec_offset = elec_offset; }
