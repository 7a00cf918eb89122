/*
 * Numbers as the host tools take them (sixphase-sim's options, sixphase-link's arguments, the
 * motor parameter file's values): plain decimals only, one rule for every tool. Accepted: an
 * optional sign, digits with an optional fraction, an optional exponent (1500, -0.5, .5, 2e-6).
 * Refused: anything around it (spaces, trailing text), hexadecimal (0x10), a leading zero
 * before more digits (010, which C's base-0 parsing reads as octal 8), inf and nan, and a value
 * that overflows. Host code only.
 */
#ifndef DECIMAL_ARG_H
#define DECIMAL_ARG_H

/* 1 when s is a plain decimal as above (integer_only: no fraction, no exponent), else 0. */
int decimal_is_plain(const char *s, int integer_only);

/* s as a plain decimal, finite, in [lo, hi], into *out; 0, or -1 (out untouched). */
int decimal_parse(const char *s, int integer_only, double lo, double hi, double *out);

#endif /* DECIMAL_ARG_H */
