/*
 * The parameter ranges' one list (control/include/ctl_param_ranges.h, issue 26) against what
 * derives from it: for every row, ctl_params_check refuses a value just outside either bound
 * with the row's reason, does not refuse the bound itself for that reason (another check may
 * bind first: a resistance of 1000 ohm leaves no discrete model, a speed gain of 1e4 passes the
 * per-unit limit), and the reason's text carries the bounds as the list writes them.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "ctl_params.h"

typedef struct {
    const char *row;
    size_t offset, size; /* the field in ctl_params_t: float, or int16_t */
    ctl_param_error_t error;
    double lo, hi;
    const char *lo_text, *hi_text;
} range_row_t;

#define ROW(row, field, error, lo, hi, unit, what, value)                                          \
    {#row,                                                                                         \
     offsetof(ctl_params_t, field),                                                                \
     sizeof(((ctl_params_t *)0)->field),                                                           \
     error,                                                                                        \
     lo,                                                                                           \
     hi,                                                                                           \
     CTL_RANGE_STR(lo),                                                                            \
     CTL_RANGE_STR(hi)},
static const range_row_t rows[] = {CTL_PARAM_RANGES(ROW)};
#undef ROW

/* The defaults with the row's field at v (and what makes the field count: a constant flux). */
static ctl_param_error_t check_with(const range_row_t *r, double v)
{
    ctl_params_t p;
    ctl_params_default(&p);
    if (r->error == CTL_PARAM_FLUX_REF) {
        p.flux_ref_mode = CTL_FLUX_REF_CONSTANT;
    }
    if (r->size == sizeof(float)) {
        const float f = (float)v;
        memcpy((char *)&p + r->offset, &f, sizeof f);
    } else {
        const int16_t i = (int16_t)v;
        memcpy((char *)&p + r->offset, &i, sizeof i);
    }
    return ctl_params_check(&p);
}

static void test_each_bound_refused_just_outside(void **state)
{
    size_t k;
    (void)state;
    for (k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        const range_row_t *r = &rows[k];
        const bool is_float = r->size == sizeof(float);
        const double below = is_float
                                 ? (double)nextafterf((float)r->lo, -INFINITY) - fabs(r->lo) * 1e-6
                                 : r->lo - 1.0;
        const double above = is_float
                                 ? (double)nextafterf((float)r->hi, INFINITY) + fabs(r->hi) * 1e-6
                                 : r->hi + 1.0;
        print_message("%-18s %s..%s: below %d, at %d / %d, above %d\n", r->row, r->lo_text,
                      r->hi_text, check_with(r, below), check_with(r, r->lo), check_with(r, r->hi),
                      check_with(r, above));
        assert_int_equal(check_with(r, below), r->error);
        assert_int_equal(check_with(r, above), r->error);
        assert_int_not_equal(check_with(r, r->lo), r->error);
        if (r->error != CTL_PARAM_SPEED_GAINS) { /* the per-unit limit binds first at 1e4 */
            assert_int_not_equal(check_with(r, r->hi), r->error);
        }
    }
}

static void test_each_reason_text_carries_its_bounds(void **state)
{
    size_t k;
    (void)state;
    for (k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        const range_row_t *r = &rows[k];
        const char *text = ctl_param_error_text(r->error);
        char bounds[64];
        (void)snprintf(bounds, sizeof bounds, "%s..%s", r->lo_text, r->hi_text);
        print_message("%-18s %s\n", r->row, text);
        assert_non_null(strstr(text, bounds));
    }
    assert_string_equal(ctl_param_error_text(CTL_PARAM_OK), "accepted");
    assert_string_equal(ctl_param_error_text(CTL_PARAM_ERROR_COUNT), "unknown reason");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_bound_refused_just_outside),
        cmocka_unit_test(test_each_reason_text_carries_its_bounds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
