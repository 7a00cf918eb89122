/*
 * Start-up sequence. Order matters:
 *   0. the stack's unused part painted (stack_watch.h), before anything deeper runs
 *   1. interrupts off, watchdog off (the code-start stub already disabled it)
 *   2. PLL to 150 MHz, peripheral clocks
 *   3. ramfuncs (per-period code) and ramconsts (its tables) copied to RAM, then the
 *      flash wait states set from RAM
 *   4. cycle counter, PIE with every vector on fw_unexpected_isr
 *   5. PWM configured with the outputs tripped off, then ADC, encoder, SCI
 *   6. drive_init with the parameter set (the reference machine's, or the identified one's
 *      from the motor parameter file: fw.h): INIT -> CALIBRATE (PWM off while offsets average)
 *   7. ADC SEQ1 interrupt installed and enabled, interrupts on, watchdog on
 */
#include <stdint.h>

#include "fw.h"
#include "measure/profile.h"
#include "measure/stack_watch.h"
#include "hal_adc.h"
#include "hal_cycles.h"
#include "hal_encoder.h"
#include "hal_pwm.h"

drive_t fw_drive;
fw_state_t fw_state;

#if F28335_TARGET
/* The run-time stack, .stack (TI SPRU513, --stack_size): the RTS start-up (boot.asm) defines
 * __stack at its start and points SP there; the linker defines __STACK_SIZE, its size in words,
 * as the symbol's value. COFF adds one leading underscore to C names. */
extern uint16_t _stack;
extern uint16_t _STACK_SIZE;
#else
/* Host: a stand-in stack region, painted as the target's is (the host's own stack is not the
 * C28x's and is not measured), with the first FW_HOST_STACK_IN_USE words taken as in use. */
volatile uint16_t fw_host_stack[FW_HOST_STACK_WORDS];
#endif

/* Paints the stack above this function's frame (stack_watch.h). The C28x stack grows upward:
 * everything below `here` is the callers' (c_int00, main, fw_startup), and the guard covers
 * the rest of this frame and stack_watch_paint's (return address, saved registers, locals).
 * Those words count as used. */
void fw_stack_paint(void)
{
#if F28335_TARGET
    volatile uint16_t here = 0u;
    volatile uint16_t *const base = &_stack;
    const uint16_t in_use = (uint16_t)((uint16_t)(&here - base) + FW_STACK_PAINT_GUARD);
    stack_watch_paint(&drive_stack, base, (uint16_t)(uintptr_t)&_STACK_SIZE, in_use);
#else
    stack_watch_paint(&drive_stack, fw_host_stack, FW_HOST_STACK_WORDS, FW_HOST_STACK_IN_USE);
#endif
}

/* The identified machine's values (fw.h: the motor parameter file) over the reference's. */
static void fw_motor_params(ctl_params_t *p)
{
#if defined(SIXPHASE_MOTOR_R_OHM)
    p->resistance_ohm = SIXPHASE_MOTOR_R_OHM;
#endif
#if defined(SIXPHASE_MOTOR_LD_H)
    p->ld_h = SIXPHASE_MOTOR_LD_H;
#endif
#if defined(SIXPHASE_MOTOR_LQ_H)
    p->lq_h = SIXPHASE_MOTOR_LQ_H;
#endif
#if defined(SIXPHASE_MOTOR_LXY_H)
    p->l_xy_h = SIXPHASE_MOTOR_LXY_H;
#endif
#if defined(SIXPHASE_MOTOR_PSI_F_WB)
    p->pm_flux_wb = SIXPHASE_MOTOR_PSI_F_WB;
#endif
#if defined(SIXPHASE_MOTOR_POLE_PAIRS)
    p->pole_pairs = (int16_t)SIXPHASE_MOTOR_POLE_PAIRS;
#endif
#if defined(SIXPHASE_MOTOR_INERTIA_KG_M2)
    p->inertia_kg_m2 = SIXPHASE_MOTOR_INERTIA_KG_M2;
#endif
#if defined(SIXPHASE_MOTOR_SPEED_KP_NMS)
    p->speed_kp_nm_per_rad_s = SIXPHASE_MOTOR_SPEED_KP_NMS;
#endif
#if defined(SIXPHASE_MOTOR_SPEED_KI_NM)
    p->speed_ki_nm_per_rad = SIXPHASE_MOTOR_SPEED_KI_NM;
#endif
    (void)p;
}

bool fw_startup(void)
{
    ctl_params_t p;
    bool hal_ok;

    fw_stack_paint(); /* first: no local of this frame is live yet */
    hal_ok = true;
    f28335_interrupts_disable_global();
    f28335_watchdog_disable();
    fw_state.clock_ok = f28335_clock_init();
    fw_ramfuncs_copy();
    f28335_flash_init();
    hal_cycles_init();
    f28335_pie_init(fw_unexpected_isr);

    ctl_params_default(&p);
    fw_motor_params(&p);
    if (FW_DC_UNDERVOLTAGE_OVERRIDE) {
        p.protect.dc_undervoltage_v = (float)FW_BENCH_DC_UNDERVOLTAGE_V;
    }
    if (!hal_pwm_init(FW_PWM_HZ, FW_DEAD_TIME_NS)) {
        hal_ok = false;
    }
    if (!hal_adc_init()) {
        hal_ok = false;
    }
    if (!hal_encoder_init(HAL_BOARD_ENCODER_LINES, (uint16_t)p.pole_pairs, FW_ENCODER_OFFSET)) {
        hal_ok = false;
    }
    if (!f28335_sci_init(FW_SCI_BAUD)) {
        hal_ok = false;
    }
    fw_state.hal_ok = hal_ok;
    fw_state.unexpected_isr = 0u;
    link_service_init(&fw_state.link, FW_LINK_GAP_CYCLES);

    drive_init(&fw_drive, &p);
    /* indirect-call: ctl_healthy_step, ctl_ddc_select -> prof_ctl_stage (tools/stack_depth.py) */
    /* indirect-call: ctl_postfault_step, pf_select_ddc -> prof_ctl_stage */
    /* indirect-call: ctl_foc_healthy_step -> prof_ctl_stage (FOC-VSD's stage marks) */
    ctl_set_stage_hook(&fw_drive.ctl, prof_ctl_stage); /* stage timing (profile.h) */
    if (!fw_state.clock_ok || !hal_ok) {
        /* Never run on a limp-mode clock or a half-configured inverter; the
         * link stays up to report it. */
        drive_trip(&fw_drive, DRIVE_FAULT_STARTUP);
    }

    f28335_pie_install(1u, 1u, fw_adc_isr);
    f28335_pie_enable(1u, 1u);
    f28335_interrupts_enable_global();
    f28335_watchdog_enable();
    return fw_state.clock_ok && hal_ok;
}
