/* The candidate searches pick the right candidate on hand-built cases. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "ctl_ddc.h"
#include "ctl_mptc.h"
#include "ctl_tables.h"
#include "ctl_vectors.h"
#include "ctl_vvmptc.h"
#include "test_rng.h"
#include "test_support.h"
#include "ctl_qmath.h"

static ctl_model_t model;

static int setup(void **state)
{
    (void)state;
    return ctl_model_init(&model, 2.0f, 0.035f, 0.055f, 0.01f, 0.225f, 3, 1e-4f) ? 0 : -1;
}

/* A horizon at rotor angle 0 with a plausible free response at rated load. */
static ctl_horizon_t horizon(void)
{
    ctl_horizon_t h;
    h.model = &model;
    h.id2_free = CTL_Q(-0.08);
    h.iq2_free = CTL_Q(0.30);
    h.sin1 = CTL_Q(0.0);
    h.cos1 = CTL_Q(1.0);
    h.vdc = CTL_Q(1.0);
    h.torque_ref = CTL_Q(0.0);
    h.flux_ref = CTL_Q(0.45);
    h.lambda = CTL_Q(0.0);
    ctl_horizon_prepare(&h);
    return h;
}

/* Predicted k+2 torque and flux of a switching state held for duty d. */
static void predicted(const ctl_horizon_t *h, int16_t v, ctl_q d, ctl_q *torque, ctl_q *flux)
{
    ctl_q did;
    ctl_q diq;
    ctl_horizon_forced(h, &ctl_vector_vsd[v], &did, &diq);
    (void)ctl_horizon_cost(h, ctl_add(h->id2_free, ctl_mul(d, did)),
                           ctl_add(h->iq2_free, ctl_mul(d, diq)), torque, flux);
}

static void test_mptc_picks_the_vector_that_meets_the_torque_reference(void **state)
{
    static const int16_t targets[] = {044, 066, 024, 011, 052, 035};
    int16_t i;
    (void)state;
    for (i = 0; i < (int16_t)(sizeof targets / sizeof targets[0]); i++) {
        ctl_horizon_t h = horizon();
        ctl_choice_t c;
        ctl_q flux;
        predicted(&h, targets[i], CTL_Q(1.0), &h.torque_ref, &flux);
        ctl_mptc_select(&h, ctl_mptc49_vectors, CTL_MPTC49_CANDIDATES, 0, &c);
        assert_int_equal(c.vector, targets[i]);
        assert_near((double)ctl_to_float(c.cost), 0.0, 1e-5);
        assert_int_equal(c.candidates, 49);
    }
}

/* With a dominant flux weight the flux term decides: a reference equal to one candidate's
 * predicted flux and torque selects that candidate. */
static void test_mptc_flux_weight_selects_flux_match(void **state)
{
    ctl_horizon_t h = horizon();
    ctl_choice_t c;
    (void)state;
    predicted(&h, 026, CTL_Q(1.0), &h.torque_ref, &h.flux_ref);
    h.lambda = CTL_Q(50.0);
    ctl_mptc_select(&h, ctl_mptc13_vectors, CTL_MPTC13_CANDIDATES, 0, &c);
    assert_int_equal(c.vector, 026);
}

/* A random horizon for the pruning tests: angle, free response, references and lambda (up to
 * 200 N m/Wb in per unit and beyond), drawn in this order. */
static ctl_horizon_t random_horizon(test_rng_t *rng)
{
    ctl_horizon_t h = horizon();
    const double angle = test_rng_range(rng, 0.0, 1.0);
    ctl_sincos_pu(ctl_from_float((float)angle), &h.sin1, &h.cos1);
    h.id2_free = ctl_from_float((float)test_rng_range(rng, -0.6, 0.6));
    h.iq2_free = ctl_from_float((float)test_rng_range(rng, -0.6, 0.6));
    h.torque_ref = ctl_from_float((float)test_rng_range(rng, -1.5, 1.5));
    h.flux_ref = ctl_from_float((float)test_rng_range(rng, 0.3, 0.6));
    h.lambda = ctl_from_float((float)test_rng_range(rng, 0.0, 20.0));
    ctl_horizon_prepare(&h);
    return h;
}

/* The full cost of holding voltage v for the period, and its predicted k+2 torque and flux. */
static ctl_q full_cost(const ctl_horizon_t *h, const ctl_vsd_t *v, ctl_q *torque, ctl_q *flux)
{
    ctl_q did;
    ctl_q diq;
    ctl_horizon_forced(h, v, &did, &diq);
    return ctl_horizon_cost(h, ctl_add(h->id2_free, did), ctl_add(h->iq2_free, diq), torque, flux);
}

/* The exhaustive search skips a candidate's flux root once its torque error alone reaches the
 * best cost: over random horizons (angle, free response, references, lambda up to 200 N m/Wb in
 * per unit and beyond) it picks the candidate, cost, torque and flux that the full cost of every
 * candidate picks. */
static void test_mptc_pruning_keeps_the_choice(void **state)
{
    test_rng_t rng = {12345u};
    int32_t n;
    (void)state;
    for (n = 0; n < 20000; n++) {
        const ctl_horizon_t h = random_horizon(&rng);
        ctl_choice_t c;
        ctl_q best = CTL_Q_MAX;
        int16_t best_v = 0;
        int16_t i;
        const bool all = (n % 2) == 0;
        const int16_t *cand = all ? ctl_mptc49_vectors : ctl_mptc13_vectors;
        const int16_t count = all ? CTL_MPTC49_CANDIDATES : CTL_MPTC13_CANDIDATES;
        for (i = 0; i < count; i++) {
            ctl_q torque;
            ctl_q flux;
            const ctl_q cost = full_cost(&h, &ctl_vector_vsd[cand[i]], &torque, &flux);
            if (cost < best) {
                best = cost;
                best_v = cand[i];
            }
        }
        ctl_mptc_select(&h, cand, count, 0, &c);
        assert_int_equal(c.vector, best_v);
        assert_true(c.cost == best);
    }
}

/* Predicted k+2 torque and flux of virtual vector k held for the period. */
static void predicted_virtual(const ctl_horizon_t *h, int16_t k, ctl_q *torque, ctl_q *flux)
{
    (void)full_cost(h, &ctl_vv_vsd[k], torque, flux);
}

/* VV-MPTC on simple states: a torque reference equal to one virtual vector's predicted torque
 * picks that virtual vector (its large state, duty 1, 13 candidates); a reference equal to the
 * zero vector's picks the zero vector, as u77 after a state with more upper switches on. */
static void test_vvmptc_picks_the_virtual_vector_that_meets_the_torque_reference(void **state)
{
    int16_t k;
    (void)state;
    for (k = 0; k < CTL_VV_COUNT; k++) {
        ctl_horizon_t h = horizon();
        ctl_choice_t c;
        ctl_q flux;
        predicted_virtual(&h, k, &h.torque_ref, &flux);
        assert_int_equal(ctl_vvmptc_select(&h, 0, &c), k);
        assert_int_equal(c.vector, ctl_vv_states[k][0]);
        assert_true(c.duty == CTL_Q(1.0));
        assert_int_equal(c.candidates, CTL_VVMPTC_CANDIDATES);
        assert_near((double)ctl_to_float(c.cost), 0.0, 1e-5);
    }
    {
        ctl_horizon_t h = horizon();
        ctl_choice_t c;
        ctl_q flux;
        predicted(&h, 0, CTL_Q(0.0), &h.torque_ref, &flux);
        assert_int_equal(ctl_vvmptc_select(&h, 066, &c), CTL_VV_NONE);
        assert_int_equal(c.vector, 077);
        assert_int_equal(ctl_vvmptc_select(&h, 044, &c), CTL_VV_NONE);
        assert_int_equal(c.vector, 0);
    }
}

/* With the pruning VV-MPTC picks the candidate, and the cost, that the full cost of all 13
 * picks, over random horizons (as the MPTC test above). */
static void test_vvmptc_pruning_keeps_the_choice(void **state)
{
    test_rng_t rng = {54321u};
    int32_t n;
    (void)state;
    for (n = 0; n < 20000; n++) {
        const ctl_horizon_t h = random_horizon(&rng);
        ctl_choice_t c;
        ctl_q torque;
        ctl_q flux;
        ctl_q best = ctl_horizon_cost(&h, h.id2_free, h.iq2_free, &torque, &flux);
        int16_t best_k = CTL_VV_NONE;
        int16_t k;
        for (k = 0; k < CTL_VV_COUNT; k++) {
            const ctl_q cost = full_cost(&h, &ctl_vv_vsd[k], &torque, &flux);
            if (cost < best) {
                best = cost;
                best_k = k;
            }
        }
        assert_int_equal(ctl_vvmptc_select(&h, 0, &c), best_k);
        assert_true(c.cost == best);
    }
}

/* The zero candidate is realised as u77 when the state in force has more upper switches on. */
static void test_mptc_zero_vector_follows_state_in_force(void **state)
{
    ctl_horizon_t h = horizon();
    ctl_choice_t c;
    ctl_q flux;
    (void)state;
    predicted(&h, 0, CTL_Q(0.0), &h.torque_ref, &flux);
    ctl_mptc_select(&h, ctl_mptc13_vectors, CTL_MPTC13_CANDIDATES, 066, &c);
    assert_int_equal(c.vector, 077);
    ctl_mptc_select(&h, ctl_mptc13_vectors, CTL_MPTC13_CANDIDATES, 044, &c);
    assert_int_equal(c.vector, 0);
}

static ctl_ddc_config_t paper_flux_error; /* built by main (the paper's six levels) */
static ctl_ddc_config_t paper_xy_table;
static ctl_ddc_config_t guarded;

/* Flux at k+1 in sector I (angle 0), x-y flux in x-y sector 0, |psi| below the reference:
 * table 1 row 0 candidates; the duty whose torque meets Tref is chosen. */
static void test_ddc_picks_duty_that_meets_torque(void **state)
{
    const ctl_q duties[] = {CTL_Q(0.2), CTL_Q(0.4), CTL_Q(0.6), CTL_Q(0.8), CTL_Q(1.0)};
    ctl_ddc_flux_t f = {CTL_Q(0.40), CTL_Q(0.0), CTL_Q(0.16), CTL_Q(0.01), CTL_Q(0.001)};
    int16_t i;
    (void)state;
    for (i = 0; i < 5; i++) {
        ctl_horizon_t h = horizon();
        ctl_choice_t c;
        ctl_q flux;
        const int16_t v = ctl_ddc_table2_flux[0][0][0][0];
        predicted(&h, v, duties[i], &h.torque_ref, &flux);
        ctl_ddc_select(&h, &f, &paper_flux_error, 0, &c);
        assert_int_equal(c.flux_sector, 0);
        assert_int_equal(c.xy_sector, 0);
        assert_false(c.braking);
        assert_int_equal(c.vector, v);
        assert_near((double)ctl_to_float(c.duty), (double)ctl_to_float(duties[i]), 1e-6);
        assert_int_equal(c.candidates, 6);
    }
}

/* Flux-error reading: |psi| above the reference selects the flux-lowering direction (105 deg
 * in sector I), the pair u62 (x-y 345 deg) / u26 (x-y 165 deg); with psi_xy at 100 deg only
 * u62 opposes it. Below the reference the flux-raising pair u24 (x-y 195 deg) / u66 (x-y
 * 15 deg) applies, and u24 opposes psi_xy. */
static void test_ddc_flux_error_reading_lowers_flux_and_xy(void **state)
{
    ctl_horizon_t h = horizon();
    ctl_choice_t c;
    /* psi_xy at 100 deg: cos 100 = -0.1736, sin 100 = 0.9848 */
    ctl_ddc_flux_t f = {CTL_Q(0.50), CTL_Q(0.0), CTL_Q(0.25), CTL_Q(-0.01736), CTL_Q(0.09848)};
    (void)state;
    h.torque_ref = CTL_Q(2.0); /* far above: full duty */
    ctl_ddc_select(&h, &f, &paper_flux_error, 0, &c);
    assert_int_equal(c.vector, 062);
    f.psi_mag_sq = CTL_Q(0.09); /* below the reference: flux-raising pair u24 / u66 */
    ctl_ddc_select(&h, &f, &paper_flux_error, 0, &c);
    assert_int_equal(c.vector, 024);
}

/* The x-y-table reading follows the paper's Table 2 in sector I. */
static void test_ddc_xy_reading_follows_paper_table2(void **state)
{
    static const int16_t expected[4] = {024, 062, 066, 026};
    int16_t quadrant;
    (void)state;
    for (quadrant = 0; quadrant < 4; quadrant++) {
        const double ang = (45.0 + 90.0 * quadrant) * TEST_PI / 180.0;
        ctl_ddc_flux_t f = {CTL_Q(0.45), CTL_Q(0.0), CTL_Q(0.2025),
                            ctl_from_float((float)(0.01 * cos(ang))),
                            ctl_from_float((float)(0.01 * sin(ang)))};
        ctl_horizon_t h = horizon();
        ctl_choice_t c;
        h.torque_ref = CTL_Q(2.0);
        ctl_ddc_select(&h, &f, &paper_xy_table, 0, &c);
        assert_int_equal(c.vector, expected[quadrant]);
    }
}

/* When the zero vector alone leaves torque above the reference, the torque-lowering half of
 * table 1 is used and a large drop picks full duty of a lowering vector. */
static void test_ddc_braking_half(void **state)
{
    ctl_horizon_t h = horizon();
    ctl_choice_t c;
    ctl_q t0;
    ctl_q flux;
    ctl_ddc_flux_t f = {CTL_Q(0.45), CTL_Q(0.0), CTL_Q(0.2025), CTL_Q(0.01), CTL_Q(0.001)};
    int16_t k;
    bool in_lower_half = false;
    (void)state;
    predicted(&h, 0, CTL_Q(0.0), &t0, &flux);
    h.torque_ref = ctl_sub(t0, CTL_Q(1.0));
    ctl_ddc_select(&h, &f, &paper_flux_error, 0, &c);
    assert_true(c.braking);
    for (k = 0; k < 4; k++) {
        in_lower_half = in_lower_half || (ctl_ddc_table1[0][1][k] == c.vector);
    }
    assert_true(in_lower_half);
    assert_near((double)ctl_to_float(c.duty), 1.0, 1e-6);
    assert_true(c.torque < t0);
}

/* Duty 0 (the zero vector) wins when it already meets the reference exactly. */
static void test_ddc_zero_duty(void **state)
{
    ctl_horizon_t h = horizon();
    ctl_choice_t c;
    ctl_q flux;
    ctl_ddc_flux_t f = {CTL_Q(0.45), CTL_Q(0.0), CTL_Q(0.2025), CTL_Q(0.01), CTL_Q(0.001)};
    (void)state;
    predicted(&h, 0, CTL_Q(0.0), &h.torque_ref, &flux);
    ctl_ddc_select(&h, &f, &paper_flux_error, 0, &c);
    assert_near((double)ctl_to_float(c.duty), 0.0, 1e-9);
    assert_false(c.braking);
}

/* The heavy-flux-weighting trap and the torque guard: with a flux reference met by the zero
 * vector and a torque reference met by full duty, a large lambda makes the paper's search
 * give up torque for flux; the guard keeps the duty within one level of the torque-best one
 * (full duty here), so the torque error stays within one duty step. */
static void test_torque_guard(void **state)
{
    ctl_horizon_t h = horizon();
    ctl_choice_t paper;
    ctl_choice_t guard;
    ctl_q t0;
    ctl_q t1;
    ctl_q psi1;
    ctl_ddc_flux_t f = {CTL_Q(0.40), CTL_Q(0.0), CTL_Q(0.16), CTL_Q(0.01), CTL_Q(0.001)};
    const int16_t v = ctl_ddc_table2_flux[0][0][0][0];
    (void)state;
    predicted(&h, v, CTL_Q(0.0), &t0, &h.flux_ref);
    predicted(&h, v, CTL_Q(1.0), &t1, &psi1);
    h.torque_ref = t1;
    h.lambda = CTL_Q(20.0);
    ctl_horizon_prepare(&h);
    ctl_ddc_select(&h, &f, &paper_flux_error, 0, &paper);
    ctl_ddc_select(&h, &f, &guarded, 0, &guard);
    assert_true(paper.duty < CTL_Q(0.8)); /* the trap: torque given up for flux */
    assert_true(guard.duty >= CTL_Q(0.8));
    assert_true(ctl_abs(ctl_sub(guard.torque, h.torque_ref)) <=
                ctl_add(ctl_div(ctl_abs(ctl_sub(t1, t0)), CTL_Q(5.0)), CTL_Q(1e-6)));
    /* with no flux weight the guard changes nothing */
    h.lambda = CTL_Q(0.0);
    ctl_ddc_select(&h, &f, &paper_flux_error, 0, &paper);
    ctl_ddc_select(&h, &f, &guarded, 0, &guard);
    assert_int_equal(paper.duty, guard.duty);
}

/* The flux tie band (docs/improvements.md): with a flux reference met by duty 0.6 and a torque
 * reference near duty 0.8, the guard alone lets a large lambda take 0.6 (one level away); with
 * the band of a quarter level the flux term only decides when the two levels' torque errors
 * differ by less than that, i.e. near the midpoint between them. */
static void test_flux_tie_band(void **state)
{
    static const ctl_q fraction[2] = {CTL_Q(0.1), CTL_Q(0.45)}; /* of the step, from 0.8 down */
    ctl_ddc_config_t tie;
    ctl_ddc_flux_t f = {CTL_Q(0.40), CTL_Q(0.0), CTL_Q(0.16), CTL_Q(0.01), CTL_Q(0.001)};
    const int16_t v = ctl_ddc_table2_flux[0][0][0][0];
    int16_t i;
    (void)state;
    ctl_ddc_config_init(&tie, 0, 6, true, 0.25f);
    for (i = 0; i < 2; i++) {
        ctl_horizon_t h = horizon();
        ctl_choice_t guard;
        ctl_choice_t banded;
        ctl_q t6;
        ctl_q t8;
        ctl_q psi8;
        predicted(&h, v, CTL_Q(0.6), &t6, &h.flux_ref);
        predicted(&h, v, CTL_Q(0.8), &t8, &psi8);
        h.torque_ref = ctl_sub(t8, ctl_mul(fraction[i], ctl_sub(t8, t6)));
        h.lambda = CTL_Q(50.0);
        ctl_ddc_select(&h, &f, &guarded, 0, &guard);
        ctl_ddc_select(&h, &f, &tie, 0, &banded);
        assert_int_equal(guard.duty, tie.levels[2]); /* 0.6: the flux term moves it a level */
        /* 0.1 step from 0.8: the errors differ by 0.8 step, beyond the band; 0.45: by 0.1 */
        assert_int_equal(banded.duty, (i == 0) ? tie.levels[1] : tie.levels[2]);
    }
}

int main(void)
{
    ctl_ddc_config_init(&paper_flux_error, 0, 6, false, 0.0f);
    ctl_ddc_config_init(&paper_xy_table, 1, 6, false, 0.0f);
    ctl_ddc_config_init(&guarded, 0, 6, true, 0.0f);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mptc_picks_the_vector_that_meets_the_torque_reference),
        cmocka_unit_test(test_mptc_flux_weight_selects_flux_match),
        cmocka_unit_test(test_mptc_pruning_keeps_the_choice),
        cmocka_unit_test(test_mptc_zero_vector_follows_state_in_force),
        cmocka_unit_test(test_ddc_picks_duty_that_meets_torque),
        cmocka_unit_test(test_ddc_flux_error_reading_lowers_flux_and_xy),
        cmocka_unit_test(test_ddc_xy_reading_follows_paper_table2),
        cmocka_unit_test(test_ddc_braking_half),
        cmocka_unit_test(test_flux_tie_band),
        cmocka_unit_test(test_ddc_zero_duty),
        cmocka_unit_test(test_torque_guard),
        cmocka_unit_test(test_vvmptc_picks_the_virtual_vector_that_meets_the_torque_reference),
        cmocka_unit_test(test_vvmptc_pruning_keeps_the_choice),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
