/*
 * Where the zero vector goes in a discrete-duty command, "vector v for duty d, a zero vector
 * for the rest", realised with centred pulses (each leg high in one pulse centred in the
 * period): u00 at the period edges with v in the middle (a leg of v on for d), or v at the
 * edges with u77 in the middle (a leg off v on for 1 - d). The paper leaves the choice open.
 *
 *   by ones (the earlier rule, ctl_params_t.fewest_transitions false): u77 when v has four or
 *     more upper switches on, so each leg of v switches at most twice inside the period;
 *   fewest transitions (the default): the arrangement that switches fewer legs, counting the
 *     change at the period boundary from the edges the period before left; a tie keeps the
 *     rule by ones.
 *
 * A zero-vector command (duty 0, or v is u00 or u77) holds u00 or u77 for the whole period,
 * chosen by the same rules from the vector in force before.
 */
#ifndef CTL_PULSE_H
#define CTL_PULSE_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_vectors.h"

/* Legs that change state from a to b (6-bit states, S_A = bit 5). */
static inline int16_t ctl_pulse_legs_switching(int16_t a, int16_t b)
{
    return ctl_vector_ones((int16_t)(a ^ b));
}

/* True for u77 (in the middle, or for the whole period of a zero-vector command). */
static inline bool ctl_pulse_high_zero(int16_t vector, bool zero, int16_t vector_in_force,
                                       int16_t edges_before, bool fewest_transitions)
{
    const int16_t ones = ctl_vector_ones(zero ? vector_in_force : vector);
    const bool by_ones = ones > 3;
    int16_t cost_low;
    int16_t cost_high;
    if (!fewest_transitions) {
        return by_ones;
    }
    if (zero) {
        cost_low = ctl_pulse_legs_switching(edges_before, 0);
        cost_high = ctl_pulse_legs_switching(edges_before, 077);
    } else { /* inside the period each leg that differs from the zero vector switches twice */
        cost_low = (int16_t)(ctl_pulse_legs_switching(edges_before, 0) + 2 * ones);
        cost_high = (int16_t)(ctl_pulse_legs_switching(edges_before, vector) + 2 * (6 - ones));
    }
    return (cost_low == cost_high) ? by_ones : (cost_high < cost_low);
}

/* The legs' states at the period boundary of that arrangement (full duty: the vector). */
static inline int16_t ctl_pulse_edges(int16_t vector, bool zero, bool high_zero, bool full_duty)
{
    if (zero) {
        return high_zero ? 077 : 0;
    }
    return (high_zero || full_duty) ? vector : 0;
}

#endif /* CTL_PULSE_H */
