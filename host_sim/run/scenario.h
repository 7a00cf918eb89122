/*
 * What one run simulates: the scenario's plan (speeds, load, event time, duration, analysis
 * window, speed-loop torque limit) from the configuration, and the load torque over time.
 */
#ifndef SIM_SCENARIO_H
#define SIM_SCENARIO_H

#include "sim_config.h"

/* Default length of the ride-through fault runs (sim_open_phase.h): injection, detection, the
 * hand-off, the recovery and a 0.2 s analysis window of five-leg operation. */
#define SIM_OPEN_PHASE_DURATION_S 0.8

typedef struct {
    double speed;        /* r/min: final reference */
    double speed0;       /* r/min: initial speed and reference */
    double load;         /* N*m after the event (steady: from the start, ramped) */
    double load0;        /* N*m before the event */
    double duration;     /* s */
    double t_event;      /* s: reference or load step */
    double window;       /* s: analysis window at the end of the run */
    double torque_limit; /* N*m: speed-loop output limit */
    double theta0_rad;   /* mechanical angle of the rotor at power-up (commission: from the
                          * seed, anywhere; the others: 0, at the index) */
} sim_plan_t;

void sim_plan(const sim_config_t *c, sim_plan_t *pl);

/* Load torque (N*m) at scenario time t, before any injected fault. */
double sim_load_at(const sim_config_t *c, const sim_plan_t *pl, double t);

#endif /* SIM_SCENARIO_H */
