/*
 * Identification step 7, the mechanics: viscous and Coulomb friction, then the inertia, with
 * the current regulated in the rotor's frame (i_d = 0) as in the flux step. The shaft torque
 * is the machine's, T = 3 Pn (psi_f i_q + (L_d - L_q) i_d i_q) from the measured currents
 * (psi_f the identified one if the flux step ran, ok or poor, else the parameter set's; on a poor
 * one an ok J or B is reported poor with its reason); the speed is the
 * encoder's, mechanical rad/s. The model is J dw/dt = T - B w - Tc sign(w).
 *
 *  1. Probe: minus the test current along q from standstill until the rotor reaches -w_top
 *     (half the flux step's test speed): a first inertia, the torque's integral over the speed
 *     reached (friction makes it high, which only slows the loops below). Nothing assumes the
 *     parameter set's inertia, so any machine from 0.2 to 10 times it (and beyond) is safe.
 *  2. Friction: a speed loop of a fixed 20 rad/s bandwidth, its gains from the probe's
 *     inertia, holds -w_top, -w_top/2, +w_top/2, +w_top. At each, once the speed has stayed
 *     within 0.2 % of the point's for 0.1 s (at least 0.4 s, at most 2 s: a heavy rotor's loop
 *     still settling put its transient into every turn), over 16 whole electrical turns (the
 *     harmonics' and sensor offsets' torque averages out), the mean torque is
 *     B w + Tc sign(w) + J dw/dt, the last from the speed's drift between the first and the
 *     last turn (the encoder's counts per turn). Least squares over the four points gives B and
 *     Tc. Their uncertainty: the scatter of blocks of two turns (neighbouring turns correlate
 *     through the loop), the x-y plane's torque that its power bounds, and the fit's residuals,
 *     propagated. Between the directions the rotor stops and
 *     stands for 0.25 s: a rotor turned back under current dwells near one angle, where the
 *     protection's open-phase window would see a phase carry little and call it open.
 *  3. Inertia, by acceleration-deceleration runs (the run-up / retardation method, e.g. IEEE
 *     Std 115's retardation test, here with a known electrical torque both ways): a constant
 *     torque -Ta from +w_top down to 0.2 w_top, +Ta back up, no speed loop. In the band
 *     0.3..0.9 w_top each run's speed is fitted by least squares against time (running sums
 *     only): its slope alpha, and its means of T, w and sign(w); each run gives
 *     J = (T - B w - Tc sign(w)) / alpha. Runs up and down cross the same band, so an error in
 *     the friction cancels to first order between them (J = 2 Ta / (alpha_up - alpha_down)
 *     with the friction left out). Ta is sized from the probe so that a run lasts about 0.25 s,
 *     but at least four times the friction torque at w_top and half the test current (below
 *     that the torque the currents' small errors leave, a few mN m, biased J by up to 3 %).
 *     Three runs each way; their scatter gives the uncertainty. The friction is fitted again
 *     with the runs' inertia (the points' drift), and the inertia once more.
 *  4. Stop: the speed loop takes the rotor back to standstill.
 * The sequence's open-phase watch judges a phase only while it carries a share of the test
 * current: in the probe and the runs, not while the speed loop holds a speed with the friction's
 * few mA (holding i_d at the test current there would let it judge, but measured, the currents'
 * small errors then add a drag of 0.1 N m at w_top to the friction). A phase that opens during
 * the friction points is found at the runs, and the sequence fails with open_phase as before.
 *
 * Both results' uncertainty adds the torque constant's: psi_f's relative sigma and the current
 * channels' scale (ident_ctx.c). About 11.5 s on the reference machine; a rotor with ten times
 * its inertia takes 23 s (the runs at the test current), within the step's time bound (36.5 s).
 */
#ifndef IDENT_MECH_H
#define IDENT_MECH_H

#include "ident.h"

#define IDENT_MECH_POINTS 4 /* steady speeds of the friction measurement */
#define IDENT_MECH_RUNS 6   /* acceleration runs, half of them each way */

/* A running least-squares line of speed against time, and the means beside it. */
typedef struct {
    int32_t n;
    float st, stt, sw, stw, storque, ssign; /* sums of t (s), t^2, w, t w, T, sign(w) */
} ident_mech_fit_t;

typedef struct {
    float kt;           /* N m per A of i_q, 3 Pn psi_f */
    float kt_rel_sigma; /* psi_f's relative uncertainty */
    float w_top;        /* mechanical rad/s */
    float j_probe;      /* kg m^2, from the probe */
    float torque_sum;   /* probe: sum of T over its periods */
    ident_pi_t speed_pi;
    float speed_ref;  /* mechanical rad/s, ramped */
    float accel_max;  /* rad/s^2 the ramps ask for */
    int16_t point;    /* friction point measured */
    uint32_t in_band; /* settling: periods the speed has stayed near the point's */
    int32_t turn_start;
    float turn_torque; /* sum over the open turn */
    int32_t turn_n;
    ident_blocks_t point_torque; /* per-turn means of T, in blocks of turns */
    int32_t point_turns;         /* whole turns of the point so far */
    float xy_power;              /* the point's x-y power, summed (mech_xy_power) */
    int32_t xy_n;
    int32_t point_counts, point_periods;    /* over the point's whole turns */
    float first_w, first_t, last_w, last_t; /* the first and the last turn's speed, centre (s) */
    /* each point's speed, mean torque, its standard error and the speed's drift (rad/s^2):
     * the torque also accelerated the rotor, J times the drift, taken out with the inertia */
    float point_w[IDENT_MECH_POINTS], point_t[IDENT_MECH_POINTS];
    float point_sigma[IDENT_MECH_POINTS], point_accel[IDENT_MECH_POINTS];
    float max_speed_error; /* of a friction point, relative */
    float b, tc, b_sigma;  /* friction */
    float i_run;           /* A along q of the runs */
    int16_t direction;     /* +1, -1 */
    uint32_t since_reversal;
    int16_t runs;
    ident_mech_fit_t fit;
    /* each run's slope and its means of T, w and sign(w) */
    float run_alpha[IDENT_MECH_RUNS], run_torque[IDENT_MECH_RUNS];
    float run_w[IDENT_MECH_RUNS], run_sign[IDENT_MECH_RUNS];
} ident_mech_t;

void ident_mech_begin(ident_ctx_t *x, ident_mech_t *s);
ident_status_t ident_mech_step(ident_ctx_t *x, ident_mech_t *s, const ident_input_t *in);

#define IDENT_MECH_SECONDS 11.5f

#endif /* IDENT_MECH_H */
