/*
 * The period loop of a run, in the target's order: at the start of period k the plant is
 * sampled (ADC, encoder), the drive's control ISR runs and writes duties, and the inverter
 * applies the duties written in period k-1 while the plant is integrated over the period.
 */
#include <math.h>
#include <stdio.h>

#include "hal_sim.h"
#include "sim_open_phase.h"
#include "sim_run_state.h"

#define LOOP_RAD_S_TO_RPM (60.0 / (2.0 * 3.14159265358979323846))
#define LOOP_ISR_TIMING_EVERY 8
#define LOOP_LOAD_STANDSTILL_RAD_S 1.0 /* a passive load's full torque from this speed up */

/* Scenario events due at the start of period k: the speed-reference step, a fault. */
static void loop_events(sim_run_t *rs, long k, double t)
{
    const sim_plan_t *pl = &rs->plan;
    if (k > 0 && pl->speed != pl->speed0 && t >= pl->t_event && t - rs->ts < pl->t_event) {
        rs->ops->set_speed_rpm(pl->speed);
    }
    if (sim_fault_update(&rs->fault, t)) {
        (void)sim_fault_plant(&rs->fault, &rs->cfg->plant, rs->open_phase.isolated_seen,
                              &rs->plant);
    }
}

/* Hardware over-current comparator, sampled once per period (a real one acts within
 * microseconds): trips the HAL's trip-zone input and forces the outputs off. */
static void loop_hw_trip(sim_run_t *rs, sim_result_t *r, const plant_out_t *o, double t)
{
    int j;
    if (!(rs->cfg->trip_current_a > 0.0) || hal_sim_bus.hw_trip) {
        return;
    }
    for (j = 0; j < 6; j++) {
        if (fabs(o->i_phase[j]) > rs->cfg->trip_current_a) {
            hal_sim_bus.hw_trip = true;
            hal_sim_bus.forced_off = true;
            r->trip_time_s = t;
            return;
        }
    }
}

/* Sensors, the drive's control ISR and what it reports. Every LOOP_ISR_TIMING_EVERY-th call
 * is timed on the host clock (two clock reads per call would cost more than the sensors). */
static void loop_control(sim_run_t *rs, sim_result_t *r, const plant_out_t *o, long k, double t,
                         sim_ctl_status_t *st)
{
    hal_sim_clock_advance(rs->ts_ns);
    sim_adc_sample(&rs->adc, &rs->plant, o->i_phase, &rs->fault);
    sim_encoder_sample(&rs->encoder, &rs->plant, &rs->x, t, rs->ts, &rs->fault);
    if (k % LOOP_ISR_TIMING_EVERY == 0) {
        const double w0 = sim_wall_now();
        rs->ops->isr();
        rs->isr_wall_s += sim_wall_now() - w0;
        rs->isr_timed++;
    } else {
        rs->ops->isr();
    }
    if (sim_fault_overrun(&rs->fault)) {
        rs->ops->report_overrun(); /* fw_isr's end-of-ISR check, on a simulated ISR time */
    }
    rs->ops->period_status(st);
    if (st->faulted && r->fault_time_s < 0.0) {
        r->fault_time_s = t;
        r->fault = st->fault;
        rs->k_detect = k;
        if (rs->fault.active) {
            r->fault_inject_s = rs->fault.t_inject;
            r->fault_detect_ms = 1e3 * (t - rs->fault.t_inject);
        }
    }
    if (rs->k_detect >= 0 && !hal_sim_bus.forced_off) {
        r->outputs_off = false;
    }
    if (st->torque_limited) {
        r->torque_limited_s += rs->ts;
        if (r->torque_limited_first_s < 0.0) {
            r->torque_limited_first_s = t;
        }
    }
}

/* The plant at the period start: the phase currents always (ADC, trip comparator); angle, flux
 * and torque only when something reads them (trace.csv, the analysis window's metrics, an
 * observer), else left at zero. */
static void loop_outputs(const sim_run_t *rs, bool in_win, plant_out_t *o)
{
    const sim_observer_t *ob = rs->cfg->observer;
    if (rs->rec.trace_on || in_win || (ob && ob->period)) {
        plant_outputs(&rs->plant, &rs->x, o);
    } else {
        plant_phase_currents(&rs->plant, &rs->x, o->i_phase);
        o->i_alpha = o->i_beta = o->psi_d = o->psi_q = o->psi_s = 0.0;
        o->torque_nm = o->theta_e = 0.0;
    }
}

/* The trace row's period-start part. */
static void loop_row_start(const sim_run_t *rs, const plant_out_t *o, double t,
                           const sim_ctl_status_t *st, sim_trace_row_t *row)
{
    int j;
    row->t = t;
    row->speed_rpm = rs->x.omega_m * LOOP_RAD_S_TO_RPM;
    row->theta_e = o->theta_e;
    for (j = 0; j < 6; j++) {
        row->i_phase[j] = o->i_phase[j];
    }
    row->i_d = rs->x.i_d;
    row->i_q = rs->x.i_q;
    row->i_x = rs->x.i_x;
    row->i_y = rs->x.i_y;
    row->te = o->torque_nm;
    row->psi_s = o->psi_s;
    row->tref = st->torque_ref_nm;
    row->psi_ref = st->flux_ref_wb;
    /* the command in force (sim_loop_period zeroes it when the outputs went off at this
     * period's start: a trip, the plant runs the period with every switch open) */
    row->vector = rs->applied_vector;
    row->duty = rs->applied_duty;
}

/* A plant sample of the analysis window: metrics, fine.csv, observer. */
static void loop_fine_sample(void *ctx, double t_rel, const plant_state_t *s, unsigned legs)
{
    sim_run_t *rs = (sim_run_t *)ctx;
    double iph[6];
    sim_fine_row_t row;
    (void)legs;
    plant_phase_currents(&rs->plant, s, iph);
    row.t = rs->t_period + t_rel;
    row.i_a = iph[0];
    row.theta_e_unwrapped = (double)rs->plant.pole_pairs * s->theta_m;
    row.i_x = s->i_x;
    row.i_y = s->i_y;
    row.te = plant_torque(&rs->plant, s);
    row.speed_rpm = s->omega_m * LOOP_RAD_S_TO_RPM;
    sim_metrics_add_fine(&rs->metrics, &row, iph);
    sim_recorder_fine(&rs->rec, &row);
    if (rs->cfg->observer && rs->cfg->observer->fine) {
        rs->cfg->observer->fine(rs->cfg->observer->ctx, &row);
    }
}

/* The inverter and the plant over the period; returns the period-average torque. */
static double loop_integrate(sim_run_t *rs, bool in_win, double t, const sim_period_input_t *in)
{
    rs->inv.counting = in_win;
    rs->t_period = t;
    return inverter_run_period(&rs->inv, &rs->plant, &rs->x, in->duty, in->forced_off,
                               in->t_load_nm, false, in_win ? rs->fine_times : NULL,
                               in_win ? rs->n_fine : 0, in_win ? loop_fine_sample : NULL, rs);
}

/* Compares shadow-loaded at the period boundary, and the command they carry. */
static void loop_next_command(sim_run_t *rs, const sim_ctl_status_t *st)
{
    int j;
    for (j = 0; j < 6; j++) {
        rs->duty[j] = hal_sim_duty_fraction(j);
    }
    sim_fault_duty(&rs->fault, hal_sim_bus.forced_off, rs->duty);
    if (!hal_sim_bus.forced_off && st->enable) {
        rs->applied_vector = st->vector;
        rs->applied_duty = st->duty;
    } else {
        rs->applied_vector = 0;
        rs->applied_duty = 0.0;
    }
}

/* A passive load (a brake, friction, a fan): |load| against the direction of motion,
 * proportional below the speed at which it would stop the rotor within one period, so it
 * stops a coasting rotor and never drives it backwards. */
static double loop_passive_load(const sim_run_t *rs, double load_nm)
{
    const double w0 = fmax(LOOP_LOAD_STANDSTILL_RAD_S, fabs(load_nm) * rs->ts / rs->plant.j_kgm2);
    return fabs(load_nm) * fmax(-1.0, fmin(1.0, rs->x.omega_m / w0));
}

int sim_loop_period(sim_run_t *rs, sim_result_t *r, long k)
{
    const double t = (double)k * rs->ts;
    const bool in_win = (k >= rs->k_win);
    sim_period_input_t in;
    sim_ctl_status_t st;
    sim_trace_row_t row;
    plant_out_t o;
    int j;
    in.t_load_nm = sim_load_at(rs->cfg, &rs->plan, t);
    if (rs->cfg->passive_load) {
        in.t_load_nm = loop_passive_load(rs, in.t_load_nm);
    }
    in.t_load_nm = sim_fault_load(&rs->fault, in.t_load_nm);
    loop_events(rs, k, t);
    loop_outputs(rs, in_win, &o);
    loop_hw_trip(rs, r, &o, t);
    loop_control(rs, r, &o, k, t, &st);
    if (hal_sim_bus.forced_off) { /* a trip at this period's start: every switch open */
        rs->applied_vector = 0;
        rs->applied_duty = 0.0;
    }
    if (rs->open_phase.t_event < 0.0 && rs->open_phase.isolated_seen == 0u &&
        hal_sim_bus.isolated == 0u) {
        rs->ops->background(); /* the usual period: no open-phase event, six legs */
    } else {
        sim_open_phase_period(rs, r, t, &st);
    }
    loop_row_start(rs, &o, t, &st, &row);
    if (rs->open_phase.t_event >= 0.0) {
        sim_open_phase_track(rs, t, row.speed_rpm, rs->plan.speed, row.i_phase);
    }
    for (j = 0; j < 6; j++) {
        in.duty[j] = rs->duty[j];
    }
    in.forced_off = hal_sim_bus.forced_off;
    in.plant = &rs->plant;
    row.te_avg = loop_integrate(rs, in_win, t, &in);
    sim_recorder_trace(&rs->rec, &row);
    sim_metrics_add_period(&rs->metrics, &row, in_win);
    if (rs->cfg->observer && rs->cfg->observer->period) {
        rs->cfg->observer->period(rs->cfg->observer->ctx, &row, &in);
    }
    loop_next_command(rs, &st);
    if (!(rs->x.i_d == rs->x.i_d) || fabs(rs->x.i_d) > 1e4 || fabs(rs->x.i_q) > 1e4 ||
        fabs(rs->x.omega_m) > 1e5) {
        return -1;
    }
    return 0;
}

bool sim_loop_pil_failed(const sim_run_t *rs, long k, char *err, size_t err_len)
{
    if (!rs->pil_open || !sim_pil_error()) {
        return false;
    }
    (void)snprintf(err, err_len, "%s (at %.4f s simulated)", sim_pil_error(), (double)k * rs->ts);
    return true;
}

int sim_loop_out_limit(const sim_run_t *rs, long k, char *err, size_t err_len)
{
    if (!rs->rec.limit_reached) {
        return 0;
    }
    (void)snprintf(err, err_len,
                   "the output files reached --out-limit-mb %g (MB) at %.4f s simulated: stopped "
                   "there, the files end at the last whole row",
                   rs->cfg->out_limit_mb, (double)k * rs->ts);
    return -1;
}

int sim_loop_run(sim_run_t *rs, sim_result_t *r, char *err, size_t err_len)
{
    const sim_plan_t *pl = &rs->plan;
    long k;
    if (rs->cfg->scenario == SIM_SCEN_ACCEL || rs->cfg->scenario == SIM_SCEN_REVERSAL) {
        sim_metrics_track_settle(&rs->metrics, pl->t_event, pl->speed, 0.02 * fabs(pl->speed));
    } else if (rs->cfg->scenario == SIM_SCEN_LOAD_STEP) {
        sim_metrics_track_reach(&rs->metrics, pl->t_event, 0.9 * pl->load);
    }
    if (rs->cfg->scenario == SIM_SCEN_ACCEL || rs->cfg->scenario == SIM_SCEN_REVERSAL ||
        rs->cfg->scenario == SIM_SCEN_LOAD_STEP) {
        sim_metrics_track_speed(&rs->metrics, pl->t_event, pl->speed, 0.02 * fabs(pl->speed));
    }
    rs->wall0_s = sim_wall_now();
    for (k = 0; k < rs->n_periods; k++) {
        if (sim_loop_period(rs, r, k) != 0) {
            (void)snprintf(err, err_len, "plant state diverged");
            return -1;
        }
        if (sim_loop_pil_failed(rs, k, err, err_len)) {
            return -1;
        }
        if (rs->rec.limit_reached && sim_loop_out_limit(rs, k, err, err_len) != 0) {
            return -1; /* the flag tested here: no call in the usual period */
        }
    }
    rs->wall1_s = sim_wall_now();
    return 0;
}
