/*
 * Linker command file: TMS320F28335, everything in SARAM (debug builds loaded
 * by Code Composer Studio; boot mode "boot to SARAM", or the debugger sets
 * the PC to code_start).
 *
 *   code start   BEGIN 0x000000 (boot-to-M0 entry) -> codestart.asm
 *   .text        L0..L3 together with ramfuncs (already in RAM: the copy
 *                done by fw_ramfuncs_copy moves the section onto itself; likewise
 *                ramconsts, empty here: the tables stay in .econst)
 *   constants    L4..L7: .cinit, .pinit, .econst, .switch
 *   .ebss        L4..L7
 *   .stack       M0 + M1 after the entry and the boot ROM's stack (0x700 words)
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
   RAMM0M1    : origin = 0x000050, length = 0x0007B0   /* M0 and M1 SARAM: the stack */
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
   ramconsts  : > RAML4L7,
                LOAD_START(_RamconstsLoadStart),
                LOAD_END(_RamconstsLoadEnd),
                RUN_START(_RamconstsRunStart),
                PAGE = 1

   .cinit     : > RAML4L7, PAGE = 1
   .pinit     : > RAML4L7, PAGE = 1
   .econst    : > RAML4L7, PAGE = 1
   .switch    : > RAML4L7, PAGE = 1
   .ebss      : > RAML4L7, PAGE = 1

   .stack     : > RAMM0M1, PAGE = 1
   .esysmem   : > RAML4L7, PAGE = 1   /* empty: no heap */
   .cio       : > RAML4L7, PAGE = 1   /* empty: no C I/O */

   .reset     : > RESET,   PAGE = 0, TYPE = DSECT
}
