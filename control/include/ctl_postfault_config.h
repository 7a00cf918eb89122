/*
 * Post-fault configuration: what the control step needs to keep the machine running with one
 * phase open (ctl_params_t.open_phase), built outside the ISR with the rest of the
 * configuration (docs/design.md, "Open-phase operation").
 *
 * Model. With two isolated neutrals phase k carries i_k = c_k . (i_alpha, i_beta, i_x, i_y),
 * c_k = (cos th_k, sin th_k, cos 5th_k, sin 5th_k). With phase k open, i_k = 0 and the open
 * terminal's voltage is whatever keeps it so: it enters the VSD voltage along c_k only, so the
 * currents evolve as in the healthy machine projected onto c_k . i = 0 along M^-1 c_k (M the
 * inductance matrix). A state and the same state with the open leg's bit flipped differ by a
 * voltage along c_k and are equivalent: the 32 states of the five healthy legs are all there is.
 *
 * Current references. The x-y currents then have a part forced by the alpha-beta currents,
 * -(c_k,ab . i_ab) c_k,xy, and one free component along c_k,xy rotated by 90 deg. Minimum copper
 * loss (ML) keeps the free component at zero; maximum torque (MT) uses it to hold a second phase
 * at zero current, which lowers the peak phase current for a given alpha-beta current (Che et
 * al., IEEE TPEL 2014, two isolated neutrals). Either way the free component's reference is a
 * fixed linear function of i_ab, free_ref . i_ab (zero for ML).
 */
#ifndef CTL_POSTFAULT_CONFIG_H
#define CTL_POSTFAULT_CONFIG_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_q.h"
#include "ctl_tables.h"

/* How the free x-y current component is used after an open phase. */
typedef enum {
    CTL_POSTFAULT_MIN_LOSS = 0,  /* free component zero: least copper loss (default) */
    CTL_POSTFAULT_MAX_TORQUE = 1 /* free component zeroes a second phase: lowest peak current */
} ctl_postfault_strategy_t;

#define CTL_POSTFAULT_STATES 32 /* switching states of the five healthy legs */
#define CTL_POSTFAULT_NO_LEG (-1)

typedef struct {
    int16_t open_leg; /* 0..5 (A..F), or CTL_POSTFAULT_NO_LEG: healthy, nothing below is used */
    int16_t zero_leg; /* MT: the healthy phase held at zero current; else CTL_POSTFAULT_NO_LEG */
    uint16_t quiet;   /* bit k (A = bit 0): phase k carries no current by design (open, or the
                       * one MT holds at zero); the open-phase check judges the others only */
    ctl_q c_alpha;    /* the open phase's VSD row c_k */
    ctl_q c_beta;
    ctl_q c_x;
    ctl_q c_y;
    ctl_q free_ref_alpha; /* reference of the free x-y current per unit i_alpha, i_beta */
    ctl_q free_ref_beta;
    float peak_ratio; /* peak phase current per unit alpha-beta current amplitude (healthy: 1) */
    /* DDC: [flux sector][0 torque up, 1 down][0 raise, 1 lower flux][free x-y voltage 0 > 0,
     * 1 < 0] -> the state of the five healthy legs with the largest effective alpha-beta voltage
     * along the direction the healthy table 1 aims at (+-75 / +-105 deg from the sector centre) */
    int16_t ddc_table[CTL_SECTORS][2][2][2];
    /* MPTC: the zero state first, then one state per distinct non-zero effective voltage (all
     * of them: mptc_all; the largest 12 in alpha-beta, ties at the twelfth included: mptc_large) */
    int16_t mptc_all[CTL_POSTFAULT_STATES];
    int16_t mptc_all_count;
    int16_t mptc_large[CTL_POSTFAULT_STATES];
    int16_t mptc_large_count;
} ctl_postfault_config_t;

/* Builds pf for open phase open_leg (CTL_POSTFAULT_NO_LEG: healthy, only open_leg is written)
 * with the machine's inductances (SI; the table build uses the mean of L_d and L_q). The caller
 * has checked the arguments (ctl_params_check). Background only. */
void ctl_postfault_config_build(ctl_postfault_config_t *pf, int16_t open_leg,
                                ctl_postfault_strategy_t strategy, float ld_h, float lq_h,
                                float lxy_h);

/* Peak phase current per unit alpha-beta current amplitude with open_leg open under the strategy
 * (1 for CTL_POSTFAULT_NO_LEG: healthy); the torque limit is divided by it. */
float ctl_postfault_peak_ratio(int16_t open_leg, ctl_postfault_strategy_t strategy);

/* The effective voltage of a switching state with phase open_leg open, per unit of Vdc
 * (alpha, beta, x, y): the voltage with its component along c_k removed in the metric of the
 * inductances l_ab (alpha-beta) and l_xy, the part of the voltage that moves currents. */
void ctl_postfault_effective_voltage(int16_t state, int16_t open_leg, float l_ab, float l_xy,
                                     float out[4]);

#endif /* CTL_POSTFAULT_CONFIG_H */
