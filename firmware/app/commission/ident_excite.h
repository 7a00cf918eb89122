/*
 * Excitation for the motor identification (commissioning, docs/commissioning.md): the
 * amplitude-invariant VSD of the six phase currents, a rotation into a frame, a current
 * regulator (a PI per axis in a chosen frame for alpha-beta and in the stationary x-y plane,
 * each with a voltage limit, which can be held while a test voltage is injected on top), the
 * modulator that turns the stationary voltage request into six leg duties, and a commanded
 * angle that moves with limited acceleration. Single-precision float, SI units (A, V, s),
 * angles in turns; bounded work per control period.
 */
#ifndef IDENT_EXCITE_H
#define IDENT_EXCITE_H

#include <stdbool.h>
#include <stdint.h>

#include "hal_pwm.h"

#define IDENT_PHASES 6

/* Sine and cosine of an angle in turns (the control core's table, any angle). */
void ident_sincos(float turns, float *s, float *c);

/* Angle in (-0.5, 0.5] turn of a difference of angles in turns. */
float ident_wrap_half(float turns);

/* An HAL angle (2^32 = one turn) in turns, [0, 1). */
float ident_turns_u32(uint32_t angle);

/* alpha, beta, x, y of the six phase currents (or voltages), amplitude invariant. */
void ident_vsd(const float phase[IDENT_PHASES], float out[4]);

/* Phase k's value of (alpha, beta, x, y): the inverse, each set's neutral floating. */
float ident_vsd_phase(const float v[4], int16_t k);

/* (a, b) into a frame at the angle whose sine and cosine are s, c; and back. */
void ident_to_frame(float a, float b, float s, float c, float out[2]);
void ident_from_frame(float d, float q, float s, float c, float out[2]);

/* A PI controller: proportional gain, integral gain times the period, its integrator. */
typedef struct {
    float kp, ki_ts, integ;
} ident_pi_t;

/* Axes of the regulator (a held axis keeps its output, integrator frozen, and gets the
 * injection added; the others regulate). */
#define IDENT_HOLD_D 0x1u
#define IDENT_HOLD_Q 0x2u
#define IDENT_HOLD_X 0x4u
#define IDENT_HOLD_Y 0x8u

/* The current regulator: d, q in the frame the caller chooses (the commanded angle or the
 * rotor's), x, y stationary. */
typedef struct {
    ident_pi_t d, q, x, y;
    float kp_dq, ki_ts_dq;  /* the nominal d and q gains */
    float limit_dq;         /* |u_dq| limit, V */
    float limit_xy;         /* |u_x|, |u_y| limit, V */
    uint16_t hold;          /* IDENT_HOLD_* of the axes held */
    float u_dq[2], u_xy[2]; /* the PIs' outputs (kept while held) */
    float inject_dq[2];     /* test voltage added in the frame, V */
    float inject_xy[2];     /* test voltage added in x-y, V */
    float u[4];             /* the request: alpha, beta, x, y, V */
    bool saturated;         /* a limit clipped the output this period */
} ident_reg_t;

/* Gains for a bandwidth of bw_rad_s with the inductances given: kp = L bw, ki = kp bw / 3 (a
 * disturbance such as a dead-time step decays at about bw / 2, not at R / L); integrators
 * cleared, every axis regulating. */
void ident_reg_init(ident_reg_t *r, float l_dq, float l_xy, float bw_rad_s, float ts,
                    float limit_dq, float limit_xy);

/* The d and q gains: kp (ohm) and ki (ohm/s), or back to the ones of ident_reg_init. */
void ident_reg_gains_dq(ident_reg_t *r, float kp, float ki, float ts);
void ident_reg_gains_nominal(ident_reg_t *r);

/* Hold an axis at the output u (V) from now on (its integrator set to it). */
void ident_reg_hold(ident_reg_t *r, uint16_t axis, float u);

/* One period: the output angle's sine and cosine, references and measurements in the frame
 * (d, q) and in x-y; fills r->u. */
void ident_reg_step(ident_reg_t *r, float s, float c, const float ref_dq[2], const float i_dq[2],
                    const float ref_xy[2], const float i_xy[2]);

/* Six leg duties (HAL unsigned Q15) for the stationary voltage request u (alpha, beta, x, y, V)
 * on a DC link of vdc: duty = 1/2 + v_k / vdc per phase, clamped to 0..1. */
void ident_modulate(const float u[4], float vdc, uint16_t duty[IDENT_PHASES]);

/* A commanded angle that moves at a speed ramped with limited acceleration. */
typedef struct {
    float angle;  /* turns, [0, 1) */
    float travel; /* turns moved since ident_traj_reset, signed */
    float speed;  /* turns/s */
    float target; /* turns/s the speed ramps to */
    float accel;  /* turns/s^2 */
} ident_traj_t;

void ident_traj_reset(ident_traj_t *t, float angle);
/* One period of ts seconds. */
void ident_traj_step(ident_traj_t *t, float ts);

#endif /* IDENT_EXCITE_H */
