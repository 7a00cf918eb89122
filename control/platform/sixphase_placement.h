/*
 * Where the target runs the control period's code and tables: from RAM.
 *
 * The F28335 image is loaded in flash; start-up copies the section `.TI.ramfunc` (code) and
 * `ramconsts` (tables) to RAM before anything else runs there (F28335_flash.cmd,
 * fw_ramfuncs_copy). A function that a control period executes is marked SIXPHASE_RAMFUNC at
 * its definition, a constant table it reads SIXPHASE_RAMCONST, as TI's C2000Ware marks its RAM
 * functions in the source (`.TI.ramfunc`, TI SPRU514: GCC `section` attribute). Nothing else is
 * marked: tools/image_check.py proves that the marked set is exactly the period's.
 *
 * Keyed on TI's compiler itself (__TI_COMPILER_VERSION__), not on the target macro that the
 * AVR proxy defines to take TI's code paths.
 *
 * Declared once here, in a folder of its own that the control core, the drive and the HAL all
 * include (it holds nothing else: the HAL sees no control code), so they use the same marks. Empty
 * on the host; the Arm proxy build of tools/check_target_memory.sh (SIXPHASE_PLACEMENT_PROXY) gives
 * gcc the same sections.
 */
#ifndef SIXPHASE_PLACEMENT_H
#define SIXPHASE_PLACEMENT_H

#if defined(__TI_COMPILER_VERSION__) || defined(SIXPHASE_PLACEMENT_PROXY)
#define SIXPHASE_RAMFUNC __attribute__((section(".TI.ramfunc")))
#define SIXPHASE_RAMCONST __attribute__((section("ramconsts")))
#else
#define SIXPHASE_RAMFUNC
#define SIXPHASE_RAMCONST
#endif

/* A function kept out of its only caller, so that it can run from elsewhere than the caller
 * (a comparison controller's part of the period left in flash while the product's runs from
 * RAM; tools/flash_on_purpose.txt). GCC and TI's compiler take the same attribute. */
#if defined(__GNUC__) || defined(__TI_COMPILER_VERSION__)
#define SIXPHASE_NOINLINE __attribute__((noinline))
#else
#define SIXPHASE_NOINLINE
#endif

#endif /* SIXPHASE_PLACEMENT_H */
