/*
 * The simulated incremental encoder behind the eQEP: quadrature x4 count of the mechanical
 * angle, the electrical angle of the counted position, the speed from edge timing (count
 * change over the last 1 ms divided by the time between the latest edges at both ends of
 * that window: eQEP capture, "T-method"; edge times interpolated between samples), and the
 * HAL's edge watchdog (no edge for 10 ms after turning faster than 5 rev/s: signal lost,
 * latched), and the index pulse, which re-homes the HAL after hal_encoder_rehome. With
 * quantisation off the encoder reports the exact angle and speed.
 *
 * The interface counts from its power-up position until the index pulse has been seen (a
 * rotor that has not yet passed it), then from the index; the angle is computed with the
 * drive's configuration of the HAL (pole pairs, offset: hal_sim_bus), as the eQEP driver
 * computes it, so a drive configured for the wrong machine sees what it would see on the
 * bench. The plant says where the index sits and whether A and B are swapped
 * (plant_params_t).
 */
#ifndef SIM_ENCODER_H
#define SIM_ENCODER_H

#include <stdbool.h>
#include <stdint.h>

#include "fault_inject.h"
#include "plant.h"

/* The speed window is 1 ms: 100 periods at the highest sampling rate (100 kHz). */
#define SIM_ENCODER_RING_MAX 128

typedef struct {
    int64_t count_prev;
    double pos_prev; /* counts, continuous */
    double edge_t_prev;
    double edge_speed_rev_s; /* speed reported while the count still moved */
    bool qep_error;          /* signal loss latched, as the eQEP HAL does */
    int64_t ring_count[SIM_ENCODER_RING_MAX];
    double ring_t[SIM_ENCODER_RING_MAX];
    int ring_len, ring_pos;
    bool first; /* the next sample starts the speed window afresh */
    /* counting and the index */
    bool index_seen;
    bool turn_known;    /* turn_prev holds the last sample's turn (false after a restart) */
    int64_t count0;     /* count at power-up: the interface counts from there */
    int64_t turn_prev;  /* floor(count / counts per turn): a change is an index pulse */
    int64_t turn_lo;    /* turn_prev * counts per turn: the turn's first count */
    double theta_stuck; /* the shaft angle a stuck encoder keeps reporting */
    double shaft0_rad;  /* the counted shaft angle at power-up (exact angle before the index) */
} sim_encoder_t;

void sim_encoder_init(sim_encoder_t *enc, double ts);

/* The interface powers up with the rotor at x: homed, the index counts as seen from the start
 * (every scenario but commissioning: the rotor was turned past it before); otherwise it counts
 * from here until the rotor passes the index. */
void sim_encoder_power_up(sim_encoder_t *enc, const plant_params_t *p, const plant_state_t *x,
                          bool homed);

/* Forget the speed history (the rotor was repositioned): the next sample refills the window
 * as if the shaft had turned at its present speed before. */
void sim_encoder_restart(sim_encoder_t *enc);

/* Read the shaft at time t (period ts), let the fault act and post the reading to the HAL. */
void sim_encoder_sample(sim_encoder_t *enc, const plant_params_t *p, const plant_state_t *x,
                        double t, double ts, sim_fault_state_t *fs);

#endif /* SIM_ENCODER_H */
