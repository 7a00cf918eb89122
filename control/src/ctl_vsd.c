#include "ctl_vsd.h"

/* Rows of the amplitude-invariant VSD matrix without the 1/3 factor:
 * cos th_k, sin th_k, cos 5th_k, sin 5th_k for th = 0, 120, 240, 30, 150, 270 deg. */
#define CTL_VSD_SQRT3_2 0.86602540378443865

static const ctl_q vsd_cos1[6] = {
    CTL_Q(1.0), CTL_Q(-0.5), CTL_Q(-0.5), CTL_Q(CTL_VSD_SQRT3_2), CTL_Q(-CTL_VSD_SQRT3_2),
    CTL_Q(0.0)};
static const ctl_q vsd_sin1[6] = {
    CTL_Q(0.0), CTL_Q(CTL_VSD_SQRT3_2), CTL_Q(-CTL_VSD_SQRT3_2), CTL_Q(0.5), CTL_Q(0.5),
    CTL_Q(-1.0)};
static const ctl_q vsd_cos5[6] = {
    CTL_Q(1.0), CTL_Q(-0.5), CTL_Q(-0.5), CTL_Q(-CTL_VSD_SQRT3_2), CTL_Q(CTL_VSD_SQRT3_2),
    CTL_Q(0.0)};
static const ctl_q vsd_sin5[6] = {
    CTL_Q(0.0), CTL_Q(-CTL_VSD_SQRT3_2), CTL_Q(CTL_VSD_SQRT3_2), CTL_Q(0.5), CTL_Q(0.5),
    CTL_Q(-1.0)};

void ctl_vsd_forward(const ctl_q phase[6], ctl_vsd_t *out)
{
    ctl_q a = CTL_Q(0.0);
    ctl_q b = CTL_Q(0.0);
    ctl_q x = CTL_Q(0.0);
    ctl_q y = CTL_Q(0.0);
    int16_t k;
    for (k = 0; k < 6; k++) {
        a = ctl_add(a, ctl_mul(phase[k], vsd_cos1[k]));
        b = ctl_add(b, ctl_mul(phase[k], vsd_sin1[k]));
        x = ctl_add(x, ctl_mul(phase[k], vsd_cos5[k]));
        y = ctl_add(y, ctl_mul(phase[k], vsd_sin5[k]));
    }
    out->alpha = ctl_mul(a, CTL_Q(1.0 / 3.0));
    out->beta = ctl_mul(b, CTL_Q(1.0 / 3.0));
    out->x = ctl_mul(x, CTL_Q(1.0 / 3.0));
    out->y = ctl_mul(y, CTL_Q(1.0 / 3.0));
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
