/* The run's metrics, see sim_metrics.h. */
#include "sim_metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SIM_FINE_ARRAYS 12 /* t, theta, six phases, i_x, i_y, te, speed */

int sim_metrics_open(sim_metrics_t *m, size_t fine_cap, size_t ctl_cap)
{
    double *p;
    int k;
    memset(m, 0, sizeof *m);
    m->block = (double *)calloc(SIM_FINE_ARRAYS * fine_cap + 2u * ctl_cap + 1u, sizeof(double));
    if (!m->block) {
        return -1;
    }
    p = m->block;
    m->t = p;
    m->theta = (p += fine_cap);
    for (k = 0; k < 6; k++) {
        m->i_phase[k] = (p += fine_cap);
    }
    m->i_x = (p += fine_cap);
    m->i_y = (p += fine_cap);
    m->te = (p += fine_cap);
    m->speed_rpm = (p += fine_cap);
    m->t_ctl = (p += fine_cap);
    m->te_ctl = p + ctl_cap;
    m->cap = fine_cap;
    m->cap_ctl = ctl_cap;
    return 0;
}

void sim_metrics_close(sim_metrics_t *m)
{
    free(m->block);
    m->block = NULL;
}

void sim_metrics_track_settle(sim_metrics_t *m, double t_event, double target, double tol)
{
    m->track_settle = true;
    m->t_event = t_event;
    metrics_settle_begin(&m->settle, t_event, target, tol);
}

void sim_metrics_track_reach(sim_metrics_t *m, double t_event, double level)
{
    m->track_reach = true;
    m->t_event = t_event;
    metrics_reach_begin(&m->reach, t_event, level);
}

void sim_metrics_track_speed(sim_metrics_t *m, double t_event, double target, double tol)
{
    m->track_speed = true;
    m->speed_reached = false;
    m->speed_peak_error = 0.0;
    metrics_settle_begin(&m->speed_settle, t_event, target, tol);
}

static void track_speed_add(sim_metrics_t *m, double t, double speed_rpm)
{
    const double err = fabs(speed_rpm - m->speed_settle.final_value);
    if (t < m->speed_settle.t_from) {
        return;
    }
    metrics_settle_add(&m->speed_settle, t, speed_rpm);
    m->speed_reached = m->speed_reached || err <= m->speed_settle.tol_abs;
    if (m->speed_reached && err > m->speed_peak_error) {
        m->speed_peak_error = err;
    }
}

void sim_metrics_add_fine(sim_metrics_t *m, const sim_fine_row_t *row, const double i_phase[6])
{
    size_t i;
    int k;
    if (m->n >= m->cap) {
        return;
    }
    i = m->n++;
    m->t[i] = row->t;
    m->theta[i] = row->theta_e_unwrapped;
    for (k = 0; k < 6; k++) {
        m->i_phase[k][i] = i_phase[k];
    }
    m->i_x[i] = row->i_x;
    m->i_y[i] = row->i_y;
    m->te[i] = row->te;
    m->speed_rpm[i] = row->speed_rpm;
}

void sim_metrics_add_period(sim_metrics_t *m, const sim_trace_row_t *row, bool in_window)
{
    if (m->track_settle) {
        metrics_settle_add(&m->settle, row->t, row->speed_rpm);
    }
    if (m->track_reach) {
        metrics_reach_add(&m->reach, row->t, row->te_avg);
    }
    if (m->track_speed) {
        track_speed_add(m, row->t, row->speed_rpm);
    }
    if (in_window && m->n_ctl < m->cap_ctl) {
        int k;
        m->t_ctl[m->n_ctl] = row->t;
        m->te_ctl[m->n_ctl] = row->te;
        m->n_ctl++;
        m->tref_sum += row->tref;
        m->tref_n++;
        for (k = 0; k < 6; k++) {
            m->phase_peak_a = fmax(m->phase_peak_a, fabs(row->i_phase[k]));
        }
    }
}

/* THD of every phase over [first, n) and the six-phase means. */
static void sim_metrics_thd(const sim_metrics_t *m, size_t first, sim_result_t *r)
{
    static const double each_phase[6][METRICS_MAX_CHANNELS] = {
        {1, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0}, {0, 0, 1, 0, 0, 0},
        {0, 0, 0, 1, 0, 0}, {0, 0, 0, 0, 1, 0}, {0, 0, 0, 0, 0, 1}};
    const double *phases[6];
    metrics_thd_t th[6];
    double sum_thd = 0.0, sum_thd50 = 0.0, sum_rms = 0.0;
    int k, meaningful;
    for (k = 0; k < 6; k++) {
        phases[k] = m->i_phase[k] + first;
    }
    meaningful = metrics_thd_combined(phases, 6, each_phase, 6, m->theta + first, m->n - first, th);
    for (k = 0; k < 6; k++) {
        r->thd_phase_percent[k] = (th[k].thd >= 0.0) ? 100.0 * th[k].thd : -1.0;
        sum_thd += th[k].thd;
        sum_thd50 += th[k].thd_h50;
        sum_rms += th[k].total_rms_ac;
    }
    r->phase_current_rms_a = sum_rms / 6.0;
    /* the headline needs all six: a phase below the threshold makes the mean meaningless */
    r->thd_percent = (meaningful == 6) ? 100.0 * sum_thd / 6.0 : -1.0;
    r->thd50_percent = (meaningful == 6) ? 100.0 * sum_thd50 / 6.0 : -1.0;
}

/* Ripple, means and x-y rms over the plant samples [first, n); the sampled ripple over the
 * control samples from the same instant on. */
static void sim_metrics_window_stats(const sim_metrics_t *m, size_t first, sim_result_t *r)
{
    const size_t n = m->n - first;
    size_t c0 = 0;
    r->torque_ripple_nm = metrics_std(m->te + first, n);
    r->torque_ripple_pp_nm = metrics_peak_to_peak(m->te + first, n);
    r->torque_mean_nm = metrics_mean(m->te + first, n);
    r->speed_mean_rpm = metrics_mean(m->speed_rpm + first, n);
    r->xy_current_rms_a = metrics_rms2(m->i_x + first, m->i_y + first, n);
    if (first < m->n) {
        while (c0 < m->n_ctl && m->t_ctl[c0] < m->t[first]) {
            c0++;
        }
    }
    r->torque_ripple_sampled_nm = metrics_std(m->te_ctl + c0, m->n_ctl - c0);
}

void sim_metrics_finish(const sim_metrics_t *m, sim_result_t *r)
{
    size_t first = m->n;
    int k;
    r->thd_periods = metrics_whole_periods(m->theta, m->n, m->n, &first);
    if (r->thd_periods < 1) {
        first = 0; /* no whole period: the statistics over the whole window, no THD */
    }
    r->stats_from_s = (first < m->n) ? m->t[first] : r->window_start_s;
    r->thd_percent = r->thd50_percent = -1.0;
    r->phase_current_rms_a = 0.0;
    for (k = 0; k < 6; k++) {
        r->thd_phase_percent[k] = -1.0;
    }
    if (r->thd_periods >= 1) {
        sim_metrics_thd(m, first, r);
    }
    sim_metrics_window_stats(m, first, r);
    r->phase_current_peak_a = m->phase_peak_a;
    r->torque_ref_mean_nm = (m->tref_n > 0) ? m->tref_sum / (double)m->tref_n : 0.0;
    r->transient_ms = -1.0;
    if (m->track_settle && metrics_settle_result(&m->settle) >= 0.0) {
        r->transient_ms = 1e3 * (metrics_settle_result(&m->settle) - m->t_event);
    } else if (m->track_reach && metrics_reach_result(&m->reach) >= 0.0) {
        r->transient_ms = 1e3 * (metrics_reach_result(&m->reach) - m->t_event);
    }
    r->speed_settle_ms = r->speed_peak_error_rpm = -1.0;
    if (m->track_speed && metrics_settle_result(&m->speed_settle) >= 0.0) {
        r->speed_settle_ms = 1e3 * (metrics_settle_result(&m->speed_settle) - m->t_event);
    }
    if (m->track_speed && m->speed_reached) {
        r->speed_peak_error_rpm = m->speed_peak_error;
    }
}
