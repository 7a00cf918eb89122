/*
 * The simulator's figures, drawn by Python scripts with matplotlib (found at configure time,
 * cmake/plot_python.cmake): the reproduce report's, a sweep's, and one run's.
 */
#ifndef SIM_PLOTS_H
#define SIM_PLOTS_H

typedef enum {
    SIM_PLOT_REPRODUCE = 0, /* host_sim/report/plot_reproduce.py DIR -> DIR/plots/ */
    SIM_PLOT_SWEEP = 1,     /* host_sim/report/plot_sweep.py DIR -> DIR/plots/ */
    SIM_PLOT_RUN = 2,       /* host_sim/report/plot_run.py DIR -> DIR/run.png */
    SIM_PLOT_PIL = 3        /* host_sim/report/plot_pil.py DIR -> DIR/pil.png (run --pil) */
} sim_plot_t;

/* Runs the script on dir; 0 on success, -1 after a one-line message on stderr (no Python
 * with matplotlib, or the script failed). */
int sim_plot(sim_plot_t which, const char *dir);

/* The same in parts, so that the figures are drawn while the caller goes on (reproduce draws its
 * runs' figures while its last runs compute): start runs the script on dir, with part as its
 * second argument when not NULL, in a child process whose standard input stays open until
 * sim_plot_open_gate (the script's cue that the rest of its input is written); finish opens
 * the gate if still closed and collects the script. */
typedef struct {
    int pid;     /* -1: not running */
    int fd;      /* the script's stderr */
    int gate_fd; /* the write end of its stdin, -1 once closed */
    char script[1200];
    char what[1400];
} sim_plot_job_t;
int sim_plot_start(sim_plot_t which, const char *dir, const char *part, sim_plot_job_t *job);
void sim_plot_open_gate(sim_plot_job_t *job);
int sim_plot_finish(sim_plot_job_t *job);
/* Ends a started script before its gate (its remaining input will not come): stopped and
 * collected, no message. */
void sim_plot_cancel(sim_plot_job_t *job);

#endif /* SIM_PLOTS_H */
