/*
 * The run's drive table with its periods on a PIL target, see pil.h. Each call the run makes
 * on its drive runs on the reference at once and goes to the target in front of the next
 * period; each period runs on the reference from the plant's inputs, then on the target from
 * the same inputs, and the target's outputs are the ones the plant gets. One session a process
 * (the simulator runs one run a process).
 */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hal_sim.h"
#include "pil.h"
#include "pil_session.h"
#include "pil_stats.h"

#define PIL_CALLS_MAX 240u

static struct {
    const sim_ctl_ops_t *ref;
    sim_ctl_ops_t table;
    pil_session_t s;
    const char *error;
    uint16_t calls[PIL_CALLS_MAX];
    uint16_t ncalls;
    double ts;
    struct timespec t_first, t_last;
    pil_stats_t stats;
} pil;

static void pil_fail(void) { pil.error = pil.s.err; }

/* A call record queued for the target (sent at once when the queue would overflow). */
static void pil_enqueue(uint16_t code, const uint16_t *args, uint16_t n)
{
    uint16_t k;
    if (pil.error) {
        return;
    }
    if (pil.ncalls + 1u + n > PIL_CALLS_MAX) {
        if (pil_session_calls(&pil.s, pil.calls, pil.ncalls) != 0) {
            pil_fail();
            return;
        }
        pil.ncalls = 0u;
    }
    pil.calls[pil.ncalls++] = code;
    for (k = 0u; k < n; k++) {
        pil.calls[pil.ncalls++] = args[k];
    }
}

static void pil_enqueue_real(uint16_t code, double v)
{
    uint16_t a[4];
    sxl_put_u32(a, sim_ctl_wire_real_bits(v));
    pil_enqueue(code, a, 4u);
}

static int pil_init(const sim_ctl_config_t *cfg, const char **why)
{
    uint16_t image[SIM_CTL_CONFIG_IMAGE_BYTES];
    sim_ctl_config_t as_sent; /* the values the target decodes: the reference takes the same */
    int rc;
    int rc_target = -1;
    sim_ctl_config_encode(cfg, image);
    sim_ctl_config_decode(image, &as_sent);
    rc = pil.ref->init(&as_sent, why);
    if (rc == 1) {
        return 1;
    }
    if (pil_session_init(&pil.s, &as_sent, &hal_sim_bus, &rc_target) != 0) {
        pil_fail();
        *why = pil.error;
        return 1;
    }
    if (rc_target != rc) {
        (void)snprintf(pil.s.err, sizeof pil.s.err,
                       "PIL: the target's drive init gave %d, the reference's %d", rc_target, rc);
        pil_fail();
        *why = pil.error;
        return 1;
    }
    return rc;
}

/* One period on the target from the inputs the reference had; the plant gets its outputs. */
static void pil_isr(void)
{
    const hal_sim_bus_t in = hal_sim_bus;
    sim_ctl_wire_out_t mine;
    sim_ctl_wire_out_t theirs;
    sim_ctl_status_t st;
    const uint16_t room = (uint16_t)(SXL_MAX_PAYLOAD - SXL_PIL_IN_BYTES);
    pil.ref->isr();
    if (pil.error) {
        return;
    }
    sim_ctl_wire_outputs_of_bus(&hal_sim_bus, &mine);
    pil.ref->status(&st);
    mine.state = (uint16_t)st.state;
    mine.faults = (uint16_t)st.faults_latched;
    if (pil.ncalls > room && pil_session_calls(&pil.s, pil.calls, pil.ncalls) != 0) {
        pil_fail();
        return;
    }
    if (pil_session_step(&pil.s, &in, (uint16_t)pil.stats.steps, pil.calls,
                         (pil.ncalls > room) ? 0u : pil.ncalls, &theirs) != 0) {
        pil_fail();
        return;
    }
    pil.ncalls = 0u;
    sim_ctl_wire_outputs_to_bus(&theirs, &hal_sim_bus);
    (void)clock_gettime(CLOCK_MONOTONIC, &pil.t_last);
    if (pil.stats.steps == 0u) {
        pil.t_first = pil.t_last;
    }
    pil_stats_add(&pil.stats, &in, &mine, &theirs, (double)pil.stats.steps * pil.ts);
}

static void pil_request_run(void)
{
    pil.ref->request_run();
    pil_enqueue(SXL_PIL_CALL_RUN, NULL, 0u);
}
static void pil_request_clear(void)
{
    pil.ref->request_clear();
    pil_enqueue(SXL_PIL_CALL_CLEAR, NULL, 0u);
}
static void pil_set_speed_rpm(double rpm)
{
    pil.ref->set_speed_rpm(sim_ctl_wire_real_of(sim_ctl_wire_real_bits(rpm)));
    pil_enqueue_real(SXL_PIL_CALL_SET_SPEED, rpm);
}
static void pil_set_torque_nm(double nm)
{
    pil.ref->set_torque_nm(sim_ctl_wire_real_of(sim_ctl_wire_real_bits(nm)));
    pil_enqueue_real(SXL_PIL_CALL_SET_TORQUE, nm);
}
static void pil_report_overrun(void)
{
    pil.ref->report_overrun();
    pil_enqueue(SXL_PIL_CALL_OVERRUN, NULL, 0u);
}
static void pil_background(void)
{
    pil.ref->background();
    pil_enqueue(SXL_PIL_CALL_BACKGROUND, NULL, 0u);
}
static int pil_isolate_leg(int leg)
{
    const uint16_t a = (uint16_t)((leg >= 0 && leg < 6) ? leg : 0xFF);
    const int ok = pil.ref->isolate_leg(leg);
    pil_enqueue(SXL_PIL_CALL_ISOLATE_LEG, &a, 1u);
    return ok;
}
static int pil_commission_start(unsigned mask, unsigned permille)
{
    uint16_t a[4];
    const int rc = pil.ref->commission_start(mask, permille);
    sxl_put_u16(a, (uint16_t)mask);
    sxl_put_u16(&a[2], (uint16_t)permille);
    pil_enqueue(SXL_PIL_CALL_COMMISSION_START, a, 4u);
    return rc;
}
static int pil_commission_apply(unsigned *applied, double speed_gains[2])
{
    const int rc = pil.ref->commission_apply(applied, speed_gains);
    pil_enqueue(SXL_PIL_CALL_COMMISSION_APPLY, NULL, 0u);
    return rc;
}
static int pil_read_fault_record(sim_fault_record_t *r)
{
    const int got = pil.ref->read_fault_record(r);
    if (got) {
        pil_enqueue(SXL_PIL_CALL_READ_FAULT_RECORD, NULL, 0u);
    }
    return got;
}
static void pil_profile(void) {} /* the target times its own periods */

const sim_ctl_ops_t *sim_pil_open(const sim_ctl_ops_t *ref, const char *target, double ts_s,
                                  const char *csv_path, char *err, size_t err_len)
{
    memset(&pil, 0, sizeof pil);
    pil.ref = ref;
    pil.ts = ts_s;
    if (pil_session_open(&pil.s, target, ref->arith) != 0 ||
        pil_stats_open(&pil.stats, csv_path, pil.s.err, sizeof pil.s.err) != 0) {
        (void)snprintf(err, err_len, "%s", pil.s.err);
        pil_session_close(&pil.s);
        return NULL;
    }
    pil.stats.float_image = pil.s.arith == SXL_PIL_ARITH_FLOAT;
    pil.table =
        *ref; /* the queries (status, commissioning status, the link) stay the reference's */
    pil.table.init = pil_init;
    pil.table.isr = pil_isr;
    pil.table.request_run = pil_request_run;
    pil.table.set_speed_rpm = pil_set_speed_rpm;
    pil.table.set_torque_nm = pil_set_torque_nm;
    pil.table.report_overrun = pil_report_overrun;
    pil.table.read_fault_record = pil_read_fault_record;
    pil.table.request_clear = pil_request_clear;
    pil.table.background = pil_background;
    pil.table.isolate_leg = pil_isolate_leg;
    pil.table.commission_start = pil_commission_start;
    pil.table.commission_apply = pil_commission_apply;
    pil.table.profile = pil_profile;
    (void)snprintf(pil.stats.summary.target, sizeof pil.stats.summary.target, "%s", target);
    return &pil.table;
}

const char *sim_pil_error(void) { return pil.error; }

void sim_pil_close(sim_pil_summary_t *s)
{
    const double wall = (double)(pil.t_last.tv_sec - pil.t_first.tv_sec) +
                        1e-9 * (double)(pil.t_last.tv_nsec - pil.t_first.tv_nsec);
    pil.stats.summary.emulated = pil.s.port.emulated != 0;
    pil.stats.summary.icount_shift = pil.s.port.icount_shift;
    pil.stats.summary.counter_hz = (double)pil.s.counter_hz;
    pil_stats_close(&pil.stats, wall, s);
    pil_session_close(&pil.s);
    pil.ref = NULL;
}
