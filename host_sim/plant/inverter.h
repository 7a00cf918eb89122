/*
 * Two-level six-leg inverter with centre-aligned PWM and dead time, driving
 * the plant over one carrier period.
 *
 * Leg k with duty d: upper switch commanded on in [(1-d)/2 Ts, (1+d)/2 Ts)
 * (d = 1: the whole period, d = 0: never). After every commanded transition
 * both switches are off for the dead time; the leg then follows its current
 * (i > 0 flows through the lower diode: leg at 0; i < 0: upper diode, Vdc;
 * i = 0: the commanded state). The current sign is taken at the start of
 * each constant-voltage interval. Dead intervals that run past the period
 * end carry over into the next period.
 *
 * A floating leg (both switches off for good, its phase still connected: an isolated leg,
 * inverter_set_floating) conducts through its diodes whenever its terminal would leave the
 * rails: its phase is open (plant_params_t.phase_open) while the voltage that holds its current
 * at zero (plant_open_terminal_voltage) lies within [0, Vdc]; below 0 the lower diode conducts
 * (leg at 0, current into the machine), above Vdc the upper one (leg at Vdc, current out), until
 * the current returns to zero, where the diode blocks (the current is commutated to exactly
 * zero). Decided every INV_FLOAT_STEP_S; the plant is integrated with RK4 in such periods. With
 * two isolated neutrals the other set's switching reaches the floating terminal through the
 * small x-y inductance, so this happens in a large share of every period (docs/simulator.md).
 */
#ifndef SIM_INVERTER_H
#define SIM_INVERTER_H

#include <stdbool.h>
#include <stdint.h>

#include "plant.h"
#include "inverter_program.h"
#include "plant_stepper.h"

typedef void (*inverter_sample_fn)(void *ctx, double t_rel, const plant_state_t *s,
                                   unsigned leg_state);

typedef struct {
    double ts;                     /* carrier period, s */
    double td;                     /* dead time in force (0 when off), s */
    inv_legs_t legs;               /* commanded state and dead intervals, carried between periods */
    unsigned eff;                  /* effective leg states of the last interval (S_A = bit 5) */
    bool off;                      /* outputs forced off in the last period */
    bool counting;                 /* count effective transitions */
    uint64_t transitions;          /* effective leg transitions while counting */
    double switched_amps;          /* sum of |phase current| over those transitions, A */
    double u_table[64][4];         /* per-unit-of-Vdc VSD voltage of each state */
    double u_vdc[64][4];           /* u_table times the DC link voltage u_vdc_of */
    double u_vdc_of;               /* the voltage u_vdc was built for (V) */
    int intervals;                 /* constant-voltage intervals in the last period */
    inv_cache_t cache;             /* recent periods' switching programs (inverter_program.h) */
    unsigned floating;             /* bit k: leg k (A = bit 0) floats (inverter_set_floating) */
    int float_state[PLANT_PHASES]; /* per floating leg: 0 open, 1 lower diode, 2 upper diode */
    double float_conduct_s;        /* time a floating leg's diode conducted, while counting */
    plant_stepper_t stepper;       /* integrates the plant over the intervals */
} inverter_t;

/* Start an inverter (all legs off); inverter_free releases what it takes. */
void inverter_init(inverter_t *inv, const plant_params_t *p, double ts);
void inverter_free(inverter_t *inv);

/* The legs (bit k: leg k, A = bit 0) whose switches are off for good while their phases stay
 * connected; a leg newly floating starts open (its current commutated to zero by the caller). */
void inverter_set_floating(inverter_t *inv, unsigned legs);

#define INV_FLOAT_STEP_S 1e-6 /* a floating leg's state is decided this often */

/* Advance plant and inverter by one period with the given leg duties
 * (fractions 0..1). forced_off: all switches off (currents are commutated
 * to zero at once; valid while the line back-EMF stays below Vdc).
 * sample_t: sorted times in [0, ts) at which cb is called with the state
 * (may be NULL / 0). Returns the period-average electromagnetic torque.
 * The plant is integrated as p->integrator asks (plant_stepper.h). */
double inverter_run_period(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                           const double duty[PLANT_PHASES], bool forced_off, double t_load,
                           bool lock_mech, const double *sample_t, int n_samples,
                           inverter_sample_fn cb, void *ctx);

#endif /* SIM_INVERTER_H */
