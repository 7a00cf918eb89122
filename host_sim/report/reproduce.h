/* `sixphase-sim reproduce`: the paper's comparison, report and plots. */
#ifndef SIM_REPRODUCE_H
#define SIM_REPRODUCE_H

#include <stdbool.h>

/* Runs every case (fork, `jobs` at a time), writes DIR/report.md, DIR/summary.json,
 * DIR/timings.md, DIR/runs/CASE/ and, with plots, DIR/plots/ (PNG). Returns the process exit
 * status. */
int sim_reproduce(const char *out_dir, int jobs, bool plots, int quiet);

#endif /* SIM_REPRODUCE_H */
