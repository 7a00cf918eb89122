#include "ctl_predict.h"

#include "ctl_placement.h"
#include "ctl_pu.h"

/* Coefficients must be comfortably inside the Q24 range (|x| < 128). */
static bool coefficient_fits(float x) { return x > -100.0f && x < 100.0f; }

/* The range analysis (docs/range-analysis.md) of this model: the largest magnitude each quantity
 * the steps compute with the bounded forms (ctl_q.h) can reach from inputs of the domain
 * (ctl_range.h), by the triangle inequality; true when all stay below CTL_RANGE_BOUND. A sine or
 * cosine counts as 1.01 (the one-period angle series overshoots 1 by less than 1e-4). The
 * coefficients are those of ctl_model_init, all positive; the largest quantity is kept in one
 * running maximum. Not inlined, and no helper: its frame would add to ctl_model_init's on the
 * background's deepest path (tools/check_stack_bound.sh). */
SIXPHASE_NOINLINE static bool range_fits(const float *coef, float w)
{
    const float u = (float)CTL_RANGE_VDC * (float)CTL_RANGE_VECTOR_SUM * 1.01f; /* |u_d|, |u_x| */
    float i = (float)CTL_RANGE_CURRENT * 1.4142136f * 1.01f; /* |i_d|, |i_q| at k */
    float largest = (coef[2] > coef[6]) ? coef[2] : coef[6];
    float id;
    float iq;
    int16_t step;
    largest *= (float)CTL_RANGE_VDC * 1.01f; /* c V (and c V cos) of ctl_horizon_prepare */
    /* x-y at k+1: a_xy i + c_xy u */
    id = coef[7] * (float)CTL_RANGE_CURRENT + coef[8] * u;
    largest = (id > largest) ? id : largest;
    id *= coef[11]; /* its flux, L_xy i_x, for the x-y sector */
    largest = (id > largest) ? id : largest;
    /* k+1 under the command in force, then k+2: the free response plus a candidate's forced
     * part (c V times |v_alpha| + |v_beta|, which u covers); the speed term w i of k and k+1 */
    for (step = 0; step < 2; step++) {
        id = coef[0] * i + coef[1] * w * i + coef[2] * u;
        iq = coef[3] * i + coef[4] * w * i + coef[5] * w + coef[6] * u;
        largest = (w * i > largest) ? w * i : largest;
        i = (id > i) ? id : i;
        i = (iq > i) ? iq : i;
        /* the open-phase step's projections hold its k+1 and k+2 currents to this */
        i = (i > (float)CTL_RANGE_PROJECTED) ? i : (float)CTL_RANGE_PROJECTED;
        largest = (i > largest) ? i : largest; /* the currents themselves */
        /* k+1's flux turned to alpha-beta (ctl_park_inverse_bnd): |psi_d| + |psi_q| */
        id = (step == 0) ? (coef[12] + (coef[9] + coef[10]) * i) * 1.01f : 0.0f;
        largest = (id > largest) ? id : largest;
    }
    /* there a candidate's k+2 current is a held free response plus a held forced response */
    i = (i > 2.0f * (float)CTL_RANGE_PROJECTED) ? i : 2.0f * (float)CTL_RANGE_PROJECTED;
    largest = (i > largest) ? i : largest;
    /* the fluxes of any of these currents: psi_f + L_d i, L_q i */
    id = coef[12] + coef[9] * i;
    iq = coef[10] * i;
    largest = (id > largest) ? id : largest;
    largest = (iq > largest) ? iq : largest;
    return largest < (float)CTL_RANGE_BOUND;
}

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
    float omega_max;
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
    omega_max = (float)CTL_RANGE_ANGLE / ts;
    omega_max = (omega_max < (float)CTL_RANGE_SPEED) ? omega_max : (float)CTL_RANGE_SPEED;
    if (!range_fits(coef, omega_max)) {
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
    m->omega_max = ctl_from_float(omega_max);
    m->pole_pairs = pole_pairs;
    return true;
}
