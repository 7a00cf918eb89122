/*
 * PWM of the six inverter legs. One implementation per platform
 * (hal/f28335/, hal/sim/). Knows nothing of the control method.
 *
 * A duty is the fraction of the period the upper switch of a leg is on, as
 * one pulse centred in the period (up-down carrier, active while the counter
 * is above the compare value). Written duties take effect at the start of the
 * next period (compares shadow-loaded at counter zero).
 */
#ifndef HAL_PWM_H
#define HAL_PWM_H

#include <stdbool.h>
#include <stdint.h>

#define HAL_PWM_LEGS 6
#define HAL_PWM_DUTY_ONE 32768u /* duties are unsigned Q15, 0..32768 */

/* Configure the six legs for a carrier frequency; outputs stay forced off. */
bool hal_pwm_init(uint32_t carrier_hz, uint32_t dead_time_ns);

/* Leg duties A..F for the next period; values above HAL_PWM_DUTY_ONE are clamped. */
void hal_pwm_write(const uint16_t duty[HAL_PWM_LEGS]);

/* Both switches of every leg off at once (software trip); latched until enable. */
void hal_pwm_force_off(void);

/* Release the outputs after hal_pwm_force_off or init (clears a trip latch). */
void hal_pwm_enable(void);

/* True while the outputs are forced off (software or hardware trip). */
bool hal_pwm_is_off(void);

/* True if the hardware trip input (over-current comparator) has fired. */
bool hal_pwm_hw_trip_seen(void);

/* Both switches of leg `leg` (0..5, A..F) off for good: through hal_pwm_write and hal_pwm_enable,
 * until hal_pwm_restore_legs (running on five legs after an open phase). False, and nothing
 * done, for a leg out of range. hal_pwm_is_off judges the other legs. */
bool hal_pwm_isolate_leg(int16_t leg);

/* Isolated legs, bit k for leg k (A = bit 0). */
uint16_t hal_pwm_isolated_legs(void);

/* Ends every isolation: the legs follow hal_pwm_force_off and hal_pwm_enable again (they stay
 * off until the next enable). */
void hal_pwm_restore_legs(void);

#endif /* HAL_PWM_H */
