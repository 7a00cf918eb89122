#include "ctl_flux_ref.h"

#include "ctl_pu.h"
#include "ctl_placement.h"

/* MTPA operating point for a current magnitude i (SI): the d-axis current that maximises
 * torque per ampere for a salient machine (L_d < L_q gives i_d < 0). */
static void mtpa_point(float i, float ld, float lq, float psi_f, int16_t pp, float *torque,
                       float *flux)
{
    const float dl = lq - ld;
    float id = 0.0f;
    float iq;
    float pd;
    float pq;
    if (dl > 1.0e-9f) {
        const float a = psi_f / (4.0f * dl);
        id = a - ctl_sqrtf(a * a + 0.5f * i * i);
    }
    iq = ctl_sqrtf(i * i - id * id);
    pd = psi_f + ld * id;
    pq = lq * iq;
    *torque = 3.0f * (float)pp * (pd * iq - pq * id);
    *flux = ctl_sqrtf(pd * pd + pq * pq);
}

void ctl_flux_ref_init(ctl_flux_ref_t *f, ctl_flux_ref_mode_t mode, float constant_wb, float ld_h,
                       float lq_h, float psi_f_wb, int16_t pole_pairs, float torque_max_nm)
{
    const float psi_b = CTL_BASE_FLUX_WB_F;
    const float torque_max_pu = torque_max_nm / CTL_BASE_TORQUE_NM_F;
    int16_t k;
    f->mode = mode;
    f->constant = ctl_from_float(constant_wb / psi_b);
    f->torque_max = ctl_from_float(torque_max_pu);
    f->points_per_torque = ctl_from_float((float)(CTL_FLUX_REF_TABLE_POINTS - 1) / torque_max_pu);
    /* Tabulate flux against torque at equal torque steps: bisect the current magnitude
     * that gives each torque (torque rises monotonically with current on the MTPA curve). */
    for (k = 0; k < CTL_FLUX_REF_TABLE_POINTS; k++) {
        const float target = torque_max_nm * (float)k / (float)(CTL_FLUX_REF_TABLE_POINTS - 1);
        float lo = 0.0f;
        float hi = 1.0f;
        float t;
        float flux;
        int16_t it;
        mtpa_point(hi, ld_h, lq_h, psi_f_wb, pole_pairs, &t, &flux);
        while (t < target && hi < 1.0e4f) {
            hi *= 2.0f;
            mtpa_point(hi, ld_h, lq_h, psi_f_wb, pole_pairs, &t, &flux);
        }
        for (it = 0; it < 40; it++) {
            const float mid = 0.5f * (lo + hi);
            mtpa_point(mid, ld_h, lq_h, psi_f_wb, pole_pairs, &t, &flux);
            if (t < target) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        mtpa_point(0.5f * (lo + hi), ld_h, lq_h, psi_f_wb, pole_pairs, &t, &flux);
        f->table[k] = ctl_from_float(flux / psi_b);
    }
}

SIXPHASE_RAMFUNC ctl_q ctl_flux_ref_run(const ctl_flux_ref_t *f, ctl_q torque_ref_pu)
{
    ctl_q pos;
    int16_t k;
    ctl_q frac;
    if (f->mode == CTL_FLUX_REF_CONSTANT) {
        return f->constant;
    }
    /* Torque magnitude to table position; beyond the span the last point holds. */
    pos = ctl_mul(ctl_min(ctl_abs(torque_ref_pu), f->torque_max), f->points_per_torque);
    if (!(pos < CTL_Q(CTL_FLUX_REF_TABLE_POINTS - 1))) { /* at or past the end, or NaN */
        return f->table[CTL_FLUX_REF_TABLE_POINTS - 1];
    }
    if (!(pos > CTL_Q(0.0))) {
        return f->table[0];
    }
#if CTL_MATH_FLOAT
    k = (int16_t)pos; /* defined: 0 < pos < points - 1 */
    frac = pos - (float)k;
#else
    k = (int16_t)(pos >> CTL_Q_FRAC_BITS);
    frac = pos & (CTL_Q_ONE - 1);
#endif
    return ctl_add(f->table[k], ctl_mul(frac, ctl_sub(f->table[k + 1], f->table[k])));
}
