/*
 * Linker command file: TMS320F28335, boot from flash.
 *
 * Program (PAGE 0) and data (PAGE 1) memory used by the sixphase firmware.
 * The peripheral register frames are not placed here: the HAL addresses
 * them directly (hal/f28335/include/f28335_regs.h holds the base addresses).
 *
 *   code start   BEGIN 0x33FFF6 (boot-to-flash entry) -> codestart.asm -> _c_int00 -> main.
 *                Everything that runs before fw_ramfuncs_copy (codestart, the run-time
 *                library's start-up, main up to the copy) runs where it is loaded: in flash.
 *   ramfuncs     loaded to FLASHD, run from L0..L3 (copied by fw_ramfuncs_copy): the functions
 *                the sources mark SIXPHASE_RAMFUNC (sixphase_placement.h: the whole healthy
 *                control period, and the flash wait-state set-up), and the run-time library
 *                members the period calls, named one by one. The open-phase step, the
 *                commissioning and a fault's latching run from flash, and so does the
 *                MPTC-49/13 search in the Q24 image (docs/porting.md section 7).
 *   ramconsts    loaded to FLASHA, run from L4..L5 (copied likewise): the tables the sources
 *                mark SIXPHASE_RAMCONST, and the jump tables of the objects whose period
 *                functions have a switch.
 *   .text        FLASHC, FLASHB (start-up, background loop, parameter builds)
 *   constants    FLASHA: .cinit, .pinit, .econst, .switch of everything else
 *   .stack       M0 + M1, 0x700 words (--stack_size, cmake/ti-c2000-toolchain.cmake;
 *                tools/check_stack_bound.sh bounds its use: background plus a nested control
 *                interrupt, 20 % left); it must lie below 0x10000; start-up paints it from
 *                __stack for the measured mark (docs/porting.md 8)
 *   .ebss        L6..L7
 * tools/image_check.py (CI) proves it: the boot path runs at its load address, the period's
 * code, tables and jump tables and nothing else run from RAM, every memory range holds its
 * sections (docs/porting.md section 7).
 *
 * The CSM password locations (0x33FFF8..0x33FFFF) are left erased (0xFFFF):
 * never program them to all zeros, that locks the device for good.
 */

MEMORY
{
PAGE 0 :   /* program */
   RAML0L3    : origin = 0x008000, length = 0x004000   /* L0..L3 SARAM: ramfuncs run here */
   RAML4L5    : origin = 0x00C000, length = 0x002000   /* L4, L5 SARAM: ramconsts run here */
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
   RAML6L7    : origin = 0x00E000, length = 0x002000   /* L6, L7 SARAM: .ebss */
}

SECTIONS
{
   codestart  : > BEGIN,   PAGE = 0
   ramfuncs   : {
                   *(.TI.ramfunc)
                   /* TI's run-time library: what the period's code calls (image_check.py maps
                    * the proxy's helper calls to these members): 16- and 32-bit integer
                    * division, and the 64-bit multiply in the Q24 image. (No float division
                    * and no 64-bit division: the period's code does neither.) */
#ifdef SIXPHASE_FW_Q24
                   -l rts2800_fpu32.lib<i_div28.asm.obj l_div28.asm.obj ll_mpy28.asm.obj>(.text)
#else
                   -l rts2800_fpu32.lib<i_div28.asm.obj l_div28.asm.obj>(.text)
#endif
                }
                LOAD = FLASHD,
                RUN = RAML0L3,
                LOAD_START(_RamfuncsLoadStart),
                LOAD_END(_RamfuncsLoadEnd),
                RUN_START(_RamfuncsRunStart),
                PAGE = 0
   /* The constant tables and jump tables of the same path, copied to L4..L5. One PAGE holds
    * both ranges of a LOAD/RUN pair: the tables run on the program page, in a range of their
    * own (the C28x's memory is unified, -mt); .ebss has L6..L7 on the data page.
    * Object names match both CMake's (drive.c.obj) and CCS's (drive.obj) naming. */
   ramconsts  : {
                   *(ramconsts)
                   *drive.*obj(.switch)
                   *drive_capture.*obj(.switch)
                }
                LOAD = FLASHA,
                RUN = RAML4L5,
                LOAD_START(_RamconstsLoadStart),
                LOAD_END(_RamconstsLoadEnd),
                RUN_START(_RamconstsRunStart),
                PAGE = 0

   .text      : >> FLASHC | FLASHB, PAGE = 0
   .cinit     : > FLASHA,  PAGE = 0
   .pinit     : > FLASHA,  PAGE = 0
   .econst    : > FLASHA,  PAGE = 0
   .switch    : > FLASHA,  PAGE = 0

   .stack     : > RAMM0M1, PAGE = 1
   .ebss      : > RAML6L7, PAGE = 1
   .esysmem   : > RAML6L7, PAGE = 1   /* empty: no heap */
   .cio       : > RAML6L7, PAGE = 1   /* empty: no C I/O */

   /* Boot ROM reset vector; not loaded (the boot ROM owns 0x3FFFC0). */
   .reset     : > RESET,   PAGE = 0, TYPE = DSECT
   vectors    : > VECTORS, PAGE = 0, TYPE = DSECT
}
