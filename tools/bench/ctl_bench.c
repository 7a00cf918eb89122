/*
 * ctl-bench: cost of one control step per controller and arithmetic, over operating points
 * recorded by the simulator (trace.csv files). Prints one line per configuration with the
 * wall time per step. Under valgrind's callgrind (run with --collect-atstart=no) each
 * configuration's measured loop is collected alone and dumped under its own name, which
 * gives repeatable instruction counts; tools/bench/run_benchmark.py does that.
 *
 * With --worst-step each configuration is replayed one step at a time instead, every step
 * collected and dumped on its own (run under callgrind with --combine-dumps=yes), with a
 * parameter change requested in the background every CHANGE_EVERY steps, so the steps that
 * take a new set are among those measured.
 *
 * usage: ctl-bench [--reps N] [--vdc V] [--worst-step] TRACE.csv...
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
#include "ctl_params.h"
#include "trace_csv.h"

static bench_point_t points[BENCH_MAX_POINTS];

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

/* The core's controllers by name (CTL_CONTROLLER_LIST), in id order. */
#define BENCH_CONTROLLER_NAME(id, number, name, what) name,
static const char *const controller_names[CTL_CONTROLLER_COUNT] = {
    CTL_CONTROLLER_LIST(BENCH_CONTROLLER_NAME)};
#undef BENCH_CONTROLLER_NAME

/* Parameter changes during the per-step replay: one every this many steps. */
#define CHANGE_EVERY 500u

/* Every step measured alone; dump label "w-<config>-<step>-<1 if it took a new set>". */
static void worst_step_replay(int16_t controller, int arith, size_t n)
{
    char label[64];
    int16_t change = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        bool applies;
        if (i % CHANGE_EVERY == CHANGE_EVERY / 2u) {
            (void)(arith ? flt_bench_request_change(change) : bench_request_change(change));
            change++;
        }
        applies = arith ? flt_bench_change_pending() : bench_change_pending();
        snprintf(label, sizeof label, "w-%s_%s-%zu-%d", controller_names[controller],
                 arith ? "float" : "fixed", i, applies ? 1 : 0);
        CALLGRIND_TOGGLE_COLLECT;
        (void)(arith ? flt_bench_step(i) : bench_step(i));
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS_AT(label);
    }
}

typedef struct {
    bool worst_step;
    double reps;
    size_t n; /* operating points read */
} bench_args_t;

/* Options and trace files; 0 on success, else the exit status. */
static int parse_args(int argc, char **argv, bench_args_t *args)
{
    double vdc = 540.0;
    int traces = 0;
    int a;
    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--reps") == 0 && a + 1 < argc) {
            if (parse_positive("--reps", argv[++a], &args->reps) != 0) {
                return 2;
            }
        } else if (strcmp(argv[a], "--vdc") == 0 && a + 1 < argc) {
            if (parse_positive("--vdc", argv[++a], &vdc) != 0) {
                return 2;
            }
        } else if (strcmp(argv[a], "--worst-step") == 0) {
            args->worst_step = true;
        } else if (argv[a][0] == '-') {
            fprintf(stderr,
                    "ctl-bench: unknown option '%s' (usage: ctl-bench [--reps N] [--vdc V] "
                    "[--worst-step] TRACE.csv...)\n",
                    argv[a]);
            return 2;
        } else {
            const long got =
                trace_csv_read(argv[a], points, args->n, BENCH_MAX_POINTS, vdc, "ctl-bench");
            if (got < 0) {
                return 1;
            }
            args->n = (size_t)got;
            traces++;
        }
    }
    if (traces == 0 || args->n == 0) {
        fprintf(stderr, "ctl-bench: no operating points (usage: ctl-bench [--reps N] [--vdc V] "
                        "TRACE.csv...)\n");
        return 2;
    }
    return 0;
}

static int setup_controller(int16_t controller, int arith)
{
    if ((arith ? flt_bench_setup(controller) : bench_setup(controller)) != 0) {
        fprintf(stderr, "ctl-bench: controller %s (%s) did not initialise\n",
                controller_names[controller], arith ? "float" : "fixed");
        return 1;
    }
    return 0;
}

static int run_worst_steps(size_t n)
{
    int16_t controller;
    int arith;
    for (controller = 0; controller < CTL_CONTROLLER_COUNT; controller++) {
        for (arith = 0; arith < 2; arith++) {
            if (setup_controller(controller, arith) != 0) {
                return 1;
            }
            worst_step_replay(controller, arith, n);
        }
    }
    return 0;
}

/* The measured passes: every controller in both arithmetics, then the protection check. */
static int run_measured(size_t n, double reps)
{
    int16_t controller;
    int arith;
    for (controller = 0; controller < CTL_CONTROLLER_COUNT; controller++) {
        for (arith = 0; arith < 2; arith++) {
            char label[32];
            double t0, t1;
            uint32_t sum;
            snprintf(label, sizeof label, "%s_%s", controller_names[controller],
                     arith ? "float" : "fixed");
            if (setup_controller(controller, arith) != 0) {
                return 1;
            }
            CALLGRIND_TOGGLE_COLLECT;
            t0 = now_s();
            sum = arith ? flt_bench_run((int32_t)reps) : bench_run((int32_t)reps);
            t1 = now_s();
            CALLGRIND_TOGGLE_COLLECT;
            CALLGRIND_DUMP_STATS_AT(label);
            printf("%s steps %zu ns_per_step %.1f checksum %08x digest %08x\n", label,
                   n * (size_t)reps, 1e9 * (t1 - t0) / ((double)n * reps), (unsigned)sum,
                   (unsigned)(arith ? flt_bench_digest() : bench_digest()));
        }
    }
    for (arith = 0; arith < 2; arith++) {
        const char *label = arith ? "protect_float" : "protect_fixed";
        double t0, t1;
        uint32_t sum;
        CALLGRIND_TOGGLE_COLLECT;
        t0 = now_s();
        sum = arith ? flt_bench_protect_run((int32_t)reps) : bench_protect_run((int32_t)reps);
        t1 = now_s();
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS_AT(label);
        printf("%s steps %zu ns_per_step %.1f checksum %08x\n", label, n * (size_t)reps,
               1e9 * (t1 - t0) / ((double)n * reps), (unsigned)sum);
    }
    return 0;
}

int main(int argc, char **argv)
{
    bench_args_t args = {false, 5.0, 0u};
    const int rc = parse_args(argc, argv, &args);
    if (rc != 0) {
        return rc;
    }
    args.n = bench_prepare(points, args.n);
    (void)flt_bench_prepare(points, args.n);
    printf("points %zu reps %d\n", args.n, (int)args.reps);
    return args.worst_step ? run_worst_steps(args.n) : run_measured(args.n, args.reps);
}
