#include "ctl_postfault_config.h"

#include "ctl_vectors.h"
#include "ctl_qmath.h"

#define PF_SAME 1.0e-4f /* effective voltages (per unit of Vdc) closer than this are one */

static float pf_abs(float x) { return (x < 0.0f) ? -x : x; }

/* The VSD row c_k of phase k: the state with only leg k on has the voltage c_k / 3 (the other
 * legs' common mode drops out with isolated neutrals). */
static void pf_phase_row(int16_t leg, float c[4])
{
    const ctl_vsd_t *v = &ctl_vector_vsd[1 << (5 - leg)];
    c[0] = 3.0f * ctl_to_float(v->alpha);
    c[1] = 3.0f * ctl_to_float(v->beta);
    c[2] = 3.0f * ctl_to_float(v->x);
    c[3] = 3.0f * ctl_to_float(v->y);
}

void ctl_postfault_effective_voltage(int16_t state, int16_t open_leg, float l_ab, float l_xy,
                                     float out[4])
{
    const ctl_vsd_t *v = &ctl_vector_vsd[(uint16_t)state & 077u];
    float c[4];
    float u[4];
    float w_u;
    float w_c;
    int16_t i;
    pf_phase_row(open_leg, c);
    u[0] = ctl_to_float(v->alpha);
    u[1] = ctl_to_float(v->beta);
    u[2] = ctl_to_float(v->x);
    u[3] = ctl_to_float(v->y);
    /* w = M^-1 c: the current change the open terminal's voltage would cause */
    w_u = (c[0] * u[0] + c[1] * u[1]) / l_ab + (c[2] * u[2] + c[3] * u[3]) / l_xy;
    w_c = (c[0] * c[0] + c[1] * c[1]) / l_ab + (c[2] * c[2] + c[3] * c[3]) / l_xy;
    for (i = 0; i < 4; i++) {
        out[i] = u[i] - c[i] * (w_u / w_c);
    }
}

/* i_xy = m i_ab of a strategy (m row-major 2x2): ML -c_xy c_ab^T; MT the x-y currents that keep
 * phases open_leg and zero_leg both at zero (false if that pair leaves no solution). */
static bool pf_strategy_matrix(int16_t open_leg, int16_t zero_leg, float m[4])
{
    float ck[4];
    float cm[4];
    float det;
    pf_phase_row(open_leg, ck);
    if (zero_leg == CTL_POSTFAULT_NO_LEG) {
        m[0] = -ck[2] * ck[0];
        m[1] = -ck[2] * ck[1];
        m[2] = -ck[3] * ck[0];
        m[3] = -ck[3] * ck[1];
        return true;
    }
    pf_phase_row(zero_leg, cm);
    /* [ck_xy; cm_xy] i_xy = -[ck_ab; cm_ab] i_ab */
    det = ck[2] * cm[3] - ck[3] * cm[2];
    if (pf_abs(det) < 0.1f) {
        return false;
    }
    m[0] = -(cm[3] * ck[0] - ck[3] * cm[0]) / det;
    m[1] = -(cm[3] * ck[1] - ck[3] * cm[1]) / det;
    m[2] = -(ck[2] * cm[0] - cm[2] * ck[0]) / det;
    m[3] = -(ck[2] * cm[1] - cm[2] * ck[1]) / det;
    return true;
}

/* Amplitude of phase j's current per unit alpha-beta current amplitude: i_j = a_j . i_ab with
 * a_j = c_j,ab + m^T c_j,xy, a rotating i_ab of amplitude 1 gives a peak of |a_j|. */
static float pf_phase_peak(int16_t j, const float m[4])
{
    float c[4];
    float a0;
    float a1;
    pf_phase_row(j, c);
    a0 = c[0] + m[0] * c[2] + m[2] * c[3];
    a1 = c[1] + m[1] * c[2] + m[3] * c[3];
    return ctl_sqrtf(a0 * a0 + a1 * a1);
}

static float pf_peak(const float m[4], uint16_t *quiet)
{
    float peak = 0.0f;
    int16_t j;
    *quiet = 0u;
    for (j = 0; j < 6; j++) {
        const float a = pf_phase_peak(j, m);
        if (a < 1.0e-3f) {
            *quiet |= (uint16_t)(1u << j);
        }
        peak = (a > peak) ? a : peak;
    }
    return peak;
}

/* The strategy's current geometry: the x-y currents per unit alpha-beta current (m), the healthy
 * phase it holds at zero, the phases without current and the peak ratio. Small on purpose: the
 * peak ratio is wanted on its own too (ctl_config_build), on the background's stack. */
typedef struct {
    float m[4];
    int16_t zero_leg;
    uint16_t quiet;
    float peak_ratio;
} pf_geometry_t;

static void pf_strategy_geometry(int16_t open_leg, ctl_postfault_strategy_t strategy,
                                 pf_geometry_t *g)
{
    int16_t j;
    (void)pf_strategy_matrix(open_leg, CTL_POSTFAULT_NO_LEG, g->m);
    g->zero_leg = CTL_POSTFAULT_NO_LEG;
    g->peak_ratio = pf_peak(g->m, &g->quiet);
    for (j = 0; j < 6 && strategy == CTL_POSTFAULT_MAX_TORQUE; j++) {
        float m[4];
        uint16_t quiet;
        float peak;
        if (j == open_leg || !pf_strategy_matrix(open_leg, j, m)) {
            continue;
        }
        peak = pf_peak(m, &quiet);
        if (peak < g->peak_ratio - 1.0e-4f) {
            g->peak_ratio = peak;
            g->quiet = quiet;
            g->zero_leg = j;
            g->m[0] = m[0];
            g->m[1] = m[1];
            g->m[2] = m[2];
            g->m[3] = m[3];
        }
    }
}

/* The strategy's current geometry into pf: zero leg, quiet phases, peak ratio, free reference. */
static void pf_build_strategy(ctl_postfault_config_t *pf, ctl_postfault_strategy_t strategy)
{
    pf_geometry_t g;
    float ck[4];
    pf_strategy_geometry(pf->open_leg, strategy, &g);
    pf->zero_leg = g.zero_leg;
    pf->quiet = g.quiet;
    pf->peak_ratio = g.peak_ratio;
    /* free component = perp . i_xy = (m^T perp) . i_ab, perp = c_xy turned by 90 deg (exactly
     * 0 for minimum loss, whose forced part lies along c_xy) */
    pf_phase_row(pf->open_leg, ck);
    pf->free_ref_alpha = CTL_Q(0.0);
    pf->free_ref_beta = CTL_Q(0.0);
    if (pf->zero_leg != CTL_POSTFAULT_NO_LEG) {
        pf->free_ref_alpha = ctl_from_float(-ck[3] * g.m[0] + ck[2] * g.m[2]);
        pf->free_ref_beta = ctl_from_float(-ck[3] * g.m[1] + ck[2] * g.m[3]);
    }
    pf->c_alpha = ctl_from_float(ck[0]);
    pf->c_beta = ctl_from_float(ck[1]);
    pf->c_x = ctl_from_float(ck[2]);
    pf->c_y = ctl_from_float(ck[3]);
}

float ctl_postfault_peak_ratio(int16_t open_leg, ctl_postfault_strategy_t strategy)
{
    pf_geometry_t g;
    if (open_leg < 0 || open_leg > 5) {
        return 1.0f;
    }
    pf_strategy_geometry(open_leg, strategy, &g);
    return g.peak_ratio;
}

/* The 32 states of the healthy legs (the open leg's bit clear) and their effective voltages. */
typedef struct {
    int16_t state[CTL_POSTFAULT_STATES];
    float u[CTL_POSTFAULT_STATES][4];
    float free[CTL_POSTFAULT_STATES]; /* along c_xy turned by 90 deg */
} pf_states_t;

static void pf_states(pf_states_t *st, int16_t open_leg, float l_ab, float l_xy)
{
    const int16_t bit = (int16_t)(1 << (5 - open_leg));
    float c[4];
    int16_t s;
    int16_t n = 0;
    pf_phase_row(open_leg, c);
    for (s = 0; s < CTL_VECTOR_COUNT; s++) {
        if ((s & bit) == 0) {
            st->state[n] = s;
            ctl_postfault_effective_voltage(s, open_leg, l_ab, l_xy, st->u[n]);
            st->free[n] = -c[3] * st->u[n][2] + c[2] * st->u[n][3];
            n++;
        }
    }
}

/* Direction angle (deg) as a unit vector, through the core's sine table. */
static void pf_direction(int16_t deg, float d[2])
{
    ctl_q s;
    ctl_q c;
    ctl_sincos_pu(ctl_from_float((float)deg / 360.0f), &s, &c);
    d[0] = ctl_to_float(c);
    d[1] = ctl_to_float(s);
}

/* The state with the largest effective alpha-beta voltage along direction deg whose free x-y
 * voltage has the sign asked for (negative: sign 1); any sign if none has it. */
static int16_t pf_pick(const pf_states_t *st, int16_t deg, int16_t sign)
{
    float d[2];
    float best = 0.0f;
    int16_t pick = -1;
    int16_t pass;
    int16_t n;
    pf_direction(deg, d);
    for (pass = 0; pass < 2 && pick < 0; pass++) {
        for (n = 0; n < CTL_POSTFAULT_STATES; n++) {
            const float along = st->u[n][0] * d[0] + st->u[n][1] * d[1];
            const bool signed_ok = (sign == 0) ? (st->free[n] > PF_SAME) : (st->free[n] < -PF_SAME);
            if ((pass == 1 || signed_ok) && along > best + PF_SAME) {
                best = along;
                pick = st->state[n];
            }
        }
    }
    return (pick < 0) ? 0 : pick;
}

static void pf_build_ddc(ctl_postfault_config_t *pf, const pf_states_t *st)
{
    int16_t s;
    int16_t h;
    int16_t f;
    int16_t sign;
    for (s = 0; s < CTL_SECTORS; s++) {
        for (h = 0; h < 2; h++) {
            for (f = 0; f < 2; f++) {
                /* the healthy table 1's directions: +-75 deg raises the flux, +-105 lowers it */
                const int16_t offset = (int16_t)((f == 0) ? 75 : 105);
                const int16_t deg = (int16_t)(30 * s + ((h == 0) ? offset : -offset) + 360);
                for (sign = 0; sign < 2; sign++) {
                    pf->ddc_table[s][h][f][sign] = pf_pick(st, deg, sign);
                }
            }
        }
    }
}

static float pf_ab_magnitude(const float u[4]) { return ctl_sqrtf(u[0] * u[0] + u[1] * u[1]); }

static bool pf_same(const float a[4], const float b[4])
{
    return pf_abs(a[0] - b[0]) < PF_SAME && pf_abs(a[1] - b[1]) < PF_SAME &&
           pf_abs(a[2] - b[2]) < PF_SAME && pf_abs(a[3] - b[3]) < PF_SAME;
}

/* One state per distinct non-zero effective voltage (the lowest-numbered), zero state first. */
static void pf_build_mptc_all(ctl_postfault_config_t *pf, const pf_states_t *st, int16_t *index)
{
    static const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    int16_t n;
    pf->mptc_all[0] = 0;
    pf->mptc_all_count = 1;
    for (n = 0; n < CTL_POSTFAULT_STATES; n++) {
        bool seen = pf_same(st->u[n], zero);
        int16_t k;
        for (k = 1; k < pf->mptc_all_count && !seen; k++) {
            seen = pf_same(st->u[n], st->u[index[k]]);
        }
        if (!seen) {
            index[pf->mptc_all_count] = n;
            pf->mptc_all[pf->mptc_all_count] = st->state[n];
            pf->mptc_all_count++;
        }
    }
}

/* The zero state and the non-zero candidates whose alpha-beta magnitude reaches the twelfth
 * largest (ties included), in the order of mptc_all. */
static void pf_build_mptc_large(ctl_postfault_config_t *pf, const pf_states_t *st,
                                const int16_t *index)
{
    float twelfth = 0.0f;
    int16_t k;
    int16_t j;
    for (k = 1; k < pf->mptc_all_count; k++) {
        const float mag = pf_ab_magnitude(st->u[index[k]]);
        int16_t larger = 0;
        for (j = 1; j < pf->mptc_all_count; j++) {
            larger =
                (int16_t)(larger + ((pf_ab_magnitude(st->u[index[j]]) > mag + PF_SAME) ? 1 : 0));
        }
        if (larger < 12 && (twelfth == 0.0f || mag < twelfth)) {
            twelfth = mag; /* the smallest magnitude with fewer than 12 above it */
        }
    }
    pf->mptc_large[0] = 0;
    pf->mptc_large_count = 1;
    for (k = 1; k < pf->mptc_all_count; k++) {
        if (pf_ab_magnitude(st->u[index[k]]) > twelfth - PF_SAME) {
            pf->mptc_large[pf->mptc_large_count] = pf->mptc_all[k];
            pf->mptc_large_count++;
        }
    }
}

void ctl_postfault_config_build(ctl_postfault_config_t *pf, int16_t open_leg,
                                ctl_postfault_strategy_t strategy, float ld_h, float lq_h,
                                float lxy_h)
{
    /* static: 390 words would not fit the background's stack on the target (the build runs in
     * the background only, never twice at once) */
    static pf_states_t st;
    int16_t index[CTL_POSTFAULT_STATES];
    pf->open_leg = open_leg;
    if (open_leg < 0 || open_leg > 5) {
        pf->open_leg = CTL_POSTFAULT_NO_LEG;
        return;
    }
    pf_build_strategy(pf, strategy);
    /* the tables with the mean alpha-beta inductance: the rotor angle is not known here */
    pf_states(&st, open_leg, 0.5f * (ld_h + lq_h), lxy_h);
    pf_build_ddc(pf, &st);
    pf_build_mptc_all(pf, &st, index);
    pf_build_mptc_large(pf, &st, index);
}
