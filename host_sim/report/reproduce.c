/*
 * `sixphase-sim reproduce`: the paper's comparison (brief §8; the runs in reproduce_cases.c)
 * run in parallel worker processes, the report beside the paper's numbers
 * (reproduce_report.c), and the plots (through the Python script found at configure time).
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, isatty */

#include "reproduce.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "plots.h"
#include "reproduce_cases.h"
#include "reproduce_commission.h"
#include "reproduce_postfault.h"
#include "reproduce_report.h"
#include "run/batch.h"
#include "run/sim.h"

static double rep_now(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct {
    bool tty;
    double t0;
} rep_progress_t;

/* Progress on a terminal only; a failed run is named either way. */
static void rep_case_done(void *ctx, const sim_case_t *c, int done, int total)
{
    const rep_progress_t *pr = (const rep_progress_t *)ctx;
    if (!c->ok) {
        fprintf(stderr, "%sreproduce: %s failed: %s\n", pr->tty ? "\n" : "", c->name, c->err);
    }
    if (pr->tty) {
        const double el = rep_now() - pr->t0;
        fprintf(stderr, "\rreproduce: %d of %d runs (%.0f %%), about %.0f s left   %s", done, total,
                100.0 * done / total, el / done * (total - done), (done == total) ? "\n" : "");
    }
}

static void rep_write_gitignore(const char *out_dir)
{
    char path[1200];
    FILE *g;
    (void)snprintf(path, sizeof path, "%s/.gitignore", out_dir);
    g = fopen(path, "w");
    if (g) {
        fprintf(g, "# raw traces and host timings of the reproduce runs: regenerated, not "
                   "committed\nruns/\ntimings.md\n");
        (void)fclose(g);
    }
}

static int rep_write_all(const char *out_dir, const rep_case_t *cases, int n, double wall, int jobs)
{
    rep_write_gitignore(out_dir);
    if (rep_write_summary(out_dir, cases, n) != 0 || rep_write_report(out_dir, cases, n) != 0 ||
        rep_write_timings(out_dir, cases, n, wall, jobs) != 0) {
        fprintf(stderr, "sixphase-sim: cannot write the report in '%s'\n", out_dir);
        return -1;
    }
    return 0;
}

int sim_reproduce(const char *out_dir, int jobs, bool plots, int quiet)
{
    rep_progress_t progress;
    sim_plot_job_t plot;
    bool drawing;
    const double t0 = rep_now();
    rep_case_t *cases;
    int n = 0, n1, n2, failures, rc, round;
    double wall;
    char err[1400];
    if (sim_check_out_dir(out_dir, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 1;
    }
    cases = sim_batch_alloc(REP_MAX_CASES);
    if (!cases) {
        fprintf(stderr, "sixphase-sim: mmap failed\n");
        return 1;
    }
    rep_cases_first_batch(cases, &n, out_dir);
    rep_cases_improvement_sweep(cases, &n, out_dir);
    rep_cases_postfault(cases, &n, out_dir);
    rep_cases_commission(cases, &n);
    n1 = n;
    if (!quiet) {
        fprintf(stderr, "reproduce: %d runs, %d workers\n", n1, jobs);
    }
    progress.tty = !quiet && isatty(2);
    progress.t0 = t0;
    failures = sim_batch_run(cases, 0, n1, jobs, rep_case_done, &progress);
    /* the runs' figures need only the first batch's traces: drawn while the rest computes, the
     * summary's once the report is written (the script waits at its gate) */
    drawing =
        plots && sim_plot_start(SIM_PLOT_REPRODUCE, out_dir, "traces-then-summary", &plot) == 0;
    for (round = 1; round <= REP_EQSW_ROUNDS; round++) { /* equal switching frequency */
        const int from = n;
        if (rep_cases_equal_switching(cases, &n, out_dir, round) == 0) {
            break;
        }
        failures += sim_batch_run(cases, from, n, jobs, rep_case_done, &progress);
    }
    n2 = n; /* the controller set the commissioning identified (section 10) */
    rep_cases_commission_identified(cases, &n);
    failures += sim_batch_run(cases, n2, n, jobs, rep_case_done, &progress);
    wall = rep_now() - t0;
    rc = rep_write_all(out_dir, cases, n, wall, jobs);
    if (drawing && rc != 0) {
        sim_plot_cancel(&plot); /* no summary.json of this run to draw */
    } else if (drawing && sim_plot_finish(&plot) == 0 && !quiet) {
        fprintf(stderr, "plots written to %s/plots\n", out_dir);
    }
    if (rc == 0 && !quiet) {
        fprintf(stderr,
                "reproduce: %d runs, %d failed, %.1f s wall (runs %.1f s); report "
                "%s/report.md\n",
                n, failures, rep_now() - t0, wall, out_dir);
    }
    sim_batch_free(cases, REP_MAX_CASES);
    return (failures || rc != 0) ? 1 : 0;
}
