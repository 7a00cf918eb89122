/*
 * Unit tests of the vector space decomposition (ctl_vsd.h) and of the 64 inverter
 * voltage vectors (ctl_vectors.h), built against ctl_fixed and ctl_float.
 *
 * References are computed here in double from the defining formulas of the method
 * notes (§2 VSD matrix and phase-voltage formula, §3 vector groups and examples).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "test_support.h"

#include <math.h>

#include "ctl_constants.h"
#include "ctl_q.h"
#include "ctl_qmath.h"
#include "ctl_tables.h"
#include "ctl_vectors.h"
#include "ctl_vsd.h"
#include "q24_exact.h" /* qd, dq: every dq here is of |x| <= 3, never saturated */
#include "test_rng.h"
#include "vsd_reference.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* ---------------------------------------------------------------- helpers */

/* Tolerance of the VSD transforms on per-unit values of magnitude up to ~3. */
#define VSD_TOL 2.0e-6
/* One Q24 LSB: the constant tables are exact to half of it in both arithmetics. */
#define TABLE_TOL Q24_LSB

static test_rng_t rng = {0x2545F491u};
static double rng_range(double lo, double hi) { return test_rng_range(&rng, lo, hi); }

/* Angle in [0, 360) degrees. */
static double ang_deg(double yy, double xx)
{
    double a = atan2(yy, xx) / DEG;
    if (a < 0.0) {
        a += 360.0;
    }
    if (a >= 360.0) {
        a -= 360.0;
    }
    return a;
}

/* |a - b| folded into [0, 180] degrees. */
static double ang_dist(double a, double b)
{
    double d = fmod(fabs(a - b), 360.0);
    return (d > 180.0) ? 360.0 - d : d;
}

static vsd_d table_vsd(int32_t v)
{
    const ctl_vsd_t *t = &ctl_vector_vsd[v];
    vsd_d r;
    r.alpha = qd(t->alpha);
    r.beta = qd(t->beta);
    r.x = qd(t->x);
    r.y = qd(t->y);
    return r;
}

static double vsd_dist(vsd_d a, vsd_d b)
{
    return fabs(a.alpha - b.alpha) + fabs(a.beta - b.beta) + fabs(a.x - b.x) + fabs(a.y - b.y);
}

/* Closed-form group magnitudes (alpha-beta), per unit of Vdc. */
#define MAG_G4 (2.0 / 3.0 * 0.96592582628906829) /* 2/3 cos 15 = 0.6440 */
#define MAG_G3 (1.41421356237309505 / 3.0)       /* sqrt(2)/3  = 0.4714 */
#define MAG_G2 (1.0 / 3.0)                       /*              0.3333 */
#define MAG_G1 (2.0 / 3.0 * 0.25881904510252076) /* 2/3 sin 15 = 0.1725 */

/* Group 0..4 by |u_ab| (G4 largest), -1 if none matches. */
static int32_t group_of(vsd_d u)
{
    const double m = vsd_ref_mag_ab(u);
    if (fabs(m - MAG_G4) < 1e-6) {
        return 4;
    }
    if (fabs(m - MAG_G3) < 1e-6) {
        return 3;
    }
    if (fabs(m - MAG_G2) < 1e-6) {
        return 2;
    }
    if (fabs(m - MAG_G1) < 1e-6) {
        return 1;
    }
    if (m < 1e-6) {
        return 0;
    }
    return -1;
}

/* --------------------------------------------------------------- the VSD */

static void random_phases(double p[6], double amp)
{
    /* Each three-phase set sums to zero (no zero-sequence component). */
    p[0] = rng_range(-amp, amp);
    p[1] = rng_range(-amp, amp);
    p[2] = -p[0] - p[1];
    p[3] = rng_range(-amp, amp);
    p[4] = rng_range(-amp, amp);
    p[5] = -p[3] - p[4];
}

static void test_vsd_forward_matches_formula(void **state)
{
    double max_err = 0.0;
    int32_t i;
    (void)state;
    for (i = 0; i < 20000; i++) {
        double p[6];
        ctl_q pq[6];
        double pin[6];
        vsd_d want;
        ctl_vsd_t got;
        int32_t k;
        /* Arbitrary six phase values, zero sequence included: it must not leak. */
        for (k = 0; k < 6; k++) {
            p[k] = rng_range(-3.0, 3.0);
            pq[k] = dq(p[k]);
            pin[k] = qd(pq[k]);
        }
        want = vsd_ref_forward(pin);
        ctl_vsd_forward(pq, &got);
        expect_close(qd(got.alpha), want.alpha, VSD_TOL, "forward alpha", pin[0]);
        expect_close(qd(got.beta), want.beta, VSD_TOL, "forward beta", pin[0]);
        expect_close(qd(got.x), want.x, VSD_TOL, "forward x", pin[0]);
        expect_close(qd(got.y), want.y, VSD_TOL, "forward y", pin[0]);
        max_err = fmax(max_err,
                       fmax(fmax(fabs(qd(got.alpha) - want.alpha), fabs(qd(got.beta) - want.beta)),
                            fmax(fabs(qd(got.x) - want.x), fabs(qd(got.y) - want.y))));
    }
    print_message("ctl_vsd_forward: max component err %.3g (tol %.1g)\n", max_err, VSD_TOL);
}

/* Phase values at the ends of Q24's range (fixed point): each row computed exactly and ended
 * once, saturated to Q24's range by ctl_vsd_forward and held to +-CTL_RANGE_CURRENT by the steps'
 * ctl_vsd_forward_in_range; no intermediate sum saturates on its own (i_B + i_C at the top of
 * the range would, and halve a's share of it). Float has no range to end at. */
/* The constants' half-LSB error times phase values up to 2^7 per unit, over three terms. */
#define VSD_END_TOL 4.0e-5
static void test_vsd_rows_end_once(void **state)
{
#if CTL_MATH_FLOAT
    (void)state;
#else
    static const ctl_q ends[4] = {INT32_MAX, INT32_MIN, INT32_MAX / 2, 0};
    const double q24_max = (double)INT32_MAX / 16777216.0;
    const double held = (double)CTL_RANGE_CURRENT;
    int32_t n;
    (void)state;
    for (n = 0; n < 4096; n++) { /* every phase at each of the four ends: 4^6 */
        ctl_q pq[6];
        double pin[6];
        vsd_d want;
        ctl_vsd_t sat;
        ctl_vsd_t in_range;
        int32_t k;
        int32_t code = n;
        for (k = 0; k < 6; k++) {
            pq[k] = ends[code % 4];
            pin[k] = qd(pq[k]);
            code /= 4;
        }
        want = vsd_ref_forward(pin);
        ctl_vsd_forward(pq, &sat);
        ctl_vsd_forward_in_range(pq, &in_range);
        expect_close(qd(sat.alpha), fmax(-q24_max, fmin(q24_max, want.alpha)), VSD_END_TOL,
                     "saturated alpha", pin[1]);
        expect_close(qd(sat.x), fmax(-q24_max, fmin(q24_max, want.x)), VSD_END_TOL, "saturated x",
                     pin[1]);
        expect_close(qd(sat.beta), fmax(-q24_max, fmin(q24_max, want.beta)), VSD_END_TOL,
                     "saturated beta", pin[1]);
        expect_close(qd(sat.y), fmax(-q24_max, fmin(q24_max, want.y)), VSD_END_TOL, "saturated y",
                     pin[1]);
        expect_close(qd(in_range.alpha), fmax(-held, fmin(held, want.alpha)), VSD_END_TOL,
                     "held alpha", pin[1]);
        expect_close(qd(in_range.y), fmax(-held, fmin(held, want.y)), VSD_END_TOL, "held y",
                     pin[1]);
    }
#endif
}

static void test_vsd_round_trip(void **state)
{
    double max_err = 0.0;
    int32_t i;
    (void)state;
    for (i = 0; i < 20000; i++) {
        double p[6];
        ctl_q pq[6];
        ctl_q back[6];
        ctl_vsd_t v;
        ctl_vsd_t v2;
        int32_t k;
        random_phases(p, 1.5);
        for (k = 0; k < 6; k++) {
            pq[k] = dq(p[k]);
        }
        ctl_vsd_forward(pq, &v);
        ctl_vsd_inverse(&v, back);
        for (k = 0; k < 6; k++) {
            const double e = fabs(qd(back[k]) - qd(pq[k]));
            max_err = fmax(max_err, e);
            expect_close(qd(back[k]), qd(pq[k]), VSD_TOL, "forward->inverse phase", p[k]);
        }
        /* The inverse produces zero-sequence-free sets. */
        expect_close(qd(back[0]) + qd(back[1]) + qd(back[2]), 0.0, VSD_TOL, "inverse o1", p[0]);
        expect_close(qd(back[3]) + qd(back[4]) + qd(back[5]), 0.0, VSD_TOL, "inverse o2", p[3]);

        /* And the other way round: inverse then forward. */
        v.alpha = dq(rng_range(-2.0, 2.0));
        v.beta = dq(rng_range(-2.0, 2.0));
        v.x = dq(rng_range(-1.0, 1.0));
        v.y = dq(rng_range(-1.0, 1.0));
        ctl_vsd_inverse(&v, back);
        ctl_vsd_forward(back, &v2);
        expect_close(qd(v2.alpha), qd(v.alpha), VSD_TOL, "inverse->forward alpha", qd(v.alpha));
        expect_close(qd(v2.beta), qd(v.beta), VSD_TOL, "inverse->forward beta", qd(v.beta));
        expect_close(qd(v2.x), qd(v.x), VSD_TOL, "inverse->forward x", qd(v.x));
        expect_close(qd(v2.y), qd(v.y), VSD_TOL, "inverse->forward y", qd(v.y));
    }
    print_message("VSD round trip: max phase err %.3g (tol %.1g)\n", max_err, VSD_TOL);
}

/* Six phases of the h-th harmonic: i_k = amp cos(h (wt - th_k)). */
static void harmonic_phases(ctl_q pq[6], double amp, double wt, double h)
{
    int32_t k;
    for (k = 0; k < 6; k++) {
        pq[k] = dq(amp * cos(h * (wt - vsd_ref_phase_deg[k] * DEG)));
    }
}

static void test_vsd_amplitude_invariance(void **state)
{
    static const double amps[] = {0.3, 1.0, 2.5};
    int32_t a;
    int32_t i;
    (void)state;
    for (a = 0; a < 3; a++) {
        const double amp = amps[a];
        for (i = 0; i < 720; i++) {
            const double wt = 2.0 * PI * (double)i / 720.0;
            ctl_q pq[6];
            ctl_vsd_t v;
            /* Fundamental: alpha-beta = amp [cos wt, sin wt], nothing in x-y. */
            harmonic_phases(pq, amp, wt, 1.0);
            ctl_vsd_forward(pq, &v);
            expect_close(qd(v.alpha), amp * cos(wt), VSD_TOL, "fundamental alpha", wt);
            expect_close(qd(v.beta), amp * sin(wt), VSD_TOL, "fundamental beta", wt);
            expect_close(qd(v.x), 0.0, VSD_TOL, "fundamental x", wt);
            expect_close(qd(v.y), 0.0, VSD_TOL, "fundamental y", wt);
            /* 5th harmonic: x-y = amp [cos 5wt, sin 5wt] (method notes §2). */
            harmonic_phases(pq, amp, wt, 5.0);
            ctl_vsd_forward(pq, &v);
            expect_close(qd(v.alpha), 0.0, VSD_TOL, "5th alpha", wt);
            expect_close(qd(v.beta), 0.0, VSD_TOL, "5th beta", wt);
            expect_close(qd(v.x), amp * cos(5.0 * wt), VSD_TOL, "5th x", wt);
            expect_close(qd(v.y), amp * sin(5.0 * wt), VSD_TOL, "5th y", wt);
            /* 7th harmonic: x-y = amp [cos 7wt, -sin 7wt]. */
            harmonic_phases(pq, amp, wt, 7.0);
            ctl_vsd_forward(pq, &v);
            expect_close(qd(v.alpha), 0.0, VSD_TOL, "7th alpha", wt);
            expect_close(qd(v.beta), 0.0, VSD_TOL, "7th beta", wt);
            expect_close(qd(v.x), amp * cos(7.0 * wt), VSD_TOL, "7th x", wt);
            expect_close(qd(v.y), -amp * sin(7.0 * wt), VSD_TOL, "7th y", wt);
            /* 11th and 13th fall back into alpha-beta (negative / positive sequence). */
            harmonic_phases(pq, amp, wt, 11.0);
            ctl_vsd_forward(pq, &v);
            expect_close(qd(v.alpha), amp * cos(11.0 * wt), VSD_TOL, "11th alpha", wt);
            expect_close(qd(v.beta), -amp * sin(11.0 * wt), VSD_TOL, "11th beta", wt);
            expect_close(qd(v.x), 0.0, VSD_TOL, "11th x", wt);
            expect_close(qd(v.y), 0.0, VSD_TOL, "11th y", wt);
            harmonic_phases(pq, amp, wt, 13.0);
            ctl_vsd_forward(pq, &v);
            expect_close(qd(v.alpha), amp * cos(13.0 * wt), VSD_TOL, "13th alpha", wt);
            expect_close(qd(v.beta), amp * sin(13.0 * wt), VSD_TOL, "13th beta", wt);
            expect_close(qd(v.x), 0.0, VSD_TOL, "13th x", wt);
            expect_close(qd(v.y), 0.0, VSD_TOL, "13th y", wt);
        }
    }
}

/* -------------------------------------------------------------------- Park */

/* sin/cos of the library are within 1e-5 (test_q); Park products of values up to 2. */
#define PARK_TOL 5.0e-5

static void test_park(void **state)
{
    double max_rt = 0.0;
    int32_t i;
    ctl_q d;
    ctl_q q;
    ctl_q al;
    ctl_q be;
    (void)state;
    /* Exact rotations with exact sine/cosine. */
    ctl_park(CTL_Q(0.75), CTL_Q(-0.5), CTL_Q(0.0), CTL_Q(1.0), &d, &q);
    expect_close(qd(d), 0.75, 0.0, "park 0 deg d", 0.0);
    expect_close(qd(q), -0.5, 0.0, "park 0 deg q", 0.0);
    ctl_park(CTL_Q(0.75), CTL_Q(-0.5), CTL_Q(1.0), CTL_Q(0.0), &d, &q);
    expect_close(qd(d), -0.5, 0.0, "park 90 deg d", 90.0);
    expect_close(qd(q), -0.75, 0.0, "park 90 deg q", 90.0);
    ctl_park_inverse(CTL_Q(-0.5), CTL_Q(-0.75), CTL_Q(1.0), CTL_Q(0.0), &al, &be);
    expect_close(qd(al), 0.75, 0.0, "park_inverse 90 deg alpha", 90.0);
    expect_close(qd(be), -0.5, 0.0, "park_inverse 90 deg beta", 90.0);
    for (i = 0; i < 50000; i++) {
        const double ad = rng_range(-2.0, 2.0);
        const double bd = rng_range(-2.0, 2.0);
        const ctl_q angle = dq(rng_range(-3.0, 3.0)); /* turns */
        const double th = 2.0 * PI * qd(angle);
        const ctl_q a = dq(ad);
        const ctl_q b = dq(bd);
        ctl_q s;
        ctl_q c;
        ctl_sincos_pu(angle, &s, &c);
        ctl_park(a, b, s, c, &d, &q);
        /* d = alpha cos th + beta sin th, q = -alpha sin th + beta cos th. */
        expect_close(qd(d), qd(a) * cos(th) + qd(b) * sin(th), PARK_TOL, "park d", th);
        expect_close(qd(q), -qd(a) * sin(th) + qd(b) * cos(th), PARK_TOL, "park q", th);
        ctl_park_inverse(d, q, s, c, &al, &be);
        max_rt = fmax(max_rt, fmax(fabs(qd(al) - qd(a)), fabs(qd(be) - qd(b))));
        expect_close(qd(al), qd(a), PARK_TOL, "park round trip alpha", th);
        expect_close(qd(be), qd(b), PARK_TOL, "park round trip beta", th);
    }
    print_message("Park round trip: max err %.3g (tol %.1g)\n", max_rt, PARK_TOL);
}

/* --------------------------------------------------------- voltage vectors */

static void test_vector_table(void **state)
{
    double max_err = 0.0;
    int32_t v;
    (void)state;
    assert_int_equal(CTL_VECTOR_COUNT, 64);
    for (v = 0; v < 64; v++) {
        const vsd_d want = vsd_ref_state(v);
        const vsd_d got = table_vsd(v);
        double p[6];
        ctl_q pq[6];
        ctl_vsd_t f;
        int32_t k;
        expect_close(got.alpha, want.alpha, TABLE_TOL, "ctl_vector_vsd alpha", (double)v);
        expect_close(got.beta, want.beta, TABLE_TOL, "ctl_vector_vsd beta", (double)v);
        expect_close(got.x, want.x, TABLE_TOL, "ctl_vector_vsd x", (double)v);
        expect_close(got.y, want.y, TABLE_TOL, "ctl_vector_vsd y", (double)v);
        max_err = fmax(max_err, vsd_dist(got, want));
        /* The library's own transform of the phase voltages agrees with its table. */
        for (k = 0; k < 6; k++) {
            const double s1 = (double)vsd_ref_state_leg(v, (k < 3) ? 0 : 3);
            const double s2 = (double)vsd_ref_state_leg(v, (k < 3) ? 1 : 4);
            const double s3 = (double)vsd_ref_state_leg(v, (k < 3) ? 2 : 5);
            p[k] = (double)vsd_ref_state_leg(v, k) - (s1 + s2 + s3) / 3.0;
            pq[k] = dq(p[k]);
        }
        ctl_vsd_forward(pq, &f);
        expect_close(qd(f.alpha), got.alpha, VSD_TOL, "vsd_forward(phase voltages) alpha",
                     (double)v);
        expect_close(qd(f.beta), got.beta, VSD_TOL, "vsd_forward(phase voltages) beta", (double)v);
        expect_close(qd(f.x), got.x, VSD_TOL, "vsd_forward(phase voltages) x", (double)v);
        expect_close(qd(f.y), got.y, VSD_TOL, "vsd_forward(phase voltages) y", (double)v);
    }
    print_message("ctl_vector_vsd vs formula: max L1 err %.3g\n", max_err);
}

static void test_vector_groups(void **state)
{
    /* Brief §3: |u_ab| quoted to 3 decimals, states per group, |u_xy|. */
    static const double quoted_ab[5] = {0.0, 0.173, 0.333, 0.471, 0.644};
    static const double quoted_xy[5] = {0.0, 0.644, 0.333, 0.471, 0.173};
    static const int32_t count_expected[5] = {4, 12, 24, 12, 12};
    int32_t count[5] = {0, 0, 0, 0, 0};
    int32_t dir_count[5][12];
    int32_t v;
    int32_t g;
    int32_t k;
    (void)state;
    for (g = 0; g < 5; g++) {
        for (k = 0; k < 12; k++) {
            dir_count[g][k] = 0;
        }
    }
    for (v = 0; v < 64; v++) {
        const vsd_d u = table_vsd(v);
        const int32_t grp = group_of(u);
        double a;
        double offset;
        if (grp < 0) {
            print_error("state 0%02o: |u_ab| %.6f matches no group\n", (unsigned)v,
                        vsd_ref_mag_ab(u));
            fail();
        }
        count[grp]++;
        expect_close(vsd_ref_mag_ab(u), quoted_ab[grp], 6e-4, "|u_ab| vs brief", (double)v);
        expect_close(vsd_ref_mag_xy(u), quoted_xy[grp], 6e-4, "|u_xy| vs brief", (double)v);
        if (grp == 0) {
            /* Zero vectors: u00, u07, u70, u77. */
            assert_true(v == 000 || v == 007 || v == 070 || v == 077);
            expect_close(vsd_ref_mag_xy(u), 0.0, 1e-7, "|u_xy| zero", (double)v);
            continue;
        }
        /* G4, G3, G1 sit at 15 + 30k deg, G2 at 30k deg. */
        a = ang_deg(u.beta, u.alpha);
        offset = (grp == 2) ? 0.0 : 15.0;
        k = (int32_t)floor((a - offset) / 30.0 + 0.5);
        expect_close(ang_dist(a, offset + 30.0 * (double)k), 0.0, 1e-4, "alpha-beta angle",
                     (double)v);
        dir_count[grp][(k % 12 + 12) % 12]++;
    }
    for (g = 0; g < 5; g++) {
        if (count[g] != count_expected[g]) {
            print_error("group G%ld has %ld states, want %ld\n", (long)g, (long)count[g],
                        (long)count_expected[g]);
            fail();
        }
    }
    /* 12 distinct directions per group: once each for G4 G3 G1, twice for G2. */
    for (g = 1; g < 5; g++) {
        for (k = 0; k < 12; k++) {
            assert_int_equal(dir_count[g][k], (g == 2) ? 2 : 1);
        }
    }
}

/* The two G2 states of one direction have equal x-y voltages too; at each 15 + 30k deg, the G4
 * and the G3 vector have opposite x-y components (what VV-MPTC's virtual vectors cancel). */
static void test_vector_pairs(void **state)
{
    int32_t v;
    (void)state;
    for (v = 0; v < 64; v++) {
        const vsd_d u = table_vsd(v);
        int32_t w;
        int32_t twins = 0;
        int32_t partners = 0;
        for (w = 0; w < 64; w++) {
            const vsd_d o = table_vsd(w);
            const double da = ang_dist(ang_deg(u.beta, u.alpha), ang_deg(o.beta, o.alpha));
            if (w == v) {
                continue;
            }
            if (group_of(u) == 2 && group_of(o) == 2 && da < 1e-4) {
                twins++;
                assert_true(vsd_dist(u, o) < 1e-7);
            }
            if (group_of(u) == 4 && group_of(o) == 3 && da < 1e-4) {
                partners++;
                expect_close(ang_dist(ang_deg(u.y, u.x), ang_deg(o.y, o.x)), 180.0, 1e-4,
                             "G4/G3 x-y opposite", (double)v);
            }
        }
        if (group_of(u) == 2) {
            assert_int_equal(twins, 1);
        }
        if (group_of(u) == 4) {
            assert_int_equal(partners, 1);
        }
    }
    /* Closed forms of the magnitudes (sanity of the quoted values). */
    expect_close(MAG_G4, 0.644, 5e-4, "G4 closed form", 4.0);
    expect_close(MAG_G3, 0.471, 5e-4, "G3 closed form", 3.0);
    expect_close(MAG_G1, 0.173, 5e-4, "G1 closed form", 1.0);
}

static void test_vector_examples(void **state)
{
    /* Method notes §3 table: state (octal), |u_ab| @ angle, |u_xy| @ angle. */
    static const struct {
        int32_t v;
        double ab;
        double ab_deg;
        double xy;
        double xy_deg;
    } ex[] = {
        {066, 0.644, 75.0, 0.173, 15.0},   {024, 0.471, 75.0, 0.471, 195.0},
        {026, 0.644, 105.0, 0.173, 165.0}, {062, 0.471, 105.0, 0.471, 345.0},
        {044, 0.644, 15.0, 0.173, 75.0},   {065, 0.471, 15.0, 0.471, 255.0},
        {045, 0.644, 345.0, 0.173, 285.0}, {054, 0.471, 345.0, 0.471, 105.0},
    };
    int32_t i;
    (void)state;
    /* u24 is state 024 octal = 20: A0 B1 C0 | D1 E0 F0. */
    assert_int_equal(024, 20);
    for (i = 0; i < (int32_t)(sizeof ex / sizeof ex[0]); i++) {
        const vsd_d u = table_vsd(ex[i].v);
        const double v = (double)ex[i].v;
        expect_close(vsd_ref_mag_ab(u), ex[i].ab, 6e-4, "example |u_ab|", v);
        expect_close(ang_dist(ang_deg(u.beta, u.alpha), ex[i].ab_deg), 0.0, 1e-4,
                     "example alpha-beta angle", v);
        expect_close(vsd_ref_mag_xy(u), ex[i].xy, 6e-4, "example |u_xy|", v);
        expect_close(ang_dist(ang_deg(u.y, u.x), ex[i].xy_deg), 0.0, 1e-4, "example x-y angle", v);
    }
}

static void test_vector_leg_ones(void **state)
{
    int16_t v;
    int16_t leg;
    (void)state;
    for (v = 0; v < 64; v++) {
        int32_t ones = 0;
        for (leg = 0; leg < 6; leg++) {
            const int32_t want = vsd_ref_state_leg(v, leg);
            ones += want;
            assert_int_equal(ctl_vector_leg(v, leg), want);
        }
        assert_int_equal(ctl_vector_ones(v), ones);
    }
    /* u24 = A0 B1 C0 D1 E0 F0. */
    assert_int_equal(ctl_vector_leg(024, 0), 0);
    assert_int_equal(ctl_vector_leg(024, 1), 1);
    assert_int_equal(ctl_vector_leg(024, 2), 0);
    assert_int_equal(ctl_vector_leg(024, 3), 1);
    assert_int_equal(ctl_vector_leg(024, 4), 0);
    assert_int_equal(ctl_vector_leg(024, 5), 0);
    assert_int_equal(ctl_vector_ones(024), 2);
    assert_int_equal(ctl_vector_ones(077), 6);
    assert_int_equal(ctl_vector_ones(000), 0);
    assert_int_equal(ctl_vector_ones(052), 3);
}

static void test_mptc49(void **state)
{
    int32_t i;
    int32_t j;
    int32_t v;
    (void)state;
    assert_int_equal(CTL_MPTC49_CANDIDATES, 49);
    assert_int_equal(ctl_mptc49_vectors[0], 0); /* zero vector u00 first */
    for (i = 0; i < 49; i++) {
        const int32_t s = ctl_mptc49_vectors[i];
        assert_true(s >= 0 && s < 64);
        if (i > 0) {
            /* Every other candidate has a non-zero voltage. */
            const vsd_d u = vsd_ref_state(s);
            assert_true(vsd_ref_mag_ab(u) + vsd_ref_mag_xy(u) > 0.1);
        }
        /* All 49 voltages distinct in alpha-beta-x-y. */
        for (j = 0; j < i; j++) {
            if (vsd_dist(vsd_ref_state(s), vsd_ref_state(ctl_mptc49_vectors[j])) < 1e-6) {
                print_error("mptc49[%ld] = 0%02o and [%ld] = 0%02o have the same voltage\n",
                            (long)i, (unsigned)s, (long)j, (unsigned)ctl_mptc49_vectors[j]);
                fail();
            }
        }
    }
    /* Every distinct voltage of the 64 states is among them. */
    for (v = 0; v < 64; v++) {
        int32_t found = 0;
        for (i = 0; i < 49; i++) {
            if (vsd_dist(vsd_ref_state(v), vsd_ref_state(ctl_mptc49_vectors[i])) < 1e-6) {
                found++;
            }
        }
        if (found != 1) {
            print_error("state 0%02o's voltage appears %ld times in mptc49\n", (unsigned)v,
                        (long)found);
            fail();
        }
    }
}

static void test_mptc13(void **state)
{
    int32_t i;
    int32_t j;
    int32_t g4_states = 0;
    int32_t v;
    (void)state;
    assert_int_equal(CTL_MPTC13_CANDIDATES, 13);
    assert_int_equal(ctl_mptc13_vectors[0], 0);
    for (i = 1; i < 13; i++) {
        const int32_t s = ctl_mptc13_vectors[i];
        assert_true(s >= 0 && s < 64);
        expect_close(vsd_ref_mag_ab(vsd_ref_state(s)), MAG_G4, 1e-9, "mptc13 entry is G4",
                     (double)s);
        for (j = 0; j < i; j++) {
            assert_true(s != ctl_mptc13_vectors[j]);
        }
    }
    /* ... and they are all 12 G4 states. */
    for (v = 0; v < 64; v++) {
        if (fabs(vsd_ref_mag_ab(vsd_ref_state(v)) - MAG_G4) < 1e-9) {
            g4_states++;
        }
    }
    assert_int_equal(g4_states, 12);
}

/* VV-MPTC's virtual vectors: in direction 15 + 30 k deg the G4 state for sqrt(3) - 1 of the
 * period and the G3 state of the same alpha-beta direction for the rest; the average has no x-y
 * voltage and an alpha-beta magnitude of sqrt(2) (3 - sqrt(3)) / 3 = 0.598 Vdc; the table holds
 * that average; within each three-phase set one state's legs are a subset of the other's (the
 * centred per-leg duties then give each set its two parts for exactly their shares). */
static void test_virtual_vectors(void **state)
{
    const double share = sqrt(3.0) - 1.0;
    const double mag = sqrt(2.0) * (3.0 - sqrt(3.0)) / 3.0;
    int32_t k;
    (void)state;
    expect_close(qd(CTL_K_VV_LARGE_SHARE), share, TABLE_TOL, "CTL_K_VV_LARGE_SHARE", 0.0);
    for (k = 0; k < CTL_VV_COUNT; k++) {
        const int32_t large = ctl_vv_states[k][0];
        const int32_t medium = ctl_vv_states[k][1];
        const vsd_d l = vsd_ref_state(large);
        const vsd_d m = vsd_ref_state(medium);
        const double dir = (15.0 + 30.0 * (double)k) * TEST_PI / 180.0;
        vsd_d avg;
        int32_t set;
        avg.alpha = share * l.alpha + (1.0 - share) * m.alpha;
        avg.beta = share * l.beta + (1.0 - share) * m.beta;
        avg.x = share * l.x + (1.0 - share) * m.x;
        avg.y = share * l.y + (1.0 - share) * m.y;
        expect_close(vsd_ref_mag_ab(l), MAG_G4, 1e-9, "virtual vector's large state is G4", k);
        expect_close(vsd_ref_mag_ab(m), MAG_G3, 1e-9, "virtual vector's medium state is G3", k);
        expect_close(avg.x, 0.0, 1e-12, "virtual vector x", k);
        expect_close(avg.y, 0.0, 1e-12, "virtual vector y", k);
        expect_close(avg.alpha, mag * cos(dir), 1e-12, "virtual vector alpha", k);
        expect_close(avg.beta, mag * sin(dir), 1e-12, "virtual vector beta", k);
        expect_close(qd(ctl_vv_vsd[k].alpha), avg.alpha, TABLE_TOL, "ctl_vv_vsd alpha", k);
        expect_close(qd(ctl_vv_vsd[k].beta), avg.beta, TABLE_TOL, "ctl_vv_vsd beta", k);
        expect_close(qd(ctl_vv_vsd[k].x), 0.0, TABLE_TOL, "ctl_vv_vsd x", k);
        expect_close(qd(ctl_vv_vsd[k].y), 0.0, TABLE_TOL, "ctl_vv_vsd y", k);
        for (set = 070; set > 0; set >>= 3) {
            const int32_t a = large & set;
            const int32_t b = medium & set;
            assert_true((a & ~b) == 0 || (b & ~a) == 0);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vsd_forward_matches_formula),
        cmocka_unit_test(test_vsd_rows_end_once),
        cmocka_unit_test(test_vsd_round_trip),
        cmocka_unit_test(test_vsd_amplitude_invariance),
        cmocka_unit_test(test_park),
        cmocka_unit_test(test_vector_table),
        cmocka_unit_test(test_vector_groups),
        cmocka_unit_test(test_vector_pairs),
        cmocka_unit_test(test_vector_examples),
        cmocka_unit_test(test_vector_leg_ones),
        cmocka_unit_test(test_mptc49),
        cmocka_unit_test(test_mptc13),
        cmocka_unit_test(test_virtual_vectors),
    };
    print_message("arithmetic: %s\n", CTL_MATH_FLOAT ? "float" : "Q24 fixed point");
    return cmocka_run_group_tests(tests, NULL, NULL);
}
