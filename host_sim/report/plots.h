/*
 * The simulator's figures, drawn by Python scripts with matplotlib (found at configure time,
 * cmake/plot_python.cmake): the reproduce report's, a sweep's, and one run's.
 */
#ifndef SIM_PLOTS_H
#define SIM_PLOTS_H

typedef enum {
    SIM_PLOT_REPRODUCE = 0, /* host_sim/report/plot_reproduce.py DIR -> DIR/plots/ */
    SIM_PLOT_SWEEP = 1,     /* host_sim/report/plot_sweep.py DIR -> DIR/plots/ */
    SIM_PLOT_RUN = 2        /* host_sim/report/plot_run.py DIR -> DIR/run.png */
} sim_plot_t;

/* Runs the script on dir; 0 on success, -1 after a one-line message on stderr (no Python
 * with matplotlib, or the script failed). */
int sim_plot(sim_plot_t which, const char *dir);

#endif /* SIM_PLOTS_H */
