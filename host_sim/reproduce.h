/* `sixphase-sim reproduce`: the paper's comparison, report and plots. */
#ifndef SIM_REPRODUCE_H
#define SIM_REPRODUCE_H

/* Runs every case (fork, `jobs` at a time), writes DIR/report.md, DIR/summary.json,
 * DIR/runs/CASE/ and DIR/plots/ (PNG). Returns the process exit status. */
int sim_reproduce(const char *out_dir, int jobs, int quiet);

#endif /* SIM_REPRODUCE_H */
