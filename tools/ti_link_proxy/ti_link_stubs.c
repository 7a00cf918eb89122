/*
 * The only stand-ins of the host link check of the TI source list (CMakeLists.txt beside):
 * what TI's compiler and the assembly start-up provide and the C sources reference. Any
 * other undefined symbol is a source missing from cmake/sources.cmake, and fails the link.
 */
#include <stdint.h>

#include "f28335_compiler.h"

/* Core registers (cl2000: __cregister). */
volatile uint16_t IER;
volatile uint16_t IFR;

/* __asm(" EALLOW") and the other single-instruction intrinsics. */
void f28335_proxy_intrinsic(const char *instruction) { (void)instruction; }

/* The linker's and the RTS start-up's stack symbols (__stack, __STACK_SIZE). */
uint16_t _stack;
uint16_t _STACK_SIZE;

/* Symbols of the linker command files (ramfuncs and ramconsts load and run addresses). */
uint16_t RamfuncsLoadStart;
uint16_t RamfuncsLoadEnd;
uint16_t RamfuncsRunStart;
uint16_t RamconstsLoadStart;
uint16_t RamconstsLoadEnd;
uint16_t RamconstsRunStart;
