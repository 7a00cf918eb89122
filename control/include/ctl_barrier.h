/*
 * Compiler barrier for hand-offs between the background loop and the control ISR.
 *
 * A volatile flag orders only volatile accesses: the compiler may still move the plain
 * stores that fill a buffer past the store that publishes it. CTL_COMPILER_BARRIER()
 * forbids moving any memory access across it, on every compiler the firmware is built with:
 *   - gcc and clang (host, tests, the AVR proxy): an empty asm with a memory clobber;
 *   - TI cl2000 and any other compiler: a call to ctl_compiler_barrier(), an empty function
 *     in its own translation unit. The caller cannot see its body, so it must assume the
 *     call reads and writes any memory reachable from elsewhere, and completes every store
 *     before it and loads nothing early. This holds as long as ctl_barrier.c is not
 *     compiled together with its callers (no --program_level_compile / -pm over it, no LTO).
 * The C28x executes memory accesses in program order, so no hardware barrier is needed.
 */
#ifndef CTL_BARRIER_H
#define CTL_BARRIER_H

void ctl_compiler_barrier(void);

#if defined(__TMS320C2000__) || defined(__TMS320C28XX__) || !defined(__GNUC__)
#define CTL_COMPILER_BARRIER() ctl_compiler_barrier()
#else
#define CTL_COMPILER_BARRIER() __asm__ __volatile__("" ::: "memory")
#endif

#endif /* CTL_BARRIER_H */
