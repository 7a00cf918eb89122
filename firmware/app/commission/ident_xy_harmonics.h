/*
 * Harmonic current regulation in the x-y plane for the identification steps that turn the
 * rotor (flux, mechanics). The magnet's 5th and 7th flux harmonics and the dead time's
 * residual drive x-y currents at 5 and 7 times the electrical frequency, which the x-y PI
 * (150 Hz) only partly rejects. With the 5th and 7th harmonic flux those currents make a torque
 * the fundamental's estimate leaves out: a drag that grows faster than the speed (5 % of the
 * friction on the reference machine, enough to push the friction outside its limit, issue 25).
 *
 * One integrator per sequence (+5, -5, +7, -7) in a frame turning at that multiple of the
 * rotor's angle, in parallel with the PI (the synchronous-frame harmonic PI of six-phase
 * current control, e.g. Che, Levi et al., IEEE TPEL 29(1), 2014). Each integrator's gain is
 * the impedance its frame sees (the machine's R + j h w L_xy and the PI's own kp and ki, which
 * act on the same error) times the rate KH: each harmonic current then decays as exp(-KH t)
 * whatever the speed, with no phase to tune. Below MIN_SPEED the integrators hold (the
 * impedance's PI part grows without bound as the frequency goes to zero).
 */
#ifndef IDENT_XY_HARMONICS_H
#define IDENT_XY_HARMONICS_H

#include <stdbool.h>

#define IDENT_XY_SEQUENCES 4 /* +5, -5, +7, -7 */

typedef struct {
    bool on;
    float integ[IDENT_XY_SEQUENCES][2]; /* V, in each sequence's frame */
} ident_xy_harmonics_t;

/* What one period's regulation needs: the rotor's angle at the measurement and at the output
 * (sine, cosine), its electrical speed (rad/s), the machine's R and L_xy, the x-y PI's gains
 * (kp in ohm, ki times the period), the period. */
typedef struct {
    float s_meas, c_meas, s_out, c_out;
    float w_e;
    float r, l_xy;
    float kp, ki_ts, ts;
} ident_xy_harmonics_in_t;

/* Off, integrators cleared. */
void ident_xy_harmonics_reset(ident_xy_harmonics_t *h);

/* Switch on (integrators from zero). */
void ident_xy_harmonics_start(ident_xy_harmonics_t *h);

/* One period: from the x-y current error (reference minus measurement, A), the voltage to add
 * to the x-y request (V); zero while off. */
void ident_xy_harmonics_step(ident_xy_harmonics_t *h, const ident_xy_harmonics_in_t *in,
                             const float err_xy[2], float u_xy[2]);

#endif /* IDENT_XY_HARMONICS_H */
