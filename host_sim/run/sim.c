/*
 * One simulation run, see sim.h. The parts live in their own files: the scenario's plan
 * (scenario.c), set-up and the drive's calibration (sim_setup.c), the sensors (sim_adc.c,
 * sim_encoder.c), the period loop (sim_loop.c), the output files (recorder.c), the metrics
 * (sim_metrics.c, sim_result.c) and metrics.json (sim_json.c).
 */
#include "sim.h"

#include <stdio.h>
#include <string.h>

#include "sim_run_state.h"

/* An open phase can happen in any motion (braking, accelerating, reversing) and during
 * commissioning; the other faults are injected into rated steady operation. */
static bool sim_fault_scenario_ok(sim_fault_t f, sim_scenario_t s)
{
    if (f == SIM_FAULT_OPEN_PHASE) {
        return true; /* commissioning included: every step watches for it */
    }
    return s == SIM_SCEN_STEADY;
}

/* What can be refused before anything is set up. */
static int sim_check_config(const sim_config_t *c, char *err, size_t err_len)
{
    const char *chk = plant_params_check(&c->plant);
    const char *msg = NULL;
    if (chk[0] != '\0') {
        msg = chk;
    } else if (!(c->fs_hz >= 1000.0 && c->fs_hz <= 100000.0)) {
        msg = "fs must be in [1000, 100000] Hz";
    } else if (c->fault != SIM_FAULT_NONE && (!sim_fault_scenario_ok(c->fault, c->scenario) ||
                                              sim_fault_info(c->fault) == NULL)) {
        msg = "fault injection runs on the steady scenario only (an open phase on any)";
    } else if (c->duration_s > SIM_MAX_DURATION_S) {
        msg = "duration above 36000 s (10 h)";
    }
    if (msg) {
        (void)snprintf(err, err_len, "%s", msg);
        return -1;
    }
    return 0;
}

static void sim_result_clear(sim_result_t *r)
{
    memset(r, 0, sizeof *r);
    r->fault_inject_s = -1.0;
    r->fault_detect_ms = -1.0;
    r->open_phase_event_s = -1.0;
    r->isolated_leg = -1;
    r->isolation_ms = -1.0;
    r->postfault_start_ms = -1.0;
    r->recover_ms = -1.0;
    r->torque_limited_first_s = -1.0;
}

/* The files that are written once the run is over: close the CSVs, write metrics.json. */
static int sim_finish_files(sim_run_t *rs, const sim_result_t *r, char *err, size_t err_len)
{
    char path[1200];
    if (sim_recorder_close(&rs->rec, err, err_len) != 0) {
        return -1;
    }
    if (!rs->cfg->out_dir) {
        return 0;
    }
    (void)snprintf(path, sizeof path, "%s/metrics.json", rs->cfg->out_dir);
    if (sim_write_metrics_json(path, rs->cfg, r) != 0) {
        (void)snprintf(err, err_len, "cannot write %s", path);
        return -1;
    }
    return 0;
}

/* The PIL session's end: its statistics into r; -1 (with why in err) when it failed. */
static int sim_end_pil(sim_run_t *rs, sim_result_t *r, char *err, size_t err_len)
{
    int rc = 0;
    if (!rs->pil_open) {
        return 0;
    }
    if (sim_pil_error() && err) {
        (void)snprintf(err, err_len, "%s", sim_pil_error());
        rc = -1;
    }
    sim_pil_close(&r->pil);
    rs->pil_open = false;
    return rc;
}

int sim_run(const sim_config_t *c, sim_result_t *r, char *err, size_t err_len)
{
    sim_run_t rs;
    int rc = -1;
    sim_result_clear(r);
    if (sim_check_config(c, err, err_len) != 0) {
        return -1;
    }
    if (c->out_dir && sim_check_out_dir(c->out_dir, err, err_len) != 0) {
        return -1; /* found before simulating, not after */
    }
    if (sim_setup(&rs, c, err, err_len) == 0 && sim_setup_calibrate(&rs, r, err, err_len) == 0 &&
        ((c->scenario == SIM_SCEN_COMMISSION) ? sim_commission_loop(&rs, r, err, err_len)
                                              : sim_loop_run(&rs, r, err, err_len)) == 0) {
        sim_result_fill(&rs, r); /* the drive's end state: the PIL reference's, still open */
        if (sim_end_pil(&rs, r, err, err_len) == 0) {
            rc = sim_finish_files(&rs, r, err, err_len);
        }
    }
    (void)sim_end_pil(&rs, r, NULL, 0u); /* a failed run's session too: the emulator stopped */
    if (rc != 0 && rs.rec.limit_reached) {
        char close_err[64]; /* the files up to the limit are kept, flushed and closed */
        (void)sim_recorder_close(&rs.rec, close_err, sizeof close_err);
    }
    sim_teardown(&rs, rc == 0);
    return rc;
}
