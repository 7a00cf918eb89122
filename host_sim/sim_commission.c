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

int sim_commission_loop(sim_run_t *rs, sim_result_t *r, char *err, size_t err_len)
{
    const sim_config_t *c = rs->cfg;
    sim_ctl_status_t st;
    long k = 0;
    r->comm.ran = true;
    r->comm.apply_result = -1;
    rs->wall0_s = sim_wall_now();
    if (rs->ops->commission_start((unsigned)c->commission_steps,
                                  (unsigned)c->commission_permille) == 0) {
        for (k = 0; k < rs->n_periods; k++) {
            if (sim_loop_period(rs, r, k) != 0) {
                (void)snprintf(err, err_len, "plant state diverged");
                return -1;
            }
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
    if (r->comm.state == SXL_COMM_STATE_DONE) {
        r->comm.apply_result = rs->ops->commission_apply(&r->comm.applied);
    }
    return 0;
}
