/*
 * Everything compiler-specific of the F28335 port, in one header.
 *
 * Built by TI's cl2000 (__TMS320C2000__ defined): the real intrinsics,
 * interrupt keyword, core registers and code placement.
 * Built by any other compiler (host gcc for the driver tests): harmless
 * stand-ins that record what the code asked for, so tests can check it.
 *
 * Nothing outside this header may use __asm, cregister, interrupt or a
 * TI #pragma directly. Code placement (what runs from RAM) is sixphase_placement.h's.
 */
#ifndef F28335_COMPILER_H
#define F28335_COMPILER_H

#include <stdint.h>

/* Compile-time check usable in C99 (no _Static_assert): a negative array size
 * fails the build. Use at file scope. */
#define F28335_CT_CONCAT2(a, b) a##b
#define F28335_CT_CONCAT(a, b) F28335_CT_CONCAT2(a, b)
#define F28335_CT_ASSERT(cond, tag)                                                                \
    typedef char F28335_CT_CONCAT(f28335_ct_assert_##tag##_, __LINE__)[(cond) ? 1 : -1]

#if defined(__TMS320C2000__) || defined(__TMS320C28XX__)

#define F28335_TARGET 1

/* Interrupt service routine qualifier (cl2000 accepts __interrupt in all modes). */
#define F28335_INTERRUPT __interrupt

/* Core registers IER/IFR are not memory mapped. */
extern __cregister volatile uint16_t IER;
extern __cregister volatile uint16_t IFR;

#define F28335_EALLOW() __asm(" EALLOW")
#define F28335_EDIS() __asm(" EDIS")
#define F28335_EINT() __asm(" CLRC INTM")
#define F28335_DINT() __asm(" SETC INTM")
#define F28335_ERTM() __asm(" CLRC DBGM")
#define F28335_NOP() __asm(" NOP")
/* Flush the flash pipeline after changing wait states: eight NOPs. */
#define F28335_FLUSH_PIPELINE() __asm(" RPT #7 || NOP")
#define F28335_IER_SET(mask) (IER |= (uint16_t)(mask))
#define F28335_IER_CLEAR(mask) (IER &= (uint16_t) ~(uint16_t)(mask))
#define F28335_IFR_CLEAR_ALL() (IFR = 0x0000u)

/* Absolute address to a pointer; only the target build uses real addresses. */
#define F28335_ADDR(type, addr) ((type *)(addr))

#elif defined(F28335_LINK_PROXY)

/* Host link check of the target source list (tools/ti_link_proxy): the target code paths,
 * real addresses included, compiled by the host compiler so that linking exactly the TI
 * list finds every missing source. The intrinsics become calls into the one stub file
 * (tools/ti_link_proxy/ti_link_stubs.c). The result is linked, never run. */
#define F28335_TARGET 1

#define F28335_INTERRUPT

extern volatile uint16_t IER;
extern volatile uint16_t IFR;
void f28335_proxy_intrinsic(const char *instruction);

#define F28335_EALLOW() f28335_proxy_intrinsic("EALLOW")
#define F28335_EDIS() f28335_proxy_intrinsic("EDIS")
#define F28335_EINT() f28335_proxy_intrinsic("CLRC INTM")
#define F28335_DINT() f28335_proxy_intrinsic("SETC INTM")
#define F28335_ERTM() f28335_proxy_intrinsic("CLRC DBGM")
#define F28335_NOP() f28335_proxy_intrinsic("NOP")
#define F28335_FLUSH_PIPELINE() f28335_proxy_intrinsic("RPT #7 || NOP")
#define F28335_IER_SET(mask) (IER |= (uint16_t)(mask))
#define F28335_IER_CLEAR(mask) (IER &= (uint16_t) ~(uint16_t)(mask))
#define F28335_IFR_CLEAR_ALL() (IFR = 0x0000u)

/* through uintptr_t: host pointers are wider than the 32-bit address arithmetic */
#define F28335_ADDR(type, addr) ((type *)(uintptr_t)(addr))

#else /* host build: stand-ins */

#define F28335_TARGET 0

#define F28335_INTERRUPT

/* Host mirror of the core state the target keeps in CPU registers. */
typedef struct {
    uint16_t ier;          /* IER */
    uint16_t ifr;          /* IFR */
    uint16_t intm;         /* 1 = interrupts globally masked (reset state) */
    uint16_t eallow;       /* 1 = protected registers writable */
    uint32_t eallow_count; /* how many EALLOW were executed */
    uint32_t nop_count;
} f28335_host_core_t;

extern f28335_host_core_t f28335_host_core;

/* EALLOW / EDIS on the host also watch the EALLOW-protected registers (f28335_host_regs.c):
 * a change of one of them made while protected counts as a violation, which on the target is a
 * write the CPU ignores. */
void f28335_host_eallow(void);
void f28335_host_edis(void);
#define F28335_EALLOW() f28335_host_eallow()
#define F28335_EDIS() f28335_host_edis()
#define F28335_EINT() (f28335_host_core.intm = 0u)
#define F28335_DINT() (f28335_host_core.intm = 1u)
#define F28335_ERTM() ((void)0)
#define F28335_NOP() (f28335_host_core.nop_count++)
#define F28335_FLUSH_PIPELINE() (f28335_host_core.nop_count += 8u)
#define F28335_IER_SET(mask) (f28335_host_core.ier |= (uint16_t)(mask))
#define F28335_IER_CLEAR(mask) (f28335_host_core.ier &= (uint16_t) ~(uint16_t)(mask))
#define F28335_IFR_CLEAR_ALL() (f28335_host_core.ifr = 0x0000u)

#endif /* __TMS320C2000__ */

#endif /* F28335_COMPILER_H */
