/*
 * The reproduce report (reproduce_report.c) shows each phase's THD beside the six-phase mean,
 * the headline figure (issue 12): for section 1's runs, a row with the six phases, the mean and
 * the spread max/min; "n/a" where a phase's THD is not meaningful or the run failed.
 */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "report/reproduce_cases.h"
#include "report/reproduce_report.h"

static void add_case(rep_case_t *cases, int *n, const char *name, const double phase[6],
                     double mean)
{
    rep_case_t *c = &cases[(*n)++];
    int k;
    memset(c, 0, sizeof *c);
    (void)snprintf(c->name, sizeof c->name, "%s", name);
    sim_config_default(&c->cfg);
    c->ok = 1;
    c->res.fault_time_s = c->res.trip_time_s = -1.0;
    c->res.thd_percent = mean;
    for (k = 0; k < 6; k++) {
        c->res.thd_phase_percent[k] = phase[k];
    }
}

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    char *buf;
    long len;
    assert_non_null(f);
    assert_int_equal(fseek(f, 0, SEEK_END), 0);
    len = ftell(f);
    assert_true(len > 0);
    rewind(f);
    buf = calloc((size_t)len + 1u, 1u);
    assert_non_null(buf);
    assert_int_equal(fread(buf, 1u, (size_t)len, f), (size_t)len);
    (void)fclose(f);
    return buf;
}

static void test_phase_thd_table(void **state)
{
    static const double mptc[6] = {383.883, 405.684, 237.793, 420.895, 341.471, 408.808};
    static const double ddc[6] = {27.7034, 29.3674, 27.6905, 28.2194, 27.7626, 28.5316};
    static const double part[6] = {30.0, -1.0, 31.0, 32.0, 33.0, 34.0}; /* phase B meaningless */
    rep_case_t *cases = calloc(8, sizeof *cases);
    char dir[] = "/tmp/test_sim_report_XXXXXX", path[64];
    char *text;
    int n = 0;
    (void)state;
    assert_non_null(cases);
    assert_non_null(mkdtemp(dir));
    add_case(cases, &n, "steady_mptc49_l20", mptc, 366.422);
    add_case(cases, &n, "steady_ddc_l100", ddc, 28.2125);
    add_case(cases, &n, "steady_mptc13_l200", part, -1.0);
    assert_int_equal(rep_write_report(dir, cases, n), 0);
    (void)snprintf(path, sizeof path, "%s/report.md", dir);
    text = read_all(path);
    assert_non_null(strstr(text, "| method, lambda | A | B | C | D | E | F | mean | max/min |"));
    assert_non_null(
        strstr(text, "| MPTC-49, 20 | 383.9 | 405.7 | 237.8 | 420.9 | 341.5 | 408.8 | **366.4** | "
                     "1.77 |"));
    assert_non_null(
        strstr(text, "| DDC, 100 | 27.7 | 29.4 | 27.7 | 28.2 | 27.8 | 28.5 | **28.2** | 1.06 |"));
    assert_non_null(
        strstr(text, "| MPTC-13, 200 | 30.0 | n/a | 31.0 | 32.0 | 33.0 | 34.0 | **n/a** | n/a |"));
    assert_non_null(
        strstr(text, "| DDC, product, 20 | n/a | n/a | n/a | n/a | n/a | n/a | **n/a** | n/a |"));
    free(text);
    (void)remove(path);
    (void)rmdir(dir);
    free(cases);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_phase_thd_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
