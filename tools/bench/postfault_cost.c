/*
 * The post-fault control step's cost (docs/design.md, "Open-phase operation"): replays the
 * periods of a ride-through run after the isolation (trace.csv of `sixphase-sim run
 * --ride-through`) in torque mode through ctl_step of one controller, with the open phase of the
 * run or with all six phases healthy, the command in force each step's own.
 *
 *   postfault-cost TRACE CONTROLLER LEG [--worst-step]
 *       CONTROLLER 0 DDC, 1 MPTC-49, 2 MPTC-13; LEG -1 (healthy) .. 5
 *
 * Built once per arithmetic (callgrind counts ctl_step: postfault_cost.sh) and once more with
 * CTL_COUNT_OPS, when it prints the worst step's primitive operations priced as
 * tools/bench/run_benchmark.py prices them for the F28335. With --worst-step every step is
 * collected and dumped on its own (run under callgrind with --collect-atstart=no
 * --combine-dumps=yes), labelled "p-<controller>_<arith>-<step>": run_benchmark.py's budget
 * for the post-fault step.
 */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <valgrind/callgrind.h>

#include "ctl.h"
#include "ctl_pu.h"

#define MAX_POINTS 20000
#define FROM_S 0.33 /* after the isolation at 0.32 s */

static ctl_t ctl;
static ctl_meas_t meas[MAX_POINTS];
static ctl_q torque_ref[MAX_POINTS];

/* The trace's periods from FROM_S on; the count, or -1. */
static int read_trace(const char *path)
{
    FILE *f = fopen(path, "r");
    char line[1024];
    int n = 0;
    if (!f || !fgets(line, sizeof line, f)) {
        return -1;
    }
    while (n < MAX_POINTS && fgets(line, sizeof line, f)) {
        double v[17];
        char *s = line;
        int k;
        for (k = 0; k < 17; k++) {
            v[k] = strtod(s, &s);
            s += (*s == ',') ? 1 : 0;
        }
        if (v[0] < FROM_S) {
            continue;
        }
        for (k = 0; k < 6; k++) {
            meas[n].i_phase[k] = ctl_from_float((float)(v[3 + k] / CTL_BASE_CURRENT_A));
        }
        meas[n].vdc = ctl_from_float((float)(540.0 / CTL_BASE_VOLTAGE_V));
        meas[n].theta_e = ctl_from_float((float)(v[2] / CTL_TWO_PI));
        meas[n].omega_e =
            ctl_from_float((float)(v[1] * CTL_TWO_PI / 60.0 * 3.0 / CTL_BASE_OMEGA_RAD_S));
        torque_ref[n] = ctl_from_float((float)(v[16] / CTL_BASE_TORQUE_NM));
        n++;
    }
    (void)fclose(f);
    return n;
}

/* One step: alone under callgrind with --worst-step, priced by its operations in the
 * CTL_COUNT_OPS build (the worst estimate, cycles, kept in *worst). */
static void measured_step(int i, int controller, bool each, double *worst, ctl_cmd_t *cmd)
{
#if defined(CTL_COUNT_OPS)
    /* run_benchmark.py's prices (cycles per primitive) and overhead factor */
    static const double fixed[CTL_OP_KINDS] = {10, 14, 60, 150, 25};
    static const double flt[CTL_OP_KINDS] = {2, 2, 15, 25, 20};
    double cycles = 0.0;
    int k;
    for (k = 0; k < CTL_OP_KINDS; k++) {
        ctl_op_counts[k] = 0u;
    }
    ctl_step(&ctl, &meas[i], cmd);
    for (k = 0; k < CTL_OP_KINDS; k++) {
        cycles += (double)ctl_op_counts[k] * (CTL_MATH_FLOAT ? flt[k] : fixed[k]);
    }
    *worst = (1.5 * cycles > *worst) ? 1.5 * cycles : *worst;
    (void)controller;
    (void)each;
#else
    (void)worst;
    if (each) {
        char label[64];
        snprintf(label, sizeof label, "p-%s_%s-%d", ctl_controller_name(controller),
                 CTL_MATH_FLOAT ? "float" : "fixed", i);
        CALLGRIND_TOGGLE_COLLECT;
        ctl_step(&ctl, &meas[i], cmd);
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS_AT(label);
    } else {
        ctl_step(&ctl, &meas[i], cmd);
    }
#endif
}

/* An integer argument within [lo, hi], or a one-line error. */
static int parse_int(const char *what, const char *text, long lo, long hi, int *out)
{
    char *end;
    const long v = strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < lo || v > hi) {
        fprintf(stderr, "postfault-cost: %s must be %ld..%ld, got '%s'\n", what, lo, hi, text);
        return -1;
    }
    *out = (int)v;
    return 0;
}

int main(int argc, char **argv)
{
    ctl_params_t p;
    unsigned long checksum = 0u;
    double worst = 0.0;
    bool each = false;
    int controller;
    int leg;
    int n;
    int i;
    if (argc == 5 && strcmp(argv[4], "--worst-step") == 0) {
        each = true;
    } else if (argc != 4) {
        fprintf(stderr, "postfault-cost: usage: postfault-cost TRACE CONTROLLER LEG "
                        "[--worst-step]\n");
        return 2;
    }
    if (parse_int("CONTROLLER", argv[2], 0, CTL_CONTROLLER_COUNT - 1, &controller) != 0 ||
        parse_int("LEG", argv[3], -1, 5, &leg) != 0) {
        return 2;
    }
    if ((n = read_trace(argv[1])) <= 0) {
        fprintf(stderr, "postfault-cost: no periods after %.2f s in %s\n", FROM_S, argv[1]);
        return 2;
    }
    ctl_params_default(&p);
    p.controller = (ctl_controller_t)controller;
    p.open_phase = (int16_t)leg;
    if (!ctl_init(&ctl, &p)) {
        fprintf(stderr, "postfault-cost: parameters refused\n");
        return 2;
    }
    ctl_set_loop_mode(&ctl, CTL_LOOP_TORQUE);
    for (i = 0; i < n; i++) {
        ctl_cmd_t cmd;
        int k;
        ctl_set_torque_ref(&ctl, torque_ref[i]);
        measured_step(i, controller, each, &worst, &cmd);
        checksum = checksum * 31u + (unsigned long)cmd.vector;
        for (k = 0; k < CTL_PHASES; k++) { /* the duties too, bit for bit */
            uint32_t bits;
            memcpy(&bits, &cmd.leg_duty[k], sizeof bits);
            checksum = checksum * 31u + bits;
        }
    }
    printf("steps %d checksum %lu", n, checksum);
    if (worst > 0.0) {
        printf(" worst estimate %.0f cycles %.1f us", worst, worst / 150.0);
    }
    printf("\n");
    return 0;
}
