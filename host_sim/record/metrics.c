/* Metric functions, see metrics.h. */
#include "metrics.h"

#include <math.h>

double metrics_mean(const double *x, size_t n)
{
    double s = 0.0;
    size_t i;
    if (n == 0) {
        return 0.0;
    }
    for (i = 0; i < n; i++) {
        s += x[i];
    }
    return s / (double)n;
}

double metrics_std(const double *x, size_t n)
{
    double m, s = 0.0;
    size_t i;
    if (n < 2) {
        return 0.0;
    }
    m = metrics_mean(x, n);
    for (i = 0; i < n; i++) {
        s += (x[i] - m) * (x[i] - m);
    }
    return sqrt(s / (double)n);
}

double metrics_peak_to_peak(const double *x, size_t n)
{
    double lo, hi;
    size_t i;
    if (n == 0) {
        return 0.0;
    }
    lo = hi = x[0];
    for (i = 1; i < n; i++) {
        lo = (x[i] < lo) ? x[i] : lo;
        hi = (x[i] > hi) ? x[i] : hi;
    }
    return hi - lo;
}

double metrics_rms2(const double *a, const double *b, size_t n)
{
    double s = 0.0;
    size_t i;
    if (n == 0) {
        return 0.0;
    }
    for (i = 0; i < n; i++) {
        s += a[i] * a[i] + b[i] * b[i];
    }
    return sqrt(s / (double)n);
}

/* Sums of x cos(h theta) and x sin(h theta), h = 1..50, per channel. */
typedef struct {
    double a[51][METRICS_MAX_CHANNELS], b[51][METRICS_MAX_CHANNELS];
} metrics_projections_t;

/* Projections on cos / sin (h theta), h = 1..50, of every channel, with e^{j h theta} by
 * repeated complex multiplication (one libm call per sample, shared by the channels). The
 * channel loop runs over METRICS_MAX_CHANNELS, the unused ones at zero, so its width is a
 * constant the compiler vectorises (issue 28: a third of reproduce's instructions were here);
 * each channel's sums are the same operations in the same order, so the same bits. */
static void metrics_harmonics(const double *const *x, int channels, const double *theta, size_t n,
                              metrics_projections_t *pr)
{
    size_t i;
    int h, k;
    for (h = 0; h <= 50; h++) {
        for (k = 0; k < METRICS_MAX_CHANNELS; k++) {
            pr->a[h][k] = pr->b[h][k] = 0.0;
        }
    }
    for (i = 0; i < n; i++) {
        const double c1 = cos(theta[i]), s1 = sin(theta[i]);
        double ch = c1, sh = s1, xi[METRICS_MAX_CHANNELS] = {0.0};
        for (k = 0; k < channels; k++) {
            xi[k] = x[k][i];
        }
        for (h = 1; h <= 50; h++) {
            double t;
            for (k = 0; k < METRICS_MAX_CHANNELS; k++) {
                pr->a[h][k] += xi[k] * ch;
                pr->b[h][k] += xi[k] * sh;
            }
            t = ch * c1 - sh * s1;
            sh = sh * c1 + ch * s1;
            ch = t;
        }
    }
}

/* Means and covariance (population) of the basis signals. */
static void metrics_moments(const double *const *x, int channels, size_t n,
                            double mean[METRICS_MAX_CHANNELS],
                            double cov[METRICS_MAX_CHANNELS][METRICS_MAX_CHANNELS])
{
    size_t i;
    int j, l;
    for (j = 0; j < channels; j++) {
        mean[j] = metrics_mean(x[j], n);
    }
    for (j = 0; j < channels; j++) {
        for (l = j; l < channels; l++) {
            double s = 0.0;
            for (i = 0; i < n; i++) {
                s += (x[j][i] - mean[j]) * (x[l][i] - mean[l]);
            }
            cov[j][l] = cov[l][j] = s / (double)n;
        }
    }
}

/* One combination's THD from the basis projections and covariance. */
static int metrics_thd_of(const metrics_projections_t *pr,
                          double cov[METRICS_MAX_CHANNELS][METRICS_MAX_CHANNELS], const double *w,
                          int channels, size_t n, metrics_thd_t *out)
{
    double q1 = 0.0, sum_h = 0.0, q2 = 0.0;
    int h, j, l;
    for (j = 0; j < channels; j++) {
        for (l = 0; l < channels; l++) {
            q2 += w[j] * cov[j][l] * w[l];
        }
    }
    for (h = 1; h <= 50; h++) {
        double ah = 0.0, bh = 0.0, qh2;
        for (j = 0; j < channels; j++) {
            ah += w[j] * pr->a[h][j];
            bh += w[j] * pr->b[h][j];
        }
        ah = ah * 2.0 / (double)n;
        bh = bh * 2.0 / (double)n;
        qh2 = 0.5 * (ah * ah + bh * bh);
        if (h == 1) {
            q1 = sqrt(qh2);
        } else {
            sum_h += qh2;
        }
    }
    out->fundamental_rms = q1;
    out->total_rms_ac = sqrt(fmax(q2, 0.0));
    if (!(q1 >= METRICS_THD_MIN_FUNDAMENTAL_RMS)) {
        return -1;
    }
    out->thd = sqrt(fmax(q2 - q1 * q1, 0.0)) / q1;
    out->thd_h50 = sqrt(sum_h) / q1;
    return 0;
}

int metrics_thd_combined(const double *const *basis, int n_basis,
                         const double weights[][METRICS_MAX_CHANNELS], int n_out,
                         const double *theta, size_t n, metrics_thd_t *out)
{
    metrics_projections_t pr;
    double mean[METRICS_MAX_CHANNELS], cov[METRICS_MAX_CHANNELS][METRICS_MAX_CHANNELS];
    int k, meaningful = 0;
    for (k = 0; k < n_out; k++) {
        out[k].fundamental_rms = 0.0;
        out[k].total_rms_ac = 0.0;
        out[k].thd = -1.0;
        out[k].thd_h50 = -1.0;
    }
    if (n < 8 || n_basis < 1 || n_basis > METRICS_MAX_CHANNELS || n_out > METRICS_MAX_CHANNELS) {
        return 0;
    }
    metrics_harmonics(basis, n_basis, theta, n, &pr);
    metrics_moments(basis, n_basis, n, mean, cov);
    for (k = 0; k < n_out; k++) {
        if (metrics_thd_of(&pr, cov, weights[k], n_basis, n, &out[k]) == 0) {
            meaningful++;
        }
    }
    return meaningful;
}

int metrics_thd(const double *x, const double *theta, size_t n, metrics_thd_t *out)
{
    static const double identity[1][METRICS_MAX_CHANNELS] = {{1.0}};
    const double *const basis[1] = {x};
    return (metrics_thd_combined(basis, 1, identity, 1, theta, n, out) == 1) ? 0 : -1;
}

int metrics_whole_periods(const double *theta_unwrapped, size_t n, size_t max_samples,
                          size_t *first)
{
    const double two_pi = 6.28318530717958648;
    size_t start, i;
    double span, target;
    int periods;
    *first = n;
    if (n < 2) {
        return 0;
    }
    start = (max_samples < n) ? n - max_samples : 0;
    span = fabs(theta_unwrapped[n - 1] - theta_unwrapped[start]);
    periods = (int)floor(span / two_pi);
    if (periods < 1) {
        return 0;
    }
    /* first sample whose remaining span (to the last sample) is below periods * 2 pi:
     * the n - i samples then cover periods * 2 pi to within one sample step */
    target = (double)periods * two_pi;
    {
        /* half a sample step of tolerance keeps exact multiples from rounding either way */
        const double half_step = 0.5 * span / (double)(n - 1 - start);
        target -= half_step;
    }
    for (i = start; i + 1 < n; i++) {
        if (fabs(theta_unwrapped[n - 1] - theta_unwrapped[i]) < target) {
            break;
        }
    }
    *first = i;
    return periods;
}

double metrics_switching_freq(const unsigned *states, size_t n, double window_s)
{
    unsigned long count = 0;
    size_t i;
    if (n < 2 || !(window_s > 0.0)) {
        return 0.0;
    }
    for (i = 1; i < n; i++) {
        unsigned diff = (states[i] ^ states[i - 1]) & 63u;
        while (diff != 0u) {
            count += diff & 1u;
            diff >>= 1;
        }
    }
    return (double)count / 2.0 / window_s / 6.0;
}

void metrics_settle_begin(metrics_settle_t *m, double t_from, double final_value, double tol_abs)
{
    m->t_from = t_from;
    m->final_value = final_value;
    m->tol_abs = tol_abs;
    m->started = false;
    m->t_first = 0.0;
    m->have_out = false;
    m->out_pending = false;
    m->t_after_out = 0.0;
}

void metrics_settle_add(metrics_settle_t *m, double t, double x)
{
    if (!(t >= m->t_from)) {
        return;
    }
    if (!m->started) {
        m->started = true;
        m->t_first = t;
    }
    if (fabs(x - m->final_value) > m->tol_abs) {
        m->have_out = true;
        m->out_pending = true;
    } else if (m->out_pending) {
        m->out_pending = false;
        m->t_after_out = t;
    }
}

double metrics_settle_result(const metrics_settle_t *m)
{
    if (!m->started) {
        return -1.0;
    }
    if (!m->have_out) {
        return m->t_first;
    }
    return m->out_pending ? -1.0 : m->t_after_out; /* still outside at the end: never settled */
}

double metrics_settle_time(const double *t, const double *x, size_t n, double t_from,
                           double final_value, double tol_abs)
{
    metrics_settle_t m;
    size_t i;
    metrics_settle_begin(&m, t_from, final_value, tol_abs);
    for (i = 0; i < n; i++) {
        metrics_settle_add(&m, t[i], x[i]);
    }
    return metrics_settle_result(&m);
}

void metrics_reach_begin(metrics_reach_t *m, double t_from, double level)
{
    m->t_from = t_from;
    m->level = level;
    m->dir = 0;
    m->hit = false;
    m->t_hit = -1.0;
}

void metrics_reach_add(metrics_reach_t *m, double t, double x)
{
    if (t < m->t_from || m->hit) {
        return;
    }
    if (m->dir == 0) {
        m->dir = (x < m->level) ? 1 : -1;
    }
    if ((m->dir > 0 && x >= m->level) || (m->dir < 0 && x <= m->level)) {
        m->hit = true;
        m->t_hit = t;
    }
}

double metrics_reach_result(const metrics_reach_t *m) { return m->t_hit; }

double metrics_first_reach(const double *t, const double *x, size_t n, double t_from, double level)
{
    metrics_reach_t m;
    size_t i;
    metrics_reach_begin(&m, t_from, level);
    for (i = 0; i < n; i++) {
        metrics_reach_add(&m, t[i], x[i]);
    }
    return metrics_reach_result(&m);
}
