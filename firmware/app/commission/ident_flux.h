/*
 * Identification step 6, the magnet flux, with the rotor turning. The current is regulated in
 * the rotor's frame (the encoder's angle plus the identified offset, the output rotated ahead
 * by the 1.5 periods until the voltage acts); a speed loop gives i_q and takes the rotor to a
 * steady speed (the lower of 10 % of the DC link over the parameter set's flux and 30 % of the
 * over-speed limit: 600 r/min on the reference machine). i_d is held at +I and then at -I (the
 * test current). Over ten whole electrical turns each, counted on the encoder:
 *   u_q = R i_q + w (L_d i_d + psi_f) + Vdt_q,   u_d = R i_d - w L_q i_q + Vdt_d
 * where Vdt is the dead-time voltage (and the devices' drops): Vd times the phase currents'
 * signs, s = VSD(sign(i_k)) in the rotor frame, the pattern the inverter itself follows. With
 * the current along +d or -d that vector lies along d and flips with i_d; only its small q
 * part (from i_q, which carries friction, and from the x-y harmonic currents that shift the
 * zero crossings) reaches u_q. Vd comes from the two runs' u_d (Vd s_d flips with i_d, the
 * rest does not), and Vd s_q is taken out of each run's u_q:
 *   Vd = [(u_d - R i_d + w L_q i_q)+ - (...)-] / (s_d+ - s_d-)
 *   psi_f = mean over the runs of (u_q - R i_q - w L_d i_d - Vd s_q) / w
 * where w L_d i_d cancels between +I and -I up to their difference (L_d the identified one if
 * the inductance step ran, else the parameter set's) and the 6th-harmonic ripple of the dead
 * time averages out over whole turns. Every term is a mean over whole turns of per-period
 * values. The voltage is the regulator's request, the speed the encoder's count over the
 * turns. About 3.5 s. A run starts once the speed has stayed near its target for a while (at most
 * FLUX_SETTLE_MAX_S): the test current's torque comes from the machine's flux, so a weak magnet
 * reaches the speed late (issue 25); the speed loop's gain comes from the inertia the ramp up
 * showed. A run's turns must agree in speed within +-5 % (else POOR, NO_SPEED), at whatever
 * speed friction lets the rotor hold. The step ends once the rotor stands again (at most 4 s
 * after the ramp down). The x-y harmonic regulator runs throughout (ident_xy_harmonics.h).
 */
#ifndef IDENT_FLUX_H
#define IDENT_FLUX_H

#include "ident.h"

typedef struct {
    int16_t run;         /* 0: +I, 1: -I */
    float speed_ref;     /* rad/s electrical, ramped */
    float speed_target;  /* rad/s electrical */
    ident_pi_t speed_pi; /* i_q from the speed error */
    float iq_time; /* A s: i_q's integral over the ramp up (the inertia the loop is tuned for) */
    int32_t turn_start;                                   /* position at the open turn's start */
    float sum_ud, sum_uq, sum_id, sum_iq, sum_sd, sum_sq; /* over the open turn */
    int32_t n;                                            /* samples in it */
    float run_ud[2], run_uq[2], run_id[2], run_iq[2], run_w[2], run_sd[2], run_sq[2]; /* means */
    int32_t run_n[2];                 /* turns in each run */
    ident_blocks_t psi[2];            /* per-turn raw estimates (without the dead-time q part) */
    float run_w_min[2], run_w_max[2]; /* each run's slowest and fastest turn, rad/s */
    uint32_t in_band; /* consecutive settling periods with the speed near its target */
} ident_flux_t;

void ident_flux_begin(ident_ctx_t *x, ident_flux_t *s);
ident_status_t ident_flux_step(ident_ctx_t *x, ident_flux_t *s, const ident_input_t *in);

#define IDENT_FLUX_SECONDS 3.5f

#endif /* IDENT_FLUX_H */
