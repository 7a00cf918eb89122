/*
 * Advances the plant over the constant-voltage intervals of one carrier period, with the
 * integrator the parameters ask for:
 *
 * exact (default): the electrical equations solved exactly per interval (plant_exact.h) at a
 *   speed held over the period, the mid-period speed predicted from the last period's change
 *   (w_k + (w_k - w_k-1) / 2: the angle error of holding the speed then telescopes instead of
 *   accumulating); the rotor angle advances with it; at the period end the speed takes the
 *   period's torque integral (trapezoidal per interval), load and friction. Coefficients are
 *   rebuilt when the parameters change (fault injection) and when the speed does (per period).
 * rk4: classical RK4 with free mechanics in every interval (plant_integrate_nosync), as before
 *   the exact solution existed; also where the exact solution does not apply
 *   (plant_exact_applies: no resistance, an extra phase resistance, or an open phase).
 */
#ifndef SIM_PLANT_STEPPER_H
#define SIM_PLANT_STEPPER_H

#include <stdbool.h>

#include "plant.h"
#include "plant_exact.h"

typedef struct {
    plant_exact_t exact;
    plant_exact_point_t point;  /* the present instant of the period being integrated */
    plant_state_t point_of;     /* the state the last period's end point belongs to */
    bool point_known;           /* point_of holds: a period ended exactly (plant_stepper_end) */
    plant_params_t params_seen; /* the parameters the coefficients were made of */
    bool have_params;
    unsigned generation;            /* changes with the coefficients (plant_stepper_span) */
    bool use_exact;                 /* this period */
    bool lock_mech;                 /* this period */
    double omega_start, omega_prev; /* mechanical speed at this and the last period start */
    int starts_seen;                /* periods started (saturates at 2) */
} plant_stepper_t;

void plant_stepper_init(plant_stepper_t *st);

/* Every period start, forced off or not: the speed history for the held-speed prediction. */
void plant_stepper_mark_period(plant_stepper_t *st, const plant_state_t *s);

/* Choose the method and prepare the period. The exact method carries cos_e / sin_e from period
 * to period (plant_stepper_end keeps them of unit length) and takes them as they are; RK4
 * recomputes them from theta_m first. After writing the state directly, call plant_sync_angle
 * (plant.h) as always. */
void plant_stepper_begin(plant_stepper_t *st, const plant_params_t *p, plant_state_t *s,
                         bool lock_mech);

/* What plant_stepper_step needs of an interval's length alone (after plant_stepper_begin). It
 * holds while st->generation does not change, so the inverter keeps it with the interval. */
static inline void plant_stepper_span(const plant_stepper_t *st, double h, plant_exact_span_t *sp)
{
    if (st->use_exact && h > 0.0) {
        plant_exact_span(&st->exact, h, sp);
    } else {
        sp->decay_dq = sp->decay_xy = 0.0; /* not used */
    }
}

/* One constant-voltage interval of h seconds, sp from plant_stepper_span(h); returns the torque
 * integral (N*m*s). Inline: the inverter calls it for every interval. */
static inline double plant_stepper_step(plant_stepper_t *st, const plant_params_t *p,
                                        plant_state_t *s, const double u[4], double t_load,
                                        double h, const plant_exact_span_t *sp)
{
    if (st->use_exact) {
        return (h > 0.0) ? plant_exact_step(&st->exact, s, u, h, sp, &st->point) : 0.0;
    }
    return plant_integrate_nosync(p, s, u, t_load, st->lock_mech, h);
}

/* Close the period of length ts with its torque integral: the speed update of the exact
 * method (RK4 has integrated the mechanics already), cos_e / sin_e scaled back to unit length,
 * and the end point kept for the next period when nothing else moves the state. */
void plant_stepper_end(plant_stepper_t *st, const plant_params_t *p, plant_state_t *s,
                       double t_load, double torque_integral, double ts);

#endif /* SIM_PLANT_STEPPER_H */
