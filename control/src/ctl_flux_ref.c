#include "ctl_flux_ref.h"

#include "ctl_pu.h"
#include "ctl_placement.h"
#include "ctl_qmath.h"

/* MTPA operating point for a current magnitude i (SI): the d-axis current that maximises
 * torque per ampere for a salient machine (L_d < L_q gives i_d < 0). */
static float mtpa_id(float i, float ld, float lq, float psi_f)
{
    const float dl = lq - ld;
    if (dl > 1.0e-9f) {
        const float a = psi_f / (4.0f * dl);
        return a - ctl_sqrtf(a * a + 0.5f * i * i);
    }
    return 0.0f;
}

static void mtpa_point(float i, float ld, float lq, float psi_f, int16_t pp, float *torque,
                       float *flux)
{
    const float id = mtpa_id(i, ld, lq, psi_f);
    float iq;
    float pd;
    float pq;
    iq = ctl_sqrtf(i * i - id * id);
    pd = psi_f + ld * id;
    pq = lq * iq;
    *torque = 3.0f * (float)pp * (pd * iq - pq * id);
    *flux = ctl_sqrtf(pd * pd + pq * pq);
}

/* The operating point on the circle |i| = i (SI) that gives the torque target, between the MTPA
 * point (d-axis current id_mtpa, the circle's largest torque) and the pure -d current (no
 * torque): torque falls monotonically over that arc, so bisect the d-axis current. Its flux
 * returned, its d-axis current in *id_out. */
static float floor_point_flux(float i, float target, float ld, float lq, float psi_f, int16_t pp,
                              float id_mtpa, float *id_out)
{
    float lo = -i;      /* torque 0 */
    float hi = id_mtpa; /* torque >= target */
    float id;
    float iq;
    int16_t it;
    for (it = 0; it < 40; it++) {
        const float mid = 0.5f * (lo + hi);
        const float iq_mid = ctl_sqrtf(i * i - mid * mid);
        if (3.0f * (float)pp * iq_mid * (psi_f + (ld - lq) * mid) < target) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    id = 0.5f * (lo + hi);
    iq = ctl_sqrtf(i * i - id * id);
    *id_out = id;
    return ctl_sqrtf((psi_f + ld * id) * (psi_f + ld * id) + (lq * iq) * (lq * iq));
}

/* The smallest current on the MTPA curve that gives the torque target (SI); torque rises
 * monotonically with current on that curve, so bisect the current magnitude. */
static float mtpa_current_for_torque(const ctl_flux_ref_machine_t *m, float target)
{
    float lo = 0.0f;
    float hi = 1.0f;
    float t;
    float flux;
    int16_t it;
    mtpa_point(hi, m->ld_h, m->lq_h, m->psi_f_wb, m->pole_pairs, &t, &flux);
    while (t < target && hi < 1.0e4f) {
        hi *= 2.0f;
        mtpa_point(hi, m->ld_h, m->lq_h, m->psi_f_wb, m->pole_pairs, &t, &flux);
    }
    for (it = 0; it < 40; it++) {
        const float mid = 0.5f * (lo + hi);
        mtpa_point(mid, m->ld_h, m->lq_h, m->psi_f_wb, m->pole_pairs, &t, &flux);
        if (t < target) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return 0.5f * (lo + hi);
}

void ctl_flux_ref_init(ctl_flux_ref_t *f, ctl_flux_ref_mode_t mode, float constant_wb,
                       const ctl_flux_ref_machine_t *m, float torque_max_nm, float floor_a,
                       ctl_q *id_pu)
{
    const float psi_b = CTL_BASE_FLUX_WB_F;
    const float torque_max_pu = torque_max_nm / CTL_BASE_TORQUE_NM_F;
    int16_t k;
    f->mode = mode;
    f->constant = ctl_from_float(constant_wb / psi_b);
    f->torque_max = ctl_from_float(torque_max_pu);
    f->points_per_torque = ctl_from_float((float)(CTL_FLUX_REF_TABLE_POINTS - 1) / torque_max_pu);
    /* from the top down: the top's current bounds the floor (there the reference is plain MTPA);
     * below the floor current the point of the floor's circle that gives the target, else the
     * MTPA point (one call site each: inlined, for the background's stack bound) */
    for (k = CTL_FLUX_REF_TABLE_POINTS - 1; k >= 0; k--) {
        const float target = torque_max_nm * (float)k / (float)(CTL_FLUX_REF_TABLE_POINTS - 1);
        const float i = mtpa_current_for_torque(m, target);
        float t;
        float flux;
        float id;
        if (k == CTL_FLUX_REF_TABLE_POINTS - 1 && floor_a > i) {
            floor_a = i;
        }
        if (i < floor_a) {
            flux = floor_point_flux(floor_a, target, m->ld_h, m->lq_h, m->psi_f_wb, m->pole_pairs,
                                    mtpa_id(floor_a, m->ld_h, m->lq_h, m->psi_f_wb), &id);
        } else {
            mtpa_point(i, m->ld_h, m->lq_h, m->psi_f_wb, m->pole_pairs, &t, &flux);
            id = mtpa_id(i, m->ld_h, m->lq_h, m->psi_f_wb);
        }
        f->table[k] = ctl_from_float(flux / psi_b);
        if (id_pu != 0 && k % CTL_FLUX_REF_CURRENT_STRIDE == 0) { /* constant mode: i_d = 0 */
            id_pu[k / CTL_FLUX_REF_CURRENT_STRIDE] = (mode == CTL_FLUX_REF_MTPA)
                                                         ? ctl_from_float(id / CTL_BASE_CURRENT_A_F)
                                                         : CTL_Q(0.0);
        }
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
    /* Torque magnitude to table position; beyond the span the last point holds. Bounded: at most
     * torque_max times (points - 1) / torque_max, the table's last index. */
    pos = ctl_mul_bnd(ctl_min(ctl_abs(torque_ref_pu), f->torque_max), f->points_per_torque);
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
