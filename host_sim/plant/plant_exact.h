/*
 * Exact solution of the machine's electrical equations over one constant-voltage interval at
 * a held speed.
 *
 * With the speed w_e constant the electrical model is linear and time-invariant in the rotor
 * frame (d-q) and in the stationary x-y plane, driven by the interval's constant stationary
 * voltage (rotating at -w_e as seen from the rotor), the PM flux's back-EMF (constant in d-q)
 * and its 5th and 7th harmonics (rotating at 5 w_e and -7 w_e in x-y). Each plane's solution is
 * a forced response that follows the drive plus a free response that decays:
 *
 *   i(t0 + h) = i_p(t0 + h) + Phi(h) (i(t0) - i_p(t0))
 *
 * d-q: Phi = e^{A h} of the 2x2 system matrix, written as e^{sigma h} (C(h) I + S(h) (A - sigma I))
 *      with C, S the cos / sin (or cosh / sinh) of the eigenvalue pair; i_p = X Park(u) + p0, X
 *      solving A X - X W = -L^-1 for the rotating drive W, p0 = -A^-1 (back-EMF / L).
 * x-y: as a complex number, Phi = e^{-R h / L_xy}, i_p = u / R + k5 e^{j 5 th} + k7 e^{-j 7 th}.
 *
 * The coefficients that depend on the speed are computed once per control period
 * (plant_exact_set_speed); the rest once per parameter set (plant_exact_init). No step-size
 * error: only rounding, and the held speed (the speed changes by under 0.1 % within a period at
 * these inertias; docs/simulator.md gives the measured effect).
 *
 * Needs a resistance (a loss-free circuit driven at its own frequency has no bounded forced
 * response) and no extra phase resistance (a single-phase resistance makes the d-q equations
 * depend on the angle): plant_exact_applies() says when; plant_stepper.c falls back to RK4.
 */
#ifndef SIM_PLANT_EXACT_H
#define SIM_PLANT_EXACT_H

#include <stdbool.h>

#include "plant.h"

typedef struct {
    /* from the parameters */
    double pn, r, inv_r, ld, lq, inv_ld, inv_lq, psi_f, t3pn, ld_minus_lq;
    double five_psi5, seven_psi7, inv_lxy, a_xy; /* a_xy = R / L_xy */
    bool harm;
    double half_diff_sq, a00_a11, a_trace, n1_re, n2_im, a_xy_sq; /* set_speed's constant parts */
    /* at the held speed (a[0][0], a[1][1] and sigma from the parameters) */
    double omega_m, w_e; /* mechanical and electrical rad/s */
    double a[2][2];      /* d-q system matrix */
    double sigma, q;     /* (A - sigma I)^2 = -q I */
    double x[2][2];      /* forced d-q response per rotor-frame volt */
    double p0_d, p0_q;   /* forced d-q response to the PM back-EMF */
    double k5_re, k5_im; /* forced x-y response to the 5th-harmonic EMF, per e^{j 5 th} */
    double k7_re, k7_im; /* forced x-y response to the 7th-harmonic EMF, per e^{-j 7 th} */
} plant_exact_t;

/* The instant an interval starts from, with what its end gives the next interval for free. */
typedef struct {
    double c5, s5, c7, s7; /* e^{j 5 th}, e^{j 7 th} of the electrical angle */
    double harm_x, harm_y; /* forced x-y response to the harmonic EMF (continuous in time) */
    double torque_nm;
} plant_exact_point_t;

/* What an interval's solution needs of its length h alone, not of the speed: the decay of the
 * free response in both planes. The inverter's switching programs repeat (inverter_program.h),
 * so this is computed once per interval of a program rather than once per interval run. */
typedef struct {
    double decay_dq; /* e^{sigma h} */
    double decay_xy; /* e^{-R h / L_xy} */
} plant_exact_span_t;

/* True when the exact solution applies to these parameters. */
bool plant_exact_applies(const plant_params_t *p);

/* The parameter-dependent coefficients (call again when the parameters change). */
void plant_exact_init(plant_exact_t *e, const plant_params_t *p);

/* The speed-dependent coefficients for a held mechanical speed (rad/s). */
void plant_exact_set_speed(plant_exact_t *e, double omega_m);

/* The harmonic phasors and the torque of state s (cos_e / sin_e must be current). */
void plant_exact_point(const plant_exact_t *e, const plant_state_t *s, plant_exact_point_t *pt);

/* The same point after plant_exact_set_speed: only its forced x-y response depends on the speed. */
void plant_exact_point_new_speed(const plant_exact_t *e, plant_exact_point_t *pt);

/* The length-only coefficients of an interval of h seconds (h > 0). */
void plant_exact_span(const plant_exact_t *e, double h, plant_exact_span_t *sp);

/* Advance s by h seconds (sp from plant_exact_span for this h and e's parameters) with the
 * stationary voltage u = [u_alpha, u_beta, u_x, u_y] (V) at the held speed: currents exactly,
 * angle (theta_m, cos_e, sin_e) by omega_m h; the speed is left alone. pt is the start point on
 * entry and the end point on return. Returns the torque integral over the interval (N*m*s,
 * trapezoidal: the torque is smooth within an interval). */
double plant_exact_step(const plant_exact_t *e, plant_state_t *s, const double u[4], double h,
                        const plant_exact_span_t *sp, plant_exact_point_t *pt);

#endif /* SIM_PLANT_EXACT_H */
