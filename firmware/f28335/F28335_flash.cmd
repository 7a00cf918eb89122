/*
 * Linker command file: TMS320F28335, boot from flash.
 *
 * Program (PAGE 0) and data (PAGE 1) memory used by the sixphase firmware.
 * The peripheral register frames are not placed here: the HAL addresses
 * them directly (hal/f28335/include/f28335_regs.h holds the base addresses).
 *
 *   code start   BEGIN 0x33FFF6 (boot-to-flash entry) -> codestart.asm
 *   ramfuncs     loaded to FLASHD, run from L0..L3 (copied by fw_ramfuncs_copy): the
 *                code of the whole per-period path, function by function - control ISR,
 *                drive step, control step, protection, the drivers they call and the
 *                run-time library routines the compiler calls from them - and the flash
 *                wait-state set-up. The Q24 image (linked with --define=SIXPHASE_FW_Q24,
 *                firmware/f28335/CMakeLists.txt) leaves the MPTC-49/13 search in flash: it
 *                would not fit L0..L3 beside the rest (docs/porting.md section 7)
 *   ramconsts    loaded to FLASHA, run from L4..L7 (copied likewise): the constant
 *                tables of that path. Nothing of a healthy control period waits on flash.
 *                The open-phase control step (ctl_postfault.c, only after a leg is
 *                isolated) stays in flash: L0..L3 cannot hold it too (docs/porting.md 7).
 *   .text        FLASHC, FLASHB (start-up, background loop, parameter builds)
 *   constants    FLASHA: .cinit, .pinit, .econst, .switch of everything else
 *   .stack       M0 + M1, 0x700 words (tools/check_target_memory.sh sizes it: background
 *                plus a nested control interrupt, with margin; it must lie below 0x10000)
 *   .ebss        L4..L7
 * docs/porting.md section 7 has the RAM budget (tools/check_target_memory.sh).
 *
 * The CSM password locations (0x33FFF8..0x33FFFF) are left erased (0xFFFF):
 * never program them to all zeros, that locks the device for good.
 */

MEMORY
{
PAGE 0 :   /* program */
   RAML0L3    : origin = 0x008000, length = 0x004000   /* L0..L3 SARAM: ramfuncs run here */
   OTP        : origin = 0x380400, length = 0x000400
   FLASHH     : origin = 0x300000, length = 0x008000
   FLASHG     : origin = 0x308000, length = 0x008000
   FLASHF     : origin = 0x310000, length = 0x008000
   FLASHE     : origin = 0x318000, length = 0x008000
   FLASHD     : origin = 0x320000, length = 0x008000
   FLASHC     : origin = 0x328000, length = 0x008000
   FLASHB     : origin = 0x330000, length = 0x008000
   FLASHA     : origin = 0x338000, length = 0x007F80
   CSM_RSVD   : origin = 0x33FF80, length = 0x000076   /* must be 0x0000 when the CSM is used */
   BEGIN      : origin = 0x33FFF6, length = 0x000002
   CSM_PWL    : origin = 0x33FFF8, length = 0x000008
   ADC_CAL    : origin = 0x380080, length = 0x000009   /* TI factory ADC trim routine */
   RESET      : origin = 0x3FFFC0, length = 0x000002
   VECTORS    : origin = 0x3FFFC2, length = 0x00003E

PAGE 1 :   /* data */
   BOOT_RSVD  : origin = 0x000000, length = 0x000050   /* boot ROM stack */
   RAMM0M1    : origin = 0x000050, length = 0x0007B0   /* M0 and M1 SARAM: the stack */
   RAML4L7    : origin = 0x00C000, length = 0x004000   /* L4..L7 SARAM */
}

SECTIONS
{
   codestart  : > BEGIN,   PAGE = 0
   /* Object names match both CMake's (ctl.c.obj) and CCS's (ctl.obj) naming. */
   /* The functions a control period can execute (tools/check_target_memory.sh fails when one
    * is missing: it names the line to add), each in its own subsection (cl2000
    * --gen_func_subsections=on); static helpers and header inlines are listed too, in case
    * cl2000 keeps them out of line. Those of the HAL marked F28335_RAMFUNC (the ISR, ADC,
    * PWM and encoder reads, the cycle counter, the flash set-up) come with *(ramfuncs). */
   ramfuncs   : {
                   *(ramfuncs)
                   /* control/include/ctl_predict.h */
                   *(.text:_ctl_flux_d) *(.text:_ctl_flux_magnitude) *(.text:_ctl_flux_q)
                   *(.text:_ctl_predict_dq) *(.text:_ctl_predict_dq_free)
                   *(.text:_ctl_predict_xy) *(.text:_ctl_torque_flux) *(.text:_ctl_torque_psi)
                   /* control/include/ctl_pulse.h */
                   *(.text:_ctl_pulse_edges) *(.text:_ctl_pulse_high_zero)
                   *(.text:_ctl_pulse_legs_switching)
                   /* control/include/ctl_q.h */
                   *(.text:_ctl_abs) *(.text:_ctl_add) *(.text:_ctl_clamp) *(.text:_ctl_div)
                   *(.text:_ctl_from_turn_u32) *(.text:_ctl_max) *(.text:_ctl_min)
                   *(.text:_ctl_mul) *(.text:_ctl_mul_acc) *(.text:_ctl_mul_add)
                   *(.text:_ctl_mul_dec) *(.text:_ctl_mul_int) *(.text:_ctl_mul_q16)
                   *(.text:_ctl_mul_sub) *(.text:_ctl_q48_to_q24) *(.text:_ctl_sat64)
                   *(.text:_ctl_sub) *(.text:_ctl_to_qn)
                   /* control/include/ctl_search.h */
                   *(.text:_ctl_horizon_cost) *(.text:_ctl_horizon_cost_of)
                   *(.text:_ctl_horizon_forced) *(.text:_ctl_horizon_prepare)
                   /* control/include/ctl_vectors.h */
                   *(.text:_ctl_vector_leg) *(.text:_ctl_vector_ones)
                   /* control/include/ctl_vsd.h */
                   *(.text:_ctl_park) *(.text:_ctl_park_inverse)
                   /* control/src/ctl.c */
                   *(.text:_advance_angle) *(.text:_command_from_choice)
                   *(.text:_ctl_config) *(.text:_ctl_config_take) *(.text:_ctl_diag_flux_est)
                   *(.text:_ctl_postfault_config) *(.text:_ctl_pulse_arrange)
                   *(.text:_ctl_pulse_set_difference) *(.text:_ctl_reset)
                   *(.text:_ctl_reset_command) *(.text:_ctl_step) *(.text:_mid_period_angles)
                   *(.text:_predict) *(.text:_select_ddc)
                   *(.text:_use_config)
                   /* ctl.c's copy of ctl_diag_record.h (the open-phase step's stays in flash) */
                   *ctl.*obj(.text:_ctl_diag_record)
                   /* control/src/ctl_ddc.c, and its copy of ctl_ddc_levels.h (the open-phase
                    * step's copy, if not inlined, stays in flash with that step) */
                   *ctl_ddc.*obj(.text:_ctl_ddc_competing_levels)
                   *ctl_ddc.*obj(.text:_ctl_ddc_levels_search)
                   *(.text:_ctl_ddc_select)
                   /* control/src/ctl_flux_ref.c */
                   *(.text:_ctl_flux_ref_run)
#ifndef SIXPHASE_FW_Q24   /* the Q24 image runs the MPTC-49/13 search from flash */
                   /* control/src/ctl_mptc.c */
                   *(.text:_ctl_mptc_select)
#endif
                   /* control/src/ctl_postfault.c: the open-phase step (ctl_postfault_step and
                    * its helpers) runs from flash in both images: L0..L3 would be 93 % full */
                   /* control/src/ctl_protect.c. In flash: the writing of a fault record (once
                    * in the period that latches a fault, with the latching), a clear (in
                    * FAULT, outputs off) and the quiet phases (with a leg isolated, beside the
                    * open-phase step) */
                   *(.text:_any_nan) *(.text:_check_adc)
                   *(.text:_check_encoder) *(.text:_check_open_phase)
                   *(.text:_check_open_phase_fast) *(.text:_ctl_protect_check)
                   *(.text:_ctl_protect_converter_alive)
                   *(.text:_filtered) *(.text:_open_phase_fast_reset)
                   *(.text:_open_phase_fast_restart) *(.text:_open_phase_fast_verdict)
                   *(.text:_open_phase_restart) *(.text:_open_phase_verdict)
                   *(.text:_sixty_fourth) *(.text:_turn_difference)
                   /* control/src/ctl_q.c */
                   *(.text:_ctl_cos_pu) *(.text:_ctl_sector24) *(.text:_ctl_sin_pu)
                   *(.text:_ctl_sincos_pu) *(.text:_ctl_sqrt) *(.text:_ctl_sqrtf)
                   *(.text:_ctl_wrap_turn) *(.text:_quarter_turn_on) *(.text:_sin_of_wrapped)
                   *(.text:_top_bit)
                   /* control/src/ctl_speed_pi.c */
                   *(.text:_ctl_speed_pi_reset) *(.text:_ctl_speed_pi_run)
                   /* control/src/ctl_vsd.c */
                   *(.text:_ctl_vsd_alpha_beta_phases) *(.text:_ctl_vsd_forward)
                   /* firmware/app/capture.c */
                   *(.text:_capture_due) *(.text:_capture_sample) *(.text:_capture_triggered)
                   /* firmware/app/drive.c */
                   *(.text:_drive_calibrate) *(.text:_drive_clear_blockers)
                   *(.text:_drive_control_isr) *(.text:_drive_control_step)
                   *(.text:_drive_duty_to_hal) *(.text:_drive_fault_from_mask)
                   *(.text:_drive_fault_step) *(.text:_drive_fault_to_mask)
                   *(.text:_drive_limits) *(.text:_drive_omega_scale) *(.text:_drive_protect)
                   *(.text:_drive_ready_step) *(.text:_drive_refuse_run)
                   *(.text:_drive_run_check)
                   *(.text:_drive_run_step) *(.text:_drive_scale_measurements)
                   *(.text:_drive_start_calibration)
                   /* a fault's latching (drive_latch_fault, drive_enter_fault, drive_trip,
                      drive_report_overrun) runs from flash: once, in the
                      period that latches it, after the outputs are off (docs/porting.md 7) */
                   /* firmware/app/drive_open_phase.c */
                   *(.text:_drive_open_phase_gate) *(.text:_drive_open_phase_gate_update)
                   *(.text:_drive_open_phase_in_force) *(.text:_drive_open_phase_period)
                   *(.text:_drive_open_phase_update)
                   /* firmware/app/drive_capture.c */
                   *(.text:_capture_pu) *(.text:_capture_scale) *(.text:_drive_capture_period)
                   *(.text:_drive_capture_value)
                   /* firmware/app/profile.c */
                   *(.text:_prof_begin) *(.text:_prof_count_overrun) *(.text:_prof_ctl_stage)
                   *(.text:_prof_elapsed) *(.text:_prof_end) *(.text:_prof_mark)
                   *(.text:_prof_permille) *(.text:_prof_record)
                   /* hal/f28335/src/f28335_adc.c */
                   *(.text:_f28335_adc_sequence_pending)
                   /* hal/f28335/src/f28335_eqep.c */
                   *(.text:_abs32) *(.text:_f28335_qep_angle) *(.text:_f28335_qep_speed_capture)
                   *(.text:_f28335_qep_speed_unit) *(.text:_hal_encoder_rehome)
                   *(.text:_qep_count_step) *(.text:_qep_track_position)
                   *(.text:_qep_unit_period)
                   /* hal/f28335/src/f28335_gpio.c */
                   *(.text:_f28335_gpio_read)
                   /* hal/f28335/src/f28335_pwm.c */
                   *(.text:_f28335_pwm_cmpa_for) *(.text:_f28335_pwm_force_for)
                   *(.text:_hal_pwm_enable) *(.text:_hal_pwm_hw_trip_seen)
                   *(.text:_hal_pwm_is_off) *(.text:_pwm_force_all)
                   -lrts2800_fpu32.lib(.text)
                }
                LOAD = FLASHD,
                RUN = RAML0L3,
                LOAD_START(_RamfuncsLoadStart),
                LOAD_END(_RamfuncsLoadEnd),
                RUN_START(_RamfuncsRunStart),
                PAGE = 0
   /* The constant tables of the same path, copied to data RAM beside .ebss. */
   ramconsts  : {
                   *ctl_tables.*obj(.econst)
                   *ctl_q.*obj(.econst)
                   *ctl_vsd.*obj(.econst)
                   *drive.*obj(.econst)
                   *drive_capture.*obj(.econst)
                   *f28335_adc.*obj(.econst)
                }
                LOAD = FLASHA,
                RUN = RAML4L7,
                LOAD_START(_RamconstsLoadStart),
                LOAD_END(_RamconstsLoadEnd),
                RUN_START(_RamconstsRunStart),
                PAGE = 1

   .text      : >> FLASHC | FLASHB, PAGE = 0
   .cinit     : > FLASHA,  PAGE = 0
   .pinit     : > FLASHA,  PAGE = 0
   .econst    : > FLASHA,  PAGE = 0
   .switch    : > FLASHA,  PAGE = 0

   .stack     : > RAMM0M1, PAGE = 1
   .ebss      : > RAML4L7, PAGE = 1
   .esysmem   : > RAML4L7, PAGE = 1   /* empty: no heap */
   .cio       : > RAML4L7, PAGE = 1   /* empty: no C I/O */

   /* Boot ROM reset vector; not loaded (the boot ROM owns 0x3FFFC0). */
   .reset     : > RESET,   PAGE = 0, TYPE = DSECT
   vectors    : > VECTORS, PAGE = 0, TYPE = DSECT
}
