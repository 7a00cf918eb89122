#include "ctl_predict.h"

#include "ctl_pu.h"

/* Coefficients must be comfortably inside the Q24 range (|x| < 128). */
static bool coefficient_fits(float x) { return x > -100.0f && x < 100.0f; }

bool ctl_model_init(ctl_model_t *m, float r_ohm, float ld_h, float lq_h, float lxy_h,
                    float psi_f_wb, int16_t pole_pairs, float ts_s)
{
    const float lb = (float)CTL_BASE_INDUCTANCE_H;
    float r;
    float ld;
    float lq;
    float lxy;
    float psi;
    float ts;
    float coef[13];
    int16_t i;
    if (!(r_ohm >= 0.0f && ld_h > 0.0f && lq_h > 0.0f && lxy_h > 0.0f && psi_f_wb >= 0.0f &&
          ts_s > 0.0f && pole_pairs > 0 && pole_pairs <= 64)) {
        return false;
    }
    r = r_ohm / (float)CTL_BASE_IMPEDANCE_OHM;
    ld = ld_h / lb;
    lq = lq_h / lb;
    lxy = lxy_h / lb;
    psi = psi_f_wb / (float)CTL_BASE_FLUX_WB;
    ts = ts_s / (float)CTL_BASE_TIME_S;
    coef[0] = 1.0f - r * ts / ld;
    coef[1] = lq / ld * ts;
    coef[2] = ts / ld;
    coef[3] = 1.0f - r * ts / lq;
    coef[4] = ld / lq * ts;
    coef[5] = psi / lq * ts;
    coef[6] = ts / lq;
    coef[7] = 1.0f - r * ts / lxy;
    coef[8] = ts / lxy;
    coef[9] = ld;
    coef[10] = lq;
    coef[11] = lxy;
    coef[12] = psi;
    for (i = 0; i < 13; i++) {
        if (!coefficient_fits(coef[i])) {
            return false;
        }
    }
    /* Euler is only meaningful when a step is short against the electrical time constants. */
    if (coef[0] <= 0.0f || coef[3] <= 0.0f || coef[7] <= 0.0f || ts > 1.0f) {
        return false;
    }
    m->a_d = ctl_from_float(coef[0]);
    m->b_d = ctl_from_float(coef[1]);
    m->c_d = ctl_from_float(coef[2]);
    m->a_q = ctl_from_float(coef[3]);
    m->b_q = ctl_from_float(coef[4]);
    m->e_q = ctl_from_float(coef[5]);
    m->c_q = ctl_from_float(coef[6]);
    m->a_xy = ctl_from_float(coef[7]);
    m->c_xy = ctl_from_float(coef[8]);
    m->ld = ctl_from_float(ld);
    m->lq = ctl_from_float(lq);
    m->lxy = ctl_from_float(lxy);
    m->psi_f = ctl_from_float(psi);
    m->ts = ctl_from_float(ts);
    m->pole_pairs = pole_pairs;
    return true;
}
