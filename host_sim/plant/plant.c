/* Host plant: six-phase PMSM in VSD coordinates. See plant.h. */
#include "plant.h"

#include <math.h>
#include <stddef.h>

#include "ctl_machine.h"
#include "hal_board.h"

#define PLANT_PI 3.14159265358979323846

const double plant_phase_angle_rad[PLANT_PHASES] = {0.0,
                                                    2.0 * PLANT_PI / 3.0,
                                                    4.0 * PLANT_PI / 3.0,
                                                    PLANT_PI / 6.0,
                                                    5.0 * PLANT_PI / 6.0,
                                                    3.0 * PLANT_PI / 2.0};

/* cos th_k, sin th_k, cos 5th_k, sin 5th_k as exact constants (the same values
 * plant_phase_currents uses), so the derivative needs no libm. */
#define PLANT_H3 0.86602540378443864676 /* sqrt(3)/2 */
static const double plant_vsd_row[4][PLANT_PHASES] = {
    {1.0, -0.5, -0.5, PLANT_H3, -PLANT_H3, 0.0},
    {0.0, PLANT_H3, -PLANT_H3, 0.5, 0.5, -1.0},
    {1.0, -0.5, -0.5, -PLANT_H3, PLANT_H3, 0.0},
    {0.0, -PLANT_H3, PLANT_H3, 0.5, 0.5, -1.0},
};

void plant_params_default(plant_params_t *p)
{
    p->r_ohm = CTL_MACHINE_R_OHM; /* the machine the controller assumes by default */
    p->ld_h = CTL_MACHINE_LD_H;
    p->lq_h = CTL_MACHINE_LQ_H;
    p->lxy_h = CTL_MACHINE_LXY_H;
    p->psi_f_wb = CTL_MACHINE_PSI_F_WB;
    p->psi5_wb = 0.006;
    p->psi7_wb = 0.002;
    p->pole_pairs = CTL_MACHINE_POLE_PAIRS;
    p->j_kgm2 = CTL_MACHINE_INERTIA_KG_M2;
    p->b_nms = 0.001;
    p->vdc_v = CTL_MACHINE_VDC_V;
    p->dead_time_s = 2e-6;
    for (int k = 0; k < PLANT_PHASES; k++) {
        p->phase_extra_r_ohm[k] = 0.0;
        p->phase_open[k] = false;
    }
    p->integrator = PLANT_INTEGRATOR_EXACT;
    p->max_step_s = 50e-6;
    p->dead_time_on = true;
    p->harmonics_on = true;
    p->adc_offset_on = true;
    p->adc_offset_counts = HAL_BOARD_ADC_OFFSET_TOLERANCE_COUNTS;
    p->adc_gain_on = true;
    p->adc_gain_error = HAL_BOARD_ADC_GAIN_TOLERANCE;
    p->adc_noise_on = true;
    p->adc_noise_counts = 1.0;
    p->current_sensor_span_a = 0.5 * HAL_BOARD_CURRENT_FULL_SPAN_A;
    p->encoder_quant_on = true;
    p->encoder_lines = 2500u;
    p->encoder_offset_rad = 0.0;
    p->encoder_reversed = false;
    p->encoder_stuck = false;
}

const char *plant_params_check(const plant_params_t *p)
{
    if (!(p->r_ohm >= 0.0 && p->r_ohm < 1e3)) {
        return "resistance must be in [0, 1000) ohm";
    }
    if (!(p->ld_h > 1e-6 && p->ld_h < 10.0) || !(p->lq_h > 1e-6 && p->lq_h < 10.0)) {
        return "L_d and L_q must be in (1e-6, 10) H";
    }
    if (!(p->lxy_h > 1e-6 && p->lxy_h < 10.0)) {
        return "L_xy must be in (1e-6, 10) H";
    }
    if (!(p->psi_f_wb >= 0.0 && p->psi_f_wb < 10.0) || !(fabs(p->psi5_wb) < 1.0) ||
        !(fabs(p->psi7_wb) < 1.0)) {
        return "PM flux values out of range";
    }
    if (p->pole_pairs < 1 || p->pole_pairs > 64) {
        return "pole pairs must be in 1..64";
    }
    if (!(p->j_kgm2 > 0.0 && p->j_kgm2 < 1e3) || !(p->b_nms >= 0.0 && p->b_nms < 1e3)) {
        return "inertia must be positive and friction non-negative";
    }
    if (!(p->vdc_v > 0.0 && p->vdc_v < 2000.0)) {
        return "Vdc must be in (0, 2000) V";
    }
    if (!(p->dead_time_s >= 0.0 && p->dead_time_s < 50e-6)) {
        return "dead time must be in [0, 50) us";
    }
    if (p->integrator != PLANT_INTEGRATOR_EXACT && p->integrator != PLANT_INTEGRATOR_RK4) {
        return "integrator must be exact or rk4";
    }
    if (!(p->max_step_s > 1e-9 && p->max_step_s <= 1e-3)) {
        return "plant step must be in (1 ns, 1 ms]";
    }
    for (int k = 0; k < PLANT_PHASES; k++) {
        if (!(p->phase_extra_r_ohm[k] >= 0.0 && p->phase_extra_r_ohm[k] < 1e5)) {
            return "extra phase resistance must be in [0, 1e5) ohm";
        }
    }
    if (!(p->current_sensor_span_a >= PLANT_SENSOR_SPAN_MIN_A &&
          p->current_sensor_span_a <= PLANT_SENSOR_SPAN_MAX_A)) {
        return "current sensor span must be in [2, 200] A";
    }
    if (p->encoder_lines < 1u || p->encoder_lines > 1000000u) {
        return "encoder lines must be in 1..1e6";
    }
    if (!(fabs(p->encoder_offset_rad) <= 64.0)) {
        return "encoder offset out of range";
    }
    return "";
}

void plant_vector_voltage(unsigned state, double vdc, double u[4])
{
    double v[PLANT_PHASES];
    int k;
    const double s1 = (double)(((state >> 5) & 1u) + ((state >> 4) & 1u) + ((state >> 3) & 1u));
    const double s2 = (double)(((state >> 2) & 1u) + ((state >> 1) & 1u) + (state & 1u));
    for (k = 0; k < PLANT_PHASES; k++) {
        const double sk = (double)((state >> (5 - k)) & 1u);
        v[k] = vdc * (sk - ((k < 3) ? s1 : s2) / 3.0);
    }
    u[0] = u[1] = u[2] = u[3] = 0.0;
    for (k = 0; k < PLANT_PHASES; k++) {
        const double th = plant_phase_angle_rad[k];
        u[0] += v[k] * cos(th);
        u[1] += v[k] * sin(th);
        u[2] += v[k] * cos(5.0 * th);
        u[3] += v[k] * sin(5.0 * th);
    }
    for (k = 0; k < 4; k++) {
        u[k] /= 3.0;
    }
}

void plant_sync_angle(const plant_params_t *p, plant_state_t *s)
{
    const double th = (double)p->pole_pairs * s->theta_m;
    s->cos_e = cos(th);
    s->sin_e = sin(th);
}

void plant_phase_currents(const plant_params_t *p, const plant_state_t *s, double i[PLANT_PHASES])
{
    const double c = s->cos_e;
    const double sn = s->sin_e;
    (void)p;
    const double ia = s->i_d * c - s->i_q * sn;
    const double ib = s->i_d * sn + s->i_q * c;
    /* i_k = alpha cos th_k + beta sin th_k + x cos 5th_k + y sin 5th_k, angles exact:
     * th  = 0, 120, 240, 30, 150, 270 deg;  5th = 0, 240, 120, 150, 30, 270 deg */
    const double h = 0.86602540378443864676; /* sqrt(3)/2 */
    i[0] = ia + s->i_x;
    i[1] = -0.5 * ia + h * ib - 0.5 * s->i_x - h * s->i_y;
    i[2] = -0.5 * ia - h * ib - 0.5 * s->i_x + h * s->i_y;
    i[3] = h * ia + 0.5 * ib - h * s->i_x + 0.5 * s->i_y;
    i[4] = -h * ia + 0.5 * ib + h * s->i_x + 0.5 * s->i_y;
    i[5] = -ib - s->i_y;
}

/* d psi_pm,xy / d theta_e given cos/sin of theta_e. */
static void plant_xy_emf_shape(const plant_params_t *p, double c, double s, double *gx, double *gy)
{
    /* z = e^{j th}; z^5 and z^7 by complex products */
    const double c2 = c * c - s * s, s2 = 2.0 * c * s;
    const double c4 = c2 * c2 - s2 * s2, s4 = 2.0 * c2 * s2;
    const double c5 = c4 * c - s4 * s, s5 = c4 * s + s4 * c;
    const double c7 = c5 * c2 - s5 * s2, s7 = c5 * s2 + s5 * c2;
    *gx = -5.0 * p->psi5_wb * s5 - 7.0 * p->psi7_wb * s7;
    *gy = 5.0 * p->psi5_wb * c5 - 7.0 * p->psi7_wb * c7;
}

double plant_torque(const plant_params_t *p, const plant_state_t *s)
{
    const double pn3 = 3.0 * (double)p->pole_pairs;
    double te = pn3 * ((p->ld_h - p->lq_h) * s->i_d * s->i_q + p->psi_f_wb * s->i_q);
    if (p->harmonics_on) {
        double gx, gy;
        plant_xy_emf_shape(p, s->cos_e, s->sin_e, &gx, &gy);
        te += pn3 * (gx * s->i_x + gy * s->i_y);
    }
    return te;
}

void plant_outputs(const plant_params_t *p, const plant_state_t *s, plant_out_t *o)
{
    const double two_pi = 2.0 * PLANT_PI;
    const double th = (double)p->pole_pairs * s->theta_m;
    plant_phase_currents(p, s, o->i_phase);
    o->i_alpha = s->i_d * s->cos_e - s->i_q * s->sin_e;
    o->i_beta = s->i_d * s->sin_e + s->i_q * s->cos_e;
    o->psi_d = p->ld_h * s->i_d + p->psi_f_wb;
    o->psi_q = p->lq_h * s->i_q;
    o->psi_s = sqrt(o->psi_d * o->psi_d + o->psi_q * o->psi_q);
    o->torque_nm = plant_torque(p, s);
    o->theta_e = th - two_pi * floor(th / two_pi);
}

/* cos and sin of a small angle (|d| < 0.35: Taylor to 10th/11th order, error < 1e-13). */
static inline void plant_small_rot(double d, double *c, double *s)
{
    if (fabs(d) < 0.35) {
        const double d2 = d * d;
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

/* plant_deriv and plant_rk4_gen are instantiated with a constant `extra`;
 * without forced inlining gcc keeps one shared copy and the normal path pays
 * for the fault path (register pressure, hoisted work). */
#if defined(__GNUC__)
#define PLANT_FORCE_INLINE inline __attribute__((always_inline))
#else
#define PLANT_FORCE_INLINE inline
#endif

/* Coefficients computed once per interval (no divisions in the derivative). */
typedef struct {
    double pn, r, ld, lq, psi_f, inv_ld, inv_lq, inv_lxy, inv_j, b, five_psi5, seven_psi7;
    double t3pn;
    double r_extra_3[PLANT_PHASES]; /* phase_extra_r_ohm / 3 (VSD projection scale) */
    bool harm;
    bool extra_r; /* any phase_extra_r_ohm non-zero; keeps the normal path unchanged */
    int n_open;   /* phases with phase_open, listed in open[] */
    int open[PLANT_PHASES];
    bool fault; /* extra_r or n_open: the fault instantiation of the integrator */
} plant_coef_t;

static void plant_coef(const plant_params_t *p, plant_coef_t *k)
{
    k->pn = (double)p->pole_pairs;
    k->r = p->r_ohm;
    k->ld = p->ld_h;
    k->lq = p->lq_h;
    k->psi_f = p->psi_f_wb;
    k->inv_ld = 1.0 / p->ld_h;
    k->inv_lq = 1.0 / p->lq_h;
    k->inv_lxy = 1.0 / p->lxy_h;
    k->inv_j = 1.0 / p->j_kgm2;
    k->b = p->b_nms;
    k->five_psi5 = 5.0 * p->psi5_wb;
    k->seven_psi7 = 7.0 * p->psi7_wb;
    k->t3pn = 3.0 * k->pn;
    k->harm = p->harmonics_on;
    k->extra_r = false;
    for (int n = 0; n < PLANT_PHASES; n++) {
        k->extra_r = k->extra_r || (p->phase_extra_r_ohm[n] != 0.0);
    }
    if (k->extra_r) { /* normal runs skip this per-interval work */
        for (int n = 0; n < PLANT_PHASES; n++) {
            k->r_extra_3[n] = p->phase_extra_r_ohm[n] / 3.0;
        }
    }
    k->n_open = 0;
    for (int n = 0; n < PLANT_PHASES; n++) {
        if (p->phase_open[n]) {
            k->open[k->n_open++] = n;
        }
    }
    k->fault = k->extra_r || k->n_open > 0;
}

/* Solves g x = r for the n <= 6 open-phase multipliers by elimination with partial pivoting; a
 * pivot below 1e-9 of the largest diagonal entry marks a constraint that the others already
 * imply (all three phases of one set open), whose multiplier is left at 0. */
static void plant_open_solve(int n, double g[PLANT_PHASES][PLANT_PHASES], double r[PLANT_PHASES],
                             double x[PLANT_PHASES])
{
    double tol = 0.0;
    bool used[PLANT_PHASES] = {false, false, false, false, false, false};
    int col;
    for (col = 0; col < n; col++) {
        tol = fmax(tol, fabs(g[col][col]) * 1e-9);
        x[col] = 0.0;
    }
    for (col = 0; col < n; col++) {
        int piv = -1;
        for (int i = 0; i < n; i++) {
            if (!used[i] && (piv < 0 || fabs(g[i][col]) > fabs(g[piv][col]))) {
                piv = i;
            }
        }
        if (piv < 0 || fabs(g[piv][col]) <= tol) {
            continue; /* dependent: this multiplier stays 0 */
        }
        used[piv] = true;
        for (int i = 0; i < n; i++) {
            if (i != piv) {
                const double f = g[i][col] / g[piv][col];
                for (int j = 0; j < n; j++) {
                    g[i][j] -= f * g[piv][j];
                }
                r[i] -= f * r[piv];
            }
        }
        x[col] = r[piv] / g[piv][col];
    }
}

/* The open phases' rows in the rotor frame (c_d, c_q turn with the rotor), their response
 * M^-1 c and their Gram matrix c_j . M^-1 c_l. */
typedef struct {
    double a[PLANT_PHASES][4];
    double b[PLANT_PHASES][4];
    double g[PLANT_PHASES][PLANT_PHASES];
} plant_open_rows_t;

static void plant_open_rows(const plant_coef_t *p, double c, double s, plant_open_rows_t *o)
{
    for (int j = 0; j < p->n_open; j++) {
        const int k = p->open[j];
        /* cos(th_k - th) and sin(th_k - th) from the stationary row */
        o->a[j][0] = plant_vsd_row[0][k] * c + plant_vsd_row[1][k] * s;
        o->a[j][1] = plant_vsd_row[1][k] * c - plant_vsd_row[0][k] * s;
        o->a[j][2] = plant_vsd_row[2][k];
        o->a[j][3] = plant_vsd_row[3][k];
        o->b[j][0] = o->a[j][0] * p->inv_ld;
        o->b[j][1] = o->a[j][1] * p->inv_lq;
        o->b[j][2] = o->a[j][2] * p->inv_lxy;
        o->b[j][3] = o->a[j][3] * p->inv_lxy;
    }
    for (int j = 0; j < p->n_open; j++) {
        for (int l = 0; l < p->n_open; l++) {
            o->g[j][l] = o->a[j][0] * o->b[l][0] + o->a[j][1] * o->b[l][1] +
                         o->a[j][2] * o->b[l][2] + o->a[j][3] * o->b[l][3];
        }
    }
}

/* The open terminals' voltages (multipliers along c_k, volts in the VSD scale) that keep
 * d/dt (c_k . i) = 0 for the derivative dy of the state y at electrical speed we. */
static void plant_open_multipliers(const plant_coef_t *p, plant_open_rows_t *o, const double y[5],
                                   const double dy[4], double we, double lambda[PLANT_PHASES])
{
    double r[PLANT_PHASES];
    for (int j = 0; j < p->n_open; j++) {
        /* d/dt c_j = we (c_q, -c_d, 0, 0) */
        const double drift = we * (o->a[j][1] * y[0] - o->a[j][0] * y[1]);
        r[j] = -(o->a[j][0] * dy[0] + o->a[j][1] * dy[1] + o->a[j][2] * dy[2] + o->a[j][3] * dy[3] +
                 drift);
    }
    plant_open_solve(p->n_open, o->g, r, lambda);
}

/* Moves the currents along M^-1 c_k until every open phase carries none at this angle. */
static void plant_open_project(const plant_coef_t *p, double c, double s, double i[4])
{
    plant_open_rows_t o;
    double r[PLANT_PHASES];
    double mu[PLANT_PHASES];
    plant_open_rows(p, c, s, &o);
    for (int j = 0; j < p->n_open; j++) {
        r[j] = o.a[j][0] * i[0] + o.a[j][1] * i[1] + o.a[j][2] * i[2] + o.a[j][3] * i[3];
    }
    plant_open_solve(p->n_open, o.g, r, mu);
    for (int j = 0; j < p->n_open; j++) {
        for (int m = 0; m < 4; m++) {
            i[m] -= mu[j] * o.b[j][m];
        }
    }
}

typedef struct {
    double did, diq, dix, diy, dw; /* derivatives */
    double te;
} plant_deriv_t;

/* Subtract the extra-resistance drop: phase currents from the state, dv_k =
 * R_k i_k, amplitude-invariant VSD projection (1/3) sum_k dv_k row_k; the
 * zero-sequence part is taken by the isolated neutrals, so four components
 * are the whole effect. alpha-beta is rotated into d-q like the supply. */
static void plant_extra_drop(const plant_coef_t *p, const double y[5], double c, double s,
                             double *ud, double *uq, double *ux, double *uy)
{
    const double ia = y[0] * c - y[1] * s;
    const double ib = y[0] * s + y[1] * c;
    double da = 0.0, db = 0.0, dx = 0.0, dy = 0.0;
    for (int k = 0; k < PLANT_PHASES; k++) {
        const double ik = ia * plant_vsd_row[0][k] + ib * plant_vsd_row[1][k] +
                          y[2] * plant_vsd_row[2][k] + y[3] * plant_vsd_row[3][k];
        const double dv3 = p->r_extra_3[k] * ik;
        da += dv3 * plant_vsd_row[0][k];
        db += dv3 * plant_vsd_row[1][k];
        dx += dv3 * plant_vsd_row[2][k];
        dy += dv3 * plant_vsd_row[3][k];
    }
    *ud -= da * c + db * s;
    *uq -= -da * s + db * c;
    *ux -= dx;
    *uy -= dy;
}

/* `extra` is p->extra_r passed as a constant, so the normal path carries no test. */
static PLANT_FORCE_INLINE void plant_deriv(const plant_coef_t *p, const double y[5], double c,
                                           double s, const double u[4], double t_load,
                                           bool lock_mech, bool extra, plant_deriv_t *k)
{
    const double we = p->pn * y[4];
    double ud = u[0] * c + u[1] * s;
    double uq = -u[0] * s + u[1] * c;
    double ux = u[2], uy = u[3];
    double ex = 0.0, ey = 0.0;
    if (extra && p->extra_r) {
        plant_extra_drop(p, y, c, s, &ud, &uq, &ux, &uy);
    }
    k->did = (ud - p->r * y[0] + we * p->lq * y[1]) * p->inv_ld;
    k->diq = (uq - p->r * y[1] - we * (p->ld * y[0] + p->psi_f)) * p->inv_lq;
    k->te = p->t3pn * ((p->ld - p->lq) * y[0] * y[1] + p->psi_f * y[1]);
    if (p->harm) {
        const double c2 = c * c - s * s, s2 = 2.0 * c * s;
        const double c4 = c2 * c2 - s2 * s2, s4 = 2.0 * c2 * s2;
        const double c5 = c4 * c - s4 * s, s5 = c4 * s + s4 * c;
        const double c7 = c5 * c2 - s5 * s2, s7 = c5 * s2 + s5 * c2;
        const double gx = -p->five_psi5 * s5 - p->seven_psi7 * s7;
        const double gy = p->five_psi5 * c5 - p->seven_psi7 * c7;
        ex = we * gx;
        ey = we * gy;
        k->te += p->t3pn * (gx * y[2] + gy * y[3]);
    }
    k->dix = (ux - p->r * y[2] - ex) * p->inv_lxy;
    k->diy = (uy - p->r * y[3] - ey) * p->inv_lxy;
    k->dw = lock_mech ? 0.0 : (k->te - t_load - p->b * y[4]) * p->inv_j;
    if (extra && p->n_open > 0) {
        plant_open_rows_t o;
        double dy[4] = {k->did, k->diq, k->dix, k->diy};
        double lambda[PLANT_PHASES];
        plant_open_rows(p, c, s, &o);
        plant_open_multipliers(p, &o, y, dy, we, lambda);
        for (int j = 0; j < p->n_open; j++) {
            k->did += lambda[j] * o.b[j][0];
            k->diq += lambda[j] * o.b[j][1];
            k->dix += lambda[j] * o.b[j][2];
            k->diy += lambda[j] * o.b[j][3];
        }
    }
}

static PLANT_FORCE_INLINE double plant_rk4_gen(const plant_coef_t *kc, plant_state_t *s,
                                               const double u[4], double t_load, bool lock_mech,
                                               bool extra, double h)
{
    const double pn = kc->pn;
    const double y0[5] = {s->i_d, s->i_q, s->i_x, s->i_y, s->omega_m};
    double y[5];
    double c0, s0, cr, sr, c, sn;
    plant_deriv_t k1, k2, k3, k4;
    c0 = s->cos_e;
    s0 = s->sin_e;

    plant_deriv(kc, y0, c0, s0, u, t_load, lock_mech, extra, &k1);

    y[0] = y0[0] + 0.5 * h * k1.did;
    y[1] = y0[1] + 0.5 * h * k1.diq;
    y[2] = y0[2] + 0.5 * h * k1.dix;
    y[3] = y0[3] + 0.5 * h * k1.diy;
    y[4] = y0[4] + 0.5 * h * k1.dw;
    plant_small_rot(pn * 0.5 * h * y0[4], &cr, &sr); /* theta_m stage increments */
    c = c0 * cr - s0 * sr;
    sn = s0 * cr + c0 * sr;
    plant_deriv(kc, y, c, sn, u, t_load, lock_mech, extra, &k2);
    const double w2 = y[4];

    y[0] = y0[0] + 0.5 * h * k2.did;
    y[1] = y0[1] + 0.5 * h * k2.diq;
    y[2] = y0[2] + 0.5 * h * k2.dix;
    y[3] = y0[3] + 0.5 * h * k2.diy;
    y[4] = y0[4] + 0.5 * h * k2.dw;
    plant_small_rot(pn * 0.5 * h * w2, &cr, &sr);
    c = c0 * cr - s0 * sr;
    sn = s0 * cr + c0 * sr;
    plant_deriv(kc, y, c, sn, u, t_load, lock_mech, extra, &k3);
    const double w3 = y[4];

    y[0] = y0[0] + h * k3.did;
    y[1] = y0[1] + h * k3.diq;
    y[2] = y0[2] + h * k3.dix;
    y[3] = y0[3] + h * k3.diy;
    y[4] = y0[4] + h * k3.dw;
    plant_small_rot(pn * h * w3, &cr, &sr);
    c = c0 * cr - s0 * sr;
    sn = s0 * cr + c0 * sr;
    plant_deriv(kc, y, c, sn, u, t_load, lock_mech, extra, &k4);
    const double w4 = y[4];

    s->i_d = y0[0] + h / 6.0 * (k1.did + 2.0 * k2.did + 2.0 * k3.did + k4.did);
    s->i_q = y0[1] + h / 6.0 * (k1.diq + 2.0 * k2.diq + 2.0 * k3.diq + k4.diq);
    s->i_x = y0[2] + h / 6.0 * (k1.dix + 2.0 * k2.dix + 2.0 * k3.dix + k4.dix);
    s->i_y = y0[3] + h / 6.0 * (k1.diy + 2.0 * k2.diy + 2.0 * k3.diy + k4.diy);
    s->omega_m = y0[4] + h / 6.0 * (k1.dw + 2.0 * k2.dw + 2.0 * k3.dw + k4.dw);
    {
        const double dth = h / 6.0 * (y0[4] + 2.0 * w2 + 2.0 * w3 + w4);
        s->theta_m += dth;
        plant_small_rot(pn * dth, &cr, &sr);
        s->cos_e = c0 * cr - s0 * sr;
        s->sin_e = s0 * cr + c0 * sr;
    }
    if (extra && kc->n_open > 0) { /* the step's truncation error off the constraint */
        double i[4] = {s->i_d, s->i_q, s->i_x, s->i_y};
        plant_open_project(kc, s->cos_e, s->sin_e, i);
        s->i_d = i[0];
        s->i_q = i[1];
        s->i_x = i[2];
        s->i_y = i[3];
    }
    return h / 6.0 * (k1.te + 2.0 * k2.te + 2.0 * k3.te + k4.te);
}

/* The normal and the fault instantiation as separate functions: with one
 * shared body gcc hoists fault-path work into the normal path (measured
 * ~10 % slower); this way the normal path compiles as before. */
static double plant_rk4_plain(const plant_coef_t *kc, plant_state_t *s, const double u[4],
                              double t_load, bool lock_mech, double h)
{
    return plant_rk4_gen(kc, s, u, t_load, lock_mech, false, h);
}

static double plant_rk4_fault(const plant_coef_t *kc, plant_state_t *s, const double u[4],
                              double t_load, bool lock_mech, double h)
{
    return plant_rk4_gen(kc, s, u, t_load, lock_mech, true, h);
}

double plant_rk4_step(const plant_params_t *p, plant_state_t *s, const double u[4], double t_load,
                      bool lock_mech, double h)
{
    plant_coef_t kc;
    plant_coef(p, &kc);
    if (kc.fault) {
        return plant_rk4_fault(&kc, s, u, t_load, lock_mech, h);
    }
    return plant_rk4_plain(&kc, s, u, t_load, lock_mech, h);
}

double plant_integrate(const plant_params_t *p, plant_state_t *s, const double u[4], double t_load,
                       bool lock_mech, double h)
{
    plant_sync_angle(p, s);
    return plant_integrate_nosync(p, s, u, t_load, lock_mech, h);
}

double plant_integrate_nosync(const plant_params_t *p, plant_state_t *s, const double u[4],
                              double t_load, bool lock_mech, double h)
{
    double n, hs, te_int = 0.0;
    long i, steps;
    plant_coef_t kc;
    if (!(h > 0.0)) {
        return 0.0;
    }
    n = ceil(h / p->max_step_s - 1e-9);
    steps = (n < 1.0) ? 1L : (long)n;
    hs = h / (double)steps;
    plant_coef(p, &kc);
    if (kc.fault) { /* flag tested once per interval */
        for (i = 0; i < steps; i++) {
            te_int += plant_rk4_fault(&kc, s, u, t_load, lock_mech, hs);
        }
    } else {
        for (i = 0; i < steps; i++) {
            te_int += plant_rk4_plain(&kc, s, u, t_load, lock_mech, hs);
        }
    }
    return te_int;
}

void plant_open_commutate(const plant_params_t *p, plant_state_t *s)
{
    plant_coef_t kc;
    double i[4] = {s->i_d, s->i_q, s->i_x, s->i_y};
    plant_coef(p, &kc);
    if (kc.n_open == 0) {
        return;
    }
    plant_open_project(&kc, s->cos_e, s->sin_e, i);
    s->i_d = i[0];
    s->i_q = i[1];
    s->i_x = i[2];
    s->i_y = i[3];
}

double plant_open_terminal_voltage(const plant_params_t *p, const plant_state_t *s, int phase,
                                   const double u[4])
{
    plant_params_t free = *p;
    plant_coef_t kc;
    plant_deriv_t k;
    plant_open_rows_t o;
    const double y[5] = {s->i_d, s->i_q, s->i_x, s->i_y, s->omega_m};
    double lambda[PLANT_PHASES];
    double dy[4];
    for (int n = 0; n < PLANT_PHASES; n++) {
        free.phase_open[n] = false;
    }
    plant_coef(&free, &kc);
    plant_deriv(&kc, y, s->cos_e, s->sin_e, u, 0.0, true, kc.extra_r, &k);
    kc.n_open = 1;
    kc.open[0] = phase;
    dy[0] = k.did;
    dy[1] = k.diq;
    dy[2] = k.dix;
    dy[3] = k.diy;
    plant_open_rows(&kc, s->cos_e, s->sin_e, &o);
    plant_open_multipliers(&kc, &o, y, dy, kc.pn * s->omega_m, lambda);
    return 3.0 * lambda[0];
}
