/*
 * The commissioning scenario (`--scenario commission`, docs/simulator.md): after its ADC
 * calibration, at standstill and with the rotor wherever the seed put it, the drive is asked
 * for its commissioning sequence through the call the serial command makes
 * (drive_request_commission); the periods run until it leaves COMMISSION; a finished sequence
 * is applied as the serial APPLY does. The result holds the drive's results beside the plant's
 * values.
 */
#include <math.h>
#include <stdio.h>

#include "motor_params_file.h"
#include "sim_run_state.h"
#include "sxlink_commission.h"

#define COMM_RAD_TO_DEG (180.0 / 3.14159265358979323846)

/* The plant's value of each quantity (NaN where there is none). */
static void comm_truth(const plant_params_t *p, double truth[SIM_COMM_QUANTITIES])
{
    const double offset = fmod(p->encoder_offset_rad * COMM_RAD_TO_DEG, 360.0);
    truth[0] = 1.0; /* every phase carries its share */
    truth[1] = (p->encoder_reversed ? -4.0 : 4.0) * (double)p->encoder_lines / p->pole_pairs;
    truth[2] = (offset < 0.0) ? offset + 360.0 : offset;
    truth[3] = p->r_ohm;
    truth[4] = p->ld_h;
    truth[5] = p->lq_h;
    truth[6] = p->lxy_h;
    truth[7] = p->psi_f_wb;
    truth[8] = p->j_kgm2;
    truth[9] = p->b_nms;
}

/* The drive's report into the result. */
static void comm_collect(sim_run_t *rs, sim_result_t *r)
{
    sim_comm_status_t cs;
    int q;
    rs->ops->commission_status(&cs);
    r->comm.state = cs.state;
    r->comm.reason = cs.reason;
    r->comm.step = cs.step;
    r->comm.duration_s = (double)cs.periods * rs->ts;
    for (q = 0; q < SIM_COMM_QUANTITIES; q++) {
        r->comm.value[q] = cs.value[q];
        r->comm.sigma[q] = cs.sigma[q];
        r->comm.extra[q] = cs.extra[q];
        r->comm.quality[q] = cs.quality[q];
        r->comm.reason_q[q] = cs.reason_q[q];
    }
    comm_truth(&rs->plant, r->comm.truth);
}

/* DIR/motor_params.h: the OK results as the firmware's motor parameter file, as `sixphase-link
 * identify --out` writes it. */
static int comm_write_params(const sim_run_t *rs, const sim_result_t *r, char *err, size_t err_len)
{
    static const motor_param_t file_id[SIM_COMM_QUANTITIES] = {
        MOTOR_PARAM_COUNT,   MOTOR_PARAM_POLE_PAIRS, MOTOR_PARAM_ENCODER_OFFSET,
        MOTOR_PARAM_R,       MOTOR_PARAM_LD,         MOTOR_PARAM_LQ,
        MOTOR_PARAM_LXY,     MOTOR_PARAM_PSI_F,      MOTOR_PARAM_INERTIA,
        MOTOR_PARAM_FRICTION};
    const sim_commission_result_t *cr = &r->comm;
    motor_params_t m;
    char path[1200];
    FILE *f;
    int q, rc;
    motor_params_clear(&m);
    for (q = 1; q < SIM_COMM_QUANTITIES; q++) {
        double v = cr->value[q], s = cr->sigma[q];
        if (cr->quality[q] != SXL_COMM_QUALITY_OK) {
            continue;
        }
        if (q == SXL_COMM_Q_OFFSET) {
            v = floor((v / 360.0 - floor(v / 360.0)) * 4294967296.0 + 0.5);
            s = s / 360.0 * 4294967296.0;
        } else if (q == SXL_COMM_Q_COUNTS) {
            v = cr->extra[q];
            s = 0.0;
        }
        motor_params_set(&m, file_id[q], v, s, "ok");
    }
    if ((cr->applied & (1u << SXL_COMM_Q_INERTIA)) != 0u) { /* the gains APPLY designed */
        motor_params_set(&m, MOTOR_PARAM_SPEED_KP, cr->speed_kp, 0.0, "from the inertia");
        motor_params_set(&m, MOTOR_PARAM_SPEED_KI, cr->speed_ki, 0.0, "from the inertia");
    }
    (void)snprintf(path, sizeof path, "%s/motor_params.h", rs->cfg->out_dir);
    f = fopen(path, "w");
    rc = f ? motor_params_write(f, &m, "identified by sixphase-sim --scenario commission") : -1;
    if (!f || fclose(f) != 0 || rc != 0) {
        (void)snprintf(err, err_len, "cannot write %s", path);
        return -1;
    }
    return 0;
}

/* The test current's limit is the drive's; what the plant carried is measured here. */
static void comm_track_peak(const sim_run_t *rs, sim_result_t *r)
{
    double i[PLANT_PHASES];
    int k;
    plant_phase_currents(&rs->plant, &rs->x, i);
    for (k = 0; k < PLANT_PHASES; k++) {
        r->comm.phase_peak_a = fmax(r->comm.phase_peak_a, fabs(i[k]));
    }
}

int sim_commission_loop(sim_run_t *rs, sim_result_t *r, char *err, size_t err_len)
{
    const sim_config_t *c = rs->cfg;
    sim_ctl_status_t st;
    long k = 0;
    r->comm.ran = true;
    r->comm.apply_result = -1;
    r->comm.phase_peak_a = 0.0;
    rs->wall0_s = sim_wall_now();
    if (rs->ops->commission_start((unsigned)c->commission_steps,
                                  (unsigned)c->commission_permille) == 0) {
        for (k = 0; k < rs->n_periods; k++) {
            if (sim_loop_period(rs, r, k) != 0) {
                (void)snprintf(err, err_len, "plant state diverged");
                return -1;
            }
            if (sim_loop_out_limit(rs, k, err, err_len) != 0 ||
                sim_loop_pil_failed(rs, k, err, err_len)) {
                return -1;
            }
            comm_track_peak(rs, r);
            rs->ops->status(&st);
            if (!st.commissioning) {
                k++;
                break;
            }
        }
    }
    rs->wall1_s = sim_wall_now();
    rs->n_periods = (k > 0) ? k : 1;
    rs->k_win = rs->n_periods;
    comm_collect(rs, r);
    if (r->comm.state == SXL_COMM_STATE_DONE ||
        (r->comm.state == SXL_COMM_STATE_FAILED && r->comm.reason == SXL_COMM_REASON_OPEN_PHASE)) {
        double gains[2];
        r->comm.apply_result = rs->ops->commission_apply(&r->comm.applied, gains);
        r->comm.speed_kp = gains[0];
        r->comm.speed_ki = gains[1];
    }
    /* a failed or refused sequence writes no file: it would hold nothing worth building; nor
     * does one whose set the drive refused to apply (a mixed set, docs/commissioning.md 3.1) */
    return (c->out_dir && r->comm.state == SXL_COMM_STATE_DONE && r->comm.apply_result == 0)
               ? comm_write_params(rs, r, err, err_len)
               : 0;
}
