/*
 * Linker command file: TMS320F28335, boot from flash.
 *
 * Program (PAGE 0) and data (PAGE 1) memory used by the sixphase firmware.
 * The peripheral register frames are not placed here: the HAL addresses
 * them directly (hal/f28335/include/f28335_regs.h holds the base addresses).
 *
 *   code start   BEGIN 0x33FFF6 (boot-to-flash entry) -> codestart.asm
 *   ramfuncs     loaded to FLASHD, run from L0..L3 (copied by fw_ramfuncs_copy): the
 *                code of the whole per-period path - control ISR, drive step, control
 *                step, protection, the drivers they call and the run-time library
 *                routines the compiler calls from them - and the flash wait-state set-up
 *   ramconsts    loaded to FLASHA, run from L4..L7 (copied likewise): the constant
 *                tables of that path. Nothing of a control period waits on flash.
 *   .text        FLASHC, FLASHB (start-up, background loop, parameter builds)
 *   constants    FLASHA: .cinit, .pinit, .econst, .switch of everything else
 *   .stack       M0 + M1, 0x700 words (tools/check_stack.sh sizes it: background plus a
 *                nested control interrupt, with margin; the stack must lie below 0x10000)
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
   ramfuncs   : {
                   *(ramfuncs)
                   *fw_isr.*obj(.text)
                   *drive.*obj(.text)
                   *drive_capture.*obj(.text)
                   *capture.*obj(.text)
                   *profile.*obj(.text)
                   *ctl.*obj(.text)
                   *ctl_q.*obj(.text)
                   *ctl_vsd.*obj(.text)
                   *ctl_ddc.*obj(.text)
                   *ctl_mptc.*obj(.text)
                   *ctl_speed_pi.*obj(.text)
                   *ctl_flux_ref.*obj(.text)
                   *ctl_protect.*obj(.text)
                   *ctl_barrier.*obj(.text)
                   *f28335_pwm.*obj(.text)
                   *f28335_adc.*obj(.text)
                   *f28335_eqep.*obj(.text)
                   *f28335_cycles.*obj(.text)
                   *f28335_gpio.*obj(.text)
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
