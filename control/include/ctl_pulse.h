/*
 * Where the zero vector goes in a discrete-duty command, "vector v for duty d, a zero vector
 * for the rest", realised with centred pulses (each leg high in one pulse centred in the
 * period). A command is an active state for d and a zero state for 1 - d: a leg at 1 in both
 * is on all period, at 0 in both off; a leg at 1 only in the active state is high for d in
 * the middle, a leg at 1 only in the zero state high for 1 - d in the middle (so the active
 * state sits at the period edges where the zero state has its ones). The paper leaves the
 * choice open (ctl_params_t.pulse_pattern):
 *
 *   by ones (the earlier rule): u77 when v has four or more upper switches on, u00 otherwise,
 *     so each leg of v switches at most twice inside the period;
 *   fewest transitions: u00 or u77, whichever switches fewer legs, counting the change at the
 *     period boundary from the edges the period before left; a tie keeps the rule by ones;
 *   fewest transitions per set (the default): with two isolated neutrals each three-phase set
 *     (legs A B C, legs D E F) is an inverter of its own whose zero state may be 000 or 111,
 *     so u07 and u70 apply no voltage either, and a set at 000 or 111 in v (idle) may sit at
 *     either for the whole period. Of the four zero states the one that switches the fewest
 *     legs, a tie keeping u00 or u77 (the rule by ones first), then u07, then u70.
 *
 * A zero-vector command (duty 0, or v is u00 or u77) holds a zero state for the whole period,
 * chosen by the same rules from the vector in force before; a full-duty command holds its
 * active state. The period average, and so the prediction, is the same in every case.
 */
#ifndef CTL_PULSE_H
#define CTL_PULSE_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_params.h"
#include "ctl_vectors.h"

typedef enum {
    CTL_PULSE_ZERO = 0, /* the zero state all period */
    CTL_PULSE_PART = 1, /* 0 < d < 1 */
    CTL_PULSE_FULL = 2  /* the active state all period */
} ctl_pulse_kind_t;

#define CTL_PULSE_LEGS_ABC 070 /* the two three-phase sets (S_A = bit 5) */
#define CTL_PULSE_LEGS_DEF 007

typedef struct {
    int16_t active; /* state for d: v, an idle set at its zero state (per set) */
    int16_t zero;   /* state for 1 - d: 0, 07, 070 or 077 */
} ctl_pulse_t;

/* Legs that change state from a to b (6-bit states, S_A = bit 5). */
static inline int16_t ctl_pulse_legs_switching(int16_t a, int16_t b)
{
    return ctl_vector_ones((int16_t)(a ^ b));
}

/* The legs' states at the period boundary. */
static inline int16_t ctl_pulse_edges(ctl_pulse_kind_t kind, const ctl_pulse_t *p)
{
    if (kind == CTL_PULSE_ZERO) {
        return p->zero;
    }
    return (kind == CTL_PULSE_FULL) ? p->active : (int16_t)(p->active & p->zero);
}

/* Transitions of the legs in mask over one period: at its start from edges_before, then two
 * for each leg whose active and zero states differ (0 < d < 1). */
static inline int16_t ctl_pulse_transitions(ctl_pulse_kind_t kind, const ctl_pulse_t *p,
                                            int16_t edges_before, int16_t mask)
{
    int16_t n = ctl_pulse_legs_switching((int16_t)(edges_before & mask),
                                         (int16_t)(ctl_pulse_edges(kind, p) & mask));
    if (kind == CTL_PULSE_PART) {
        n = (int16_t)(n + 2 * ctl_pulse_legs_switching((int16_t)(p->active & mask),
                                                       (int16_t)(p->zero & mask)));
    }
    return n;
}

/* One set's transitions with zero state 111 less those with 000 (the sets' transitions add,
 * so the two sets' differences rank all four zero states). A set held at its zero state all
 * period (a zero command; per set, an idle set: 000 or 111 in v, no voltage at either) switches
 * only at the boundary, and is added to *held; otherwise each of its legs off v (111) or on v
 * (000) switches twice inside a partial-duty period, after the boundary to v (111) or to 000. */
static inline int16_t ctl_pulse_set_difference(ctl_pulse_kind_t kind, bool per_set, int16_t vector,
                                               int16_t edges_before, int16_t mask, int16_t *held)
{
    const int16_t v = (int16_t)(vector & mask);
    const int16_t at_one = ctl_vector_ones((int16_t)(edges_before & mask));
    if (kind == CTL_PULSE_ZERO || (per_set && (v == 0 || v == mask))) {
        *held = (int16_t)(*held | mask);
        return (int16_t)(3 - 2 * at_one);
    }
    if (kind != CTL_PULSE_PART) {
        return 0;
    }
    return (int16_t)(ctl_vector_ones((int16_t)((edges_before ^ vector) & mask)) - at_one + 6 -
                     4 * ctl_vector_ones(v));
}

/* The command's active and zero states under a pattern: of the candidate zero states (u00 or
 * u77 by ones, the other of the two, then per set u07 and u70) the first with the fewest
 * transitions, a held set at its zero state all period. */
static inline void ctl_pulse_arrange(ctl_pulse_pattern_t pattern, ctl_pulse_kind_t kind,
                                     int16_t vector, int16_t vector_in_force, int16_t edges_before,
                                     ctl_pulse_t *p)
{
    const bool zero = kind == CTL_PULSE_ZERO;
    int16_t held = zero ? 077 : 0;
    int16_t z = (ctl_vector_ones(zero ? vector_in_force : vector) > 3) ? 077 : 0;
    if (pattern != CTL_PULSE_BY_ONES) {
        /* transitions relative to u00: u77 both differences, u07 DEF's, u70 ABC's */
        const bool per_set = pattern == CTL_PULSE_FEWEST_PER_SET;
        const int16_t abc = ctl_pulse_set_difference(kind, per_set, vector, edges_before,
                                                     CTL_PULSE_LEGS_ABC, &held);
        const int16_t def = ctl_pulse_set_difference(kind, per_set, vector, edges_before,
                                                     CTL_PULSE_LEGS_DEF, &held);
        const int16_t both = (int16_t)(abc + def);
        int16_t best = (z != 0) ? both : 0;
        if (((z != 0) ? 0 : both) < best) {
            z = (int16_t)(z ^ 077);
            best = (int16_t)(both - best);
        }
        if (per_set && def < best) {
            z = CTL_PULSE_LEGS_DEF;
            best = def;
        }
        if (per_set && abc < best) {
            z = CTL_PULSE_LEGS_ABC;
        }
    }
    p->zero = z;
    p->active = (int16_t)((vector & ~held) | (z & held));
}

#endif /* CTL_PULSE_H */
