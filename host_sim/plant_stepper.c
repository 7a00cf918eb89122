/* One period of plant integration, see plant_stepper.h. */
#include "plant_stepper.h"

#include <string.h>

void plant_stepper_init(plant_stepper_t *st)
{
    memset(st, 0, sizeof *st);
    st->have_key = false;
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

static void stepper_key(const plant_params_t *p, plant_stepper_key_t *k)
{
    int n;
    k->values[0] = p->r_ohm;
    k->values[1] = p->ld_h;
    k->values[2] = p->lq_h;
    k->values[3] = p->lxy_h;
    k->values[4] = p->psi_f_wb;
    k->values[5] = p->psi5_wb;
    k->values[6] = p->psi7_wb;
    k->values[7] = (double)p->pole_pairs;
    k->values[8] = p->harmonics_on ? 1.0 : 0.0;
    k->values[9] = (double)p->integrator;
    for (n = 0; n < PLANT_PHASES; n++) {
        k->values[10 + n] = p->phase_extra_r_ohm[n];
    }
}

/* True when the parameters still match the key (stepper_key's order; checked every period, so
 * compared in place, without building a key first). */
static bool stepper_key_matches(const plant_stepper_key_t *k, const plant_params_t *p)
{
    const double *v = k->values;
    int n;
    if (v[0] != p->r_ohm || v[1] != p->ld_h || v[2] != p->lq_h || v[3] != p->lxy_h ||
        v[4] != p->psi_f_wb || v[5] != p->psi5_wb || v[6] != p->psi7_wb ||
        v[7] != (double)p->pole_pairs || v[8] != (p->harmonics_on ? 1.0 : 0.0) ||
        v[9] != (double)p->integrator) {
        return false;
    }
    for (n = 0; n < PLANT_PHASES; n++) {
        if (v[10 + n] != p->phase_extra_r_ohm[n]) {
            return false;
        }
    }
    return true;
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
    if (!st->have_key || !stepper_key_matches(&st->key, p)) {
        stepper_key(p, &st->key);
        st->have_key = true;
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
