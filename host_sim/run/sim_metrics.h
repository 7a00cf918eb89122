/*
 * The run's metrics: what the analysis window keeps (the plant samples at the fine rate and
 * the control-period samples; bounded by the window, not the run), the transient trackers over
 * the whole run (one sample at a time), and the results computed from them at the end:
 * THD of each phase current and their mean, ripple, x-y rms and means over the same whole
 * fundamental periods, the sampled ripple, peak current and transient time.
 */
#ifndef SIM_SIM_METRICS_H
#define SIM_SIM_METRICS_H

#include <stdbool.h>
#include <stddef.h>

#include "record/metrics.h"
#include "record/recorder.h"
#include "sim_config.h"

typedef struct {
    /* plant samples of the analysis window */
    size_t n, cap;
    double *t, *theta, *i_phase[6], *i_x, *i_y, *te, *speed_rpm;
    /* control-period samples of the analysis window */
    size_t n_ctl, cap_ctl;
    double *t_ctl, *te_ctl;
    double phase_peak_a;
    double tref_sum; /* the controller's torque reference over the window's control periods */
    long tref_n;
    /* transients over the whole run */
    bool track_settle, track_reach;
    double t_event;
    metrics_settle_t settle;
    metrics_reach_t reach;
    /* the speed after the event of a motion scenario: settling into its band, and the largest
     * error once it first came within the band (the load step's dip, the reversal's overshoot) */
    bool track_speed, speed_reached;
    metrics_settle_t speed_settle;
    double speed_peak_error;
    double *block; /* one allocation holds every array */
} sim_metrics_t;

/* Room for fine_cap plant samples and ctl_cap control periods. 0 on success. */
int sim_metrics_open(sim_metrics_t *m, size_t fine_cap, size_t ctl_cap);
void sim_metrics_close(sim_metrics_t *m);

/* The transient the scenario asks for: the speed settling within tol of target after t_event
 * (acceleration, reversal), or the period-average torque first reaching level (load step). */
void sim_metrics_track_settle(sim_metrics_t *m, double t_event, double target, double tol);
void sim_metrics_track_reach(sim_metrics_t *m, double t_event, double level);
/* The speed after t_event against target within tol (every motion scenario). */
void sim_metrics_track_speed(sim_metrics_t *m, double t_event, double target, double tol);

void sim_metrics_add_fine(sim_metrics_t *m, const sim_fine_row_t *row, const double i_phase[6]);
void sim_metrics_add_period(sim_metrics_t *m, const sim_trace_row_t *row, bool in_window);

/* The window's results into r (THD, ripple, x-y, means, peak, transient). */
void sim_metrics_finish(const sim_metrics_t *m, sim_result_t *r);

#endif /* SIM_SIM_METRICS_H */
