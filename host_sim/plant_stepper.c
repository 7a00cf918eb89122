/* One period of plant integration, see plant_stepper.h. */
#include "plant_stepper.h"

#include <string.h>

void plant_stepper_init(plant_stepper_t *st)
{
    memset(st, 0, sizeof *st);
    st->have_params = false;
    st->starts_seen = 0;
}

void plant_stepper_mark_period(plant_stepper_t *st, const plant_state_t *s)
{
    st->omega_prev = st->omega_start;
    st->omega_start = s->omega_m;
    if (st->starts_seen < 2) {
        st->starts_seen++;
    }
}

/* The speed held over the period: the predicted mid-period speed while the rotor is free. */
static double stepper_held_speed(const plant_stepper_t *st, const plant_state_t *s, bool lock_mech)
{
    if (lock_mech || st->starts_seen < 2) {
        return s->omega_m;
    }
    return s->omega_m + 0.5 * (st->omega_start - st->omega_prev);
}

void plant_stepper_begin(plant_stepper_t *st, const plant_params_t *p, plant_state_t *s,
                         bool lock_mech)
{
    /* Any change of the bytes (a fault injected into the plant) rebuilds the coefficients: one
     * comparison per period, and rebuilding them from unchanged parameters gives them again. */
    if (!st->have_params || memcmp(&st->params_seen, p, sizeof *p) != 0) {
        memcpy(&st->params_seen, p, sizeof *p);
        st->have_params = true;
        st->generation++;
        st->use_exact = p->integrator == PLANT_INTEGRATOR_EXACT && plant_exact_applies(p);
        if (st->use_exact) {
            plant_exact_init(&st->exact, p);
        }
    }
    st->lock_mech = lock_mech;
    if (!st->use_exact) {
        return;
    }
    {
        const double held = stepper_held_speed(st, s, lock_mech);
        if (held != st->exact.omega_m) {
            plant_exact_set_speed(&st->exact, held);
        }
        s->omega_m = held; /* what the period's samples see */
    }
    plant_exact_point(&st->exact, s, &st->point);
}

void plant_stepper_end(const plant_stepper_t *st, const plant_params_t *p, plant_state_t *s,
                       double t_load, double torque_integral, double ts)
{
    if (!st->use_exact) {
        return;
    }
    s->omega_m = st->omega_start;
    if (!st->lock_mech) {
        const double held = st->exact.omega_m;
        s->omega_m += (torque_integral - (t_load + p->b_nms * held) * ts) / p->j_kgm2;
    }
}
