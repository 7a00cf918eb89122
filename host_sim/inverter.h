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
    double ts;               /* carrier period, s */
    double td;               /* dead time in force (0 when off), s */
    inv_legs_t legs;         /* commanded state and dead intervals, carried between periods */
    unsigned eff;            /* effective leg states of the last interval (S_A = bit 5) */
    bool off;                /* outputs forced off in the last period */
    bool counting;           /* count effective transitions */
    uint64_t transitions;    /* effective leg transitions while counting */
    double u_table[64][4];   /* per-unit-of-Vdc VSD voltage of each state */
    double u_vdc[64][4];     /* u_table times the DC link voltage u_vdc_of */
    double u_vdc_of;         /* the voltage u_vdc was built for (V) */
    int intervals;           /* constant-voltage intervals in the last period */
    inv_cache_t cache;       /* recent periods' switching programs (inverter_program.h) */
    plant_stepper_t stepper; /* integrates the plant over the intervals */
} inverter_t;

/* Start an inverter (all legs off); inverter_free releases what it takes. */
void inverter_init(inverter_t *inv, const plant_params_t *p, double ts);
void inverter_free(inverter_t *inv);

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
