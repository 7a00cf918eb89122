/*
 * The stack measured on the target: start-up paints the stack's unused part with a pattern,
 * the background finds the highest word no longer holding it (the high-water mark), and the
 * status reply carries it (SXL_ST_STACK_USED, docs/serial-protocol.md). Pure: the platform
 * names the region (on the F28335 the linker's .stack, fw_startup.c). The C28x stack grows
 * upward from the section's start, so the part in use lies at the bottom and the scan runs
 * down from the far end: a word skipped inside a frame (a local never written) does not hide
 * the deeper words above it.
 *
 * One global record, drive_stack, like drive_profile. A platform that paints nothing (the
 * virtual board: the host's stack is not the C28x's) leaves its size 0: "not measured".
 */
#ifndef STACK_WATCH_H
#define STACK_WATCH_H

#include <stdint.h>

/* What start-up writes into every unused word. A word the program wrote with this very value
 * at the top of the deepest frame would be missed: the mark is then low by a word or two. */
#define STACK_WATCH_PATTERN 0x5AA5u

typedef struct {
    volatile uint16_t *base; /* first (lowest) word of the stack */
    uint16_t words;          /* its size; 0: not measured */
    uint16_t used;           /* high-water mark, words from base; never decreases */
} stack_watch_t;

extern stack_watch_t drive_stack;

/* Paints base[in_use .. words - 1] and records the region. The words below in_use are in use at
 * the call (the caller's frames and this call's own): left alone and counted as used. */
void stack_watch_paint(stack_watch_t *w, volatile uint16_t *base, uint16_t words, uint16_t in_use);

/* The high-water mark now, in words from base (0 when not measured): the scan reads down from
 * the far end to the highest word that differs from the pattern, at most `words` reads.
 * Background only: never from the control interrupt. */
uint16_t stack_watch_scan(stack_watch_t *w);

#endif /* STACK_WATCH_H */
