/*
 * F28335-only services beyond the portable HAL headers in hal/include:
 * clocks, flash, watchdog, PIE, the SCI-A byte driver and the pure helper
 * functions of the drivers (exposed so host tests can check the arithmetic).
 */
#ifndef F28335_HAL_H
#define F28335_HAL_H

#include <stdbool.h>
#include <stdint.h>

#include "f28335_regs.h"

/* ---- clocks, flash, watchdog (f28335_sysctrl.c) ---- */

/* PLL to 150 MHz from the 30 MHz crystal; HSPCLK = 25 MHz (ADC), LSPCLK =
 * 37.5 MHz (SCI); clocks of the used peripherals on. Returns false if the
 * oscillator is missing (MCLKSTS set): the device then runs from limp mode. */
bool f28335_clock_init(void);

/* Flash pipeline and wait states for 150 MHz. Runs from RAM (ramfuncs). */
void f28335_flash_init(void);

#define F28335_LSPCLK_HZ ((uint32_t)37500000u)
#define F28335_HSPCLK_HZ ((uint32_t)25000000u)

void f28335_watchdog_disable(void);
/* Enable with the slowest prescaler (about 280 ms at 30 MHz OSCCLK), reset mode. */
void f28335_watchdog_enable(void);
void f28335_watchdog_service(void);

/* ---- PIE (f28335_pie.c) ---- */

/* PIE off, every vector to default_isr, all flags and enables cleared, PIE on. */
void f28335_pie_init(f28335_isr_t default_isr);
void f28335_pie_install(uint16_t group, uint16_t index, f28335_isr_t isr);
/* Set PIEIERg.x and the CPU IER bit of the group. */
void f28335_pie_enable(uint16_t group, uint16_t index);
void f28335_pie_ack(uint16_t group);
void f28335_interrupts_enable_global(void);
void f28335_interrupts_disable_global(void);

/* ---- PWM helpers (f28335_pwm.c) ---- */

#define F28335_PWM_TRIP_GPIO 12u /* TZ1 input */

/* TBPRD for an up-down carrier at carrier_hz with TBCLK = SYSCLKOUT; 0 if out of range. */
uint16_t f28335_pwm_period_for(uint32_t carrier_hz);
/* Dead-band counts for dead_time_ns; 0xFFFF if above the 10-bit limit. */
uint16_t f28335_pwm_deadband_for(uint32_t dead_time_ns);
/* The smallest CMPA: the widest pulse, which 100 % gets, still low at CTR = 0 (where a
 * debugger halt stops the time base, f28335_pwm.c) and at CTR = 1 counting down. */
#define F28335_PWM_CMPA_MIN 1u

/* CMPA for a Q15 duty (0..32768) and period prd: on = round(duty * prd / 32768) counts per
 * half period; prd + 1 (no compare event) when on is 0, F28335_PWM_CMPA_MIN when on is prd
 * (100 %, one count short per half period), else prd - on. */
uint16_t f28335_pwm_cmpa_for(uint16_t duty_q15, uint16_t prd);
uint16_t f28335_pwm_period(void);
/* ePWM1 time-base counter: in up-down mode the counter rises from 0 at the period start
 * (ADC start of conversion), so in the first half period it is the time since then, in
 * SYSCLKOUT cycles (TBCLK = SYSCLKOUT). */
uint16_t f28335_pwm_time_base(void);

/* ---- ADC helpers (f28335_adc.c) ---- */

/* Result register slot of each quantity (conversion order of SEQ1). */
#define F28335_ADC_SLOT_VDC 6u
#define F28335_ADC_CONVERSIONS 7u
/* Channel code per slot: phases A..F = ADCINA0..A5, DC link = ADCINB0. */
extern const uint16_t f28335_adc_channels[F28335_ADC_CONVERSIONS];
/* True if a SEQ1 conversion completed that hal_adc_read has not consumed yet
 * (used by the ISR to detect an overrun). */
bool f28335_adc_sequence_pending(void);
/* Acknowledge the SEQ1 interrupt at the PIE (group 1). */
void f28335_adc_isr_ack(void);

/* ---- encoder helpers (f28335_eqep.c) ---- */

#define F28335_QEP_UNIT_HZ 500u /* unit timer: position difference every 2 ms */
#define F28335_QEP_UPPS 4u      /* capture every 2^4 = 16 counts */
#define F28335_QEP_CCPS 6u      /* capture clock SYSCLKOUT / 64 */
/* Above this speed (rev/s, Q16) the unit-timer estimate is used, below
 * F28335_QEP_LOW_SPEED_Q16 the capture estimate (hysteresis between). */
#define F28335_QEP_HIGH_SPEED_Q16 ((int32_t)15 << 16)
#define F28335_QEP_LOW_SPEED_Q16 ((int32_t)12 << 16)
/* Edges stopping while faster than this are a loss of signal (rev/s, Q16). */
#define F28335_QEP_TIMEOUT_SPEED_Q16 ((int32_t)5 << 16)
#define F28335_QEP_WATCHDOG_PRD 23438u /* 10 ms at SYSCLKOUT / 64 */
#define F28335_QEP_A_GPIO 20u          /* EQEP1A, EQEP1B = 21, EQEP1S = 22, EQEP1I = 23 */

typedef struct {
    uint32_t counts; /* 4 * lines per mechanical turn */
    /* electrical turns per count, Q48 (2^48 = one turn), as 2^16 angle_hi + angle_lo: the
     * per-sample products stay within 32 bits (no 64-bit arithmetic in the ISR) */
    uint32_t angle_hi;
    uint32_t angle_lo; /* < 2^16 */
    uint32_t elec_offset;
    /* rev/s Q16 per count of unit-timer difference, in Q16, as 2^16 ut_hi + ut_lo */
    uint32_t ut_hi;
    uint32_t ut_lo;        /* < 2^16 */
    uint32_t ut_max_delta; /* largest |difference| whose speed fits in int32 */
    /* rev/s Q16 times capture period (capture clocks), as cap_k << cap_shift (cap_shift > 0
     * only for encoders below 144 lines, whose constant exceeds 32 bits) */
    uint32_t cap_k;
    uint16_t cap_shift;
    uint32_t last_poslat;
    bool have_poslat;
    bool use_capture;   /* current estimator: capture (low speed) or unit timer */
    bool error_latched; /* counter error, phase error or signal loss seen */
    int32_t speed_q16;
    int32_t edge_speed_q16; /* speed_q16 of the last unit period in which the position moved */
    uint32_t last_pos;      /* QPOSCNT at the last read */
    int32_t position;       /* unwrapped counts since init (hal_encoder_sample_t.position) */
    bool index_seen;        /* QEPSTS.FIMF at the last read */
} f28335_qep_state_t;

/* Electrical angle (2^32 = one turn) of a position count. */
uint32_t f28335_qep_angle(const f28335_qep_state_t *q, uint32_t pos);
/* Speed from a unit-timer position difference (counts in one unit period). */
int32_t f28335_qep_speed_unit(const f28335_qep_state_t *q, int32_t delta_counts);
/* Speed magnitude from a capture period (capture clocks per 2^UPPS counts); 0 for period 0. */
int32_t f28335_qep_speed_capture(const f28335_qep_state_t *q, uint16_t period);
/* Driver state (for tests). */
const f28335_qep_state_t *f28335_qep_state(void);

/* ---- cycle counter (f28335_cycles.c) uses CPU timer 1 ---- */
#define F28335_CYCLES_TIMER 1u
/* Busy wait on the cycle counter (starts it if needed); returns at once on the host. */
void f28335_delay_us(uint32_t us);

/* ---- SCI-A byte driver (f28335_sci.c) ---- */

#define F28335_SCI_RX_GPIO 28u
#define F28335_SCI_TX_GPIO 29u

/* 8N1 with FIFOs at baud; false if the baud cannot be reached within 3 %. */
bool f28335_sci_init(uint32_t baud);
/* One received byte (0..255) if available. Recovers from receive errors. */
bool f28335_sci_read(uint16_t *byte);
/* Queue one byte if the transmit FIFO has room. */
bool f28335_sci_write(uint16_t byte);
/* Receive errors (framing, overrun, FIFO overflow) since init. */
uint16_t f28335_sci_errors(void);
/* BRR value for baud at LSPCLK (exposed for tests). */
uint16_t f28335_sci_brr_for(uint32_t baud);

#endif /* F28335_HAL_H */
