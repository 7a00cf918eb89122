/*
 * Linker command file: TMS320F28335, everything in SARAM (debug builds loaded
 * by Code Composer Studio; boot mode "boot to SARAM", or the debugger sets
 * the PC to code_start).
 *
 *   code start   BEGIN 0x000000 (boot-to-M0 entry) -> codestart.asm
 *   .text        L0..L3 together with ramfuncs (already in RAM: the copy
 *                done by fw_ramfuncs_copy moves the section onto itself)
 *   constants    L4..L7: .cinit, .pinit, .econst, .switch
 *   .ebss        L4..L7
 *   .stack       M1
 * The image is lost at power-off; use F28335_flash.cmd for stand-alone runs.
 */

MEMORY
{
PAGE 0 :   /* program */
   BEGIN      : origin = 0x000000, length = 0x000002   /* boot-to-SARAM entry in M0 */
   RAML0L3    : origin = 0x008000, length = 0x004000   /* L0..L3 SARAM */
   RESET      : origin = 0x3FFFC0, length = 0x000002

PAGE 1 :   /* data */
   BOOT_RSVD  : origin = 0x000002, length = 0x00004E   /* boot ROM stack */
   RAMM0      : origin = 0x000050, length = 0x0003B0
   RAMM1      : origin = 0x000400, length = 0x000400
   RAML4L7    : origin = 0x00C000, length = 0x004000   /* L4..L7 SARAM */
}

SECTIONS
{
   codestart  : > BEGIN,   PAGE = 0
   ramfuncs   : > RAML0L3,
                LOAD_START(_RamfuncsLoadStart),
                LOAD_END(_RamfuncsLoadEnd),
                RUN_START(_RamfuncsRunStart),
                PAGE = 0
   .text      : > RAML0L3, PAGE = 0

   .cinit     : > RAML4L7, PAGE = 1
   .pinit     : > RAML4L7, PAGE = 1
   .econst    : > RAML4L7, PAGE = 1
   .switch    : > RAML4L7, PAGE = 1
   .ebss      : > RAML4L7, PAGE = 1

   .stack     : > RAMM1,   PAGE = 1
   .esysmem   : > RAMM0,   PAGE = 1
   .cio       : > RAMM0,   PAGE = 1

   .reset     : > RESET,   PAGE = 0, TYPE = DSECT
}
