/*
 * `sixphase-sim sweep`: a grid over run options, run in parallel, one table.
 *
 *   sixphase-sim sweep --out DIR [--jobs N] [--force] [--no-plots] [--quiet] RUN OPTIONS
 *
 * Any run option that takes a number or a choice may be given as a list (a,b,c) or, for
 * numbers, a range start:stop:step (stop included when the steps land on it): for example
 * `--controller ddc,mptc49 --scenario steady --lambda 10:200:10 --fs 7500,10000`. Every grid
 * point is checked as `sixphase-sim run` would check it before anything runs.
 *
 * DIR/sweep.csv and DIR/sweep.json hold one row per point (the swept options and every
 * metric of the run); DIR/points/ one small file per finished point, so an interrupted sweep
 * rerun with the same arguments runs only the missing points; DIR/plots/ each metric against
 * the first swept option and the trade-off of THD and torque ripple against switching
 * frequency with the Pareto front (matplotlib). At most SWEEP_MAX_POINTS points without
 * --force.
 */
#ifndef SIM_SWEEP_H
#define SIM_SWEEP_H

#define SWEEP_MAX_POINTS 400
#define SWEEP_MAX_AXES 4
#define SWEEP_MAX_VALUES 256

/* argv[0] is the first option after `sweep`. Returns the process exit status. */
int sim_sweep_main(int argc, char **argv);

#endif /* SIM_SWEEP_H */
