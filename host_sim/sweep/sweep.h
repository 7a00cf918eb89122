/*
 * `sixphase-sim sweep`: a grid over run options, run in parallel, one table.
 *
 *   sixphase-sim sweep --out DIR [--jobs N] [--force] [--no-plots] [--quiet] RUN OPTIONS
 *
 * Any run option that takes a number or a choice may be given as a list (a,b,c) or, for
 * numbers, a range start:stop:step (stop included when the steps land on it): for example
 * `--controller ddc,mptc49 --lambda 10:200:10 --fs 7500,10000,12500`. The other run options
 * are passed to every point; without --scenario the points run the steady scenario. Every
 * grid point is checked as `sixphase-sim run` would check it before anything runs; the points
 * run in --jobs worker processes (default: the online processors).
 *
 * DIR/sweep.csv and DIR/sweep.json hold one row per point: the options given and everything
 * the run's metrics.json holds but the host timings (sweep_table.h), and the point's outcome
 * (ok, fault: the drive stopped in a fault, failed: the run did not finish). DIR/points/ keeps
 * one file per finished point (sweep_points.h), so an interrupted sweep rerun by the same
 * binary with the same arguments runs only the missing or damaged points. DIR/plots/
 * (plot_sweep.py): each metric against the first swept option and the trade-off of THD and torque
 * ripple against switching frequency with the Pareto front, from the ok points only. At most
 * SWEEP_MAX_POINTS points without --force. A summary line on stderr counts the points of each
 * outcome and names the faults.
 */
#ifndef SIM_SWEEP_H
#define SIM_SWEEP_H

#define SWEEP_MAX_POINTS 400

/* argv[0] is the first option after `sweep`. Returns the process exit status. */
int sim_sweep_main(int argc, char **argv);

#endif /* SIM_SWEEP_H */
