#include "ctl_vsd.h"

#include "ctl_constants.h"
#include "ctl_placement.h"

/* Rows of the amplitude-invariant VSD matrix without the 1/3 factor:
 * cos th_k, sin th_k, cos 5th_k, sin 5th_k for th = 0, 120, 240, 30, 150, 270 deg. */

SIXPHASE_RAMCONST static const ctl_q vsd_cos1[6] = {
    CTL_Q(1.0), CTL_Q(-0.5), CTL_Q(-0.5), CTL_K_SQRT3_OVER_2, -CTL_K_SQRT3_OVER_2, CTL_Q(0.0)};
SIXPHASE_RAMCONST static const ctl_q vsd_sin1[6] = {
    CTL_Q(0.0), CTL_K_SQRT3_OVER_2, -CTL_K_SQRT3_OVER_2, CTL_Q(0.5), CTL_Q(0.5), CTL_Q(-1.0)};
static const ctl_q vsd_cos5[6] = {CTL_Q(1.0),          CTL_Q(-0.5),        CTL_Q(-0.5),
                                  -CTL_K_SQRT3_OVER_2, CTL_K_SQRT3_OVER_2, CTL_Q(0.0)};
static const ctl_q vsd_sin5[6] = {CTL_Q(0.0), -CTL_K_SQRT3_OVER_2, CTL_K_SQRT3_OVER_2,
                                  CTL_Q(0.5), CTL_Q(0.5),          CTL_Q(-1.0)};

/* Each row saturated once, at its end (ctl_vsd_rows). */
SIXPHASE_RAMFUNC void ctl_vsd_forward(const ctl_q phase[6], ctl_vsd_t *out)
{
    ctl_vsd_rows_t r;
    ctl_vsd_rows(phase, &r);
    ctl_vsd_rows_end(&r, 0, out);
}

SIXPHASE_RAMFUNC void ctl_vsd_alpha_beta_phases(ctl_q alpha, ctl_q beta, ctl_q phase[6])
{
    int16_t k;
    for (k = 0; k < 6; k++) {
        phase[k] = ctl_mul_add(alpha, vsd_cos1[k], beta, vsd_sin1[k]);
    }
}

void ctl_vsd_inverse(const ctl_vsd_t *v, ctl_q phase[6])
{
    int16_t k;
    for (k = 0; k < 6; k++) {
        ctl_q p = ctl_mul(v->alpha, vsd_cos1[k]);
        p = ctl_add(p, ctl_mul(v->beta, vsd_sin1[k]));
        p = ctl_add(p, ctl_mul(v->x, vsd_cos5[k]));
        p = ctl_add(p, ctl_mul(v->y, vsd_sin5[k]));
        phase[k] = p;
    }
}
