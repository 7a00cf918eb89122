/*
 * Linker command file: TMS320F28335, boot from flash.
 *
 * Program (PAGE 0) and data (PAGE 1) memory used by the sixphase firmware.
 * The peripheral register frames are not placed here: the HAL addresses
 * them directly (hal/f28335/include/f28335_regs.h holds the base addresses).
 *
 *   code start   BEGIN 0x33FFF6 (boot-to-flash entry) -> codestart.asm
 *   .text        FLASHC, FLASHB (split as needed)
 *   constants    FLASHA: .cinit, .pinit, .econst, .switch
 *   ramfuncs     loaded to FLASHD, run from L0..L2 (copied by fw_ramfuncs_copy):
 *                the control ISR path and the flash wait-state set-up
 *   .stack       M1 (the C28x stack must lie below 0x10000)
 *   .ebss        L4..L7
 *
 * The CSM password locations (0x33FFF8..0x33FFFF) are left erased (0xFFFF):
 * never program them to all zeros, that locks the device for good.
 */

MEMORY
{
PAGE 0 :   /* program */
   RAML0L2    : origin = 0x008000, length = 0x003000   /* L0, L1, L2 SARAM: ramfuncs run here */
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
   RAMM0      : origin = 0x000050, length = 0x0003B0
   RAMM1      : origin = 0x000400, length = 0x000400
   RAML3      : origin = 0x00B000, length = 0x001000
   RAML4L7    : origin = 0x00C000, length = 0x004000   /* L4..L7 SARAM */
}

SECTIONS
{
   codestart  : > BEGIN,   PAGE = 0
   ramfuncs   : LOAD = FLASHD,
                RUN = RAML0L2,
                LOAD_START(_RamfuncsLoadStart),
                LOAD_END(_RamfuncsLoadEnd),
                RUN_START(_RamfuncsRunStart),
                PAGE = 0

   .text      : >> FLASHC | FLASHB, PAGE = 0
   .cinit     : > FLASHA,  PAGE = 0
   .pinit     : > FLASHA,  PAGE = 0
   .econst    : > FLASHA,  PAGE = 0
   .switch    : > FLASHA,  PAGE = 0

   .stack     : > RAMM1,   PAGE = 1
   .ebss      : > RAML4L7, PAGE = 1
   .esysmem   : > RAMM0,   PAGE = 1
   .cio       : > RAMM0,   PAGE = 1

   /* Boot ROM reset vector; not loaded (the boot ROM owns 0x3FFFC0). */
   .reset     : > RESET,   PAGE = 0, TYPE = DSECT
   vectors    : > VECTORS, PAGE = 0, TYPE = DSECT
}
