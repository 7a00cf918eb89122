/*
 * Simulator implementation of the HAL (hal_pwm.h, hal_adc.h, hal_encoder.h,
 * hal_cycles.h). The peripherals are a "bus" the host plant fills (ADC counts,
 * encoder angle and speed) and reads (duties, forced-off state); the drive
 * application calls the ordinary HAL functions and cannot tell the difference.
 *
 * One bus per process (the simulator parallelises by fork, not threads).
 */
#ifndef HAL_SIM_H
#define HAL_SIM_H

#include <stdbool.h>
#include <stdint.h>

#include "hal_adc.h"
#include "hal_board.h"
#include "hal_encoder.h"
#include "hal_pwm.h"

#define HAL_SIM_UART_FIFO 16

typedef struct {
    /* PWM, written by the application */
    uint32_t carrier_hz;
    uint32_t dead_time_ns;
    uint16_t duty[HAL_PWM_LEGS]; /* shadow registers: loaded at the next period start */
    uint32_t writes;             /* hal_pwm_write calls since init */
    bool forced_off;             /* latched by force_off / trip, cleared by enable */
    uint16_t isolated;           /* bit k: leg k's switches off for good (hal_pwm_isolate_leg) */
    bool hw_trip;                /* simulated trip-zone input */
    bool pwm_initialised;
    /* ADC, written by the plant at each period start */
    hal_adc_sample_t adc;
    bool adc_fresh; /* a new sequence completed and has not been read */
    bool adc_initialised;
    /* encoder, written by the plant at each period start; the configuration (lines, pole pairs,
     * offset) is the drive's, which the plant's encoder model applies as the eQEP would */
    hal_encoder_sample_t encoder;
    uint32_t encoder_lines;
    uint16_t encoder_pole_pairs;
    uint32_t encoder_elec_offset;
    bool encoder_initialised;
    bool encoder_homing_lost; /* hal_encoder_rehome: unhealthy until the plant posts the index */
    /* serial port (hal_serial.h): 16-byte FIFOs as the board's SCI has; the virtual board moves
     * bytes between them and the outside at the baud rate */
    uint16_t uart_rx[HAL_SIM_UART_FIFO], uart_tx[HAL_SIM_UART_FIFO];
    uint16_t uart_rx_head, uart_rx_count, uart_tx_head, uart_tx_count;
    uint32_t uart_rx_overruns; /* bytes that arrived with the receive FIFO full (lost) */
    /* hal_cycles.h: simulated time in nanoseconds (see hal_sim_use_host_clock) */
    uint32_t clock_ns;
} hal_sim_bus_t;

extern hal_sim_bus_t hal_sim_bus;

/* Clear the bus to its power-on state (outputs forced off, no samples). */
void hal_sim_reset(void);

/* hal_cycles.h reads simulated time by default: nanoseconds, advanced by the plant at every
 * period start (hal_sim_clock_advance), so a reading costs no host call and the profiler sees
 * no time pass inside the ISR. With host true it reads the host's monotonic clock instead (the
 * virtual board, whose profile shows host time). A process-wide choice: hal_sim_reset keeps it
 * (and zeroes the simulated clock). */
void hal_sim_use_host_clock(bool host);
void hal_sim_clock_advance(uint32_t ns);

/* The line side of the serial port: a byte arriving (false, and counted as an overrun, when
 * the receive FIFO is full) and the next byte leaving the transmit FIFO (false when empty). */
bool hal_sim_uart_arrive(uint16_t byte);
bool hal_sim_uart_depart(uint16_t *byte);

/* Physical quantity to 12-bit ADC counts: round to nearest, clamp to 0..4095. Currents over a
 * sensor span of full_span_a (-span/2 .. +span/2, zero at mid scale; the reference board's is
 * HAL_BOARD_CURRENT_FULL_SPAN_A), the DC link with hal_board.h's scaling. Offset (counts) and
 * gain error are the caller's (the plant's) business and are applied before this. */
static inline uint16_t hal_sim_clamp_counts(double counts)
{
    if (!(counts == counts) || counts <= 0.0) { /* NaN or below range */
        return 0u;
    }
    if (counts >= (double)HAL_ADC_FULL_SCALE) {
        return (uint16_t)HAL_ADC_FULL_SCALE;
    }
    return (uint16_t)(counts + 0.5);
}

/* The conversions are inline: the plant converts seven channels every control period. */
static inline uint16_t hal_sim_current_to_counts(double amps, double full_span_a)
{
    return hal_sim_clamp_counts(HAL_BOARD_CURRENT_ZERO_COUNTS +
                                amps * ((double)(HAL_ADC_FULL_SCALE + 1u) / full_span_a));
}

static inline uint16_t hal_sim_vdc_to_counts(double volts)
{
    return hal_sim_clamp_counts(volts / HAL_BOARD_VDC_V_PER_COUNT);
}

/* Publish a completed conversion sequence (sets the fresh flag). */
void hal_sim_post_adc(const hal_adc_sample_t *s);

/* Publish the encoder reading of this period. */
void hal_sim_post_encoder(const hal_encoder_sample_t *s);

/* The shaft passed the encoder's index: the homing is back (the eQEP's first-index flag). */
void hal_sim_post_encoder_index(void);

/* Duty of one leg as a fraction of the period, from the shadow registers (an isolated leg's
 * is 0: its switches are off, the plant treats its phase as open). */
static inline double hal_sim_duty_fraction(int leg)
{
    if (leg < 0 || leg >= HAL_PWM_LEGS || (((unsigned)hal_sim_bus.isolated >> leg) & 1u) != 0u) {
        return 0.0;
    }
    return (double)hal_sim_bus.duty[leg] / (double)HAL_PWM_DUTY_ONE;
}

#endif /* HAL_SIM_H */
