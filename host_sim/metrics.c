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

int metrics_thd(const double *x, const double *theta, size_t n, metrics_thd_t *out)
{
    double mean, q2 = 0.0, sum_h = 0.0, q1 = 0.0;
    size_t i;
    int h;
    out->fundamental_rms = 0.0;
    out->total_rms_ac = 0.0;
    out->thd = -1.0;
    out->thd_h50 = -1.0;
    if (n < 8) {
        return -1;
    }
    mean = metrics_mean(x, n);
    for (i = 0; i < n; i++) {
        q2 += (x[i] - mean) * (x[i] - mean);
    }
    q2 /= (double)n;
    {
        /* projections on cos / sin (h theta), h = 1..50, with e^{j h theta} by
         * repeated complex multiplication (one libm call per sample) */
        double a[51], b[51];
        for (h = 0; h <= 50; h++) {
            a[h] = b[h] = 0.0;
        }
        for (i = 0; i < n; i++) {
            const double c1 = cos(theta[i]), s1 = sin(theta[i]);
            double ch = c1, sh = s1;
            for (h = 1; h <= 50; h++) {
                double t;
                a[h] += x[i] * ch;
                b[h] += x[i] * sh;
                t = ch * c1 - sh * s1;
                sh = sh * c1 + ch * s1;
                ch = t;
            }
        }
        for (h = 1; h <= 50; h++) {
            const double ah = a[h] * 2.0 / (double)n, bh = b[h] * 2.0 / (double)n;
            const double qh2 = 0.5 * (ah * ah + bh * bh);
            if (h == 1) {
                q1 = sqrt(qh2);
            } else {
                sum_h += qh2;
            }
        }
    }
    out->fundamental_rms = q1;
    out->total_rms_ac = sqrt(q2);
    if (!(q1 >= METRICS_THD_MIN_FUNDAMENTAL_RMS)) {
        return -1;
    }
    out->thd = sqrt(fmax(q2 - q1 * q1, 0.0)) / q1;
    out->thd_h50 = sqrt(sum_h) / q1;
    return 0;
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

double metrics_settle_time(const double *t, const double *x, size_t n, double t_from,
                           double final_value, double tol_abs)
{
    size_t i;
    long last_out = -1;
    size_t i0 = n;
    for (i = 0; i < n; i++) {
        if (t[i] >= t_from) {
            if (i0 == n) {
                i0 = i;
            }
            if (fabs(x[i] - final_value) > tol_abs) {
                last_out = (long)i;
            }
        }
    }
    if (i0 == n) {
        return -1.0;
    }
    if (last_out < 0) {
        return t[i0];
    }
    if ((size_t)last_out + 1 >= n) {
        return -1.0;
    }
    return t[(size_t)last_out + 1];
}

double metrics_first_reach(const double *t, const double *x, size_t n, double t_from, double level)
{
    size_t i;
    int dir = 0;
    for (i = 0; i < n; i++) {
        if (t[i] < t_from) {
            continue;
        }
        if (dir == 0) {
            dir = (x[i] < level) ? 1 : -1;
        }
        if ((dir > 0 && x[i] >= level) || (dir < 0 && x[i] <= level)) {
            return t[i];
        }
    }
    return -1.0;
}
