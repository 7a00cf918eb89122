/*
 * F28335 firmware: start-up, the control interrupt and the background loop.
 * The same sources build for the target (cl2000) and, against RAM register
 * frames, for the host (library firmware_f28335_host, tested in
 * tests/firmware).
 */
#ifndef FW_H
#define FW_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive.h"
#include "f28335_hal.h"
#include "hal_board.h"
#include "service/link_service.h"
#include "sxlink.h"

#define FW_PWM_HZ HAL_BOARD_PWM_HZ
#define FW_DEAD_TIME_NS HAL_BOARD_DEAD_TIME_NS
#define FW_SCI_BAUD ((uint32_t)115200u)
/* The machine identified by the drive's commissioning (docs/commissioning.md): the parameter
 * file `sixphase-link identify --out FILE` writes, named at build time with
 * -DSIXPHASE_MOTOR_PARAMS="FILE" (the CMake builds: -DSIXPHASE_MOTOR_PARAMS_FILE=FILE,
 * docs/porting.md section 8). Without it the reference machine's values stand. */
#if defined(SIXPHASE_MOTOR_PARAMS)
#include SIXPHASE_MOTOR_PARAMS
/* a file that sets nothing is the wrong one or a truncated one, not the reference machine */
#if !defined(SIXPHASE_MOTOR_R_OHM) && !defined(SIXPHASE_MOTOR_LD_H) &&                             \
    !defined(SIXPHASE_MOTOR_LQ_H) && !defined(SIXPHASE_MOTOR_LXY_H) &&                             \
    !defined(SIXPHASE_MOTOR_PSI_F_WB) && !defined(SIXPHASE_MOTOR_POLE_PAIRS) &&                    \
    !defined(SIXPHASE_MOTOR_ENCODER_OFFSET)
#error "SIXPHASE_MOTOR_PARAMS names a file without any SIXPHASE_MOTOR_ entry"
#endif
#endif
/* Electrical angle of the encoder index relative to the d axis (2^32 = one turn): the
 * identified one, else 0 (the commissioning finds it; `identify --apply` sets it at run time). */
#if defined(SIXPHASE_MOTOR_ENCODER_OFFSET)
#define FW_ENCODER_OFFSET ((uint32_t)SIXPHASE_MOTOR_ENCODER_OFFSET)
#else
#define FW_ENCODER_OFFSET ((uint32_t)0u)
#endif
/* Bench images only (docs/porting.md section 8): build with -DFW_BENCH_DC_UNDERVOLTAGE_V=0
 * to check the gate signals with the DC link off, or with a lower value for a bench supply.
 * The default, 350 V, refuses RUN and trips below it (docs/faults.md). */
#if defined(FW_BENCH_DC_UNDERVOLTAGE_V)
#define FW_DC_UNDERVOLTAGE_OVERRIDE 1
#else
#define FW_DC_UNDERVOLTAGE_OVERRIDE 0
#define FW_BENCH_DC_UNDERVOLTAGE_V 0.0f
#endif
/* ISR time limit in CPU cycles: 80 % of the 15000-cycle period at 10 kHz,
 * leaving room for the conversion time before the interrupt and the latency. */
#define FW_ISR_BUDGET_CYCLES ((uint32_t)12000u)
/* Words above a local of fw_stack_paint's frame left unpainted: the rest of that frame and
 * stack_watch_paint's (2 words of return address, at most 14 of saved registers, a few locals). */
#define FW_STACK_PAINT_GUARD 32u
/* Host build: the stand-in stack region and the part of it taken as in use. */
#define FW_HOST_STACK_WORDS 64u
#define FW_HOST_STACK_IN_USE 8u
/* A partial frame older than this is dropped (cycles: 20 ms). */
#define FW_LINK_GAP_CYCLES ((uint32_t)3000000u)

typedef struct {
    bool clock_ok;
    bool hal_ok;
    uint16_t unexpected_isr;
    link_service_t link;
} fw_state_t;

extern drive_t fw_drive;
extern fw_state_t fw_state;

/* Paints the stack's unused part for its high-water mark (stack_watch.h); start-up's first step. */
void fw_stack_paint(void);
#if !F28335_TARGET
extern volatile uint16_t fw_host_stack[FW_HOST_STACK_WORDS];
#endif
/* Whole start-up; returns false if a peripheral failed (drive left in FAULT). */
bool fw_startup(void);
/* One pass of the background loop: watchdog, serial link. */
void fw_background_step(void);

/* Copy the ramfuncs (per-period code) and ramconsts (its tables) sections from their flash
 * load addresses to RAM. */
void fw_ramfuncs_copy(void);
/* Word copy used by it: n 16-bit words. */
void fw_copy_words(uint16_t *dst, const uint16_t *src, uint32_t n);

/* PIE INT1.1 (ADC SEQ1 end of sequence): the control ISR. */
F28335_INTERRUPT void fw_adc_isr(void);
/* Every other vector: outputs off, counted; on the target it then halts. */
F28335_INTERRUPT void fw_unexpected_isr(void);

#endif
