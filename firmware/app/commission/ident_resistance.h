/*
 * Identification step 3, the stator resistance. The rotor is aligned with the current (the
 * encoder step left it so); the commanded angle moves to the nearest 15 + 30 k electrical
 * degrees, where the smallest phase share of the vector is cos 75 deg = 0.26, so no phase
 * current is near zero. The current is held along that angle at the test current, at half of
 * it, and at the test current again (0.3 s settling, 0.5 s averaged in 50 ms blocks each);
 * R = (u_high - u_low) / (i_high - i_low) along the vector, the highs averaged (a slow drift,
 * such as heating, cancels). Every phase keeps its sign, so the dead-time voltage and the
 * device drops are the same at both levels and cancel, and so do the sensors' offsets. The
 * voltage is the regulator's request; its current is the measured one. About 2.5 s.
 */
#ifndef IDENT_RESISTANCE_H
#define IDENT_RESISTANCE_H

#include "ident.h"

typedef struct {
    float from, to;                    /* commanded angle: start and the 15 + 30 k degree target */
    int16_t level;                     /* 0 high, 1 low, 2 high */
    ident_blocks_t u[3], i[3];         /* along the vector: V, A, per level */
    float low_phase_sum[IDENT_PHASES]; /* each phase's current summed at the low level, A */
    int32_t low_n;                     /* its samples */
} ident_resistance_t;

void ident_resistance_begin(ident_ctx_t *x, ident_resistance_t *s);
ident_status_t ident_resistance_step(ident_ctx_t *x, ident_resistance_t *s,
                                     const ident_input_t *in);

#define IDENT_RESISTANCE_SECONDS 2.8f

#endif /* IDENT_RESISTANCE_H */
