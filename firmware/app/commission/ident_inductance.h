/*
 * Identification steps 4 and 5, the inductances, at standstill: the rotor aligned with the
 * commanded angle (15 + 30 k degrees, the resistance step's) by a DC bias current along d at
 * the test current. The axis under test is held (its regulator output frozen at the bias voltage)
 * and a symmetric square wave of voltage is added along one axis: d, then q (step 4), x, then y
 * (step 5). Its amplitude gives a peak-to-peak ripple of half the bias along d and a quarter
 * along q, x and y with the axis' inductance as the drive measured it (a first block, the
 * probe, runs with the parameter set's; y takes x's estimate), so no phase current changes
 * sign: the dead-time voltage stays a constant offset. The held axis keeps the mean of its
 * regulator output over the last 50 ms (the bias voltage without a period's noise); the first half
 * period is half long, so the ripple is centred on the bias.
 *
 * Only the injected axis is held; the others keep regulating, so the rotor stays held and
 * damped. The current's change over a control period is (average voltage - R i - offsets) T / L;
 * the voltage commanded in period k acts during period k + 1. With the square wave at +U in
 * some periods and -U in others, the mean change over the + periods minus that over the -
 * periods is 2 U T / L: the offsets (dead time, R i of the bias, a slow drift of the bias)
 * cancel. One estimate per 10 square-wave periods (a block), corrected for the resistive
 * droop over a half period with the resistance step's R (L_raw = L x / tanh x,
 * x = R N T / (2 L); docs/commissioning.md section 2.4); their spread gives the uncertainty. The
 * rotor's motion during the q injection is reported (encoder counts, in the result's extra); beyond
 * about one electrical degree the result is POOR (ROTOR_MOVED). The x and y estimates are pooled
 * into L_xy. 0.5 s per axis.
 */
#ifndef IDENT_INDUCTANCE_H
#define IDENT_INDUCTANCE_H

#include "ident.h"

typedef enum {
    IDENT_AXIS_D = 0,
    IDENT_AXIS_Q = 1,
    IDENT_AXIS_X = 2,
    IDENT_AXIS_Y = 3
} ident_axis_t;

typedef struct {
    int16_t axis;           /* ident_axis_t */
    int16_t last_axis;      /* the step's last axis */
    float amplitude;        /* V */
    float r;                /* ohm: the resistance the droop's correction takes */
    bool sized;             /* the amplitude is the measured inductance's (else: a probe) */
    float resize;           /* V: the amplitude the probe asked for, until applied (else 0) */
    int16_t skip;           /* current changes not filed (the old amplitude's) */
    int16_t sign[2];        /* the square wave's sign commanded 1 and 2 periods ago */
    float last_i;           /* the axis current one period ago */
    float sum_pos, sum_neg; /* current changes in + and - periods of the open block */
    int32_t n_pos, n_neg;
    int32_t waves; /* square waves started */
    float u_sum;   /* the axis' regulator output over the settling's second half */
    int32_t u_n;
    ident_blocks_t l[3];               /* H: d, q, and x and y pooled */
    ident_still_t still;               /* settling: the rotor within IND_STILL_COUNTS */
    int32_t p_start;                   /* position at the axis' start */
    int32_t moved;                     /* largest |position - p_start| during the axis */
    int32_t p_last;                    /* position one period ago */
    float misalign;                    /* largest |rotor - commanded angle|, turns (offset known) */
    int32_t sync_counts[2], sync_n[2]; /* counts moved, periods: under + and under - */
} ident_inductance_t;

/* first, last: the axes of the step (D..Q for step 4, X..Y for step 5). */
void ident_inductance_begin(ident_ctx_t *x, ident_inductance_t *s, ident_axis_t first,
                            ident_axis_t last);
ident_status_t ident_inductance_step(ident_ctx_t *x, ident_inductance_t *s,
                                     const ident_input_t *in);

#define IDENT_INDUCTANCE_SECONDS 1.0f /* per step (two axes) */
/* periods per estimate (a block) */
#define IDENT_INDUCTANCE_BLOCK 200

#endif /* IDENT_INDUCTANCE_H */
