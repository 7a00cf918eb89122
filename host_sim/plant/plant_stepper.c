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

/* Whether p holds the values the coefficients were made of (the fields they depend on, compared
 * by value: a byte comparison would read the structure's padding; the array of bools has none). */
static bool stepper_params_same(const plant_params_t *seen, const plant_params_t *p)
{
    int n;
    if (seen->r_ohm != p->r_ohm || seen->ld_h != p->ld_h || seen->lq_h != p->lq_h ||
        seen->lxy_h != p->lxy_h || seen->psi_f_wb != p->psi_f_wb || seen->psi5_wb != p->psi5_wb ||
        seen->psi7_wb != p->psi7_wb || seen->pole_pairs != p->pole_pairs ||
        seen->harmonics_on != p->harmonics_on || seen->integrator != p->integrator ||
        memcmp(seen->phase_open, p->phase_open, sizeof p->phase_open) != 0) {
        return false;
    }
    for (n = 0; n < PLANT_PHASES; n++) {
        if (seen->phase_extra_r_ohm[n] != p->phase_extra_r_ohm[n]) {
            return false;
        }
    }
    return true;
}

/* Whether the last period's end point is this state's: the state was not written since. */
static bool stepper_point_holds(const plant_stepper_t *st, const plant_state_t *s)
{
    const plant_state_t *o = &st->point_of;
    return st->point_known && o->i_d == s->i_d && o->i_q == s->i_q && o->i_x == s->i_x &&
           o->i_y == s->i_y && o->cos_e == s->cos_e && o->sin_e == s->sin_e;
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
    if (!st->have_params || !stepper_params_same(&st->params_seen, p)) { /* a fault injected */
        st->params_seen = *p;
        st->have_params = true;
        st->generation++;
        st->use_exact = p->integrator == PLANT_INTEGRATOR_EXACT && plant_exact_applies(p);
        if (st->use_exact) {
            plant_exact_init(&st->exact, p);
        }
    }
    st->lock_mech = lock_mech;
    if (!st->use_exact) {
        st->point_known = false;
        plant_sync_angle(p, s);
        return;
    }
    {
        const double held = stepper_held_speed(st, s, lock_mech);
        if (held != st->exact.omega_m) {
            plant_exact_set_speed(&st->exact, held);
        }
        s->omega_m = held; /* what the period's samples see */
    }
    if (stepper_point_holds(st, s)) {
        plant_exact_point_new_speed(&st->exact, &st->point);
    } else {
        plant_exact_point(&st->exact, s, &st->point);
    }
}

void plant_stepper_end(plant_stepper_t *st, const plant_params_t *p, plant_state_t *s,
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
    {
        /* one Newton step towards unit length: the rotations' rounding cannot accumulate */
        const double k = 1.5 - 0.5 * (s->cos_e * s->cos_e + s->sin_e * s->sin_e);
        s->cos_e *= k;
        s->sin_e *= k;
    }
    st->point_of = *s;
    st->point_known = true;
}
