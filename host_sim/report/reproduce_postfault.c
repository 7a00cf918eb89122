/* The open-phase runs and report section of `sixphase-sim reproduce`, see reproduce_postfault.h. */
#include "reproduce_postfault.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "run/scenario.h"

/* One open-phase run: the product's DDC (the core's defaults), fault-open-phase at 0.25 s in
 * phase `phase`, ride-through or stop, the load the derated drive can carry. */
static rep_case_t *pf_add(rep_case_t *cases, int *n, const char *dir, const char *name, int phase,
                          bool ride)
{
    rep_case_t *c = rep_add(cases, n, dir, "postfault", name, 0, SIM_SCEN_STEADY, 100.0);
    c->cfg.ddc_torque_guard = c->cfg.mid_period_angle = c->cfg.pulse_pattern = -1;
    c->cfg.flux_tie_band = -1.0;
    c->cfg.light_load_current_a = -1.0;
    c->cfg.fault = SIM_FAULT_OPEN_PHASE;
    c->cfg.fault_phase = phase;
    c->cfg.open_phase_action = ride ? 1 : -1;
    c->cfg.load_nm = REP_POSTFAULT_LOAD_NM;
    c->cfg.write_trace = strcmp(name, "pf_ride_C") == 0 || !ride;
    return c;
}

void rep_cases_postfault(rep_case_t *cases, int *n, const char *dir)
{
    static const char *const names[6] = {"pf_ride_A", "pf_ride_B", "pf_ride_C",
                                         "pf_ride_D", "pf_ride_E", "pf_ride_F"};
    rep_case_t *c;
    int k;
    for (k = 0; k < 6; k++) {
        (void)pf_add(cases, n, dir, names[k], k, true);
    }
    (void)pf_add(cases, n, dir, "pf_stop_C", 2, false);
    c = pf_add(cases, n, dir, "pf_ride_C_mt", 2, true);
    c->cfg.postfault_strategy = 1;
    c->cfg.write_trace = true;
    c = pf_add(cases, n, dir, "pf_ride_C_mptc13", 2, true);
    c->cfg.controller = 2;
    c = pf_add(cases, n, dir, "pf_ride_C_float", 2, true);
    c->cfg.arith = 1;
    c = pf_add(cases, n, dir, "pf_ride_C_open", 2, true);
    c->cfg.open_model = 1;
    c = pf_add(cases, n, dir, "pf_ride_C_800", 2, true);
    c->cfg.speed_rpm = 800.0;
    c = pf_add(cases, n, dir, "pf_ride_C_handoff6", 2, true);
    c->cfg.handoff_delay_s = 0.006;
    c = pf_add(cases, n, dir, "pf_rated_C", 2, true);
    c->cfg.load_nm = 7.0;
    c->cfg.write_trace = true;
    c = pf_add(cases, n, dir, "pf_second_C_E", 2, true);
    c->cfg.second_fault_phase = 4;
    c->cfg.second_fault_s = 0.5;
    c = pf_add(cases, n, dir, "pf_isolate_C", 2, true);
    c->cfg.fault = SIM_FAULT_NONE;
    c->cfg.fault_phase = -1;
    c->cfg.isolate_leg = 2;
    c->cfg.write_trace = true;
    c = pf_add(cases, n, dir, "pf_healthy", -1, false);
    c->cfg.fault = SIM_FAULT_NONE;
    c->cfg.duration_s = SIM_OPEN_PHASE_DURATION_S;
}

static double pf_peak(const sim_result_t *r)
{
    double m = 0.0;
    int k;
    for (k = 0; k < 6; k++) {
        m = fmax(m, r->phase_peak_a[k]);
    }
    return m;
}

/* Copper loss of the six phases over the analysis window, W. */
static double pf_loss(const rep_case_t *c)
{
    double sum = 0.0;
    int k;
    for (k = 0; k < 6; k++) {
        sum += c->res.phase_rms_a[k] * c->res.phase_rms_a[k];
    }
    return c->cfg.plant.r_ohm * sum;
}

static void pf_ms(char *buf, size_t len, double v)
{
    if (v >= 0.0) {
        (void)snprintf(buf, len, "%.1f", v);
    } else {
        (void)snprintf(buf, len, "never");
    }
}

/* One run as a table row: what happened and the five-leg operation after it. */
static void pf_row(FILE *f, const char *label, const rep_case_t *c)
{
    char iso[16], five[16], rec[16];
    int k;
    if (!c) {
        fprintf(f, "| %s | run failed | | | | | | | | |\n", label);
        return;
    }
    pf_ms(iso, sizeof iso, c->res.isolation_ms);
    pf_ms(five, sizeof five, c->res.postfault_start_ms);
    pf_ms(rec, sizeof rec, c->res.recover_ms);
    fprintf(f, "| %s | %s | %s | %.1f | %s | %.0f | %.3f |", label, iso, five, c->res.speed_dip_rpm,
            rec, c->res.speed_mean_rpm, c->res.torque_ripple_nm);
    for (k = 0; k < 6; k++) {
        fprintf(f, "%s%.2f", (k == 0) ? " " : " / ", c->res.phase_rms_a[k]);
    }
    fprintf(f, " | %.2f (%.2f) | %.2f | %.1f |\n", pf_peak(&c->res), c->res.phase_limit_peak_a,
            c->res.torque_limit_end_nm, pf_loss(c));
}

static void pf_table_head(FILE *f, const char *first)
{
    fprintf(f,
            "| %s | isolated ms | five legs ms | speed dip r/min | recovered ms | mean speed "
            "r/min | ripple N m | phase rms A..F (A) | peak A (limit) | torque limit N m | "
            "copper loss W |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
            first);
}

static void pf_section_phases(FILE *f, const rep_case_t *cases, int n)
{
    static const char *const names[6] = {"pf_ride_A", "pf_ride_B", "pf_ride_C",
                                         "pf_ride_D", "pf_ride_E", "pf_ride_F"};
    char label[16];
    int k;
    fprintf(f, "### 9.1 Each phase (DDC, minimum loss, %.1f N m, 1500 r/min)\n\n",
            REP_POSTFAULT_LOAD_NM);
    pf_table_head(f, "open phase");
    for (k = 0; k < 6; k++) {
        (void)snprintf(label, sizeof label, "%c", 'A' + k);
        pf_row(f, label, rep_find(cases, n, names[k]));
    }
    fprintf(f, "\n");
}

static void pf_section_variants(FILE *f, const rep_case_t *cases, int n)
{
    const rep_case_t *h = rep_find(cases, n, "pf_healthy");
    fprintf(f,
            "### 9.2 Phase C: strategy, controller, arithmetic, plant model, speed, hand-off\n\n");
    pf_table_head(f, "run");
    pf_row(f, "DDC, minimum loss", rep_find(cases, n, "pf_ride_C"));
    pf_row(f, "DDC, maximum torque", rep_find(cases, n, "pf_ride_C_mt"));
    pf_row(f, "MPTC-13", rep_find(cases, n, "pf_ride_C_mptc13"));
    pf_row(f, "DDC, float build", rep_find(cases, n, "pf_ride_C_float"));
    pf_row(f, "DDC, open circuit (--open-model open)", rep_find(cases, n, "pf_ride_C_open"));
    pf_row(f, "DDC, 800 r/min", rep_find(cases, n, "pf_ride_C_800"));
    pf_row(f, "DDC, hand-off 6 ms (--handoff-delay)", rep_find(cases, n, "pf_ride_C_handoff6"));
    pf_row(f, "DDC, rated load 7 N m", rep_find(cases, n, "pf_rated_C"));
    if (h) {
        fprintf(f,
                "\nHealthy reference at the same point (DDC, %.1f N m, 1500 r/min): ripple %.3f N "
                "m, phase rms %.2f A, peak %.2f A, copper loss %.1f W.\n",
                REP_POSTFAULT_LOAD_NM, h->res.torque_ripple_nm, h->res.phase_current_rms_a,
                h->res.phase_current_peak_a,
                6.0 * h->cfg.plant.r_ohm * h->res.phase_current_rms_a * h->res.phase_current_rms_a);
    }
    fprintf(f, "\n");
}

static void pf_section_stops(FILE *f, const rep_case_t *cases, int n)
{
    const rep_case_t *s = rep_find(cases, n, "pf_stop_C");
    const rep_case_t *t = rep_find(cases, n, "pf_second_C_E");
    const rep_case_t *i = rep_find(cases, n, "pf_isolate_C");
    fprintf(f, "### 9.3 Stop, a second fault, an isolation command\n\n");
    if (s) {
        fprintf(f,
                "- The same fault with the build default (stop): %s after %.1f ms, outputs off "
                "%s, the speed falls by %.0f r/min by the end of the run.\n",
                s->res.fault_time_s >= 0.0 ? "FAULT OPEN_PHASE" : "no fault",
                s->res.fault_detect_ms, s->res.outputs_off ? "from then on" : "**not**",
                s->res.speed_dip_rpm);
    }
    if (t) {
        fprintf(f,
                "- A second open phase (E at 0.5 s) while C is isolated: state %d (4 = FAULT), "
                "fault code %d at %.1f ms, %d records in the log (the one ridden through and the "
                "second), outputs off %s.\n",
                t->res.final_state, t->res.fault, 1e3 * t->res.fault_time_s, t->res.fault_records,
                t->res.outputs_off ? "yes" : "**no**");
    }
    if (i) {
        fprintf(f,
                "- An isolation command (leg C, 0.25 s) on a machine whose phase C is still "
                "connected: the leg's diodes conduct %.0f %% of the time, i_C %.2f A rms and "
                "%.2f A peak, ripple %.3f N m (the plot postfault_isolation.png): switching the "
                "leg off does not open the phase of this machine (docs/faults.md).\n",
                100.0 * i->res.diode_conduction, i->res.phase_rms_a[2], i->res.phase_peak_a[2],
                i->res.torque_ripple_nm);
    }
    fprintf(f, "\n");
}

void rep_section_postfault(FILE *f, const rep_case_t *cases, int n)
{
    fprintf(f, "## 9. Open-phase operation (docs/faults.md)\n\n");
    fprintf(f,
            "fault-open-phase (2 kohm in series from 0.25 s) with `--ride-through`, product DDC, "
            "%.1f N m: the drive detects the open phase, isolates its leg, takes the post-fault "
            "set and runs on five legs. Times from the injection; recovered = the speed stays "
            "within 2 %% of 1500 r/min from then on (0: it never left); ripple and phase rms over "
            "the last 0.2 s; limit = the peak the healthy torque limit (8.4 N m) allows, T_lim / "
            "(3 Pn psi_f), against the instantaneous peak with its switching ripple. Plots: "
            "postfault_C.png (stop beside ride-through), postfault_strategies.png, "
            "postfault_rated.png, postfault_isolation.png.\n\n",
            REP_POSTFAULT_LOAD_NM);
    pf_section_phases(f, cases, n);
    pf_section_variants(f, cases, n);
    pf_section_stops(f, cases, n);
}
