/*
 * The post-fault control step's cost (docs/design.md, "Open-phase operation"): replays the
 * periods of a ride-through run after the isolation (trace.csv of `sixphase-sim run
 * --ride-through`) in torque mode through ctl_step of one controller, with the open phase of the
 * run or with all six phases healthy, the command in force each step's own.
 *
 *   postfault-cost TRACE CONTROLLER LEG     CONTROLLER 0 DDC, 1 MPTC-49, 2 MPTC-13; LEG -1..5
 *
 * Built once per arithmetic (callgrind counts ctl_step: postfault_cost.sh) and once more with
 * CTL_COUNT_OPS, when it prints the worst step's primitive operations priced as
 * tools/bench/run_benchmark.py prices them for the F28335.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

int main(int argc, char **argv)
{
    ctl_params_t p;
    unsigned long checksum = 0u;
    double worst = 0.0;
    int n;
    int i;
    if (argc != 4 || (n = read_trace(argv[1])) <= 0) {
        fprintf(stderr, "postfault-cost: usage: postfault-cost TRACE CONTROLLER LEG\n");
        return 2;
    }
    ctl_params_default(&p);
    p.controller = (ctl_controller_t)atoi(argv[2]);
    p.open_phase = (int16_t)atoi(argv[3]);
    if (!ctl_init(&ctl, &p)) {
        fprintf(stderr, "postfault-cost: parameters refused\n");
        return 2;
    }
    ctl_set_loop_mode(&ctl, CTL_LOOP_TORQUE);
    for (i = 0; i < n; i++) {
        ctl_cmd_t cmd;
        ctl_set_torque_ref(&ctl, torque_ref[i]);
#if defined(CTL_COUNT_OPS)
        {
            /* run_benchmark.py's prices (cycles per primitive) and overhead factor */
            static const double fixed[CTL_OP_KINDS] = {10, 14, 60, 150, 25};
            static const double flt[CTL_OP_KINDS] = {2, 2, 15, 25, 20};
            double cycles = 0.0;
            int k;
            for (k = 0; k < CTL_OP_KINDS; k++) {
                ctl_op_counts[k] = 0u;
            }
            ctl_step(&ctl, &meas[i], &cmd);
            for (k = 0; k < CTL_OP_KINDS; k++) {
                cycles += (double)ctl_op_counts[k] * (CTL_MATH_FLOAT ? flt[k] : fixed[k]);
            }
            worst = (1.5 * cycles > worst) ? 1.5 * cycles : worst;
        }
#else
        ctl_step(&ctl, &meas[i], &cmd);
#endif
        checksum = checksum * 31u + (unsigned long)cmd.vector;
        for (int leg = 0; leg < CTL_PHASES; leg++) { /* the duties too, bit for bit */
            uint32_t bits;
            memcpy(&bits, &cmd.leg_duty[leg], sizeof bits);
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
