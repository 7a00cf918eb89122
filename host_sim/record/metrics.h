/*
 * Metric functions (brief §7) on sampled signals. Pure functions, no I/O.
 */
#ifndef SIM_METRICS_H
#define SIM_METRICS_H

#include <stdbool.h>
#include <stddef.h>

double metrics_mean(const double *x, size_t n);
/* Population standard deviation (divide by n). 0 for n < 2. */
double metrics_std(const double *x, size_t n);
double metrics_peak_to_peak(const double *x, size_t n);
/* RMS of the magnitude of a 2-D signal, sqrt(mean(a^2 + b^2)). */
double metrics_rms2(const double *a, const double *b, size_t n);

typedef struct {
    double fundamental_rms; /* Q1 */
    double total_rms_ac;    /* Q: RMS without DC */
    double thd;             /* sqrt(Q^2 - Q1^2) / Q1, all frequencies in the samples */
    double thd_h50;         /* sqrt(sum_{h=2..50} Q_h^2) / Q1 (power-analyser view) */
} metrics_thd_t;

/* Below this fundamental (A rms, 2 % of the 10 A base current) a THD says nothing about the
 * waveform: a no-load run's switching ripple over a vanishing fundamental reads as several
 * hundred percent. The THD is then not meaningful and not reported. */
#define METRICS_THD_MIN_FUNDAMENTAL_RMS 0.2

/* THD of x sampled uniformly over a window that holds an integer number of
 * fundamental periods; theta is the fundamental's phase (rad, unwrapped or
 * not) at each sample, so slight speed variations do not smear the
 * fundamental. Harmonic h is the projection on cos(h theta), sin(h theta).
 * Returns -1 (thd and thd_h50 -1: not meaningful) if n < 8 or the fundamental is below
 * METRICS_THD_MIN_FUNDAMENTAL_RMS, else 0. */
int metrics_thd(const double *x, const double *theta, size_t n, metrics_thd_t *out);

#define METRICS_MAX_CHANNELS 6

/* metrics_thd of n_out signals that are fixed linear combinations
 *   y_k = sum_j weights[k][j] basis_j
 * of n_basis signals sampled at the same instants (the six phase currents from i_alpha, i_beta,
 * i_x, i_y): the harmonic projections and the covariance of the basis are computed once, each
 * y_k's from them (projection and mean are linear, the AC power is w^T C w). out[k] for y_k; the
 * numbers metrics_thd gives y_k on its own, up to rounding. At most METRICS_MAX_CHANNELS of
 * each. Returns how many outputs have a meaningful THD. */
int metrics_thd_combined(const double *const *basis, int n_basis,
                         const double weights[][METRICS_MAX_CHANNELS], int n_out,
                         const double *theta, size_t n, metrics_thd_t *out);

/* Index range [*first, n) covering the largest whole number of fundamental
 * periods of an unwrapped phase that fits in the last `max_samples` samples
 * (theta must be monotonic over that range). Returns that number of periods
 * (0: not even one). */
int metrics_whole_periods(const double *theta_unwrapped, size_t n, size_t max_samples,
                          size_t *first);

/* Leg transitions of a switching-state sequence (6 bits per entry) averaged
 * over the six legs, divided by 2 and by the window length: average
 * switching frequency. */
double metrics_switching_freq(const unsigned *states, size_t n, double window_s);

/* Transient end: first time t[i] >= t_from after which |x - final| stays
 * within tol_abs until the end. Negative if it never settles. */
double metrics_settle_time(const double *t, const double *x, size_t n, double t_from,
                           double final_value, double tol_abs);

/* First time t[i] >= t_from at which x reaches level (from below if
 * level > x at t_from, else from above). Negative if never. */
double metrics_first_reach(const double *t, const double *x, size_t n, double t_from, double level);

/* The same two, one sample at a time (a run of any length keeps no history). */
typedef struct {
    double t_from, final_value, tol_abs;
    bool started;       /* a sample at or after t_from was seen */
    double t_first;     /* the first such sample's time */
    bool have_out;      /* some sample was outside the band */
    bool out_pending;   /* the latest sample was outside: the settling instant is still open */
    double t_after_out; /* time of the sample after the latest one outside */
} metrics_settle_t;

void metrics_settle_begin(metrics_settle_t *m, double t_from, double final_value, double tol_abs);
void metrics_settle_add(metrics_settle_t *m, double t, double x);
double metrics_settle_result(const metrics_settle_t *m);

typedef struct {
    double t_from, level;
    int dir; /* 0 until the first sample at or after t_from; then +1 from below, -1 above */
    bool hit;
    double t_hit; /* -1 until hit */
} metrics_reach_t;

void metrics_reach_begin(metrics_reach_t *m, double t_from, double level);
void metrics_reach_add(metrics_reach_t *m, double t, double x);
double metrics_reach_result(const metrics_reach_t *m);

#endif /* SIM_METRICS_H */
