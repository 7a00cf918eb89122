/*
 * `sixphase-sim reproduce`: the paper's comparison (brief §8) run in parallel
 * worker processes, a Markdown report beside the paper's numbers, and the
 * plots (through the Python script found at configure time).
 */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS */

#include "reproduce.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "sim.h"
#include "sxlink.h"

#ifndef SIM_PLOT_PYTHON
#define SIM_PLOT_PYTHON ""
#endif
#ifndef SIM_PLOT_SCRIPT
#define SIM_PLOT_SCRIPT ""
#endif

#define REP_MAX_CASES 64

typedef struct {
    char name[64];
    char group[16]; /* steady, eqsw, dyn, lxy, extra */
    sim_config_t cfg;
    sim_result_t res;
    int ok;
    char err[160];
} rep_case_t;

/* paper numbers, brief §8 */
static const double paper_lambda[3] = {20.0, 100.0, 200.0};
static const double paper_thd_mptc[3] = {43.5, 28.6, 52.5};
static const double paper_thd_ddc[3] = {13.5, 13.0, 12.8};
static const double paper_rip_mptc[3] = {0.42, 0.58, 0.89};
static const double paper_rip_ddc[3] = {0.29, 0.31, 0.58};

static double rep_now(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static rep_case_t *rep_add(rep_case_t *cases, int *n, const char *dir, const char *group,
                           const char *name, int controller, sim_scenario_t scen, double lambda)
{
    rep_case_t *c;
    static char dirs[REP_MAX_CASES][1100];
    static rep_case_t overflow; /* written to and ignored if the case table is full */
    if (*n >= REP_MAX_CASES) {
        fprintf(stderr, "sixphase-sim: too many reproduce cases, '%s' skipped\n", name);
        return &overflow;
    }
    c = &cases[*n];
    memset(c, 0, sizeof *c);
    (void)snprintf(c->name, sizeof c->name, "%s", name);
    (void)snprintf(c->group, sizeof c->group, "%s", group);
    sim_config_default(&c->cfg);
    c->cfg.controller = controller;
    c->cfg.scenario = scen;
    c->cfg.lambda = lambda;
    c->cfg.seed = 1u;
    c->cfg.ddc_torque_guard = 0; /* the paper's method unless a case asks for the guard */
    /* MPTC-49 peaks near 30 A (beyond the 15 A limit and the +-20 A sensors): the firmware
     * trips it within milliseconds (row protect_mptc49_l100), so its comparison rows run
     * with the software protection out of reach */
    c->cfg.protect = (controller != 1);
    (void)snprintf(dirs[*n], sizeof dirs[*n], "%s/runs/%s", dir, name);
    c->cfg.out_dir = dirs[*n];
    c->cfg.write_fine = false; /* the plots use trace.csv; fine.csv would be ~2.4 MB per run */
    (*n)++;
    return c;
}

/* Run cases[first..last) in up to `jobs` forked workers; results come back
 * through a shared anonymous mapping. */
static int rep_run_batch(rep_case_t *shared, int first, int last, int jobs, int quiet)
{
    pid_t pids[64];
    int idx[64];
    int running = 0, next = first, failures = 0, i;
    if (jobs > 64) {
        jobs = 64;
    }
    while (next < last || running > 0) {
        while (running < jobs && next < last) {
            pid_t pid = fork();
            if (pid < 0) {
                /* no fork: run in this process */
                rep_case_t *c = &shared[next];
                c->ok = (sim_run(&c->cfg, &c->res, c->err, sizeof c->err) == 0);
                next++;
                continue;
            }
            if (pid == 0) {
                rep_case_t *c = &shared[next];
                c->ok = (sim_run(&c->cfg, &c->res, c->err, sizeof c->err) == 0);
                _exit(c->ok ? 0 : 1);
            }
            pids[running] = pid;
            idx[running] = next;
            running++;
            next++;
        }
        if (running > 0) {
            int status = 0;
            const pid_t done = wait(&status);
            if (done < 0) {
                if (errno == EINTR) {
                    continue;
                }
                break;
            }
            for (i = 0; i < running; i++) {
                if (pids[i] == done) {
                    rep_case_t *c = &shared[idx[i]];
                    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !c->ok) {
                        failures++;
                        c->ok = 0;
                        if (c->err[0] == '\0') {
                            (void)snprintf(c->err, sizeof c->err, "worker crashed");
                        }
                    }
                    if (!quiet) {
                        fprintf(stderr, "  %-28s %s  (%.0fx real time)\n", c->name,
                                c->ok ? "ok" : c->err, c->res.realtime_factor);
                    }
                    pids[i] = pids[running - 1];
                    idx[i] = idx[running - 1];
                    running--;
                    break;
                }
            }
        }
    }
    return failures;
}

static const rep_case_t *rep_find(const rep_case_t *cases, int n, const char *name)
{
    int i;
    for (i = 0; i < n; i++) {
        if (strcmp(cases[i].name, name) == 0) {
            return cases[i].ok ? &cases[i] : NULL;
        }
    }
    return NULL;
}

static void fmt_num(char *buf, size_t len, double v, int digits)
{
    if (!(v == v) || v < -1e29) {
        (void)snprintf(buf, len, "n/a");
    } else {
        (void)snprintf(buf, len, "%.*f", digits, v);
    }
}

static void rep_fault(char *buf, size_t len, const sim_result_t *r)
{
    if (r->fault_time_s >= 0.0) {
        (void)snprintf(buf, len, "%s at %.1f ms%s", sxl_fault_name((uint16_t)r->fault),
                       1e3 * r->fault_time_s, (r->trip_time_s >= 0.0) ? " (hardware trip)" : "");
    } else {
        (void)snprintf(buf, len, "none");
    }
}

static void rep_params(FILE *f, const sim_config_t *c, const sim_result_t *r)
{
    const plant_params_t *p = &c->plant;
    fprintf(f, "| quantity | value | quantity | value |\n|---|---|---|---|\n");
    fprintf(f, "| R | %.3g ohm | dead time | %s (%.3g us) |\n", p->r_ohm,
            p->dead_time_on ? "on" : "off", p->dead_time_s * 1e6);
    fprintf(f,
            "| L_d / L_q | %.3g / %.3g mH | PM 5th / 7th harmonic flux | %s (%.3g / %.3g Wb) |\n",
            p->ld_h * 1e3, p->lq_h * 1e3, p->harmonics_on ? "on" : "off", p->psi5_wb, p->psi7_wb);
    fprintf(f, "| L_xy | %.3g mH | ADC quantisation | on (12 bit, +-20 A, 9.8 mA/count) |\n",
            p->lxy_h * 1e3);
    fprintf(f,
            "| psi_f | %.3g Wb | ADC offset | %s (uniform +-%.3g counts, calibrated out by the "
            "drive) |\n",
            p->psi_f_wb, p->adc_offset_on ? "on" : "off", p->adc_offset_counts);
    fprintf(f, "| Pn | %d | ADC gain error | %s (uniform +-%.3g %%) |\n", p->pole_pairs,
            p->adc_gain_on ? "on" : "off", p->adc_gain_error * 100.0);
    fprintf(f, "| J | %.3g kg m^2 | ADC noise | %s (%.3g count rms) |\n", p->j_kgm2,
            p->adc_noise_on ? "on" : "off", p->adc_noise_counts);
    fprintf(f, "| B | %.3g N m s | encoder quantisation | %s (%u lines x4) |\n", p->b_nms,
            p->encoder_quant_on ? "on" : "off", (unsigned)p->encoder_lines);
    fprintf(f, "| Vdc | %.4g V | plant RK4 max step | %.3g us |\n", p->vdc_v, p->max_step_s * 1e6);
    fprintf(f,
            "| speed PI kp / ki | %.4g N m s/rad / %.4g N m/rad | torque limit | %.3g N m (no-load "
            "runs), %.3g N m (loaded runs) |\n",
            r->p_speed_kp, r->p_speed_ki, 7.0, 8.4);
    fprintf(f,
            "| flux reference | %s (%.4g Wb when constant) | DDC duty levels / direction | %d / %s "
            "|\n\n",
            r->p_flux_ref_mode == 1 ? "MTPA" : "constant", r->p_flux_ref_wb, r->p_duty_levels,
            r->p_ddc_direction == 1 ? "x-y table" : "flux error");
}

static void rep_row_steady(FILE *f, const char *label, const rep_case_t *c, double paper_thd,
                           double paper_rip)
{
    char a[32], b[32], d[32], e[32], g[32], h[32], k[32], m[32], pt[32], pr[32], pk[32];
    if (!c) {
        fprintf(f, "| %s | run failed | | | | | | | | | | | |\n", label);
        return;
    }
    (void)snprintf(pk, sizeof pk, "%.1f%s%s", c->res.phase_current_peak_a,
                   c->res.adc_clipped > 0 ? " (ADC clipped)" : "",
                   c->res.fault_time_s >= 0.0 ? " FAULT" : "");
    fmt_num(a, sizeof a, (c->res.thd_percent >= 0.0) ? c->res.thd_percent : -1e30, 1);
    fmt_num(b, sizeof b, (c->res.thd50_percent >= 0.0) ? c->res.thd50_percent : -1e30, 1);
    fmt_num(d, sizeof d, c->res.torque_ripple_nm, 3);
    fmt_num(e, sizeof e, c->res.torque_ripple_pp_nm, 2);
    fmt_num(g, sizeof g, c->res.xy_current_rms_a, 2);
    fmt_num(h, sizeof h, c->res.switching_freq_hz, 0);
    fmt_num(k, sizeof k, c->res.speed_mean_rpm, 1);
    fmt_num(m, sizeof m, c->res.torque_mean_nm, 2);
    fmt_num(pt, sizeof pt, paper_thd, 1);
    fmt_num(pr, sizeof pr, paper_rip, 2);
    fprintf(f, "| %s | %.4g | %s | **%s** | %s | **%s** | %s | %s | %s | %s | %s | %s | %s |\n",
            label, c->res.fs_hz / 1000.0, pt, a, b, d, pr, e, g, h, k, m, pk);
}

static void rep_steady_header(FILE *f)
{
    fprintf(
        f, "| method, lambda | fs kHz | paper THD %% | THD %% | THD_50 %% | ripple std N m | paper "
           "ripple | ripple p-p | x-y rms A | f_sw Hz | speed r/min | torque N m | peak A |\n");
    fprintf(f, "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

/* The row of case "<prefix>_l<lambda>", labelled "<method>, <lambda>", against the paper's
 * DDC or conventional-MPTC figures at that lambda. */
static void rep_row_lambda(FILE *f, const rep_case_t *cases, int n, const char *prefix,
                           const char *method, int li, bool ddc)
{
    char nm[64], label[64];
    (void)snprintf(nm, sizeof nm, "%s_l%.0f", prefix, paper_lambda[li]);
    (void)snprintf(label, sizeof label, "%s, %.0f", method, paper_lambda[li]);
    rep_row_steady(f, label, rep_find(cases, n, nm), ddc ? paper_thd_ddc[li] : paper_thd_mptc[li],
                   ddc ? paper_rip_ddc[li] : paper_rip_mptc[li]);
}

/* Fault injection: each fault at rated operation, the drive's answer. */
static void rep_write_faults(FILE *f, const rep_case_t *cases, int n)
{
    int k;
    fprintf(f, "## 6. Fault injection (DDC, 1500 r/min, rated load; the fault at %.2f s)\n\n",
            SIM_FAULT_INJECT_S);
    fprintf(f,
            "| scenario | injected | expected | reported (all latched) | detection ms | bound ms | "
            "outputs off | records |\n|---|---|---|---|---|---|---|---|\n");
    for (k = 1; k < (int)SIM_FAULT_COUNT; k++) {
        const sim_fault_info_t *fi = sim_fault_info((sim_fault_t)k);
        char nm[64], mask[128], det[32];
        const rep_case_t *c;
        (void)snprintf(nm, sizeof nm, "fault_%s", fi->name);
        c = rep_find(cases, n, nm);
        if (!c) {
            fprintf(f, "| fault-%s | run failed | | | | | | |\n", fi->name);
            continue;
        }
        (void)sxl_fault_mask_str((uint16_t)c->res.faults_latched, mask, (uint16_t)sizeof mask);
        fmt_num(det, sizeof det, (c->res.fault_detect_ms >= 0.0) ? c->res.fault_detect_ms : -1e30,
                1);
        fprintf(f, "| fault-%s | %s | %s | %s (%s) | %s | %.1f | %s | %d |\n", fi->name,
                fi->injection, sxl_fault_name((uint16_t)fi->expected_fault),
                sxl_fault_name((uint16_t)c->res.fault), mask, det, fi->detect_bound_ms,
                c->res.outputs_off ? "yes" : "**no**", c->res.fault_records);
    }
    fprintf(f, "\nDetection is the first control period the drive is in FAULT, counted from the "
               "period the fault is first visible; 0.0 means the same period. Outputs off: every "
               "leg off in every period from the detection on. Power-up faults (adc-offset) are "
               "found by the offset calibration (1024 periods).\n\n");
}

static int rep_write_report(const char *dir, rep_case_t *cases, int n, double wall_s, int jobs)
{
    char path[1200];
    FILE *f;
    int i, li;
    const rep_case_t *ref;
    (void)snprintf(path, sizeof path, "%s/report.md", dir);
    f = fopen(path, "w");
    if (!f) {
        return -1;
    }
    ref = rep_find(cases, n, "steady_ddc_l100");
    fprintf(f, "# Paper reproduction: discrete-duty MPTC vs conventional MPTC (simulated)\n\n");
    fprintf(
        f,
        "Generated by `sixphase-sim reproduce` (%d runs in %d worker processes, %.1f s wall time "
        "for "
        "the runs). Paper numbers are hardware measurements (brief §8); ours come from the host "
        "plant simulator driving the real control core through the firmware's drive ISR "
        "and the simulator HAL. Discussion: docs/results.md.\n\n",
        n, jobs, wall_s);
    fprintf(f, "## Parameters (all runs unless stated)\n\n");
    if (ref) {
        rep_params(f, &ref->cfg, &ref->res);
    }
    fprintf(f,
            "Metrics (brief §7): THD of the plant's phase-A current at %g kHz over the last "
            "whole fundamental periods of the analysis window (all frequencies; the column "
            "THD_50 keeps harmonics 2..50 only, as a power analyser shows); torque ripple = "
            "standard deviation (and peak-to-peak) of the plant's electromagnetic torque at the "
            "same resolution; f_sw = leg transitions / 2 / window / 6.\n\n",
            100.0);

    fprintf(f, "## 1. Steady state, 1500 r/min, rated load, equal sampling frequency\n\n");
    rep_steady_header(f);
    for (li = 0; li < 3; li++) {
        rep_row_lambda(f, cases, n, "steady_mptc49", "MPTC-49", li, false);
        rep_row_lambda(f, cases, n, "steady_mptc13", "MPTC-13", li, false);
        rep_row_lambda(f, cases, n, "steady_ddc", "DDC", li, true);
        rep_row_lambda(f, cases, n, "guard_ddc", "DDC + torque guard", li, true);
    }
    fprintf(f, "\n\"DDC\" is the paper's method (`ddc_torque_guard` off, `--paper-ddc`); \"DDC + "
               "torque guard\" is the core's default, which limits how far the flux weighting may "
               "move the duty (docs/improvements.md), not part of the paper.\n");
    fprintf(f, "\nThe paper's \"conventional MPTC\" columns are repeated on the MPTC-13 rows for "
               "comparison; the paper evaluates 49 candidates (section 3.1) and mentions the "
               "13-candidate variant (section 3.2). Peak A: largest phase current at the control "
               "samples in the window (the board's current sensors span +-20 A).\n");
    fprintf(
        f,
        "\n![steady lambda 20](plots/steady_l20.png)\n![steady lambda 100](plots/steady_l100.png)\n"
        "![steady lambda 200](plots/steady_l200.png)\n![lambda sweep](plots/lambda_sweep.png)\n\n");

    fprintf(f, "## 2. Steady state at equal average switching frequency\n\n");
    fprintf(f, "MPTC-49's sampling frequency is raised until its average switching frequency "
               "matches DDC's at 10 kHz for the same lambda (the paper used 10 and 7.5 kHz without "
               "saying which method got which).\n\n");
    rep_steady_header(f);
    for (li = 0; li < 3; li++) {
        rep_row_lambda(f, cases, n, "eqsw_mptc49", "MPTC-49", li, false);
        rep_row_lambda(f, cases, n, "steady_ddc", "DDC", li, true);
    }

    fprintf(f,
            "\nThe paper's own pairing, as far as it can be read (10 and 7.5 kHz): DDC at 7.5 kHz "
            "against MPTC-49 at 10 kHz.\n\n");
    rep_steady_header(f);
    for (li = 0; li < 3; li++) {
        rep_row_lambda(f, cases, n, "steady_mptc49", "MPTC-49", li, false);
        rep_row_lambda(f, cases, n, "fs7k5_ddc", "DDC", li, true);
    }

    fprintf(f, "\n## 3. Dynamic tests (lambda = 100, 10 kHz)\n\n");
    fprintf(
        f,
        "Transient: acceleration and reversal until the speed stays within 2 %% of the "
        "target; load step until the period-average torque first reaches 90 %% of the new "
        "load. Ripple: torque standard deviation in the steady window at the end of the run.\n\n");
    fprintf(f, "| test | method | paper transient ms | transient ms | paper ripple N m | ripple "
               "std N m | ripple p-p | THD %% (final window) |\n");
    fprintf(f, "|---|---|---|---|---|---|---|---|\n");
    {
        static const char *tests[3] = {"accel", "reversal", "load-step"};
        static const char *labels[3] = {"acceleration 0 -> 800 r/min", "reversal 800 -> -800 r/min",
                                        "rated load step at 1500 r/min"};
        static const double p_tr[3][2] = {{125, 130}, {240, 240}, {16, 16}};
        static const double p_rp[3][2] = {{0.58, 0.28}, {0.58, 0.30}, {0.61, 0.30}};
        int ti, mi;
        for (ti = 0; ti < 3; ti++) {
            for (mi = 0; mi < 2; mi++) {
                char nm[64], t1[32], t2[32], t3[32], t4[32];
                const rep_case_t *c;
                (void)snprintf(nm, sizeof nm, "%s_%s", tests[ti], mi == 0 ? "mptc49" : "ddc");
                c = rep_find(cases, n, nm);
                if (!c) {
                    fprintf(f, "| %s | %s | run failed | | | | | |\n", labels[ti],
                            mi == 0 ? "MPTC-49" : "DDC");
                    continue;
                }
                fmt_num(t1, sizeof t1, (c->res.transient_ms >= 0.0) ? c->res.transient_ms : -1e30,
                        1);
                fmt_num(t2, sizeof t2, c->res.torque_ripple_nm, 3);
                fmt_num(t3, sizeof t3, c->res.torque_ripple_pp_nm, 2);
                fmt_num(t4, sizeof t4, (c->res.thd_percent >= 0.0) ? c->res.thd_percent : -1e30, 1);
                if (fabs(c->res.load_nm) < 1e-9) {
                    /* the no-load current is a few tens of mA: its THD only measures the ripple */
                    (void)snprintf(t4, sizeof t4, "n/a (no load)");
                }
                fprintf(f, "| %s | %s | %.0f | **%s** | %.2f | **%s** | %s | %s |\n", labels[ti],
                        mi == 0 ? "MPTC-49" : "DDC", p_tr[ti][mi], t1, p_rp[ti][mi], t2, t3, t4);
            }
        }
    }
    fprintf(f, "\n![acceleration](plots/accel.png)\n![reversal](plots/reversal.png)\n![load "
               "step](plots/load-step.png)\n\n");

    fprintf(f, "## 4. Sensitivity to the assumed x-y inductance (lambda = 100, 10 kHz)\n\n");
    fprintf(f, "| L_xy mH | method | THD %% | THD_50 %% | ripple std N m | x-y rms A | f_sw Hz "
               "|\n|---|---|---|---|---|---|---|\n");
    {
        static const char *lx[3] = {"5", "10", "20"};
        int xi, mi;
        for (xi = 0; xi < 3; xi++) {
            for (mi = 0; mi < 2; mi++) {
                char nm[64], t1[32], t2[32], t3[32], t4[32], t5[32];
                const rep_case_t *c;
                if (xi == 1) {
                    (void)snprintf(nm, sizeof nm, "steady_%s_l100", mi == 0 ? "mptc49" : "ddc");
                } else {
                    (void)snprintf(nm, sizeof nm, "lxy%s_%s", lx[xi], mi == 0 ? "mptc49" : "ddc");
                }
                c = rep_find(cases, n, nm);
                if (!c) {
                    fprintf(f, "| %s | %s | run failed | | | | |\n", lx[xi],
                            mi == 0 ? "MPTC-49" : "DDC");
                    continue;
                }
                fmt_num(t1, sizeof t1, (c->res.thd_percent >= 0.0) ? c->res.thd_percent : -1e30, 1);
                fmt_num(t2, sizeof t2, (c->res.thd50_percent >= 0.0) ? c->res.thd50_percent : -1e30,
                        1);
                fmt_num(t3, sizeof t3, c->res.torque_ripple_nm, 3);
                fmt_num(t4, sizeof t4, c->res.xy_current_rms_a, 2);
                fmt_num(t5, sizeof t5, c->res.switching_freq_hz, 0);
                fprintf(f, "| %s | %s | %s | %s | %s | %s | %s |\n", lx[xi],
                        mi == 0 ? "MPTC-49" : "DDC", t1, t2, t3, t4, t5);
            }
        }
    }

    fprintf(f, "\n## 5. Variants (steady state, 10 kHz, lambda = 100 unless stated)\n\n");
    fprintf(f, "| case | THD %% | THD_50 %% | ripple std N m | x-y rms A | f_sw Hz | speed r/min | "
               "host ISR us | drive fault |\n|---|---|---|---|---|---|---|---|---|\n");
    {
        static const char *names[14] = {
            "steady_ddc_l100",   "float_ddc_l100",     "ddc_ideal_l100",     "ddc_xytable_l20",
            "ddc_xytable_l100",  "ddc_xytable_l200",   "trip20_ddc_l100",    "steady_mptc49_l100",
            "float_mptc49_l100", "mptc49_ideal_l100",  "trip20_mptc49_l100", "steady_mptc13_l100",
            "steady_ddc_l200",   "protect_mptc49_l100"};
        static const char *labels[14] = {"DDC, fixed Q24 (default)",
                                         "DDC, float build",
                                         "DDC, every non-ideality off",
                                         "DDC, direction from x-y table, lambda 20",
                                         "DDC, direction from x-y table",
                                         "DDC, direction from x-y table, lambda 200",
                                         "DDC, 20 A hardware over-current trip",
                                         "MPTC-49, fixed Q24",
                                         "MPTC-49, float build",
                                         "MPTC-49, every non-ideality off",
                                         "MPTC-49, 20 A hardware over-current trip",
                                         "MPTC-13, fixed Q24",
                                         "DDC, flux-error direction, lambda 200",
                                         "MPTC-49, drive protection at its limits"};
        for (i = 0; i < 14; i++) {
            char t1[32], t2[32], t3[32], t4[32], t5[32], t6[32], t7[32], t8[64];
            const rep_case_t *c = rep_find(cases, n, names[i]);
            if (!c) {
                fprintf(f, "| %s | run failed | | | | | | | |\n", labels[i]);
                continue;
            }
            rep_fault(t8, sizeof t8, &c->res);
            fmt_num(t1, sizeof t1, (c->res.thd_percent >= 0.0) ? c->res.thd_percent : -1e30, 1);
            fmt_num(t2, sizeof t2, (c->res.thd50_percent >= 0.0) ? c->res.thd50_percent : -1e30, 1);
            fmt_num(t3, sizeof t3, c->res.torque_ripple_nm, 3);
            fmt_num(t4, sizeof t4, c->res.xy_current_rms_a, 2);
            fmt_num(t5, sizeof t5, c->res.switching_freq_hz, 0);
            fmt_num(t6, sizeof t6, c->res.speed_mean_rpm, 1);
            fmt_num(t7, sizeof t7, c->res.isr_mean_us, 2);
            fprintf(f, "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", labels[i], t1, t2, t3,
                    t4, t5, t6, t7, t8);
        }
    }
    fprintf(f,
            "\nThe paper's control-step times on the F28335 (MPTC 74.2 us, proposed 50.6 us) are "
            "not comparable with host ISR times; the ratio is the meaningful figure.\n\n");

    rep_write_faults(f, cases, n);

    fprintf(f, "## 7. All runs\n\n| run | scenario | method | arith | lambda | fs kHz | THD %% | "
               "ripple N m | transient ms | drive fault | real-time factor "
               "|\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < n; i++) {
        const rep_case_t *c = &cases[i];
        char t1[32], t2[32], t3[32], t4[64];
        if (!c->ok) {
            fprintf(f, "| %s | failed: %s | | | | | | | | | |\n", c->name, c->err);
            continue;
        }
        rep_fault(t4, sizeof t4, &c->res);
        fmt_num(t1, sizeof t1, (c->res.thd_percent >= 0.0) ? c->res.thd_percent : -1e30, 1);
        fmt_num(t2, sizeof t2, c->res.torque_ripple_nm, 3);
        fmt_num(t3, sizeof t3, (c->res.transient_ms >= 0.0) ? c->res.transient_ms : -1e30, 1);
        fprintf(f, "| %s | %s | %s | %s | %.0f | %.4g | %s | %s | %s | %s | %.0f |\n", c->name,
                c->res.scenario, c->res.controller, c->res.arith, c->res.lambda,
                c->res.fs_hz / 1000.0, t1, t2, t3, t4, c->res.realtime_factor);
    }
    fprintf(f, "\nPer-run traces (trace.csv, one row per control period) and metrics.json are in "
               "runs/ (not committed: regenerate with "
               "`cmake --workflow --preset reproduce`).\n");
    return (fclose(f) == 0) ? 0 : -1;
}

static void rep_json_num(FILE *f, const char *key, double v, int null_if_negative)
{
    if (!(v == v) || (null_if_negative && v < 0.0)) {
        fprintf(f, ", \"%s\": null", key);
    } else {
        fprintf(f, ", \"%s\": %.6g", key, v);
    }
}

static int rep_write_summary(const char *dir, const rep_case_t *cases, int n)
{
    char path[1200];
    FILE *f;
    int i;
    (void)snprintf(path, sizeof path, "%s/summary.json", dir);
    f = fopen(path, "w");
    if (!f) {
        return -1;
    }
    fprintf(f, "[\n");
    for (i = 0; i < n; i++) {
        const sim_result_t *r = &cases[i].res;
        fprintf(f,
                "  {\"name\": \"%s\", \"ok\": %s, \"controller\": \"%s\", \"arith\": \"%s\", "
                "\"scenario\": \"%s\"",
                cases[i].name, cases[i].ok ? "true" : "false", r->controller, r->arith,
                r->scenario);
        rep_json_num(f, "lambda", r->lambda, 0);
        rep_json_num(f, "fs_hz", r->fs_hz, 0);
        rep_json_num(f, "lxy_h", cases[i].cfg.plant.lxy_h, 0);
        rep_json_num(f, "thd_percent", r->thd_percent, 1);
        rep_json_num(f, "thd_h50_percent", r->thd50_percent, 1);
        rep_json_num(f, "torque_ripple_nm", r->torque_ripple_nm, 0);
        rep_json_num(f, "torque_ripple_pp_nm", r->torque_ripple_pp_nm, 0);
        rep_json_num(f, "xy_current_rms_a", r->xy_current_rms_a, 0);
        rep_json_num(f, "switching_freq_hz", r->switching_freq_hz, 0);
        rep_json_num(f, "speed_mean_rpm", r->speed_mean_rpm, 0);
        rep_json_num(f, "torque_mean_nm", r->torque_mean_nm, 0);
        rep_json_num(f, "phase_current_peak_a", r->phase_current_peak_a, 0);
        rep_json_num(f, "transient_ms", r->transient_ms, 1);
        rep_json_num(f, "fault_time_s", r->fault_time_s, 1);
        fprintf(f, ", \"drive_fault\": %d, \"fault_name\": \"%s\", \"outputs_off\": %s", r->fault,
                sxl_fault_name((uint16_t)r->fault), r->outputs_off ? "true" : "false");
        rep_json_num(f, "fault_detect_ms", r->fault_detect_ms, 1);
        rep_json_num(f, "realtime_factor", r->realtime_factor, 0);
        fprintf(f, "}%s\n", (i + 1 < n) ? "," : "");
    }
    fprintf(f, "]\n");
    return (fclose(f) == 0) ? 0 : -1;
}

static int rep_plot(const char *dir, int quiet)
{
    pid_t pid;
    int status = 0;
    if (SIM_PLOT_PYTHON[0] == '\0' || SIM_PLOT_SCRIPT[0] == '\0') {
        fprintf(stderr,
                "sixphase-sim: no Python with matplotlib found at configure time; plots skipped\n");
        return -1;
    }
    pid = fork();
    if (pid < 0) {
        return -1;
    }
    if (pid == 0) {
        char *argv[4];
        argv[0] = (char *)(uintptr_t)SIM_PLOT_PYTHON;
        argv[1] = (char *)(uintptr_t)SIM_PLOT_SCRIPT;
        argv[2] = (char *)(uintptr_t)dir;
        argv[3] = NULL;
        execv(SIM_PLOT_PYTHON, argv);
        _exit(127);
    }
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "sixphase-sim: plot script failed (status %d)\n", status);
        return -1;
    }
    if (!quiet) {
        fprintf(stderr, "plots written to %s/plots\n", dir);
    }
    return 0;
}

int sim_reproduce(const char *out_dir, int jobs, int quiet)
{
    rep_case_t *cases;
    int n = 0, failures, li, n1;
    double t0 = rep_now(), wall;
    const size_t bytes = sizeof(rep_case_t) * REP_MAX_CASES;
    char path[1200];

    {
        char err[1400];
        if (sim_check_out_dir(out_dir, err, sizeof err) != 0) {
            fprintf(stderr, "sixphase-sim: %s\n", err);
            return 1;
        }
    }
    cases =
        (rep_case_t *)mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (cases == MAP_FAILED) {
        fprintf(stderr, "sixphase-sim: mmap failed\n");
        return 1;
    }
    memset(cases, 0, bytes);
    for (li = 0; li < 3; li++) {
        char nm[64];
        (void)snprintf(nm, sizeof nm, "steady_mptc49_l%.0f", paper_lambda[li]);
        (void)rep_add(cases, &n, out_dir, "steady", nm, 1, SIM_SCEN_STEADY, paper_lambda[li]);
        (void)snprintf(nm, sizeof nm, "steady_ddc_l%.0f", paper_lambda[li]);
        (void)rep_add(cases, &n, out_dir, "steady", nm, 0, SIM_SCEN_STEADY, paper_lambda[li]);
        (void)snprintf(nm, sizeof nm, "steady_mptc13_l%.0f", paper_lambda[li]);
        (void)rep_add(cases, &n, out_dir, "steady", nm, 2, SIM_SCEN_STEADY, paper_lambda[li]);
        {
            rep_case_t *c;
            (void)snprintf(nm, sizeof nm, "guard_ddc_l%.0f", paper_lambda[li]);
            c = rep_add(cases, &n, out_dir, "steady", nm, 0, SIM_SCEN_STEADY, paper_lambda[li]);
            c->cfg.ddc_torque_guard = 1;
            (void)snprintf(nm, sizeof nm, "fs7k5_ddc_l%.0f", paper_lambda[li]);
            c = rep_add(cases, &n, out_dir, "eqsw", nm, 0, SIM_SCEN_STEADY, paper_lambda[li]);
            if (c) {
                c->cfg.fs_hz = 7500.0;
            }
        }
    }
    (void)rep_add(cases, &n, out_dir, "dyn", "accel_mptc49", 1, SIM_SCEN_ACCEL, 100.0);
    (void)rep_add(cases, &n, out_dir, "dyn", "accel_ddc", 0, SIM_SCEN_ACCEL, 100.0);
    (void)rep_add(cases, &n, out_dir, "dyn", "reversal_mptc49", 1, SIM_SCEN_REVERSAL, 100.0);
    (void)rep_add(cases, &n, out_dir, "dyn", "reversal_ddc", 0, SIM_SCEN_REVERSAL, 100.0);
    (void)rep_add(cases, &n, out_dir, "dyn", "load-step_mptc49", 1, SIM_SCEN_LOAD_STEP, 100.0);
    (void)rep_add(cases, &n, out_dir, "dyn", "load-step_ddc", 0, SIM_SCEN_LOAD_STEP, 100.0);
    {
        rep_case_t *c;
        c = rep_add(cases, &n, out_dir, "lxy", "lxy5_mptc49", 1, SIM_SCEN_STEADY, 100.0);
        c->cfg.plant.lxy_h = 0.005;
        c = rep_add(cases, &n, out_dir, "lxy", "lxy5_ddc", 0, SIM_SCEN_STEADY, 100.0);
        c->cfg.plant.lxy_h = 0.005;
        c = rep_add(cases, &n, out_dir, "lxy", "lxy20_mptc49", 1, SIM_SCEN_STEADY, 100.0);
        c->cfg.plant.lxy_h = 0.020;
        c = rep_add(cases, &n, out_dir, "lxy", "lxy20_ddc", 0, SIM_SCEN_STEADY, 100.0);
        c->cfg.plant.lxy_h = 0.020;
        c = rep_add(cases, &n, out_dir, "extra", "float_ddc_l100", 0, SIM_SCEN_STEADY, 100.0);
        c->cfg.arith = 1;
        c = rep_add(cases, &n, out_dir, "extra", "float_mptc49_l100", 1, SIM_SCEN_STEADY, 100.0);
        c->cfg.arith = 1;
        c = rep_add(cases, &n, out_dir, "extra", "ddc_xytable_l20", 0, SIM_SCEN_STEADY, 20.0);
        c->cfg.ddc_direction = 1;
        c = rep_add(cases, &n, out_dir, "extra", "ddc_xytable_l100", 0, SIM_SCEN_STEADY, 100.0);
        c->cfg.ddc_direction = 1;
        c = rep_add(cases, &n, out_dir, "extra", "ddc_xytable_l200", 0, SIM_SCEN_STEADY, 200.0);
        c->cfg.ddc_direction = 1;
        c = rep_add(cases, &n, out_dir, "extra", "ddc_ideal_l100", 0, SIM_SCEN_STEADY, 100.0);
        c->cfg.plant.dead_time_on = c->cfg.plant.harmonics_on = false;
        c->cfg.plant.adc_offset_on = c->cfg.plant.adc_gain_on = c->cfg.plant.adc_noise_on = false;
        c->cfg.plant.encoder_quant_on = false;
        c = rep_add(cases, &n, out_dir, "extra", "trip20_mptc49_l100", 1, SIM_SCEN_STEADY, 100.0);
        c->cfg.trip_current_a = 20.0;
        c = rep_add(cases, &n, out_dir, "extra", "protect_mptc49_l100", 1, SIM_SCEN_STEADY, 100.0);
        c->cfg.protect = true;
        c = rep_add(cases, &n, out_dir, "extra", "trip20_ddc_l100", 0, SIM_SCEN_STEADY, 100.0);
        c->cfg.trip_current_a = 20.0;
        for (li = 1; li < (int)SIM_FAULT_COUNT; li++) {
            char nm[64];
            (void)snprintf(nm, sizeof nm, "fault_%s", sim_fault_info((sim_fault_t)li)->name);
            c = rep_add(cases, &n, out_dir, "fault", nm, 0, SIM_SCEN_STEADY, 100.0);
            c->cfg.fault = (sim_fault_t)li;
            c->cfg.ddc_torque_guard = -1; /* the product's DDC, as `sixphase-sim run` */
        }
        c = rep_add(cases, &n, out_dir, "extra", "mptc49_ideal_l100", 1, SIM_SCEN_STEADY, 100.0);
        c->cfg.plant.dead_time_on = c->cfg.plant.harmonics_on = false;
        c->cfg.plant.adc_offset_on = c->cfg.plant.adc_gain_on = c->cfg.plant.adc_noise_on = false;
        c->cfg.plant.encoder_quant_on = false;
    }
    n1 = n;
    if (!quiet) {
        fprintf(stderr, "reproduce: %d runs, %d workers\n", n1, jobs);
    }
    failures = rep_run_batch(cases, 0, n1, jobs, quiet);

    /* equal average switching frequency: MPTC-49 at the sampling frequency that
     * gives DDC's switching frequency (switching frequency ~ proportional to fs) */
    for (li = 0; li < 3; li++) {
        char nm[64];
        const rep_case_t *d, *m;
        rep_case_t *c;
        double fs;
        (void)snprintf(nm, sizeof nm, "steady_ddc_l%.0f", paper_lambda[li]);
        d = rep_find(cases, n1, nm);
        (void)snprintf(nm, sizeof nm, "steady_mptc49_l%.0f", paper_lambda[li]);
        m = rep_find(cases, n1, nm);
        if (!d || !m || !(m->res.switching_freq_hz > 0.0)) {
            continue;
        }
        fs = 10000.0 * d->res.switching_freq_hz / m->res.switching_freq_hz;
        fs = 100.0 * floor(fs / 100.0 + 0.5);
        fs = (fs < 2000.0) ? 2000.0 : ((fs > 50000.0) ? 50000.0 : fs);
        (void)snprintf(nm, sizeof nm, "eqsw_mptc49_l%.0f", paper_lambda[li]);
        c = rep_add(cases, &n, out_dir, "eqsw", nm, 1, SIM_SCEN_STEADY, paper_lambda[li]);
        if (c) {
            c->cfg.fs_hz = fs;
        }
    }
    failures += rep_run_batch(cases, n1, n, jobs, quiet);
    wall = rep_now() - t0;

    {
        FILE *g;
        (void)snprintf(path, sizeof path, "%s/.gitignore", out_dir);
        g = fopen(path, "w");
        if (g) {
            fprintf(g, "# raw traces of the reproduce runs: regenerated, not committed\nruns/\n");
            (void)fclose(g);
        }
    }
    if (rep_write_summary(out_dir, cases, n) != 0 ||
        rep_write_report(out_dir, cases, n, wall, jobs) != 0) {
        fprintf(stderr, "sixphase-sim: cannot write the report in '%s'\n", out_dir);
        (void)munmap(cases, bytes);
        return 1;
    }
    (void)rep_plot(out_dir, quiet);
    if (!quiet) {
        fprintf(stderr,
                "reproduce: %d runs, %d failed, %.1f s wall (runs %.1f s, plots and report %.1f "
                "s); report %s/report.md\n",
                n, failures, rep_now() - t0, wall, rep_now() - t0 - wall, out_dir);
    }
    (void)munmap(cases, bytes);
    return failures ? 1 : 0;
}
