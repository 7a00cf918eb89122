/* Exact interval solution of the electrical equations at a held speed, see plant_exact.h. */
#include "plant_exact.h"

#include <math.h>

/* The series below are evaluated several times per interval; without forced inlining gcc calls
 * exact_exp and spills the interval's state around each call. */
#if defined(__GNUC__)
#define EXACT_INLINE inline __attribute__((always_inline))
#else
#define EXACT_INLINE inline
#endif

/* Below this resistance the forced responses grow without bound (see plant_exact.h). */
#define EXACT_MIN_R_OHM 1e-3

bool plant_exact_applies(const plant_params_t *p)
{
    int k;
    if (!(p->r_ohm >= EXACT_MIN_R_OHM)) {
        return false;
    }
    for (k = 0; k < PLANT_PHASES; k++) {
        if (p->phase_extra_r_ohm[k] != 0.0 || p->phase_open[k]) {
            return false;
        }
    }
    return true;
}

void plant_exact_init(plant_exact_t *e, const plant_params_t *p)
{
    e->pn = (double)p->pole_pairs;
    e->r = p->r_ohm;
    e->inv_r = 1.0 / p->r_ohm;
    e->ld = p->ld_h;
    e->lq = p->lq_h;
    e->inv_ld = 1.0 / p->ld_h;
    e->inv_lq = 1.0 / p->lq_h;
    e->psi_f = p->psi_f_wb;
    e->t3pn = 3.0 * e->pn;
    e->ld_minus_lq = p->ld_h - p->lq_h;
    e->harm = p->harmonics_on;
    e->five_psi5 = p->harmonics_on ? 5.0 * p->psi5_wb : 0.0;
    e->seven_psi7 = p->harmonics_on ? 7.0 * p->psi7_wb : 0.0;
    e->inv_lxy = 1.0 / p->lxy_h;
    e->a_xy = p->r_ohm / p->lxy_h;
    /* the parts of plant_exact_set_speed's expressions that do not depend on the speed */
    e->a[0][0] = -e->r * e->inv_ld;
    e->a[1][1] = -e->r * e->inv_lq;
    e->sigma = 0.5 * (e->a[0][0] + e->a[1][1]);
    {
        const double half_diff = 0.5 * (-e->r * e->inv_ld + e->r * e->inv_lq);
        e->half_diff_sq = half_diff * half_diff;
    }
    e->a00_a11 = e->a[0][0] * e->a[1][1];
    e->a_trace = e->a[0][0] + e->a[1][1];
    e->n1_re = -e->a[1][1] * e->inv_ld;
    e->n2_im = -e->a[0][0] * e->inv_lq;
    e->a_xy_sq = e->a_xy * e->a_xy;
    plant_exact_set_speed(e, 0.0);
}

/* X = [Re xi, Im xi] with (A - j w I) xi = -L^-1 (1, j): the forced response to the rotor-frame
 * voltage Park(u), which turns at -w. Cramer's rule on the complex 2x2 system, written out in
 * real arithmetic: det = (a11 a22 - a12 a21 - w^2) - j w (a11 + a22), and the numerators
 * n1 = -a22 / Ld + j (w / Ld + a12 / Lq), n2 = (a21 / Ld - w / Lq) - j a11 / Lq. */
static void exact_forced_dq(plant_exact_t *e, double det)
{
    const double w = e->w_e;
    const double det_re = det - w * w;
    const double det_im = -w * e->a_trace;
    const double inv_mag2 = 1.0 / (det_re * det_re + det_im * det_im);
    const double n1_re = e->n1_re, n1_im = w * e->inv_ld + e->a[0][1] * e->inv_lq;
    const double n2_re = e->a[1][0] * e->inv_ld - w * e->inv_lq, n2_im = e->n2_im;
    /* n / det = n conj(det) / |det|^2 */
    e->x[0][0] = (n1_re * det_re + n1_im * det_im) * inv_mag2;
    e->x[0][1] = (n1_im * det_re - n1_re * det_im) * inv_mag2;
    e->x[1][0] = (n2_re * det_re + n2_im * det_im) * inv_mag2;
    e->x[1][1] = (n2_im * det_re - n2_re * det_im) * inv_mag2;
}

/* x-y: L z' = u - R z - w (j 5 psi5 e^{j 5 th} - j 7 psi7 e^{-j 7 th}); the harmonic terms' forced
 * responses k5 = -(w / L) j 5 psi5 / (a + j 5 w) and k7 = (w / L) j 7 psi7 / (a - j 7 w). */
static void exact_forced_xy(plant_exact_t *e)
{
    const double w = e->w_e, a = e->a_xy;
    const double g5 = w * e->inv_lxy * e->five_psi5 / (e->a_xy_sq + 25.0 * w * w);
    const double g7 = w * e->inv_lxy * e->seven_psi7 / (e->a_xy_sq + 49.0 * w * w);
    e->k5_re = -g5 * 5.0 * w;
    e->k5_im = -g5 * a;
    e->k7_re = -g7 * 7.0 * w;
    e->k7_im = g7 * a;
}

void plant_exact_set_speed(plant_exact_t *e, double omega_m)
{
    const double w = e->pn * omega_m;
    const double back_emf_q = -w * e->psi_f * e->inv_lq; /* d i_q / dt from the PM flux */
    double det;
    e->omega_m = omega_m;
    e->w_e = w;
    e->a[0][1] = w * e->lq * e->inv_ld;
    e->a[1][0] = -w * e->ld * e->inv_lq;
    e->q = -(e->half_diff_sq + e->a[0][1] * e->a[1][0]);
    det = e->a00_a11 - e->a[0][1] * e->a[1][0];
    e->p0_d = e->a[0][1] * back_emf_q / det;
    e->p0_q = -e->a[0][0] * back_emf_q / det;
    exact_forced_dq(e, det);
    exact_forced_xy(e);
}

/* cos and sin of an angle: Taylor series cut where the next term is below 1e-19 (|d| < 2^-9, a
 * dead interval at rated speed: terms to d^5; |d| < 2^-6, the usual interval: to d^7; |d| < 1/16:
 * to d^9), below 1e-13 for |d| < 0.35; else libm. */
static EXACT_INLINE void exact_rotation(double d, double *c, double *s)
{
    const double d2 = d * d;
    if (fabs(d) < 0.001953125) {
        *c = 1.0 + d2 * (-1.0 / 2.0 + d2 / 24.0);
        *s = d * (1.0 + d2 * (-1.0 / 6.0 + d2 / 120.0));
    } else if (fabs(d) < 0.015625) {
        *c = 1.0 + d2 * (-1.0 / 2.0 + d2 * (1.0 / 24.0 + d2 * (-1.0 / 720.0)));
        *s = d * (1.0 + d2 * (-1.0 / 6.0 + d2 * (1.0 / 120.0 + d2 * (-1.0 / 5040.0))));
    } else if (fabs(d) < 0.0625) {
        *c = 1.0 + d2 * (-1.0 / 2.0 + d2 * (1.0 / 24.0 + d2 * (-1.0 / 720.0 + d2 / 40320.0)));
        *s = d *
             (1.0 + d2 * (-1.0 / 6.0 + d2 * (1.0 / 120.0 + d2 * (-1.0 / 5040.0 + d2 / 362880.0))));
    } else if (fabs(d) < 0.35) {
        *c = 1.0 + d2 * (-1.0 / 2.0 +
                         d2 * (1.0 / 24.0 + d2 * (-1.0 / 720.0 +
                                                  d2 * (1.0 / 40320.0 + d2 * (-1.0 / 3628800.0)))));
        *s = d * (1.0 + d2 * (-1.0 / 6.0 +
                              d2 * (1.0 / 120.0 +
                                    d2 * (-1.0 / 5040.0 +
                                          d2 * (1.0 / 362880.0 + d2 * (-1.0 / 39916800.0))))));
    } else {
        *c = cos(d);
        *s = sin(d);
    }
}

/* e^x: Taylor series where it is short enough (relative error below 1e-18 for |x| < 1/32, the
 * usual case: R h / L is a few thousandths; below 1e-17 for |x| < 1/8), else libm. */
static EXACT_INLINE double exact_exp(double x)
{
    if (fabs(x) < 0.03125) {
        return 1.0 +
               x * (1.0 +
                    x * (1.0 / 2.0 +
                         x * (1.0 / 6.0 +
                              x * (1.0 / 24.0 +
                                   x * (1.0 / 120.0 +
                                        x * (1.0 / 720.0 + x * (1.0 / 5040.0 + x / 40320.0)))))));
    }
    if (fabs(x) < 0.125) {
        return 1.0 +
               x * (1.0 +
                    x * (1.0 / 2.0 +
                         x * (1.0 / 6.0 +
                              x * (1.0 / 24.0 +
                                   x * (1.0 / 120.0 +
                                        x * (1.0 / 720.0 +
                                             x * (1.0 / 5040.0 +
                                                  x * (1.0 / 40320.0 +
                                                       x * (1.0 / 362880.0 + x / 3628800.0)))))))));
    }
    return exp(x);
}

/* C = sum (-q)^k h^2k / (2k)!, S = sum (-q)^k h^(2k+1) / (2k+1)!: cos(b h) and sin(b h) / b with
 * b = sqrt(q) for q > 0, cosh and sinh for q < 0 (real eigenvalues at very low speed). Series
 * in z = q h^2 while |z| < 1/4 (error below 1e-15), cut where the next term is below 1e-19:
 * |z| < 2^-18 (a dead interval at rated speed) to z^2, |z| < 2^-12 (the usual interval) to z^3,
 * |z| < 0.03 to z^5. */
static EXACT_INLINE void exact_cos_sin_q(double q, double h, double *c, double *s)
{
    const double z = q * h * h;
    if (fabs(z) < 3.814697265625e-6) {
        *c = 1.0 + z * (-1.0 / 2.0 + z / 24.0);
        *s = h * (1.0 + z * (-1.0 / 6.0 + z / 120.0));
    } else if (fabs(z) < 2.44140625e-4) {
        *c = 1.0 + z * (-1.0 / 2.0 + z * (1.0 / 24.0 + z * (-1.0 / 720.0)));
        *s = h * (1.0 + z * (-1.0 / 6.0 + z * (1.0 / 120.0 + z * (-1.0 / 5040.0))));
    } else if (fabs(z) < 0.03) {
        *c = 1.0 + z * (-1.0 / 2.0 +
                        z * (1.0 / 24.0 +
                             z * (-1.0 / 720.0 + z * (1.0 / 40320.0 + z * (-1.0 / 3628800.0)))));
        *s = h * (1.0 +
                  z * (-1.0 / 6.0 +
                       z * (1.0 / 120.0 +
                            z * (-1.0 / 5040.0 + z * (1.0 / 362880.0 + z * (-1.0 / 39916800.0))))));
    } else if (fabs(z) < 0.25) {
        *c = 1.0 + z * (-1.0 / 2.0 +
                        z * (1.0 / 24.0 +
                             z * (-1.0 / 720.0 +
                                  z * (1.0 / 40320.0 + z * (-1.0 / 3628800.0 + z / 479001600.0)))));
        *s = h * (1.0 +
                  z * (-1.0 / 6.0 +
                       z * (1.0 / 120.0 +
                            z * (-1.0 / 5040.0 + z * (1.0 / 362880.0 + z * (-1.0 / 39916800.0 +
                                                                            z / 6227020800.0))))));
    } else if (q > 0.0) {
        const double b = sqrt(q);
        *c = cos(b * h);
        *s = sin(b * h) / b;
    } else {
        const double b = sqrt(-q);
        *c = cosh(b * h);
        *s = sinh(b * h) / b;
    }
}

/* The forced x-y response to the harmonic EMF at the point's phasors: k5 e^{j 5 th} +
 * k7 e^{-j 7 th}. */
static EXACT_INLINE void exact_harmonic_response(const plant_exact_t *e, plant_exact_point_t *pt)
{
    pt->harm_x = e->k5_re * pt->c5 - e->k5_im * pt->s5 + e->k7_re * pt->c7 + e->k7_im * pt->s7;
    pt->harm_y = e->k5_re * pt->s5 + e->k5_im * pt->c5 - e->k7_re * pt->s7 + e->k7_im * pt->c7;
}

/* e^{j 5 th} and e^{j 7 th} from cos th, sin th by complex products (no libm), and the forced
 * x-y response there. */
static EXACT_INLINE void exact_phasors(const plant_exact_t *e, double c, double sn,
                                       plant_exact_point_t *pt)
{
    if (e->harm) {
        const double c2 = c * c - sn * sn, s2 = 2.0 * c * sn;
        const double c4 = c2 * c2 - s2 * s2, s4 = 2.0 * c2 * s2;
        pt->c5 = c4 * c - s4 * sn;
        pt->s5 = c4 * sn + s4 * c;
        pt->c7 = pt->c5 * c2 - pt->s5 * s2;
        pt->s7 = pt->c5 * s2 + pt->s5 * c2;
        exact_harmonic_response(e, pt);
    } else {
        pt->c5 = pt->c7 = 1.0;
        pt->s5 = pt->s7 = 0.0;
        pt->harm_x = pt->harm_y = 0.0;
    }
}

/* The electromagnetic torque: d-q part and, with the harmonics, the x-y part. */
static double exact_torque(const plant_exact_t *e, const plant_state_t *s,
                           const plant_exact_point_t *pt)
{
    double te = e->t3pn * (e->ld_minus_lq * s->i_d * s->i_q + e->psi_f * s->i_q);
    if (e->harm) {
        te += e->t3pn * ((-e->five_psi5 * pt->s5 - e->seven_psi7 * pt->s7) * s->i_x +
                         (e->five_psi5 * pt->c5 - e->seven_psi7 * pt->c7) * s->i_y);
    }
    return te;
}

void plant_exact_point(const plant_exact_t *e, const plant_state_t *s, plant_exact_point_t *pt)
{
    exact_phasors(e, s->cos_e, s->sin_e, pt);
    pt->torque_nm = exact_torque(e, s, pt);
}

void plant_exact_point_new_speed(const plant_exact_t *e, plant_exact_point_t *pt)
{
    if (e->harm) {
        exact_harmonic_response(e, pt);
    }
}

void plant_exact_span(const plant_exact_t *e, double h, plant_exact_span_t *sp)
{
    sp->decay_dq = exact_exp(e->sigma * h);
    sp->decay_xy = exact_exp(-e->a_xy * h);
}

/* d-q: forced response to Park(u) and the back-EMF at both ends, free response Phi(h). */
static void exact_dq(const plant_exact_t *e, plant_state_t *s, const double u[4], double h,
                     double decay, double c1, double s1)
{
    const double c0 = s->cos_e, s0 = s->sin_e;
    const double ud0 = u[0] * c0 + u[1] * s0, uq0 = -u[0] * s0 + u[1] * c0;
    const double ud1 = u[0] * c1 + u[1] * s1, uq1 = -u[0] * s1 + u[1] * c1;
    const double forced_d0 = e->x[0][0] * ud0 + e->x[0][1] * uq0 + e->p0_d;
    const double forced_q0 = e->x[1][0] * ud0 + e->x[1][1] * uq0 + e->p0_q;
    const double forced_d1 = e->x[0][0] * ud1 + e->x[0][1] * uq1 + e->p0_d;
    const double forced_q1 = e->x[1][0] * ud1 + e->x[1][1] * uq1 + e->p0_q;
    const double free_d = s->i_d - forced_d0, free_q = s->i_q - forced_q0;
    double c, sh;
    exact_cos_sin_q(e->q, h, &c, &sh);
    s->i_d = forced_d1 +
             decay * ((c + sh * (e->a[0][0] - e->sigma)) * free_d + sh * e->a[0][1] * free_q);
    s->i_q = forced_q1 +
             decay * (sh * e->a[1][0] * free_d + (c + sh * (e->a[1][1] - e->sigma)) * free_q);
}

/* x-y: forced response u / R + k5 e^{j 5 th} + k7 e^{-j 7 th} at both ends, free e^{-a h}. */
static void exact_xy(const plant_exact_t *e, plant_state_t *s, const double u[4], double decay,
                     const plant_exact_point_t *p0, const plant_exact_point_t *p1)
{
    const double dc_x = u[2] * e->inv_r, dc_y = u[3] * e->inv_r;
    s->i_x = dc_x + p1->harm_x + decay * (s->i_x - dc_x - p0->harm_x);
    s->i_y = dc_y + p1->harm_y + decay * (s->i_y - dc_y - p0->harm_y);
}

double plant_exact_step(const plant_exact_t *e, plant_state_t *s, const double u[4], double h,
                        const plant_exact_span_t *sp, plant_exact_point_t *pt)
{
    const double torque0 = pt->torque_nm;
    plant_exact_point_t end;
    double cr, sr, c1, s1;
    exact_rotation(e->w_e * h, &cr, &sr);
    c1 = s->cos_e * cr - s->sin_e * sr;
    s1 = s->sin_e * cr + s->cos_e * sr;
    exact_dq(e, s, u, h, sp->decay_dq, c1, s1);
    s->theta_m += e->omega_m * h;
    s->cos_e = c1;
    s->sin_e = s1;
    /* the harmonic phasors of the end instant, then x-y and the torque there */
    exact_phasors(e, c1, s1, &end);
    exact_xy(e, s, u, sp->decay_xy, pt, &end);
    end.torque_nm = exact_torque(e, s, &end);
    *pt = end;
    return 0.5 * h * (torque0 + end.torque_nm);
}
