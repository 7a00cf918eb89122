/*
 * Execution-time profile of the control ISR, per stage, in CPU cycles of the free-running
 * counter behind hal_cycles.h (CPU timer 1 at SYSCLKOUT on the F28335, a host clock in host
 * builds). One global struct, drive_profile, readable with the debugger and over the serial
 * link (SXL_CMD_GET_PROFILE).
 *
 * Stages of one period, in order:
 *   LATENCY     period start (ePWM counter zero, ADC start) to ISR entry: conversion time
 *               plus interrupt entry, as the platform measured it (0 where it cannot)
 *   ADC         ISR entry to the control step: ADC and encoder reads, state machine, scaling
 *   TRANSFORMS  VSD, Park, speed loop and flux reference            (inside ctl_step)
 *   PREDICT     delay compensation to k+1, free response to k+2    (inside ctl_step)
 *   TABLE       flux sectors and lookup tables (DDC; empty for MPTC) (inside ctl_step)
 *   SEARCH      candidate / duty search and the command             (inside ctl_step)
 *   PWM         duty conversion and the PWM write
 *   TOTAL       ISR entry to the end of the ISR body (without LATENCY)
 * Per stage: last, minimum, maximum and running mean (exponential, 1/64 per period).
 *
 * The cost of reading the counter is measured at init and subtracted from every stage; the
 * few instructions of bookkeeping between two readings are not counted anywhere.
 * PROFILE_ENABLE=0 compiles every call away.
 */
#ifndef PROFILE_H
#define PROFILE_H

#include <stdbool.h>
#include <stdint.h>

#ifndef PROFILE_ENABLE
#define PROFILE_ENABLE 1
#endif

typedef enum {
    PROF_LATENCY = 0,
    PROF_ADC = 1,
    PROF_TRANSFORMS = 2,
    PROF_PREDICT = 3,
    PROF_TABLE = 4,
    PROF_SEARCH = 5,
    PROF_PWM = 6,
    PROF_TOTAL = 7,
    PROF_STAGES = 8
} prof_stage_t;

typedef struct {
    uint32_t last;
    uint32_t min;
    uint32_t max;
    uint32_t mean_x256; /* running mean times 256 */
    uint32_t count;
} prof_stat_t;

typedef struct {
    prof_stat_t stage[PROF_STAGES];
    uint32_t read_cost;     /* cycles one counter reading costs (subtracted) */
    uint32_t period_cycles; /* control period in counter cycles (0: load not computed) */
    uint32_t permille_k;    /* floor(1000 * 2^16 / period_cycles) */
    uint32_t cycles_per_us;
    uint16_t load_permille_last; /* (LATENCY + TOTAL) / period of the last ISR */
    uint16_t load_permille_max;
    uint32_t overruns;
    uint32_t t_start; /* counter at ISR entry */
    uint32_t t_prev;  /* counter at the end of the previous stage */
} prof_t;

extern prof_t drive_profile;

/* Shorter control periods (6.7 us at 150 MHz) get no load figure. */
#define PROF_MIN_PERIOD_CYCLES 1000u

#if PROFILE_ENABLE
/* Clears the statistics and measures the counter's reading cost. */
void prof_init(uint32_t period_cycles, uint32_t cycles_per_second);
/* ISR entry; latency_cycles: period start to ISR entry as the platform measured it. */
void prof_begin(uint32_t latency_cycles);
/* End of a stage (the stage since the previous mark or prof_begin). */
void prof_mark(prof_stage_t stage);
/* End of the ISR body: TOTAL and CPU load. */
void prof_end(void);
void prof_count_overrun(void);
#else
static inline void prof_init(uint32_t period_cycles, uint32_t cycles_per_second)
{
    (void)period_cycles;
    (void)cycles_per_second;
}
static inline void prof_begin(uint32_t latency_cycles) { (void)latency_cycles; }
static inline void prof_mark(prof_stage_t stage) { (void)stage; }
static inline void prof_end(void) {}
static inline void prof_count_overrun(void) {}
#endif

/* Running mean in cycles, rounded. */
uint32_t prof_mean(const prof_stat_t *s);

/* The control core's stage hook (ctl_set_stage_hook): maps ctl_stage_t to the stages above. */
void prof_ctl_stage(int16_t ctl_stage);

#endif /* PROFILE_H */
