/* Identification step 7, inertia and friction: see ident_mech.h. */
#include "ident_mech.h"

#include "ctl_q.h"
#include "ctl_qmath.h"

#define MECH_TOP_FRACTION 0.5f /* w_top, of the flux step's test speed */
#define MECH_LOW_FRACTION 0.2f /* the runs turn back up here, of w_top */
#define MECH_BAND_LOW 0.3f     /* the runs' band, of w_top: the reversals stay outside it */
#define MECH_BAND_HIGH 0.9f
#define MECH_STILL_S 0.25f      /* at standstill between the directions (the protection's window) */
#define MECH_SPEED_BW 20.0f     /* rad/s, the friction step's speed loop */
#define MECH_SETTLE_S 0.4f      /* a few time constants of that loop and of its integral */
#define MECH_SETTLE_BAND 0.002f /* of the point's speed */
#define MECH_SETTLE_IN_BAND_S 0.1f
#define MECH_SETTLE_MAX_S 2.0f
#define MECH_POINT_TURNS 16 /* whole electrical turns per friction point */
#define MECH_BLOCK_TURNS 2  /* turns per block of the scatter (neighbouring turns correlate) */
#define MECH_RUN_S 0.25f    /* an acceleration run's duration the torque is sized for */
#define MECH_FRICTION_MARGIN 4.0f
#define MECH_RUN_MIN_SHARE 0.5f /* of the test current: see mech_runs_start */
#define MECH_REVERSAL_S 0.01f   /* the current settles after a reversal (150 Hz regulator) */
#define MECH_RUN_MIN_PERIODS 50
#define MECH_STOP_HOLD_S 0.2f
#define MECH_SPEED_TOLERANCE 0.05f
#define MECH_POOR_RELATIVE 0.02f /* the inertia's scatter */
#define MECH_TWO_PI 6.2831853f

enum { MC_PROBE, MC_MOVE, MC_STILL, MC_SETTLE, MC_MEASURE, MC_RUNS, MC_STOP };

static float mech_abs(float v) { return (v < 0.0f) ? -v : v; }

/* The rotor's mechanical speed, rad/s, in the rotor frame's direction. */
static float mech_speed(const ident_ctx_t *x)
{
    return MECH_TWO_PI * x->speed_e * mech_abs(x->cpe) / x->m.counts_per_turn;
}

/* The x-y plane's power this period, W / 3: the voltage that reached it (the request less the
 * dead time's feed-forward) less the resistive drop, times the currents. */
static float mech_xy_power(const ident_ctx_t *x)
{
    const float r = ident_known(x, COMM_Q_R, x->m.r);
    const float ux = x->reg.u[2] - x->comp_xy[0] - r * x->i_xy[0];
    const float uy = x->reg.u[3] - x->comp_xy[1] - r * x->i_xy[1];
    return ux * x->i_xy[0] + uy * x->i_xy[1];
}

/* The shaft torque of this period's measured currents (the reluctance term for any i_d). */
static float mech_torque(const ident_ctx_t *x, const ident_mech_t *s)
{
    const float ld = ident_known(x, COMM_Q_LD, x->m.ld);
    const float lq = ident_known(x, COMM_Q_LQ, x->m.lq);
    const float kr = 3.0f * (float)x->m.pole_pairs * (ld - lq);
    return (s->kt + kr * x->i_dq[0]) * x->i_dq[1];
}

void ident_mech_begin(ident_ctx_t *x, ident_mech_t *s)
{
    const ident_result_t *psi = &x->result[COMM_Q_PSI_F];
    /* a poor psi_f is still the machine's (the set's may be three times off: a weak magnet gave
     * J and B +234 % "ok"); the results then say whose torque constant they rest on */
    const bool identified =
        (psi->quality == COMM_QUALITY_OK || psi->quality == COMM_QUALITY_POOR) && psi->value > 0.0f;
    const float psi_f = identified ? psi->value : x->m.psi_f;
    const float pn = (float)x->m.pole_pairs;
    const float a = 0.1f * x->m.vdc / psi_f; /* the flux step's test speed, electrical */
    const float b = 0.3f * x->m.overspeed_e; /* rad/s */
    s->kt = 3.0f * pn * psi_f;
    s->kt_rel_sigma = identified ? psi->sigma / psi->value : 0.0f;
    s->w_top = MECH_TOP_FRACTION * ((a < b) ? a : b) / pn;
    s->torque_sum = 0.0f;
    s->speed_ref = 0.0f;
    s->point = 0;
    s->max_speed_error = 0.0f;
    s->runs = 0;
    x->frame = IDENT_FRAME_ROTOR;
    x->damping = 0.0f;
    x->ref_dq[0] = 0.0f;
    x->ref_dq[1] = -x->i_test;
    ident_goto(x, MC_PROBE);
}

/* The friction point k's speed: -w_top (where the probe ends), -w_top/2, +w_top/2, +w_top
 * (where the runs begin). */
static float mech_point_speed(const ident_mech_t *s, int16_t k)
{
    static const float share[IDENT_MECH_POINTS] = {-1.0f, -0.5f, 0.5f, 1.0f};
    return share[k] * s->w_top;
}

/* The probe reached -w_top: the first inertia, and the speed loop from it. */
static ident_status_t mech_probe_done(ident_ctx_t *x, ident_mech_t *s, float w)
{
    const float j = s->torque_sum * x->m.ts / w;
    float kp;
    if (!(j > 1.0e-6f && j < 1000.0f)) { /* no loop can be built on it */
        ident_set_result(x, COMM_Q_INERTIA, j, 0.0f, 0.0f, COMM_QUALITY_FAILED,
                         COMM_REASON_OUT_OF_RANGE);
        return ident_fail(x, COMM_REASON_OUT_OF_RANGE);
    }
    kp = MECH_SPEED_BW * j / s->kt; /* A per rad/s: the loop crosses at BW */
    s->j_probe = j;
    s->speed_pi.kp = kp;
    s->speed_pi.ki_ts = kp * 0.25f * MECH_SPEED_BW * x->m.ts;
    s->speed_pi.integ = 0.0f; /* the friction's share, small: the test current would overshoot */
    s->speed_ref = w;
    s->accel_max = 0.5f * s->kt * x->i_test / j;
    ident_goto(x, MC_MOVE);
    return IDENT_RUNNING;
}

/* The reference one period closer to target; true once there. */
static bool mech_ramp(const ident_ctx_t *x, ident_mech_t *s, float target)
{
    const float step = s->accel_max * x->m.ts;
    if (s->speed_ref < target - step) {
        s->speed_ref += step;
        return false;
    }
    if (s->speed_ref > target + step) {
        s->speed_ref -= step;
        return false;
    }
    s->speed_ref = target;
    return true;
}

/* At least MECH_SETTLE_S, then until the speed has stayed within MECH_SETTLE_BAND of the point's
 * for MECH_SETTLE_IN_BAND_S (at most MECH_SETTLE_MAX_S): a heavy rotor's speed was still
 * settling at the points, and the drift's correction left B 20..36 % off (six pole pairs, ten
 * times the inertia, issue 25). */
static bool mech_settled(const ident_ctx_t *x, ident_mech_t *s)
{
    const float target = mech_point_speed(s, s->point);
    const float err = mech_abs(mech_speed(x) - target);
    const bool near = err < MECH_SETTLE_BAND * mech_abs(target);
    s->in_band = (near && x->t > 1u) ? s->in_band + 1u : 0u; /* from the sub-phase's start */
    return (x->t >= ident_periods(x, MECH_SETTLE_S) &&
            s->in_band >= ident_periods(x, MECH_SETTLE_IN_BAND_S)) ||
           x->t >= ident_periods(x, MECH_SETTLE_MAX_S);
}

static void mech_point_start(ident_ctx_t *x, ident_mech_t *s, const ident_input_t *in)
{
    ident_blocks_init(&s->point_torque, MECH_BLOCK_TURNS);
    s->point_turns = 0;
    s->xy_power = 0.0f;
    s->xy_n = 0;
    s->turn_start = in->position;
    s->turn_torque = 0.0f;
    s->turn_n = 0;
    s->point_counts = 0;
    s->point_periods = 0;
    ident_goto(x, MC_MEASURE);
}

/* The mechanical speed over counts moved in n periods, exact (unlike the speed estimate). */
static float mech_count_speed(const ident_ctx_t *x, int32_t counts, int32_t n)
{
    const float turns_e = (float)counts / x->cpe;
    return MECH_TWO_PI * turns_e * mech_abs(x->cpe) / x->m.counts_per_turn / ((float)n * x->m.ts);
}

/* A whole electrical turn is complete: its mean torque, its speed at its centre. */
static void mech_close_turn(ident_ctx_t *x, ident_mech_t *s, const ident_input_t *in)
{
    const int32_t moved = in->position - s->turn_start;
    const float w = mech_count_speed(x, moved, s->turn_n);
    const float centre = ((float)s->point_periods + 0.5f * (float)s->turn_n) * x->m.ts;
    ident_blocks_add(&s->point_torque, s->turn_torque / (float)s->turn_n);
    s->point_turns++;
    if (s->point_turns == 1) {
        s->first_w = w;
        s->first_t = centre;
    }
    s->last_w = w;
    s->last_t = centre;
    s->point_counts += moved;
    s->point_periods += s->turn_n;
    s->turn_start = in->position;
    s->turn_torque = 0.0f;
    s->turn_n = 0;
}

/* One period of a friction point; true once its turns are complete. */
static bool mech_point_measure(ident_ctx_t *x, ident_mech_t *s, const ident_input_t *in)
{
    const int16_t k = s->point;
    s->turn_torque += mech_torque(x, s);
    s->turn_n++;
    s->xy_power += mech_xy_power(x);
    s->xy_n++;
    if (mech_abs((float)(in->position - s->turn_start)) >= mech_abs(x->cpe)) {
        mech_close_turn(x, s, in);
    }
    if (s->point_turns < MECH_POINT_TURNS) {
        return false;
    }
    {
        const float w = mech_count_speed(x, s->point_counts, s->point_periods);
        const float target = mech_point_speed(s, k);
        const float err = mech_abs((w - target) / target);
        s->point_w[k] = w;
        s->point_t[k] = ident_blocks_mean(&s->point_torque);
        {
            /* the x-y plane's torque, bounded by its power (the harmonic regulator holds the
             * currents near zero, but what remains of them, with small L_xy, left B 6..8 % off
             * at 1.3 % sigma): its size is added to the point's uncertainty, not taken out (the
             * dead time's share of the voltage is not known well enough to subtract) */
            const float t_xy = 3.0f * s->xy_power / ((float)s->xy_n * w);
            const float sg = ident_blocks_sigma(&s->point_torque);
            s->point_sigma[k] = ctl_sqrtf(sg * sg + t_xy * t_xy);
        }
        s->point_accel[k] = (s->last_w - s->first_w) / (s->last_t - s->first_t);
        s->max_speed_error = (err > s->max_speed_error) ? err : s->max_speed_error;
    }
    return true;
}

/* The friction fit's residual variance, sum of squares over its two degrees of freedom. */
static float mech_fit_residual_variance(const ident_mech_t *s, float j)
{
    float rss = 0.0f;
    int16_t k;
    for (k = 0; k < IDENT_MECH_POINTS; k++) {
        const float w = s->point_w[k], sg = (w < 0.0f) ? -1.0f : 1.0f;
        const float r = s->point_t[k] - j * s->point_accel[k] - s->b * w - s->tc * sg;
        rss += r * r;
    }
    return rss / (float)(IDENT_MECH_POINTS - 2);
}

/* B and Tc by least squares over the points, T - J dw/dt = B w + Tc sign(w), with inertia j. */
static void mech_friction_fit(ident_mech_t *s, float j)
{
    float sww = 0.0f, sws = 0.0f, sss = 0.0f, swt = 0.0f, sst = 0.0f, var = 0.0f, det;
    int16_t k;
    for (k = 0; k < IDENT_MECH_POINTS; k++) {
        const float w = s->point_w[k], sg = (w < 0.0f) ? -1.0f : 1.0f;
        const float t = s->point_t[k] - j * s->point_accel[k];
        sww += w * w;
        sws += w * sg;
        sss += sg * sg;
        swt += w * t;
        sst += sg * t;
        var += s->point_sigma[k] * s->point_sigma[k];
    }
    det = sww * sss - sws * sws;
    s->b = (det > 0.0f) ? (swt * sss - sst * sws) / det : 0.0f;
    s->tc = (sss > 0.0f) ? (sst - s->b * sws) / sss : 0.0f;
    /* each point's mean torque with the larger of the points' mean variance and the fit's
     * residual variance (two degrees of freedom): the residuals carry what the model B w +
     * Tc sign(w) leaves out (a drag that does not grow in proportion to the speed), which the
     * turns' scatter does not see. cov = var (A'A)^-1 */
    var /= (float)IDENT_MECH_POINTS;
    {
        const float res = mech_fit_residual_variance(s, j);
        var = (res > var) ? res : var;
    }
    s->b_sigma = (det > 0.0f) ? ctl_sqrtf(var * sss / det) : 0.0f;
}

/* The runs: a torque that lasts MECH_RUN_S across the band, and well above the friction. */
static void mech_runs_start(ident_ctx_t *x, ident_mech_t *s)
{
    const float band = (MECH_BAND_HIGH - MECH_BAND_LOW) * s->w_top;
    const float friction = mech_abs(s->b) * s->w_top + mech_abs(s->tc);
    float torque = s->j_probe * band / MECH_RUN_S;
    if (torque < MECH_FRICTION_MARGIN * friction) {
        torque = MECH_FRICTION_MARGIN * friction;
    }
    if (torque < MECH_RUN_MIN_SHARE * s->kt * x->i_test) {
        torque = MECH_RUN_MIN_SHARE * s->kt * x->i_test;
    }
    s->i_run = torque / s->kt;
    s->i_run = (s->i_run > x->i_test) ? x->i_test : s->i_run;
    s->direction = -1; /* from +w_top, down first */
    s->since_reversal = 0u;
    s->fit.n = 0;
    ident_goto(x, MC_RUNS);
}

static void mech_fit_reset(ident_mech_fit_t *f)
{
    f->n = 0;
    f->st = f->stt = f->sw = f->stw = f->storque = f->ssign = 0.0f;
}

/* A run left the band: its slope and means. */
static void mech_run_close(ident_mech_t *s)
{
    ident_mech_fit_t *f = &s->fit;
    const float n = (float)f->n;
    const float den = n * f->stt - f->st * f->st;
    const float alpha = (den > 0.0f) ? (n * f->stw - f->st * f->sw) / den : 0.0f;
    /* a run too short to fit, or flat (nothing to divide by), is left out */
    if (f->n >= MECH_RUN_MIN_PERIODS && mech_abs(alpha) > 0.0f && s->runs < IDENT_MECH_RUNS) {
        const int16_t k = s->runs;
        s->run_alpha[k] = alpha;
        s->run_torque[k] = f->storque / n;
        s->run_w[k] = f->sw / n;
        s->run_sign[k] = f->ssign / n;
        s->runs++;
    }
    mech_fit_reset(f);
}

/* One period of the runs; true once they are all measured. */
static bool mech_runs(ident_ctx_t *x, ident_mech_t *s, float w)
{
    ident_mech_fit_t *f = &s->fit;
    if ((s->direction > 0 && w >= s->w_top) ||
        (s->direction < 0 && w <= MECH_LOW_FRACTION * s->w_top)) {
        s->direction = (int16_t)-s->direction;
        s->since_reversal = 0u;
        mech_run_close(s);
    }
    s->since_reversal++;
    x->ref_dq[1] = (float)s->direction * s->i_run;
    if (w >= MECH_BAND_LOW * s->w_top && w <= MECH_BAND_HIGH * s->w_top &&
        s->since_reversal >= ident_periods(x, MECH_REVERSAL_S)) {
        const float t = (float)f->n * x->m.ts;
        f->n++;
        f->st += t;
        f->stt += t * t;
        f->sw += w;
        f->stw += t * w;
        f->storque += mech_torque(x, s);
        f->ssign += (w < 0.0f) ? -1.0f : 1.0f;
    } else if (f->n > 0) {
        mech_run_close(s);
    }
    return s->runs >= IDENT_MECH_RUNS;
}

/* The runs' inertia with the friction s holds: each run's (T - B w - Tc sign(w)) / alpha, their
 * mean and its standard error. */
static float mech_inertia(const ident_mech_t *s, float *sigma)
{
    float mean = 0.0f, m2 = 0.0f, j[IDENT_MECH_RUNS];
    int16_t k;
    for (k = 0; k < s->runs; k++) {
        j[k] = (s->run_torque[k] - s->b * s->run_w[k] - s->tc * s->run_sign[k]) / s->run_alpha[k];
        mean += j[k] / (float)s->runs;
    }
    for (k = 0; k < s->runs; k++) {
        m2 += (j[k] - mean) * (j[k] - mean);
    }
    *sigma = (s->runs > 1) ? ctl_sqrtf(m2 / ((float)(s->runs - 1) * (float)s->runs)) : 0.0f;
    return mean;
}

/* The results. The friction was fitted with the probe's inertia (its points' drift times J);
 * with the runs' inertia it is fitted again, and the inertia follows it once more. */
/* J and B are torques over motion: no better than psi_f, the torque constant's. An ok result
 * on a poor psi_f becomes poor with psi_f's reason. */
static void mech_torque_quality(const ident_ctx_t *x, int16_t *quality, int16_t *reason)
{
    const ident_result_t *psi = &x->result[COMM_Q_PSI_F];
    if (*quality == COMM_QUALITY_OK && psi->quality == COMM_QUALITY_POOR) {
        *quality = COMM_QUALITY_POOR;
        *reason = psi->reason;
    }
}

static ident_status_t mech_finish(ident_ctx_t *x, ident_mech_t *s)
{
    float j_sigma, j, b;
    int16_t quality = COMM_QUALITY_OK, reason = COMM_REASON_NONE;
    mech_friction_fit(s, mech_inertia(s, &j_sigma));
    j = mech_inertia(s, &j_sigma);
    mech_friction_fit(s, j);
    if (!(j > 1.0e-6f && j < 1000.0f)) {
        quality = COMM_QUALITY_FAILED;
        reason = COMM_REASON_OUT_OF_RANGE;
    } else if (j_sigma > MECH_POOR_RELATIVE * j) {
        quality = COMM_QUALITY_POOR;
        reason = COMM_REASON_SCATTER;
    }
    j_sigma = ctl_sqrtf(j_sigma * j_sigma + j * j * s->kt_rel_sigma * s->kt_rel_sigma);
    mech_torque_quality(x, &quality, &reason);
    ident_set_result(x, COMM_Q_INERTIA, j, j_sigma, (float)s->runs, quality, reason);
    /* a viscous coefficient below zero is noise around a frictionless shaft */
    b = (s->b > 0.0f) ? s->b : 0.0f;
    quality = COMM_QUALITY_OK;
    reason = COMM_REASON_NONE;
    if (!(b < 1000.0f)) {
        quality = COMM_QUALITY_FAILED;
        reason = COMM_REASON_OUT_OF_RANGE;
    } else if (s->max_speed_error > MECH_SPEED_TOLERANCE) {
        quality = COMM_QUALITY_POOR;
        reason = COMM_REASON_NO_SPEED;
    }
    mech_torque_quality(x, &quality, &reason);
    ident_set_result(x, COMM_Q_FRICTION, b,
                     ctl_sqrtf(s->b_sigma * s->b_sigma + b * b * s->kt_rel_sigma * s->kt_rel_sigma),
                     s->tc, quality, reason);
    return IDENT_DONE;
}

/* The friction points, one after the other, then the runs. */
static void mech_friction_period(ident_ctx_t *x, ident_mech_t *s, const ident_input_t *in)
{
    switch (x->phase) {
    case MC_MOVE: {
        /* through standstill, not across it: a rotor that turns back under current dwells
         * near one angle, where the protection's open-phase window would find a phase that
         * carried little and call it open */
        const float target = mech_point_speed(s, s->point);
        const bool across = s->speed_ref * target < 0.0f;
        if (mech_ramp(x, s, across ? 0.0f : target)) {
            ident_goto(x, across ? MC_STILL : MC_SETTLE);
        }
        break;
    }
    case MC_STILL:
        if (x->t >= ident_periods(x, MECH_STILL_S)) {
            ident_goto(x, MC_MOVE);
        }
        break;
    case MC_SETTLE:
        if (mech_settled(x, s)) {
            mech_point_start(x, s, in);
        }
        break;
    default: /* MC_MEASURE */
        if (mech_point_measure(x, s, in)) {
            s->point++;
            if (s->point < IDENT_MECH_POINTS) {
                ident_goto(x, MC_MOVE);
            } else {
                mech_friction_fit(s, s->j_probe);
                mech_runs_start(x, s);
            }
        }
        break;
    }
}

ident_status_t ident_mech_step(ident_ctx_t *x, ident_mech_t *s, const ident_input_t *in)
{
    const float w = mech_speed(x);
    switch (x->phase) {
    case MC_PROBE:
        s->torque_sum += mech_torque(x, s);
        return (w <= -s->w_top) ? mech_probe_done(x, s, w) : IDENT_RUNNING;
    case MC_RUNS:
        if (mech_runs(x, s, w)) {
            s->speed_pi.integ = 0.0f;
            s->speed_ref = w;
            ident_goto(x, MC_STOP);
        }
        return IDENT_RUNNING;
    case MC_STOP:
        if (mech_ramp(x, s, 0.0f) && x->t >= ident_periods(x, MECH_STOP_HOLD_S) &&
            mech_abs(w) < 0.05f * s->w_top) {
            return mech_finish(x, s);
        }
        break;
    default:
        mech_friction_period(x, s, in);
        break;
    }
    ident_speed_loop(x, &s->speed_pi, s->speed_ref - w);
    return IDENT_RUNNING;
}
