/*
 * The Q24 range analysis (docs/range-analysis.md, ctl_range.h) held to its claims, in a build of
 * the core that counts every bounded result beyond CTL_RANGE_BOUND (CTL_RANGE_CHECK):
 *   - the voltage tables lie inside the analysis' vector bound;
 *   - for the machine at each edge of the admitted region (a parameter pushed until
 *     ctl_model_init refuses), every controller, healthy and with phase A, C or F open, computes
 * nothing beyond the bound over steps at the corners of the domain: currents beyond it (the clamp's
 *     work), the largest speed, the largest DC link, every command in force, both torque limits;
 *   - one step past each edge the set is refused as the model's (CTL_PARAM_MODEL), and the
 *     reference machine lies at least twice inside each edge.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>

#include <cmocka.h>

#include "ctl.h"
#include "ctl_range.h"
#include "ctl_vectors.h"
#include "ctl_vsd.h"
#include "test_rng.h"

uint32_t ctl_range_violations;

static double q(ctl_q x) { return (double)ctl_to_float(x); }

/* The counter sees a bounded result beyond the bound (else every test below passes by default). */
static void test_the_check_counts(void **state)
{
    (void)state;
    ctl_range_violations = 0u;
    (void)ctl_mul_bnd(CTL_Q(8.0), CTL_Q(8.0));
    assert_int_equal(ctl_range_violations, 0);
    (void)ctl_mul_bnd(CTL_Q(8.0), CTL_Q(8.5));
    (void)ctl_add_bnd(CTL_Q(-60.0), CTL_Q(-5.0));
    assert_int_equal(ctl_range_violations, 2);
}

static void test_voltage_tables_inside_the_vector_bound(void **state)
{
    int16_t k;
    (void)state;
    for (k = 0; k < CTL_VECTOR_COUNT; k++) {
        const ctl_vsd_t *v = &ctl_vector_vsd[k];
        assert_true(fabs(q(v->alpha)) + fabs(q(v->beta)) <= CTL_RANGE_VECTOR_SUM);
        assert_true(fabs(q(v->x)) + fabs(q(v->y)) <= CTL_RANGE_VECTOR_SUM);
    }
    for (k = 0; k < CTL_VV_COUNT; k++) {
        const ctl_vsd_t *v = &ctl_vv_vsd[k];
        assert_true(fabs(q(v->alpha)) + fabs(q(v->beta)) <= CTL_RANGE_VECTOR_SUM);
        assert_true(fabs(q(v->x)) + fabs(q(v->y)) <= CTL_RANGE_VECTOR_SUM);
    }
}

/* One parameter of the machine, scaled by s (s > 1 pushes it towards the analysis' edge). */
typedef struct {
    const char *name;
    void (*apply)(ctl_params_t *p, float s);
    ctl_param_error_t beyond; /* the refusal one step further out */
} edge_t;

static void longer_sample(ctl_params_t *p, float s) { p->sample_time_s *= s; }
static void smaller_ld(ctl_params_t *p, float s) { p->ld_h /= s; }
static void larger_lq(ctl_params_t *p, float s) { p->lq_h *= s; }
static void smaller_lxy(ctl_params_t *p, float s) { p->l_xy_h /= s; }
static void larger_psi_f(ctl_params_t *p, float s) { p->pm_flux_wb *= s; }
static void larger_l(ctl_params_t *p, float s)
{
    p->ld_h *= s;
    p->lq_h *= s;
}

/* The magnet flux reaches its own range (10 Wb) before the analysis' bound. */
static const edge_t edges[] = {
    {"sample time", longer_sample, CTL_PARAM_MODEL},
    {"L_d down (saliency)", smaller_ld, CTL_PARAM_MODEL},
    {"L_q up", larger_lq, CTL_PARAM_MODEL},
    {"L_xy down", smaller_lxy, CTL_PARAM_MODEL},
    {"magnet flux up", larger_psi_f, CTL_PARAM_PM_FLUX},
    {"L_d, L_q up", larger_l, CTL_PARAM_MODEL},
};

/* The largest scale the core admits (bisection on a log scale), the set there in *at. */
static float admitted_edge(const edge_t *e, ctl_params_t *at, ctl_param_error_t *beyond)
{
    float lo = 1.0f;
    float hi = 1.0f;
    int16_t k;
    ctl_params_t p;
    do {
        hi *= 2.0f;
        ctl_params_default(&p);
        e->apply(&p, hi);
    } while (ctl_params_check(&p) == CTL_PARAM_OK && hi < 1e6f);
    *beyond = ctl_params_check(&p);
    for (k = 0; k < 40; k++) {
        const float mid = 0.5f * (lo + hi);
        ctl_params_default(&p);
        e->apply(&p, mid);
        if (ctl_params_check(&p) == CTL_PARAM_OK) {
            lo = mid;
        } else {
            hi = mid;
            *beyond = ctl_params_check(&p);
        }
    }
    ctl_params_default(at);
    e->apply(at, lo);
    return lo;
}

/* Phase currents whose VSD is (a, b, x, y). */
static void phases_of(double a, double b, double x, double y, ctl_q phase[6])
{
    ctl_vsd_t v;
    v.alpha = ctl_from_float((float)a);
    v.beta = ctl_from_float((float)b);
    v.x = ctl_from_float((float)x);
    v.y = ctl_from_float((float)y);
    ctl_vsd_inverse(&v, phase);
}

/* A corner value of one VSD current: at the bound, beyond it, zero, or anywhere between. */
static double corner(test_rng_t *rng)
{
    static const double corners[] = {CTL_RANGE_CURRENT, -CTL_RANGE_CURRENT, 1.5 * CTL_RANGE_CURRENT,
                                     -20.0, 0.0};
    const uint32_t pick = test_rng_u32(rng) % 6u;
    return (pick < 5u) ? corners[pick] : test_rng_range(rng, -CTL_RANGE_CURRENT, CTL_RANGE_CURRENT);
}

/* Steps of one controller on set p (open phase or not) at the domain's corners. */
static void run_corners(const ctl_params_t *p, uint32_t seed)
{
    ctl_t c;
    ctl_meas_t m;
    ctl_cmd_t cmd;
    test_rng_t rng;
    int32_t k;
    rng.state = seed;
    assert_true(ctl_init(&c, p));
    ctl_set_loop_mode(&c, CTL_LOOP_TORQUE);
    for (k = 0; k < 3000; k++) {
        const double w_max = q(ctl_config(&c)->model.omega_max);
        const uint32_t speed = test_rng_u32(&rng) % 4u;
        phases_of(corner(&rng), corner(&rng), corner(&rng), corner(&rng), m.i_phase);
        m.vdc = ctl_from_float((test_rng_u32(&rng) % 2u) ? (float)CTL_RANGE_VDC : 3.0f);
        m.theta_e = ctl_from_float((float)test_rng_range(&rng, 0.0, 1.0));
        m.omega_e = ctl_from_float((float)((speed == 0u)   ? w_max
                                           : (speed == 1u) ? -w_max
                                           : (speed == 2u) ? 10.0
                                                           : 0.0));
        ctl_set_torque_ref(&c, ctl_from_float((test_rng_u32(&rng) % 2u) ? 100.0f : -100.0f));
        ctl_step(&c, &m, &cmd);
    }
}

static void test_edges_compute_inside_the_bound(void **state)
{
    size_t e;
    int16_t controller;
    (void)state;
    for (e = 0; e < sizeof edges / sizeof edges[0]; e++) {
        ctl_params_t p;
        ctl_param_error_t beyond = CTL_PARAM_OK;
        const float s = admitted_edge(&edges[e], &p, &beyond);
        printf("%-20s edge at x %.4g, refused beyond as %s\n", edges[e].name, (double)s,
               ctl_param_error_text(beyond));
        /* the edge is the model's (or the parameter's own range), the reference machine well
         * inside it (at least twice away) */
        assert_true(s >= 2.0f);
        assert_int_equal(beyond, edges[e].beyond);
        for (controller = 0; controller < CTL_CONTROLLER_COUNT; controller++) {
            /* healthy, and each of phases A, C and F open (the two sets' first, middle, last) */
            static const int16_t opens[] = {CTL_POSTFAULT_NO_LEG, 0, 2, 5};
            size_t o;
            for (o = 0; o < sizeof opens / sizeof opens[0]; o++) {
                const int16_t open = opens[o];
                ctl_params_t run = p;
                run.controller = (ctl_controller_t)controller;
                run.open_phase = open;
                ctl_range_violations = 0u;
                run_corners(&run, (uint32_t)(1000u + (uint32_t)e * 10u + (uint32_t)controller));
                if (ctl_range_violations != 0u) {
                    printf("  controller %d, open phase %d: %lu bounded results beyond %d\n",
                           controller, open, (unsigned long)ctl_range_violations, CTL_RANGE_BOUND);
                }
                assert_int_equal(ctl_range_violations, 0);
            }
        }
    }
}

/* A set with a long period and a small L_d (two edges at once): its k+1 and k+2 currents exceed
 * the bound although every flux stays below it; refused as the model's. */
static void test_joint_edge_refused(void **state)
{
    ctl_params_t p;
    (void)state;
    ctl_params_default(&p);
    p.resistance_ohm = 0.5f;
    p.ld_h = 0.002f;
    p.lq_h = 0.006f;
    p.l_xy_h = 0.01f;
    p.sample_time_s = 1e-3f;
    assert_int_equal(ctl_params_check(&p), CTL_PARAM_MODEL);
}

/* Random machines drawn across the parameter ranges (log-uniform), every one the core admits run
 * at the domain's corners: the joint extremes the one-at-a-time edges above miss. */
static void test_random_admitted_machines(void **state)
{
    test_rng_t rng;
    int16_t k;
    int16_t admitted = 0;
    (void)state;
    rng.state = 28u;
    for (k = 0; k < 1000; k++) {
        ctl_params_t p;
        ctl_params_default(&p);
        p.resistance_ohm = (float)exp(test_rng_range(&rng, log(0.01), log(20.0)));
        p.ld_h = (float)exp(test_rng_range(&rng, log(5e-4), log(0.5)));
        p.lq_h = (float)exp(test_rng_range(&rng, log(5e-4), log(0.5)));
        p.l_xy_h = (float)exp(test_rng_range(&rng, log(5e-4), log(0.5)));
        p.pm_flux_wb = (float)exp(test_rng_range(&rng, log(0.01), log(2.0)));
        p.sample_time_s = (float)exp(test_rng_range(&rng, log(5e-5), log(2e-3)));
        p.pole_pairs = (int16_t)(1 + (int16_t)(test_rng_u32(&rng) % 12u));
        if (ctl_params_check(&p) != CTL_PARAM_OK) {
            continue;
        }
        admitted++;
        for (p.open_phase = CTL_POSTFAULT_NO_LEG; p.open_phase <= 2;
             p.open_phase = (int16_t)(p.open_phase + 3)) {
            ctl_range_violations = 0u;
            p.controller = (k % 2 == 0) ? CTL_CONTROLLER_DDC : CTL_CONTROLLER_MPTC49;
            run_corners(&p, (uint32_t)(5000 + k));
            assert_int_equal(ctl_range_violations, 0);
        }
    }
    printf("%d of 1000 random machines admitted, each run at the corners\n", admitted);
    assert_true(admitted >= 50);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_the_check_counts),
        cmocka_unit_test(test_voltage_tables_inside_the_vector_bound),
        cmocka_unit_test(test_edges_compute_inside_the_bound),
        cmocka_unit_test(test_joint_edge_refused),
        cmocka_unit_test(test_random_admitted_machines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
