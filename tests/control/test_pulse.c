/*
 * Zero-vector arrangement (control/src/ctl_pulse.c), over every vector and every state the
 * period before can leave at the boundary: with fewest transitions the arrangement switches
 * no more legs than the other one (period boundary plus the two edges of each pulse), and a
 * tie keeps the rule by ones; without it, the rule by ones (u77 for four or more switches on);
 * the boundary state is what the arrangement puts at the edges.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl_pulse.h"
#include "ctl_vectors.h"

/* Legs switched in a period of the arrangement after edges_before (boundary included). */
static int16_t transitions(int16_t vector, bool zero, bool high_zero, int16_t edges_before)
{
    const int16_t edges = ctl_pulse_edges(vector, zero, high_zero, false);
    int16_t inside = 0;
    if (!zero) {
        inside = (int16_t)(2 * ctl_pulse_legs_switching(vector, high_zero ? 077 : 0));
    }
    return (int16_t)(ctl_pulse_legs_switching(edges_before, edges) + inside);
}

static void test_fewest_transitions_over_every_case(void **state)
{
    int16_t v, before;
    (void)state;
    for (v = 1; v < 077; v++) {
        const bool by_ones = ctl_vector_ones(v) > 3;
        for (before = 0; before < 64; before++) {
            const bool hz = ctl_pulse_high_zero(v, false, 0, before, true);
            const int16_t chosen = transitions(v, false, hz, before);
            const int16_t other = transitions(v, false, !hz, before);
            assert_true(chosen <= other);
            if (chosen == other) {
                assert_int_equal(hz, by_ones);
            }
            assert_int_equal(ctl_pulse_high_zero(v, false, 0, before, false), by_ones);
            assert_int_equal(ctl_pulse_edges(v, false, hz, false), hz ? v : 0);
        }
    }
}

static void test_zero_vector_commands(void **state)
{
    int16_t in_force, before;
    (void)state;
    for (in_force = 0; in_force < 64; in_force++) {
        for (before = 0; before < 64; before++) {
            const bool hz = ctl_pulse_high_zero(0, true, in_force, before, true);
            const int16_t to_low = ctl_pulse_legs_switching(before, 0);
            const int16_t to_high = ctl_pulse_legs_switching(before, 077);
            assert_true(hz ? to_high <= to_low : to_low <= to_high);
            assert_int_equal(ctl_pulse_high_zero(0, true, in_force, before, false),
                             ctl_vector_ones(in_force) > 3);
            assert_int_equal(ctl_pulse_edges(0, true, hz, false), hz ? 077 : 0);
        }
    }
}

/* A full-duty vector is the vector at the boundary whichever zero vector was chosen. */
static void test_full_duty_edges(void **state)
{
    (void)state;
    assert_int_equal(ctl_pulse_edges(046, false, false, true), 046);
    assert_int_equal(ctl_pulse_edges(046, false, true, true), 046);
    assert_int_equal(ctl_pulse_edges(046, false, false, false), 0);
}

/* The case the rule by ones gets wrong: after v = 110100 at the edges, v again (three
 * switches on) costs 6 legs with u00 at the edges (3 at the boundary, 6 inside: 9) and 6 with
 * v at the edges and u77 in the middle (0 at the boundary, 6 inside). */
static void test_repeat_of_a_vector_at_the_edges(void **state)
{
    (void)state;
    assert_true(ctl_pulse_high_zero(064, false, 064, 064, true));
    assert_false(ctl_pulse_high_zero(064, false, 064, 064, false));
    assert_int_equal(transitions(064, false, true, 064), 6);
    assert_int_equal(transitions(064, false, false, 064), 9);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fewest_transitions_over_every_case),
        cmocka_unit_test(test_zero_vector_commands),
        cmocka_unit_test(test_full_duty_edges),
        cmocka_unit_test(test_repeat_of_a_vector_at_the_edges),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
