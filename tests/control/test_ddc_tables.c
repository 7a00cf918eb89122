/*
 * Unit tests of the DDC lookup tables (ctl_tables.h), built against ctl_fixed and
 * ctl_float (the tables are integer state numbers, the same in both).
 *
 * Every table entry is judged by geometry computed here in double from the
 * phase-voltage formula of the method notes §2 (v_A = S_A - (S_A+S_B+S_C)/3 ...,
 * amplitude-invariant VSD), not by re-running tools/gen_tables.py:
 *
 *  - Table 1, static DTC criterion: for a stator flux psi_s at angle phi, a voltage
 *    vector u changes |psi_s| by its radial component u . e_phi and the torque by its
 *    tangential component e_phi x u (positive = leading counter-clockwise).
 *  - Table 2: the x-y voltage of the chosen vector must point against psi_xy.
 *
 * Sectors: alpha-beta sector s spans [30s - 15, 30s + 15) deg, x-y sector j spans
 * [15j, 15j + 15) deg (ctl_tables.h).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>

#include "ctl_tables.h"
#include "ctl_vectors.h"
#include "vsd_reference.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)

/* Samples per sector, plus two points this close (deg) inside each sector edge. */
#define SAMPLES 400
#define EDGE_INSET_DEG 1.0e-3

#define MAG_G4 (2.0 / 3.0 * 0.96592582628906829) /* 0.644 */
#define MAG_G3 (1.41421356237309505 / 3.0)       /* 0.471 */

/* Radial (flux) and tangential (torque) components of u relative to a flux at phi. */
static double radial(vsd_d u, double phi) { return u.alpha * cos(phi) + u.beta * sin(phi); }
static double tangential(vsd_d u, double phi) { return -u.alpha * sin(phi) + u.beta * cos(phi); }

/* Cosine between the x-y voltage of u and an x-y flux at angle phi. */
static double cos_xy(vsd_d u, double phi)
{
    return (u.x * cos(phi) + u.y * sin(phi)) / vsd_ref_mag_xy(u);
}

/* Sample angle i (0 .. SAMPLES + 1) strictly inside [lo, lo + width) deg, in rad. */
static double sample_in(double lo_deg, double width_deg, int32_t i)
{
    double d;
    if (i == 0) {
        d = lo_deg + EDGE_INSET_DEG;
    } else if (i == SAMPLES + 1) {
        d = lo_deg + width_deg - EDGE_INSET_DEG;
    } else {
        d = lo_deg + width_deg * ((double)(i - 1) + 0.5) / (double)SAMPLES;
    }
    return d * DEG;
}

static void fail_state(const char *what, int32_t s, int32_t t, int32_t c, int32_t v, double phi)
{
    print_error("%s: sector %ld torque %ld candidate %ld = u%02o at flux angle %.6f deg\n", what,
                (long)s, (long)t, (long)c, (unsigned)v, phi / DEG);
    fail();
}

/* The paper's / brief's Table 1, torque-raising half, for sectors I..XII. */
static const int16_t brief_table1[12][4] = {
    {024, 066, 062, 026}, {062, 026, 022, 036}, {022, 036, 032, 023}, {032, 023, 033, 012},
    {033, 012, 013, 031}, {013, 031, 011, 053}, {011, 053, 015, 051}, {015, 051, 041, 055},
    {041, 055, 045, 054}, {045, 054, 065, 044}, {065, 044, 064, 046}, {064, 046, 024, 066},
};

/* ---------------------------------------------------------------- table 1 */

static void test_table1_dtc_criterion(void **state)
{
    double min_tan = 1e9;
    double min_rad = 1e9;
    int32_t s;
    int32_t t;
    int32_t c;
    int32_t i;
    (void)state;
    for (s = 0; s < CTL_SECTORS; s++) {
        const double lo = 30.0 * (double)s - 15.0;
        for (t = 0; t < 2; t++) {
            const double tsign = (t == 0) ? 1.0 : -1.0;
            vsd_d u[4];
            for (c = 0; c < 4; c++) {
                const int32_t v = ctl_ddc_table1[s][t][c];
                assert_true(v > 0 && v < 63);
                u[c] = vsd_ref_state(v);
                /* [0], [2] are G3 (0.471), [1], [3] are G4 (0.644). */
                if (fabs(vsd_ref_mag_ab(u[c]) - ((c % 2 == 0) ? MAG_G3 : MAG_G4)) > 1e-9) {
                    fail_state("wrong group", s, t, c, v, 0.0);
                }
            }
            /* G3 and G4 of one pair share the alpha-beta direction. */
            assert_true(fabs(u[0].alpha * u[1].beta - u[0].beta * u[1].alpha) < 1e-12);
            assert_true(fabs(u[2].alpha * u[3].beta - u[2].beta * u[3].alpha) < 1e-12);
            /* Open sector interior: every candidate moves torque in the demanded direction,
             * [0], [1] raise |psi_s| and [2], [3] lower it. */
            for (i = 0; i <= SAMPLES + 1; i++) {
                const double phi = sample_in(lo, 30.0, i);
                for (c = 0; c < 4; c++) {
                    const int32_t v = ctl_ddc_table1[s][t][c];
                    const double tg = tsign * tangential(u[c], phi);
                    const double rd = ((c < 2) ? 1.0 : -1.0) * radial(u[c], phi);
                    if (!(tg > 0.0)) {
                        fail_state("torque moves the wrong way", s, t, c, v, phi);
                    }
                    if (!(rd > 0.0)) {
                        fail_state("flux moves the wrong way", s, t, c, v, phi);
                    }
                    min_tan = fmin(min_tan, tg / vsd_ref_mag_ab(u[c]));
                    min_rad = fmin(min_rad, rd / vsd_ref_mag_ab(u[c]));
                }
            }
            /* At the exact sector edges one pair is perpendicular to the flux (radial
             * component 0, flux unchanged): the lower edge 30s - 15 for the pair at +-90 deg
             * from it ([0],[1] when torque up, [2],[3] when down), the upper edge 30s + 15 for
             * the other pair. That is why the flux criterion is checked on the open interior
             * only. The torque criterion still holds strictly at the edges. */
            for (c = 0; c < 4; c++) {
                const double phi_lo = lo * DEG;
                const double phi_hi = (lo + 30.0) * DEG;
                const int32_t zero_at_lo = (t == 0) ? (c < 2) : (c >= 2);
                const double r_lo = radial(u[c], phi_lo);
                const double r_hi = radial(u[c], phi_hi);
                assert_true(tsign * tangential(u[c], phi_lo) > 0.1);
                assert_true(tsign * tangential(u[c], phi_hi) > 0.1);
                if (zero_at_lo) {
                    assert_true(fabs(r_lo) < 1e-12);
                    assert_true(fabs(r_hi) > 0.1);
                } else {
                    assert_true(fabs(r_hi) < 1e-12);
                    assert_true(fabs(r_lo) > 0.1);
                }
            }
        }
    }
    print_message("table 1 interior: min tangential %.3g, min radial %.3g (per unit of |u|)\n",
                  min_tan, min_rad);
}

static void test_table1_paper_sets(void **state)
{
    int32_t s;
    int32_t c;
    int32_t d;
    (void)state;
    /* Sector I: exactly the paper's order u24 u66 u62 u26. */
    assert_int_equal(ctl_ddc_table1[0][0][0], 024);
    assert_int_equal(ctl_ddc_table1[0][0][1], 066);
    assert_int_equal(ctl_ddc_table1[0][0][2], 062);
    assert_int_equal(ctl_ddc_table1[0][0][3], 026);
    /* Every sector: the same set as the brief's Table 1 (torque-raising half). */
    for (s = 0; s < CTL_SECTORS; s++) {
        for (c = 0; c < 4; c++) {
            int32_t found = 0;
            for (d = 0; d < 4; d++) {
                if (ctl_ddc_table1[s][0][d] == brief_table1[s][c]) {
                    found++;
                }
            }
            if (found != 1) {
                print_error("sector %ld: u%02o of the brief's Table 1 found %ld times\n",
                            (long)(s + 1), (unsigned)brief_table1[s][c], (long)found);
                fail();
            }
        }
    }
}

/* -------------------------------------------------------- table 2, flux */

static void test_table2_flux_reading(void **state)
{
    double max_cos = -1.0;
    int32_t s;
    int32_t t;
    int32_t f;
    int32_t j;
    int32_t i;
    (void)state;
    for (s = 0; s < CTL_SECTORS; s++) {
        for (t = 0; t < 2; t++) {
            for (f = 0; f < 2; f++) {
                /* f = 0 raise flux -> candidates 0/1, f = 1 lower -> 2/3. */
                const int32_t g3 = ctl_ddc_table1[s][t][2 * f];
                const int32_t g4 = ctl_ddc_table1[s][t][2 * f + 1];
                for (j = 0; j < CTL_XY_SECTORS; j++) {
                    const int32_t v = ctl_ddc_table2_flux[s][t][f][j];
                    const int32_t other = (v == g3) ? g4 : g3;
                    vsd_d u;
                    vsd_d uo;
                    if (v != g3 && v != g4) {
                        print_error("table2_flux[%ld][%ld][%ld][%ld] = u%02o is neither u%02o nor "
                                    "u%02o\n",
                                    (long)s, (long)t, (long)f, (long)j, (unsigned)v, (unsigned)g3,
                                    (unsigned)g4);
                        fail();
                    }
                    u = vsd_ref_state(v);
                    uo = vsd_ref_state(other);
                    for (i = 0; i <= SAMPLES + 1; i++) {
                        const double phi = sample_in(15.0 * (double)j, 15.0, i);
                        const double cv = cos_xy(u, phi);
                        /* The chosen vector shrinks psi_xy, the other one of the pair would
                         * grow it (their x-y voltages are opposite). */
                        if (!(cv < 0.0 && cos_xy(uo, phi) > 0.0)) {
                            print_error("table2_flux[%ld][%ld][%ld][%ld] = u%02o: cos %.6f at x-y "
                                        "angle %.4f deg\n",
                                        (long)s, (long)t, (long)f, (long)j, (unsigned)v, cv,
                                        phi / DEG);
                            fail();
                        }
                        max_cos = fmax(max_cos, cv);
                    }
                }
            }
        }
    }
    print_message("table 2 (flux reading): largest cos(u_xy, psi_xy) %.3g\n", max_cos);
}

/* ---------------------------------------------------------- table 2, x-y */

static void test_table2_xy_reading(void **state)
{
    double max_cos = -1.0;
    double min_margin = 1e9;
    int32_t s;
    int32_t t;
    int32_t j;
    int32_t i;
    int32_t c;
    (void)state;
    for (s = 0; s < CTL_SECTORS; s++) {
        for (t = 0; t < 2; t++) {
            for (j = 0; j < CTL_XY_SECTORS; j++) {
                const int32_t v = ctl_ddc_table2_xy[s][t][j];
                int32_t in_row = 0;
                vsd_d u;
                for (c = 0; c < 4; c++) {
                    in_row += (ctl_ddc_table1[s][t][c] == v) ? 1 : 0;
                }
                if (in_row != 1) {
                    print_error("table2_xy[%ld][%ld][%ld] = u%02o is not a table-1 candidate\n",
                                (long)s, (long)t, (long)j, (unsigned)v);
                    fail();
                }
                u = vsd_ref_state(v);
                for (i = 0; i <= SAMPLES + 1; i++) {
                    const double phi = sample_in(15.0 * (double)j, 15.0, i);
                    const double cv = cos_xy(u, phi);
                    if (!(cv < 0.0)) {
                        print_error("table2_xy[%ld][%ld][%ld] = u%02o: cos %.6f at %.4f deg\n",
                                    (long)s, (long)t, (long)j, (unsigned)v, cv, phi / DEG);
                        fail();
                    }
                    max_cos = fmax(max_cos, cv);
                    /* Most negative cosine of the four, strictly inside the sector (the four
                     * x-y directions differ, so ties can only fall on sector edges). */
                    for (c = 0; c < 4; c++) {
                        const int32_t w = ctl_ddc_table1[s][t][c];
                        double margin;
                        if (w == v) {
                            continue;
                        }
                        margin = cos_xy(vsd_ref_state(w), phi) - cv;
                        min_margin = fmin(min_margin, margin);
                        if (!(margin > 1e-9)) {
                            print_error("table2_xy[%ld][%ld][%ld] = u%02o: u%02o opposes psi_xy "
                                        "at least as well (cos %.6f vs %.6f) at %.4f deg\n",
                                        (long)s, (long)t, (long)j, (unsigned)v, (unsigned)w,
                                        cos_xy(vsd_ref_state(w), phi), cv, phi / DEG);
                            fail();
                        }
                    }
                }
            }
        }
    }
    print_message("table 2 (x-y reading): largest cos %.3g, smallest margin to the runner-up "
                  "%.3g\n",
                  max_cos, min_margin);
}

static void test_table2_xy_paper_sector1(void **state)
{
    int32_t j;
    (void)state;
    /* The paper's Table 2 for alpha-beta sector I, torque up: x-y sectors I-III (0-90 deg)
     * u24, IV-VI u62, VII-IX u66, X-XII u26 (paper sectors are 30 deg = two of ours). */
    for (j = 0; j < CTL_XY_SECTORS; j++) {
        static const int16_t paper[4] = {024, 062, 066, 026};
        assert_int_equal(ctl_ddc_table2_xy[0][0][j], paper[j / 6]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table1_dtc_criterion),    cmocka_unit_test(test_table1_paper_sets),
        cmocka_unit_test(test_table2_flux_reading),     cmocka_unit_test(test_table2_xy_reading),
        cmocka_unit_test(test_table2_xy_paper_sector1),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
