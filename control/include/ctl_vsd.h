/*
 * Vector space decomposition of the asymmetrical six-phase machine
 * (A 0, B 120, C 240, D 30, E 150, F 270 deg), amplitude invariant (1/3
 * scaling), and the Park rotation of the alpha-beta plane.
 *
 * Forward: alpha = 1/3 sum i_k cos th_k, beta = 1/3 sum i_k sin th_k,
 *          x = 1/3 sum i_k cos 5th_k, y = 1/3 sum i_k sin 5th_k.
 * Inverse (isolated neutrals, zero-sequence o1 = o2 = 0):
 *          i_k = alpha cos th_k + beta sin th_k + x cos 5th_k + y sin 5th_k.
 */
#ifndef CTL_VSD_H
#define CTL_VSD_H

#include "ctl_constants.h"
#include "ctl_q.h"

typedef struct {
    ctl_q alpha;
    ctl_q beta;
    ctl_q x;
    ctl_q y;
} ctl_vsd_t;

void ctl_vsd_forward(const ctl_q phase[6], ctl_vsd_t *out);
void ctl_vsd_inverse(const ctl_vsd_t *v, ctl_q phase[6]);
/* The phase currents of an alpha-beta current alone (x = y = 0): each phase's share of it. */
void ctl_vsd_alpha_beta_phases(ctl_q alpha, ctl_q beta, ctl_q phase[6]);

/* The four rows of the forward VSD before their end (saturation or the domain's hold). The rows
 * share terms: with a = i_A/3 - (i_B + i_C)/6, p = (i_D - i_E) sqrt3/6, b = (i_D + i_E)/6 - i_F/3
 * and q = (i_B - i_C) sqrt3/6: alpha = a + p, x = a - p, beta = b + q, y = b - q. Six
 * multiplies instead of 24. Fixed point: exactly in 64 bits, each of a, p, b, q rounded once
 * (|phase| < 2^31 keeps every product below 2^56 and every sum inside int64); float: as it
 * comes (single precision has no range to protect here). */
#if CTL_MATH_FLOAT
typedef float ctl_vsd_wide_t;
#else
typedef int64_t ctl_vsd_wide_t;
#endif
typedef struct {
    ctl_vsd_wide_t alpha, beta, x, y;
} ctl_vsd_rows_t;

static inline void ctl_vsd_rows(const ctl_q phase[6], ctl_vsd_rows_t *r)
{
#if CTL_MATH_FLOAT
    const float a = phase[0] * CTL_K_ONE_THIRD - (phase[1] + phase[2]) * CTL_K_ONE_SIXTH;
    const float p = (phase[3] - phase[4]) * CTL_K_SQRT3_OVER_6;
    const float b = (phase[3] + phase[4]) * CTL_K_ONE_SIXTH - phase[5] * CTL_K_ONE_THIRD;
    const float q = (phase[1] - phase[2]) * CTL_K_SQRT3_OVER_6;
#else
    const int64_t a = ctl_q48_round((int64_t)phase[0] * CTL_K_ONE_THIRD -
                                    ((int64_t)phase[1] + phase[2]) * CTL_K_ONE_SIXTH);
    const int64_t p = ctl_q48_round(((int64_t)phase[3] - phase[4]) * CTL_K_SQRT3_OVER_6);
    const int64_t b = ctl_q48_round(((int64_t)phase[3] + phase[4]) * CTL_K_ONE_SIXTH -
                                    (int64_t)phase[5] * CTL_K_ONE_THIRD);
    const int64_t q = ctl_q48_round(((int64_t)phase[1] - phase[2]) * CTL_K_SQRT3_OVER_6);
#endif
#if defined(CTL_COUNT_OPS)
    ctl_op_counts[CTL_OP_MUL] += 6u;
    ctl_op_counts[CTL_OP_ADD] += 10u;
#endif
    r->alpha = a + p;
    r->x = a - p;
    r->beta = b + q;
    r->y = b - q;
}

/* A row ended: held to lim (the domain), or saturated to Q24's range (lim 0); float: as it is. */
static inline ctl_q ctl_vsd_row_end(ctl_vsd_wide_t v, ctl_q lim)
{
#if CTL_MATH_FLOAT
    (void)lim;
    return v;
#else
    return (lim > 0) ? ctl_held(v, lim) : ctl_sat64(v);
#endif
}

static inline void ctl_vsd_rows_end(const ctl_vsd_rows_t *r, ctl_q lim, ctl_vsd_t *out)
{
    out->alpha = ctl_vsd_row_end(r->alpha, lim);
    out->x = ctl_vsd_row_end(r->x, lim);
    out->beta = ctl_vsd_row_end(r->beta, lim);
    out->y = ctl_vsd_row_end(r->y, lim);
}

/* The VSD of a step's sampled phase currents, held to the domain of the range analysis
 * (ctl_range.h: each of alpha, beta, x, y within +-CTL_RANGE_CURRENT). A real sample lies inside
 * it (the board reads at most 2 per unit); one beyond it is an input the protection trips on,
 * and the step still computes nothing outside the proven bounds: the same values as
 * ctl_vsd_forward and a clamp, without its saturation tests. Inline: one call fewer in each
 * step's period. */
static inline void ctl_vsd_forward_in_range(const ctl_q phase[6], ctl_vsd_t *out)
{
    ctl_vsd_rows_t r;
    ctl_vsd_rows(phase, &r);
    ctl_vsd_rows_end(&r, CTL_Q(CTL_RANGE_CURRENT), out);
}

/* The step's sampled speed (omega_max: the model's, ctl_predict.h) and DC link held to the
 * same domain; float: as they come. */
static inline void ctl_range_clamp(ctl_q *omega, ctl_q *vdc, ctl_q omega_max)
{
#if CTL_MATH_FLOAT
    (void)omega;
    (void)vdc;
    (void)omega_max;
#else
    *omega = ctl_clamp(*omega, -omega_max, omega_max);
    *vdc = ctl_clamp(*vdc, CTL_Q(0.0), CTL_Q(CTL_RANGE_VDC));
#endif
}

/* The period average of state v held for duty at DC link vdc, u (VSD, per unit), and its d-q
 * part at the angle (s, c): bounded (duty at most 1, vdc in the domain, v within the vector
 * bound, docs/range-analysis.md). The command in force, as the healthy and open-phase steps
 * predict with it. */
static inline void ctl_voltage_in_force(const ctl_vsd_t *v, ctl_q duty, ctl_q vdc, ctl_q s, ctl_q c,
                                        ctl_vsd_t *u, ctl_q *ud, ctl_q *uq)
{
    const ctl_q scale = ctl_mul_bnd(duty, vdc);
    u->alpha = ctl_mul_bnd(v->alpha, scale);
    u->beta = ctl_mul_bnd(v->beta, scale);
    u->x = ctl_mul_bnd(v->x, scale);
    u->y = ctl_mul_bnd(v->y, scale);
    *ud = ctl_mul_add_bnd(u->alpha, c, u->beta, s);
    *uq = ctl_mul_sub_bnd(u->beta, c, u->alpha, s);
}

/* Rotation into the rotor frame by an angle given as its sine and cosine: bounded (a rotation
 * keeps |(d, q)| = |(alpha, beta)|, below 6 for currents of the domain and 2 for the voltages). */
static inline void ctl_park(ctl_q alpha, ctl_q beta, ctl_q s, ctl_q c, ctl_q *d, ctl_q *q)
{
    *d = ctl_add_bnd(ctl_mul_bnd(alpha, c), ctl_mul_bnd(beta, s));
    *q = ctl_sub_bnd(ctl_mul_bnd(beta, c), ctl_mul_bnd(alpha, s));
}

static inline void ctl_park_inverse(ctl_q d, ctl_q q, ctl_q s, ctl_q c, ctl_q *alpha, ctl_q *beta)
{
    *alpha = ctl_sub(ctl_mul(d, c), ctl_mul(q, s));
    *beta = ctl_add(ctl_mul(d, s), ctl_mul(q, c));
}
/* The same rotation in the bounded forms (the same values), for a (d, q) whose |d| + |q| the
 * range analysis bounds: the predicted flux and currents at k+1 (ctl_model_init). */
static inline void ctl_park_inverse_bnd(ctl_q d, ctl_q q, ctl_q s, ctl_q c, ctl_q *alpha,
                                        ctl_q *beta)
{
    *alpha = ctl_sub_bnd(ctl_mul_bnd(d, c), ctl_mul_bnd(q, s));
    *beta = ctl_add_bnd(ctl_mul_bnd(d, s), ctl_mul_bnd(q, c));
}

#endif /* CTL_VSD_H */
