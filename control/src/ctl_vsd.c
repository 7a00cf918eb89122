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

SIXPHASE_RAMFUNC void ctl_vsd_forward(const ctl_q phase[6], ctl_vsd_t *out)
{
    /* The rows share terms: with a = i_A/3 - (i_B + i_C)/6, p = (i_D - i_E) sqrt3/6,
     * b = (i_D + i_E)/6 - i_F/3 and q = (i_B - i_C) sqrt3/6:
     * alpha = a + p, x = a - p, beta = b + q, y = b - q. Six multiplies instead of 24. */
    const ctl_q a =
        ctl_mul_sub(phase[0], CTL_K_ONE_THIRD, ctl_add(phase[1], phase[2]), CTL_K_ONE_SIXTH);
    const ctl_q p = ctl_mul(ctl_sub(phase[3], phase[4]), CTL_K_SQRT3_OVER_6);
    const ctl_q b =
        ctl_mul_sub(ctl_add(phase[3], phase[4]), CTL_K_ONE_SIXTH, phase[5], CTL_K_ONE_THIRD);
    const ctl_q q = ctl_mul(ctl_sub(phase[1], phase[2]), CTL_K_SQRT3_OVER_6);
    out->alpha = ctl_add(a, p);
    out->x = ctl_sub(a, p);
    out->beta = ctl_add(b, q);
    out->y = ctl_sub(b, q);
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
