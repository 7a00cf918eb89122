/*
 * ctl-opcount-fixed / ctl-opcount-float: arithmetic operations per control step of the core
 * (a build with CTL_COUNT_OPS), mean and worst case over recorded operating points, per
 * controller. The counts feed the F28335 time estimate in docs/performance.md.
 *
 * usage: ctl-opcount-ARITH TRACE.csv...
 */
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "ctl_params.h"
#include "ctl_q.h"
#include "trace_csv.h"

static bench_point_t points[BENCH_MAX_POINTS];

int main(int argc, char **argv)
{
#define OPCOUNT_CONTROLLER_NAME(id, number, name, what) name,
    static const char *names[CTL_CONTROLLER_COUNT] = {CTL_CONTROLLER_LIST(OPCOUNT_CONTROLLER_NAME)};
#undef OPCOUNT_CONTROLLER_NAME
    static const char *ops[CTL_OP_KINDS] = {"add", "mul", "div", "sqrt", "sin"};
    size_t n = 0;
    int a;
    int16_t controller;
    for (a = 1; a < argc; a++) {
        long got;
        if (argv[a][0] == '-') {
            fprintf(stderr, "ctl-opcount: unknown option '%s' (usage: ctl-opcount TRACE.csv...)\n",
                    argv[a]);
            return 2;
        }
        got = trace_csv_read(argv[a], points, n, BENCH_MAX_POINTS, 540.0, "ctl-opcount");
        if (got < 0) {
            return 1;
        }
        n = (size_t)got;
    }
    if (n == 0) {
        fprintf(stderr, "ctl-opcount: no operating points (usage: ctl-opcount TRACE.csv...)\n");
        return 2;
    }
    n = bench_prepare(points, n);
    for (controller = 0; controller < CTL_CONTROLLER_COUNT; controller++) {
        double sum[CTL_OP_KINDS] = {0};
        uint32_t max[CTL_OP_KINDS] = {0};
        size_t i;
        int16_t k;
        if (bench_setup(controller) != 0) {
            fprintf(stderr, "ctl-opcount: controller %s did not initialise\n", names[controller]);
            return 1;
        }
        for (i = 0; i < n; i++) {
            memset(ctl_op_counts, 0, sizeof ctl_op_counts);
            (void)bench_step(i);
            for (k = 0; k < CTL_OP_KINDS; k++) {
                sum[k] += (double)ctl_op_counts[k];
                if (ctl_op_counts[k] > max[k]) {
                    max[k] = ctl_op_counts[k];
                }
            }
        }
        printf("%s", names[controller]);
        for (k = 0; k < CTL_OP_KINDS; k++) {
            printf(" %s_mean %.2f %s_max %u", ops[k], sum[k] / (double)n, ops[k], (unsigned)max[k]);
        }
        printf("\n");
    }
    return 0;
}
