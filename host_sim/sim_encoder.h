/*
 * The simulated incremental encoder behind the eQEP: quadrature x4 count of the mechanical
 * angle, the electrical angle of the counted position, the speed from edge timing (count
 * change over the last 1 ms divided by the time between the latest edges at both ends of
 * that window: eQEP capture, "T-method"; edge times interpolated between samples), and the
 * HAL's edge watchdog (no edge for 10 ms after turning faster than 5 rev/s: signal lost,
 * latched), and the index at mechanical angle 0, which re-homes the HAL after
 * hal_encoder_rehome. With quantisation off the encoder reports the exact angle and speed.
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
    bool first;                /* the next sample starts the speed window afresh */
    double index_lo, index_hi; /* the mechanical turn of the last sample, rad (the index sits at
                                  theta_m = 0 mod 2 pi) */
    bool index_known;
} sim_encoder_t;

void sim_encoder_init(sim_encoder_t *enc, double ts);

/* Forget the speed history (the rotor was repositioned): the next sample refills the window
 * as if the shaft had turned at its present speed before. */
void sim_encoder_restart(sim_encoder_t *enc);

/* Read the shaft at time t (period ts), let the fault act and post the reading to the HAL. */
void sim_encoder_sample(sim_encoder_t *enc, const plant_params_t *p, const plant_state_t *x,
                        double t, double ts, sim_fault_state_t *fs);

#endif /* SIM_ENCODER_H */
