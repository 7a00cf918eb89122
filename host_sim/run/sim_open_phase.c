/* Open-phase operation in a run, see sim_open_phase.h. */
#include "sim_open_phase.h"

#include <math.h>
#include <stdio.h>

#include "hal_sim.h"
#include "sim_run_state.h"

/* After the first open phase, unless told otherwise. */
#define SIM_SECOND_FAULT_DELAY_S 0.3

int sim_open_phase_begin(struct sim_run *rs, char *err, size_t err_len)
{
    const sim_config_t *c = rs->cfg;
    sim_open_phase_t *op = &rs->open_phase;
    op->isolated_seen = 0u;
    op->command_sent = false;
    op->t_event = -1.0;
    op->t_isolated = -1.0;
    op->min_speed_rpm = 0.0;
    op->peak_a = 0.0;
    if (c->fault == SIM_FAULT_OPEN_PHASE) {
        const double t2 = (c->second_fault_s > 0.0) ? c->second_fault_s
                                                    : rs->fault.t_inject + SIM_SECOND_FAULT_DELAY_S;
        sim_fault_open_phases(&rs->fault, (c->fault_phase >= 0) ? c->fault_phase : 2,
                              c->second_fault_phase, t2, c->open_model == 1);
        op->t_event = rs->fault.t_inject;
    }
    if (c->isolate_leg >= 0) {
        op->t_event = (c->isolate_s > 0.0) ? c->isolate_s : SIM_FAULT_INJECT_S;
    }
    metrics_settle_begin(&op->settle, op->t_event, rs->plan.speed,
                         SIM_OPEN_PHASE_BAND * fabs(rs->plan.speed));
    if (c->isolate_leg >= 0 && !(op->t_event < rs->plan.duration)) {
        (void)snprintf(err, err_len, "isolation time must be inside the run");
        return -1;
    }
    if (rs->fault.second_phase >= 0 &&
        !(rs->fault.t_second > rs->fault.t_inject && rs->fault.t_second < rs->plan.duration)) {
        (void)snprintf(err, err_len, "the second fault must come after the first, inside the run");
        return -1;
    }
    return 0;
}

/* The legs the drive isolated in this period's ISR: their switches are off, their currents
 * commutate at once (an open connection stays open, a connected phase floats on its diodes). */
static void sim_open_phase_legs(struct sim_run *rs, sim_result_t *r, double t)
{
    sim_open_phase_t *op = &rs->open_phase;
    plant_params_t opened;
    uint16_t floating;
    int k;
    op->isolated_seen = hal_sim_bus.isolated;
    floating = sim_fault_plant(&rs->fault, &rs->cfg->plant, op->isolated_seen, &rs->plant);
    inverter_set_floating(&rs->inv, floating);
    opened = rs->plant;
    for (k = 0; k < PLANT_PHASES; k++) {
        opened.phase_open[k] = opened.phase_open[k] || (((unsigned)floating >> k) & 1u) != 0u;
    }
    plant_open_commutate(&opened, &rs->x);
    if (op->isolated_seen != 0u && op->t_isolated < 0.0) {
        op->t_isolated = t;
    }
    if (op->isolated_seen != 0u && r->isolation_ms < 0.0 && op->t_event >= 0.0) {
        r->isolation_ms = 1e3 * (t - op->t_event);
    }
}

void sim_open_phase_period(struct sim_run *rs, sim_result_t *r, double t,
                           const sim_ctl_status_t *st)
{
    sim_open_phase_t *op = &rs->open_phase;
    if (rs->cfg->isolate_leg >= 0 && !op->command_sent && t >= op->t_event) {
        op->command_sent = true;
        (void)rs->ops->isolate_leg(rs->cfg->isolate_leg); /* the ISR acts next period */
    }
    if (hal_sim_bus.isolated != op->isolated_seen) {
        sim_open_phase_legs(rs, r, t);
    }
    /* the background is busy building the post-fault set for the hand-off delay */
    if (op->t_isolated < 0.0 || t >= op->t_isolated + rs->cfg->handoff_delay_s) {
        rs->ops->background();
    }
    if (st->postfault_in_force && r->postfault_start_ms < 0.0 && op->t_event >= 0.0) {
        r->postfault_start_ms = 1e3 * (t - op->t_event);
    }
}

void sim_open_phase_track(struct sim_run *rs, double t, double speed_rpm, double speed_ref_rpm,
                          const double i_phase[6])
{
    sim_open_phase_t *op = &rs->open_phase;
    int k;
    if (op->t_event < 0.0 || t < op->t_event) {
        return;
    }
    for (k = 0; k < 6; k++) {
        op->peak_a = fmax(op->peak_a, fabs(i_phase[k]));
    }
    /* a fall is below a positive reference, above a negative one */
    op->min_speed_rpm = fmax(op->min_speed_rpm, (speed_ref_rpm >= 0.0) ? speed_ref_rpm - speed_rpm
                                                                       : speed_rpm - speed_ref_rpm);
    metrics_settle_add(&op->settle, t, speed_rpm);
}

void sim_open_phase_finish(const struct sim_run *rs, sim_result_t *r)
{
    const sim_open_phase_t *op = &rs->open_phase;
    const sim_metrics_t *m = &rs->metrics;
    const plant_params_t *p = &rs->cfg->plant;
    sim_ctl_status_t st;
    int k;
    rs->ops->status(&st);
    r->open_phase_event_s = op->t_event;
    r->isolated_leg = st.isolated_leg;
    r->torque_limit_end_nm = st.torque_limit_nm;
    r->speed_dip_rpm = op->min_speed_rpm;
    r->peak_after_event_a = op->peak_a;
    r->recover_ms = -1.0;
    if (op->t_event >= 0.0 && metrics_settle_result(&op->settle) >= 0.0) {
        r->recover_ms = 1e3 * (metrics_settle_result(&op->settle) - op->t_event);
    }
    r->phase_limit_peak_a = rs->plan.torque_limit / (3.0 * (double)p->pole_pairs * p->psi_f_wb);
    r->diode_conduction = rs->inv.float_conduct_s / (r->window_end_s - r->window_start_s);
    for (k = 0; k < 6; k++) {
        double sq = 0.0;
        double peak = 0.0;
        size_t i;
        for (i = 0; i < m->n; i++) {
            sq += m->i_phase[k][i] * m->i_phase[k][i];
            peak = fmax(peak, fabs(m->i_phase[k][i]));
        }
        r->phase_rms_a[k] = (m->n > 0) ? sqrt(sq / (double)m->n) : 0.0;
        r->phase_peak_a[k] = peak;
    }
}

static void json_ms(FILE *f, const char *key, double v)
{
    if (v >= 0.0) {
        fprintf(f, "\"%s\": %.4g, ", key, v);
    } else {
        fprintf(f, "\"%s\": null, ", key);
    }
}

void sim_open_phase_json(FILE *f, const sim_config_t *c, const sim_result_t *r)
{
    int k;
    if (r->open_phase_event_s < 0.0) {
        fprintf(f, "  \"open_phase\": null,\n");
        return;
    }
    fprintf(f, "  \"open_phase\": {\"ride_through\": %s, \"strategy\": \"%s\", ",
            (c->open_phase_action == 1) ? "true" : "false",
            (c->postfault_strategy == 1) ? "max-torque" : "min-loss");
    fprintf(f, "\"event_s\": %.6g, \"isolated_leg\": %d, ", r->open_phase_event_s, r->isolated_leg);
    json_ms(f, "isolation_ms", r->isolation_ms);
    json_ms(f, "postfault_start_ms", r->postfault_start_ms);
    json_ms(f, "recover_ms", r->recover_ms);
    fprintf(f, "\"speed_dip_rpm\": %.4g, \"torque_limit_nm\": %.4g, ", r->speed_dip_rpm,
            r->torque_limit_end_nm);
    fprintf(f, "\"peak_after_event_a\": %.4g, ", r->peak_after_event_a);
    fprintf(f, "\"diode_conduction\": %.4g, ", r->diode_conduction);
    fprintf(f, "\"phase_limit_peak_a\": %.4g, \"phase_rms_a\": [", r->phase_limit_peak_a);
    for (k = 0; k < 6; k++) {
        fprintf(f, "%.4g%s", r->phase_rms_a[k], (k < 5) ? ", " : "], \"phase_peak_a\": [");
    }
    for (k = 0; k < 6; k++) {
        fprintf(f, "%.4g%s", r->phase_peak_a[k], (k < 5) ? ", " : "]},\n");
    }
}
