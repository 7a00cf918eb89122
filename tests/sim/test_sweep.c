/*
 * sixphase-sim sweep and plot, through the executable: a 2 x 2 grid's table equals single
 * runs of the same points (sim_run in this process); a rerun after one point's file was
 * removed runs only that point and gives the same table; bad grids are refused in one line
 * with exit 2; `run --plot` and `plot DIR` draw a 1000 x 1400 PNG.
 */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "sim.h"

static char dir[] = "/tmp/sixphase-sweep-XXXXXX";

static int sh(const char *fmt, const char *a)
{
    char cmd[1200];
    int rc;
    (void)snprintf(cmd, sizeof cmd, fmt, SIXPHASE_SIM_EXE, a);
    rc = system(cmd);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static char *read_all(const char *path)
{
    static char buf[65536];
    FILE *f = fopen(path, "r");
    size_t n;
    assert_non_null(f);
    n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static void test_table_equals_single_runs(void **state)
{
    static const char *const controllers[2] = {"ddc", "mptc13"};
    static const double lambdas[2] = {20.0, 100.0};
    char path[200], *table, line[512], *p;
    int k;
    (void)state;
    assert_non_null(mkdtemp(dir));
    assert_int_equal(sh("%s sweep --out %s --controller ddc,mptc13 --scenario steady --lambda "
                        "20,100 --duration 0.3 --no-plots --quiet",
                        dir),
                     0);
    (void)snprintf(path, sizeof path, "%s/sweep.csv", dir);
    table = read_all(path);
    p = strchr(table, '\n') + 1; /* after the header */
    for (k = 0; k < 4; k++) {
        sim_config_t c;
        sim_result_t r;
        char err[200], want[64];
        size_t n = strcspn(p, "\n");
        memcpy(line, p, n);
        line[n] = '\0';
        p += n + 1;
        sim_config_default(&c);
        c.controller = (k < 2) ? 0 : 2;
        c.scenario = SIM_SCEN_STEADY;
        c.lambda = lambdas[k % 2];
        c.duration_s = 0.3;
        c.out_dir = NULL;
        assert_int_equal(sim_run(&c, &r, err, sizeof err), 0);
        (void)snprintf(want, sizeof want, "%d,%s,%.10g,%.6g,", k, controllers[k / 2], c.lambda,
                       r.thd_percent);
        if (strncmp(line, want, strlen(want)) != 0) {
            print_error("row %d: '%s', want it to start '%s'\n", k, line, want);
            fail();
        }
    }
}

static void test_resume_runs_only_the_missing_point(void **state)
{
    char path[200], before[65536];
    struct stat kept;
    (void)state;
    (void)snprintf(path, sizeof path, "%s/sweep.csv", dir);
    (void)snprintf(before, sizeof before, "%s", read_all(path));
    (void)snprintf(path, sizeof path, "%s/points/p0000.txt", dir);
    assert_int_equal(stat(path, &kept), 0);
    (void)snprintf(path, sizeof path, "%s/points/p0002.txt", dir);
    assert_int_equal(remove(path), 0);
    sleep(1); /* a rewritten point file would show a later time */
    assert_int_equal(sh("%s sweep --out %s --controller ddc,mptc13 --scenario steady --lambda "
                        "20,100 --duration 0.3 --no-plots --quiet",
                        dir),
                     0);
    assert_int_equal(stat(path, &kept), 0); /* run again */
    {
        struct stat again;
        char p0[200];
        (void)snprintf(p0, sizeof p0, "%s/points/p0000.txt", dir);
        assert_int_equal(stat(p0, &again), 0);
        assert_true(again.st_mtime < kept.st_mtime); /* p0000 was not run again */
    }
    (void)snprintf(path, sizeof path, "%s/sweep.csv", dir);
    assert_string_equal(read_all(path), before);
}

static void test_bad_grids_refused(void **state)
{
    static const char *const bad[] = {"--lambda 10:5:1", "--lambda 10:20:0",
                                      "--lambda ,",      "--bogus 1,2",
                                      "--lambda 20,abc", "--lambda 1:250:1 --fs 5000,10000"};
    size_t k;
    (void)state;
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        char cmd[300];
        (void)snprintf(cmd, sizeof cmd,
                       "%%s sweep --out %%s --controller ddc --scenario steady %s 2>/dev/null",
                       bad[k]);
        assert_int_equal(sh(cmd, dir), 2);
    }
}

/* A point whose run fails (the fault time outside its 0.3 s) fails the sweep, and a rerun runs
 * it again rather than taking the failure as done; list values in the JSON are numbers. */
static void test_failed_points_rerun_and_json_numbers(void **state)
{
    char d2[] = "/tmp/sixphase-sweep2-XXXXXX", path[200], *json;
    (void)state;
    assert_non_null(mkdtemp(d2));
    assert_int_equal(sh("%s sweep --out %s --controller ddc --scenario fault-overcurrent "
                        "--fault-time 0.4 --duration 0.3,0.5 --no-plots --quiet 2>/dev/null",
                        d2),
                     1);
    assert_int_equal(sh("%s sweep --out %s --controller ddc --scenario fault-overcurrent "
                        "--fault-time 0.4 --duration 0.3,0.5 --no-plots --quiet 2>/dev/null",
                        d2),
                     1);
    assert_int_equal(sh("%s sweep --out %s --controller ddc --scenario steady --lambda .5,1 "
                        "--duration 0.1 --no-plots --quiet",
                        d2),
                     0);
    (void)snprintf(path, sizeof path, "%s/sweep.json", d2);
    json = read_all(path);
    assert_non_null(strstr(json, "\"lambda\": 0.5,"));
    (void)snprintf(path, sizeof path, "rm -rf %s", d2);
    assert_int_equal(system(path), 0);
}

static void test_run_plot(void **state)
{
    char path[200];
    unsigned char h[24];
    FILE *f;
    (void)state;
    assert_int_equal(sh("%s run --controller ddc --scenario steady --duration 0.2 --out %s "
                        "--plot --quiet",
                        dir),
                     0);
    (void)snprintf(path, sizeof path, "%s/run.png", dir);
    f = fopen(path, "rb");
    assert_non_null(f);
    assert_int_equal(fread(h, 1, 24, f), 24);
    fclose(f);
    assert_int_equal((h[16] << 24) | (h[17] << 16) | (h[18] << 8) | h[19], 1000); /* width */
    assert_int_equal((h[20] << 24) | (h[21] << 16) | (h[22] << 8) | h[23], 1400); /* height */
    assert_int_equal(remove(path), 0);
    assert_int_equal(sh("%s plot %s", dir), 0);
    assert_int_equal(access(path, R_OK), 0);
    assert_int_equal(sh("%s run --controller ddc --scenario steady --plot 2>/dev/null", ""), 2);
    (void)snprintf(path, sizeof path, "rm -rf %s", dir);
    assert_int_equal(system(path), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_equals_single_runs),
        cmocka_unit_test(test_resume_runs_only_the_missing_point),
        cmocka_unit_test(test_bad_grids_refused),
        cmocka_unit_test(test_failed_points_rerun_and_json_numbers),
        cmocka_unit_test(test_run_plot),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
