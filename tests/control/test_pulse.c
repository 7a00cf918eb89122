/*
 * Zero-vector arrangement (control/include/ctl_pulse.h), over every vector, every state the
 * period before can leave at the boundary and every kind of command: the arrangement applies
 * the vector's voltage; by ones follows the count of upper switches; fewest transitions
 * switches no more legs than the other of u00 and u77 (a tie keeps the rule by ones); fewest
 * transitions per set switches no more legs than any arrangement with the same voltage over
 * the four zero states (a tie keeps u00 or u77); the boundary state is what the arrangement
 * puts at the edges.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl_pulse.h"
#include "ctl_vectors.h"

static const ctl_pulse_kind_t kinds[3] = {CTL_PULSE_ZERO, CTL_PULSE_PART, CTL_PULSE_FULL};
static const int16_t zero_states[4] = {0, 077, 007, 070};

static bool same_voltage(int16_t a, int16_t b)
{
    const ctl_vsd_t *u = &ctl_vector_vsd[a];
    const ctl_vsd_t *w = &ctl_vector_vsd[b];
    return u->alpha == w->alpha && u->beta == w->beta && u->x == w->x && u->y == w->y;
}

/* A set at 000 or 111 in v: its voltage is the same at either. */
static bool has_idle_set(int16_t v)
{
    const int16_t abc = (int16_t)(v & 070);
    const int16_t def = (int16_t)(v & 007);
    return abc == 0 || abc == 070 || def == 0 || def == 007;
}

static int16_t transitions(ctl_pulse_kind_t kind, const ctl_pulse_t *p, int16_t before)
{
    return ctl_pulse_transitions(kind, p, before, 077);
}

/* The fewest transitions of any arrangement whose zero state is in zeros[0..count) and whose
 * active state is v or, with any_active, any state with v's voltage. */
static int16_t fewest_over(ctl_pulse_kind_t kind, int16_t v, int16_t before, const int16_t *zeros,
                           int16_t count, bool any_active)
{
    int16_t best = 0x7fff;
    int16_t z, a;
    for (z = 0; z < count; z++) {
        for (a = 0; a < 64; a++) {
            ctl_pulse_t p;
            int16_t n;
            const bool usable = (kind == CTL_PULSE_ZERO)
                                    ? a == zeros[z]
                                    : (a == v || (any_active && same_voltage(a, v)));
            if (!usable) {
                continue;
            }
            p.active = a;
            p.zero = zeros[z];
            n = transitions(kind, &p, before);
            best = (n < best) ? n : best;
        }
    }
    return best;
}

static void check_by_ones(ctl_pulse_kind_t kind, int16_t v, int16_t in_force, int16_t before)
{
    ctl_pulse_t p;
    const bool high = ctl_vector_ones(kind == CTL_PULSE_ZERO ? in_force : v) > 3;
    ctl_pulse_arrange(CTL_PULSE_BY_ONES, kind, v, in_force, before, &p);
    assert_int_equal(p.zero, high ? 077 : 0);
    assert_int_equal(p.active, kind == CTL_PULSE_ZERO ? p.zero : v);
}

static void check_fewest(ctl_pulse_kind_t kind, int16_t v, int16_t in_force, int16_t before)
{
    ctl_pulse_t p;
    ctl_pulse_t by_ones;
    ctl_pulse_arrange(CTL_PULSE_FEWEST_TRANSITIONS, kind, v, in_force, before, &p);
    ctl_pulse_arrange(CTL_PULSE_BY_ONES, kind, v, in_force, before, &by_ones);
    assert_true(p.zero == 0 || p.zero == 077);
    assert_int_equal(p.active, kind == CTL_PULSE_ZERO ? p.zero : v);
    assert_int_equal(transitions(kind, &p, before),
                     fewest_over(kind, v, before, zero_states, 2, false));
    if (transitions(kind, &by_ones, before) == transitions(kind, &p, before)) {
        assert_int_equal(p.zero, by_ones.zero);
    }
}

static void check_per_set(ctl_pulse_kind_t kind, int16_t v, int16_t in_force, int16_t before)
{
    ctl_pulse_t p;
    ctl_pulse_t whole;
    int16_t n;
    ctl_pulse_arrange(CTL_PULSE_FEWEST_PER_SET, kind, v, in_force, before, &p);
    ctl_pulse_arrange(CTL_PULSE_FEWEST_TRANSITIONS, kind, v, in_force, before, &whole);
    assert_true(p.zero == 0 || p.zero == 077 || p.zero == 007 || p.zero == 070);
    if (kind == CTL_PULSE_ZERO) {
        assert_int_equal(p.active, p.zero);
    } else {
        assert_true(same_voltage(p.active, v));
    }
    n = transitions(kind, &p, before);
    assert_int_equal(n, fewest_over(kind, v, before, zero_states, 4, true));
    if (transitions(kind, &whole, before) == n && (kind == CTL_PULSE_ZERO || !has_idle_set(v))) {
        /* a tie keeps u00 or u77 (with an idle set the sets' own zero states may do better) */
        assert_true(p.zero == 0 || p.zero == 077);
        if (kind == CTL_PULSE_PART) {
            assert_int_equal(p.zero, whole.zero);
        }
    }
}

static void test_every_pattern_over_every_case(void **state)
{
    int16_t k, v, in_force, before;
    (void)state;
    for (k = 0; k < 3; k++) {
        for (v = 0; v < 64; v++) {
            for (before = 0; before < 64; before++) {
                /* the vector in force only matters for zero commands */
                const int16_t last = (kinds[k] == CTL_PULSE_ZERO) ? 64 : 1;
                for (in_force = 0; in_force < last; in_force++) {
                    if (kinds[k] != CTL_PULSE_ZERO && (v == 0 || v == 077)) {
                        continue; /* u00 and u77 make zero commands */
                    }
                    check_by_ones(kinds[k], v, in_force, before);
                    check_fewest(kinds[k], v, in_force, before);
                    check_per_set(kinds[k], v, in_force, before);
                }
            }
        }
    }
}

/* The boundary state: the zero state for a zero command, the active state for full duty, and
 * for a partial duty each leg whose zero state is 1 at its active state. */
static void test_edges(void **state)
{
    const ctl_pulse_t p = {046, 070};
    (void)state;
    assert_int_equal(ctl_pulse_edges(CTL_PULSE_FULL, &p), 046);
    assert_int_equal(ctl_pulse_edges(CTL_PULSE_PART, &p), 040);
    assert_int_equal(ctl_pulse_edges(CTL_PULSE_ZERO, &p), 070);
}

/* The case the rule by ones gets wrong: after v = 110100 at the edges, v again (three
 * switches on) costs 6 legs with u00 at the edges (3 at the boundary, 6 inside: 9) and 6 with
 * v at the edges and u77 in the middle (0 at the boundary, 6 inside). */
static void test_repeat_of_a_vector_at_the_edges(void **state)
{
    ctl_pulse_t p;
    (void)state;
    ctl_pulse_arrange(CTL_PULSE_FEWEST_TRANSITIONS, CTL_PULSE_PART, 064, 064, 064, &p);
    assert_int_equal(p.zero, 077);
    assert_int_equal(transitions(CTL_PULSE_PART, &p, 064), 6);
    ctl_pulse_arrange(CTL_PULSE_BY_ONES, CTL_PULSE_PART, 064, 064, 064, &p);
    assert_int_equal(p.zero, 0);
    assert_int_equal(transitions(CTL_PULSE_PART, &p, 064), 9);
}

/* Per set, the same vector held period after period after it was at the edges (u77 in the
 * middle): ABC (110) stays at its edges with 111 in the middle, DEF (100) goes to the middle
 * with 000 at its edges, i.e. zero state u70, 5 transitions (6 with u77), then 4 a period (each
 * set switches one leg twice) against 6 with u00 or u77. From 000 at the edges u70 ties with
 * u00 (6), and the tie keeps u00. */
static void test_repeated_three_switch_vector_per_set(void **state)
{
    ctl_pulse_t p;
    int16_t edges = 064;
    int16_t period;
    (void)state;
    for (period = 0; period < 3; period++) {
        const int16_t before = edges;
        ctl_pulse_arrange(CTL_PULSE_FEWEST_PER_SET, CTL_PULSE_PART, 064, 064, before, &p);
        edges = ctl_pulse_edges(CTL_PULSE_PART, &p);
        assert_int_equal(p.zero, 070);
        assert_int_equal(edges, 060);
        assert_int_equal(transitions(CTL_PULSE_PART, &p, before), (period == 0) ? 5 : 4);
    }
    ctl_pulse_arrange(CTL_PULSE_FEWEST_TRANSITIONS, CTL_PULSE_PART, 064, 064, 064, &p);
    assert_int_equal(transitions(CTL_PULSE_PART, &p, 064), 6);
    ctl_pulse_arrange(CTL_PULSE_FEWEST_PER_SET, CTL_PULSE_PART, 064, 064, 0, &p);
    assert_int_equal(p.zero, 0);
    assert_int_equal(transitions(CTL_PULSE_PART, &p, 0), 6);
}

/* An idle set (000 or 111 in v) stays where it is: 100 000 after 000 111 at the edges keeps DEF
 * at 111, and the active state 100 111 applies the same voltage as 100 000. */
static void test_idle_set_stays(void **state)
{
    ctl_pulse_t p;
    (void)state;
    ctl_pulse_arrange(CTL_PULSE_FEWEST_PER_SET, CTL_PULSE_FULL, 040, 007, 007, &p);
    assert_int_equal(p.active, 047);
    assert_true(same_voltage(047, 040));
    assert_int_equal(transitions(CTL_PULSE_FULL, &p, 007), 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_pattern_over_every_case),
        cmocka_unit_test(test_edges),
        cmocka_unit_test(test_repeat_of_a_vector_at_the_edges),
        cmocka_unit_test(test_repeated_three_switch_vector_per_set),
        cmocka_unit_test(test_idle_set_stays),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
