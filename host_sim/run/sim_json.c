/* metrics.json of a run, see sim.h. */
#include <math.h>
#include <stdio.h>

#include "sim.h"
#include "sim_open_phase.h"
#include "sxlink.h"

static void json_num(FILE *f, const char *key, double v, bool comma)
{
    if (v == v && fabs(v) < 1e300) {
        fprintf(f, "  \"%s\": %.6g%s\n", key, v, comma ? "," : "");
    } else {
        fprintf(f, "  \"%s\": null%s\n", key, comma ? "," : "");
    }
}

/* A metric that is "not meaningful" when negative. */
static double json_or_null(double v) { return (v >= 0.0) ? v : (double)NAN; }

int sim_write_metrics_json(const char *path, const sim_config_t *c, const sim_result_t *r)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        return -1;
    }
    sim_print_metrics_json(f, c, r);
    return (fclose(f) == 0) ? 0 : -1;
}

/* The fault block: what was injected, what the drive latched and when, its first record. */
static void sim_print_fault_json(FILE *f, const sim_config_t *c, const sim_result_t *r)
{
    const sim_fault_info_t *fi = sim_fault_info(c->fault);
    const sim_fault_record_t *rec = &r->first_record;
    char names[256];
    int k;
    if (fi) {
        fprintf(f, "  \"fault_injected\": \"%s\",\n  \"fault_injection\": \"%s\",\n", fi->name,
                fi->injection);
        fprintf(f, "  \"fault_expected\": %d,\n", fi->expected_fault);
    } else {
        fprintf(f, "  \"fault_injected\": null,\n");
    }
    json_num(f, "fault_inject_s", json_or_null(r->fault_inject_s), true);
    fprintf(f, "  \"fault_code\": %d,\n  \"fault_name\": \"%s\",\n", r->fault,
            sxl_fault_name((uint16_t)r->fault));
    (void)sxl_fault_mask_str((uint16_t)r->faults_latched, names, (uint16_t)sizeof names);
    fprintf(f, "  \"fault_mask\": %u,\n  \"fault_mask_names\": \"%s\",\n", r->faults_latched,
            names);
    json_num(f, "fault_detect_ms", json_or_null(r->fault_detect_ms), true);
    fprintf(f, "  \"outputs_off\": %s,\n", r->outputs_off ? "true" : "false");
    fprintf(f, "  \"fault_records\": %d,\n", r->fault_records);
    if (!r->have_first_record) {
        fprintf(f, "  \"first_fault_record\": null,\n");
        return;
    }
    fprintf(f, "  \"first_fault_record\": {\"faults\": %u, \"t_s\": %.6g, \"i_phase_a\": [",
            rec->faults, r->first_record_t_s);
    for (k = 0; k < 6; k++) {
        fprintf(f, "%.4g%s", rec->i_phase_a[k], (k < 5) ? ", " : "");
    }
    fprintf(f,
            "], \"vdc_v\": %.5g, \"speed_rpm\": %.5g, \"torque_est_nm\": %.4g, "
            "\"torque_ref_nm\": %.4g, \"vector\": %d, \"duty\": %.4g},\n",
            rec->vdc_v, rec->speed_rpm, rec->torque_est_nm, rec->torque_ref_nm, rec->vector,
            rec->duty);
}

/* One quantity of the commissioning: identified beside true, the error (degrees for the
 * offset, per cent for the others), uncertainty, quality. */
static void sim_print_comm_quantity(FILE *f, const sim_commission_result_t *cr, int q, bool comma)
{
    const double v = cr->value[q], t = cr->truth[q];
    double error = (double)NAN;
    /* a failed count (wrong pole pairs) is still a measured number */
    if (cr->quality[q] == SXL_COMM_QUALITY_OK || cr->quality[q] == SXL_COMM_QUALITY_POOR ||
        (q == SXL_COMM_Q_COUNTS && v != 0.0)) {
        if (q == SXL_COMM_Q_OFFSET) {
            error = fmod(v - t + 540.0, 360.0) - 180.0;
        } else if (t != 0.0) {
            error = 100.0 * (v / t - 1.0);
        }
    }
    fprintf(f, "    \"%s\": {\"identified\": ", sxl_comm_quantity_name((uint16_t)q));
    fprintf(f, (v == v) ? "%.7g" : "null", v);
    fprintf(f, ", \"true\": %.7g, \"%s\": ", t,
            (q == SXL_COMM_Q_OFFSET) ? "error_deg" : "error_percent");
    fprintf(f, (error == error) ? "%.4g" : "null", error);
    fprintf(f, ", \"sigma\": %.4g, \"extra\": %.6g, \"quality\": \"%s\", \"reason\": \"%s\"}%s\n",
            cr->sigma[q], cr->extra[q], sxl_comm_quality_name((uint16_t)cr->quality[q]),
            sxl_comm_reason_name((uint16_t)cr->reason_q[q]), comma ? "," : "");
}

/* The commissioning scenario's block. */
static void sim_print_commission_json(FILE *f, const sim_result_t *r)
{
    const sim_commission_result_t *cr = &r->comm;
    int q;
    if (!cr->ran) {
        return;
    }
    fprintf(f,
            "  \"commission\": {\"state\": \"%s\", \"reason\": \"%s\", \"last_step\": \"%s\", "
            "\"duration_s\": %.6g, \"apply_result\": %d, \"applied_mask\": %u, "
            "\"phase_current_peak_a\": %.4g, \"results\": {\n",
            sxl_comm_state_name((uint16_t)cr->state), sxl_comm_reason_name((uint16_t)cr->reason),
            sxl_comm_step_name((uint16_t)cr->step), cr->duration_s, cr->apply_result, cr->applied,
            cr->phase_peak_a);
    for (q = 0; q < SIM_COMM_QUANTITIES; q++) {
        sim_print_comm_quantity(f, cr, q, q + 1 < SIM_COMM_QUANTITIES);
    }
    fprintf(f, "  }},\n");
}

/* The six phases' THD as a JSON array (null where not meaningful). */
static void sim_print_phase_thd_json(FILE *f, const sim_result_t *r)
{
    int k;
    fprintf(f, "  \"thd_phase_percent\": [");
    for (k = 0; k < 6; k++) {
        if (r->thd_phase_percent[k] >= 0.0) {
            fprintf(f, "%.6g%s", r->thd_phase_percent[k], (k < 5) ? ", " : "");
        } else {
            fprintf(f, "null%s", (k < 5) ? ", " : "");
        }
    }
    fprintf(f, "],\n");
}

/* The run's metrics (brief §7) and the drive's state at the end; host_timings: the host's wall
 * times too (they differ from run to run). */
static void sim_print_results_json(FILE *f, const sim_config_t *c, const sim_result_t *r,
                                   bool host_timings)
{
    json_num(f, "window_start_s", r->window_start_s, true);
    json_num(f, "window_end_s", r->window_end_s, true);
    fprintf(f, "  \"thd_periods\": %d,\n", r->thd_periods);
    json_num(f, "whole_periods_from_s", r->stats_from_s, true);
    json_num(f, "thd_percent", json_or_null(r->thd_percent), true);
    sim_print_phase_thd_json(f, r);
    json_num(f, "thd_h50_percent", json_or_null(r->thd50_percent), true);
    json_num(f, "torque_ripple_nm", r->torque_ripple_nm, true);
    json_num(f, "torque_ripple_pp_nm", r->torque_ripple_pp_nm, true);
    json_num(f, "torque_ripple_sampled_nm", r->torque_ripple_sampled_nm, true);
    json_num(f, "torque_mean_nm", r->torque_mean_nm, true);
    json_num(f, "torque_ref_mean_nm", r->torque_ref_mean_nm, true);
    json_num(f, "speed_mean_rpm", r->speed_mean_rpm, true);
    json_num(f, "xy_current_rms_a", r->xy_current_rms_a, true);
    json_num(f, "phase_current_rms_a", r->phase_current_rms_a, true);
    json_num(f, "switching_freq_hz", r->switching_freq_hz, true);
    json_num(f, "switching_loss_w", r->switching_loss_w, true);
    json_num(f, "inverter_loss_w", r->inverter_loss_w, true);
    json_num(f, "phase_current_peak_a", r->phase_current_peak_a, true);
    fprintf(f, "  \"adc_clipped_samples\": %ld,\n", r->adc_clipped);
    json_num(f, "transient_ms", json_or_null(r->transient_ms), true);
    json_num(f, "speed_settle_ms", json_or_null(r->speed_settle_ms), true);
    json_num(f, "speed_peak_error_rpm", json_or_null(r->speed_peak_error_rpm), true);
    if (host_timings) {
        json_num(f, "realtime_factor", r->realtime_factor, true);
        json_num(f, "wall_s", r->wall_s, true);
        json_num(f, "isr_mean_us", r->isr_mean_us, true);
    }
    fprintf(f, "  \"final_drive_state\": %d,\n  \"drive_fault\": %d,\n", r->final_state, r->fault);
    json_num(f, "fault_time_s", json_or_null(r->fault_time_s), true);
    json_num(f, "hw_trip_time_s", json_or_null(r->trip_time_s), true);
    json_num(f, "trip_current_a", (c->trip_current_a > 0.0) ? c->trip_current_a : (double)NAN,
             true);
    fprintf(f, "  \"software_protection\": %s,\n", c->protect ? "true" : "false");
    /* the drive's torque-limited flag: the speed loop at its limit, the speed not held */
    json_num(f, "torque_limited_s", r->torque_limited_s, true);
    json_num(f, "torque_limited_first_s", json_or_null(r->torque_limited_first_s), true);
    fprintf(f, "  \"torque_limited_stopped\": %s,\n", r->torque_limited_stopped ? "true" : "false");
}

/* The plant's parameters and non-idealities in force. */
static void sim_print_plant_json(FILE *f, const plant_params_t *p)
{
    fprintf(f,
            "  \"plant\": {\"r_ohm\": %.6g, \"ld_h\": %.6g, \"lq_h\": %.6g, \"lxy_h\": %.6g, "
            "\"psi_f_wb\": %.6g, \"psi5_wb\": %.6g, \"psi7_wb\": %.6g, \"pole_pairs\": %d, "
            "\"j_kgm2\": %.6g, \"b_nms\": %.6g, \"vdc_v\": %.6g, \"dead_time_s\": %.6g, "
            "\"integrator\": \"%s\", \"max_step_s\": %.6g},\n",
            p->r_ohm, p->ld_h, p->lq_h, p->lxy_h, p->psi_f_wb, p->psi5_wb, p->psi7_wb,
            p->pole_pairs, p->j_kgm2, p->b_nms, p->vdc_v, p->dead_time_s,
            (p->integrator == PLANT_INTEGRATOR_RK4) ? "rk4" : "exact", p->max_step_s);
    fprintf(f,
            "  \"nonidealities\": {\"dead_time\": %s, \"pm_harmonics\": %s, "
            "\"adc_quantisation\": true, \"adc_offset\": %s, \"adc_offset_counts\": %.6g, "
            "\"adc_gain_error\": %s, \"adc_gain_error_max\": %.6g, \"adc_noise\": %s, "
            "\"adc_noise_counts\": %.6g, \"current_sensor_span_a\": %.6g, "
            "\"encoder_quantisation\": %s, "
            "\"encoder_lines\": %u, \"encoder_offset_deg\": %.6g, \"encoder_reversed\": %s, "
            "\"encoder_stuck\": %s},\n",
            p->dead_time_on ? "true" : "false", p->harmonics_on ? "true" : "false",
            p->adc_offset_on ? "true" : "false", p->adc_offset_counts,
            p->adc_gain_on ? "true" : "false", p->adc_gain_error,
            p->adc_noise_on ? "true" : "false", p->adc_noise_counts, p->current_sensor_span_a,
            p->encoder_quant_on ? "true" : "false", (unsigned)p->encoder_lines,
            p->encoder_offset_rad * (180.0 / 3.14159265358979323846),
            p->encoder_reversed ? "true" : "false", p->encoder_stuck ? "true" : "false");
}

/* The machine the controller was told (sim_ctl_machine_t: set, or the reference machine's). */
static void sim_print_ctl_machine_json(FILE *f, const sim_result_t *r)
{
    fprintf(f,
            "  \"controller_machine\": {\"r_ohm\": %.6g, \"ld_h\": %.6g, \"lq_h\": %.6g, "
            "\"lxy_h\": %.6g, \"psi_f_wb\": %.6g, \"pole_pairs\": %d, \"encoder_offset_deg\": "
            "%.6g}\n",
            r->ctl_r_ohm, r->ctl_ld_h, r->ctl_lq_h, r->ctl_lxy_h, r->ctl_psi_f_wb,
            r->ctl_pole_pairs, r->ctl_encoder_offset_deg);
}

static void sim_print_json(FILE *f, const sim_config_t *c, const sim_result_t *r, bool host_timings)
{
    fprintf(f, "{\n");
    fprintf(f, "  \"controller\": \"%s\",\n  \"arith\": \"%s\",\n  \"scenario\": \"%s\",\n",
            r->controller, r->arith, r->scenario);
    json_num(f, "lambda", r->lambda, true);
    json_num(f, "fs_hz", r->fs_hz, true);
    json_num(f, "speed_ref_rpm", r->speed_ref_rpm, true);
    json_num(f, "load_nm", r->load_nm, true);
    json_num(f, "duration_s", r->duration_s, true);
    fprintf(f, "  \"seed\": %llu,\n", (unsigned long long)c->seed);
    sim_print_results_json(f, c, r, host_timings);
    sim_print_fault_json(f, c, r);
    sim_open_phase_json(f, c, r);
    sim_print_commission_json(f, r);
    if (r->pil.on) {
        sim_pil_print_json(f, &r->pil);
    }
    fprintf(f,
            "  \"controller_params\": {\"lambda_nm_per_wb\": %.6g, \"speed_kp_nm_per_rad_s\": "
            "%.6g, \"speed_ki_nm_per_rad\": %.6g, \"torque_limit_nm\": %.6g, "
            "\"flux_ref_wb\": %.6g, \"flux_ref_mode\": %d, \"duty_levels\": %d, "
            "\"ddc_direction\": %d, \"ddc_torque_guard\": %s, \"mid_period_angle\": %s, "
            "\"pulse_pattern\": %d, \"flux_tie_band\": %.6g},\n",
            r->lambda, r->p_speed_kp, r->p_speed_ki, r->p_torque_limit, r->p_flux_ref_wb,
            r->p_flux_ref_mode, r->p_duty_levels, r->p_ddc_direction,
            r->p_ddc_torque_guard ? "true" : "false", r->p_mid_period_angle ? "true" : "false",
            r->p_pulse_pattern, r->p_flux_tie_band);
    sim_print_plant_json(f, &c->plant);
    sim_print_ctl_machine_json(f, r);
    fprintf(f, "}\n");
}

void sim_print_metrics_json(FILE *f, const sim_config_t *c, const sim_result_t *r)
{
    sim_print_json(f, c, r, true);
}

void sim_print_metrics_json_no_timings(FILE *f, const sim_config_t *c, const sim_result_t *r)
{
    sim_print_json(f, c, r, false);
}
