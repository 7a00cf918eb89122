/*
 * ctl-bench: cost of one control step per controller and arithmetic, over operating points
 * recorded by the simulator (trace.csv files). Prints one line per configuration with the
 * wall time per step. Under valgrind's callgrind (run with --collect-atstart=no) each
 * configuration's measured loop is collected alone and dumped under its own name, which
 * gives repeatable instruction counts; tools/bench/run_benchmark.py does that.
 *
 * usage: ctl-bench [--reps N] [--vdc V] TRACE.csv...
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <valgrind/callgrind.h>

#include "bench.h"

#define MAX_COLUMNS 64
#define POLE_PAIRS 3.0
#define PI 3.14159265358979323846

static bench_point_t points[BENCH_MAX_POINTS];

static int column_index(char *header, const char *name)
{
    int index = 0;
    char *save = NULL;
    char *tok = strtok_r(header, ",\n\r", &save);
    while (tok) {
        if (strcmp(tok, name) == 0) {
            return index;
        }
        index++;
        tok = strtok_r(NULL, ",\n\r", &save);
    }
    return -1;
}

/* Appends the trace's points; returns the new count or -1 with a message. */
static long read_trace(const char *path, size_t have, double vdc)
{
    /* column names of sixphase-sim's trace.csv (phase currents i_A..i_F; i_d is the d axis) */
    static const char *names[9] = {"theta_e", "speed_rpm", "i_A", "i_B", "i_C",
                                   "i_D",     "i_E",       "i_F", "Tref"};
    int col[9];
    char line[4096];
    char copy[4096];
    FILE *f = fopen(path, "r");
    int k;
    size_t n = have;
    if (!f) {
        fprintf(stderr, "ctl-bench: cannot open trace '%s': %s\n", path, strerror(errno));
        return -1;
    }
    if (!fgets(line, sizeof line, f)) {
        fprintf(stderr, "ctl-bench: trace '%s' is empty\n", path);
        fclose(f);
        return -1;
    }
    for (k = 0; k < 9; k++) {
        memcpy(copy, line, sizeof line);
        col[k] = column_index(copy, names[k]);
        if (col[k] < 0) {
            fprintf(stderr, "ctl-bench: trace '%s' has no column '%s'\n", path, names[k]);
            fclose(f);
            return -1;
        }
    }
    while (fgets(line, sizeof line, f) && n < BENCH_MAX_POINTS) {
        double v[MAX_COLUMNS];
        int c = 0;
        char *save = NULL;
        char *tok = strtok_r(line, ",\n\r", &save);
        while (tok && c < MAX_COLUMNS) {
            char *end;
            v[c] = strtod(tok, &end);
            if (end == tok) {
                v[c] = 0.0; /* non-numeric column (leg bit string) */
            }
            c++;
            tok = strtok_r(NULL, ",\n\r", &save);
        }
        for (k = 0; k < 9; k++) {
            if (col[k] >= c) {
                fprintf(stderr, "ctl-bench: short row in trace '%s'\n", path);
                fclose(f);
                return -1;
            }
        }
        points[n].theta_e = v[col[0]];
        points[n].omega_e = v[col[1]] * PI / 30.0 * POLE_PAIRS;
        for (k = 0; k < 6; k++) {
            points[n].i_phase[k] = v[col[2 + k]];
        }
        points[n].torque_ref = v[col[8]];
        points[n].vdc = vdc;
        n++;
    }
    fclose(f);
    return (long)n;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int parse_positive(const char *flag, const char *text, double *out)
{
    char *end;
    const double v = strtod(text, &end);
    if (end == text || *end != '\0' || !(v > 0.0) || !isfinite(v)) {
        fprintf(stderr, "ctl-bench: %s needs a positive number, got '%s'\n", flag, text);
        return -1;
    }
    *out = v;
    return 0;
}

int main(int argc, char **argv)
{
    static const char *names[3] = {"ddc", "mptc49", "mptc13"};
    double reps_d = 5.0;
    double vdc = 540.0;
    size_t n = 0;
    int traces = 0;
    int a;
    int16_t controller;
    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--reps") == 0 && a + 1 < argc) {
            if (parse_positive("--reps", argv[++a], &reps_d) != 0) {
                return 2;
            }
        } else if (strcmp(argv[a], "--vdc") == 0 && a + 1 < argc) {
            if (parse_positive("--vdc", argv[++a], &vdc) != 0) {
                return 2;
            }
        } else if (argv[a][0] == '-') {
            fprintf(stderr,
                    "ctl-bench: unknown option '%s' (usage: ctl-bench [--reps N] [--vdc V] "
                    "TRACE.csv...)\n",
                    argv[a]);
            return 2;
        } else {
            const long got = read_trace(argv[a], n, vdc);
            if (got < 0) {
                return 1;
            }
            n = (size_t)got;
            traces++;
        }
    }
    if (traces == 0 || n == 0) {
        fprintf(stderr, "ctl-bench: no operating points (usage: ctl-bench [--reps N] [--vdc V] "
                        "TRACE.csv...)\n");
        return 2;
    }
    (void)bench_prepare(points, n);
    (void)flt_bench_prepare(points, n);
    printf("points %zu reps %d\n", n, (int)reps_d);
    for (controller = 0; controller < 3; controller++) {
        int arith;
        for (arith = 0; arith < 2; arith++) {
            char label[32];
            double t0;
            double t1;
            uint32_t sum;
            snprintf(label, sizeof label, "%s_%s", names[controller], arith ? "float" : "fixed");
            if ((arith ? flt_bench_setup(controller) : bench_setup(controller)) != 0) {
                fprintf(stderr, "ctl-bench: controller %s did not initialise\n", label);
                return 1;
            }
            CALLGRIND_TOGGLE_COLLECT;
            t0 = now_s();
            sum = arith ? flt_bench_run((int32_t)reps_d) : bench_run((int32_t)reps_d);
            t1 = now_s();
            CALLGRIND_TOGGLE_COLLECT;
            CALLGRIND_DUMP_STATS_AT(label);
            printf("%s steps %zu ns_per_step %.1f checksum %08x\n", label, n * (size_t)reps_d,
                   1e9 * (t1 - t0) / ((double)n * reps_d), (unsigned)sum);
        }
    }
    return 0;
}
