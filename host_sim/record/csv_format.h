/*
 * Number formatting for the simulator's CSV files without printf per value.
 *
 * csv_put_fixed(out, v, d) writes exactly what printf("%.<d>f", v) writes with glibc in the
 * default rounding mode: the exact binary value rounded to d decimals, ties to even, a minus
 * sign whenever the sign bit is set (also "-0.00000"). Values the fast path cannot represent
 * exactly (magnitudes above about 1e15 / 10^d, infinities, NaN) go through snprintf, so the
 * text is the same for every double. tests/sim/test_sim_csv_format.c checks it against
 * snprintf on millions of values and on the rounding edge cases.
 */
#ifndef SIM_CSV_FORMAT_H
#define SIM_CSV_FORMAT_H

/* Longest text csv_put_fixed writes (the snprintf path of the largest double), without a
 * terminating NUL. */
#define CSV_FIXED_MAX_CHARS 330
#define CSV_FIXED_MAX_DECIMALS 9

/* printf("%.<decimals>f", v) into out (no NUL); decimals 0..CSV_FIXED_MAX_DECIMALS. Returns the
 * end of the written text. */
char *csv_put_fixed(char *out, double v, int decimals);

/* printf("%d", v) into out (no NUL). Returns the end of the written text. */
char *csv_put_int(char *out, int v);

#endif /* SIM_CSV_FORMAT_H */
