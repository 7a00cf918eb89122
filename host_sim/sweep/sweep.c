/* `sixphase-sim sweep`, see sweep.h. */
#define _DEFAULT_SOURCE /* fork, mkdir */

#include "sweep.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli.h"
#include "report/plots.h"
#include "run/batch.h"
#include "sweep_grid.h"
#include "sweep_points.h"
#include "sweep_table.h"

typedef struct {
    const sweep_grid_t *grid;
    const char *binary_id;
    double t0;   /* wall clock at the start, for the time left */
    int unsaved; /* points whose file could not be written */
} sweep_progress_t;

static double sweep_now(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void sweep_done(void *ctx, const sim_case_t *c, int done, int total)
{
    sweep_progress_t *pr = (sweep_progress_t *)ctx;
    const long p = strtol(c->name + 1, NULL, 10);
    char err[1400];
    if (sweep_point_save(pr->grid, pr->binary_id, p, c, err, sizeof err) != 0) {
        fprintf(stderr, "%ssixphase-sim: %s\n", isatty(2) ? "\n" : "", err);
        pr->unsaved++;
    }
    if (!pr->grid->quiet && isatty(2)) {
        const double el = sweep_now() - pr->t0;
        fprintf(stderr, "\rsweep: %d of %d points run (%.0f %%), about %.0f s left   ", done, total,
                100.0 * done / total, el / done * (total - done));
        if (done == total) {
            fprintf(stderr, "\n");
        }
    }
}

/* Every point checked as `run` checks it; 0, or the exit status after a one-line error. */
static int sweep_configure(const sweep_grid_t *g, long points, sim_case_t *cases)
{
    char *args[SWEEP_MAX_ARGS + 2 * SWEEP_MAX_AXES];
    long p;
    for (p = 0; p < points; p++) {
        char err[256] = "", text[4096];
        sim_cli_t cli;
        const int n = sweep_grid_args(g, p, args);
        if (sim_cli_parse_run(n, args, &cli, err, sizeof err) != 0) {
            sweep_point_args_text(g, p, text, sizeof text);
            fprintf(stderr, "sixphase-sim: sweep point %ld (%s): %s\n", p, text, err);
            return 2;
        }
        cases[p].cfg = cli.cfg;
        cases[p].cfg.out_dir = NULL;
        (void)snprintf(cases[p].name, sizeof cases[p].name, "p%04ld", p);
    }
    return 0;
}

/* Runs the points no earlier sweep of this binary finished; returns how many failed or could
 * not be saved. */
static int sweep_run_missing(const sweep_grid_t *g, long points, sim_case_t *cases, long *resumed)
{
    sim_case_t *run;
    sweep_progress_t pr;
    char binary_id[SWEEP_BINARY_ID_LEN];
    long p;
    int n = 0, k, failed;
    sweep_binary_id(binary_id);
    for (p = 0; p < points; p++) {
        cases[p].ok = sweep_point_done(g, binary_id, p);
        n += cases[p].ok ? 0 : 1;
    }
    *resumed = points - n;
    run = (n > 0) ? sim_batch_alloc(n) : NULL;
    if (n > 0 && !run) {
        return n;
    }
    for (p = 0, k = 0; p < points; p++) {
        if (!cases[p].ok) {
            run[k++] = cases[p];
        }
    }
    pr.grid = g;
    pr.binary_id = binary_id;
    pr.t0 = sweep_now();
    pr.unsaved = 0;
    failed = (n > 0) ? sim_batch_run(run, 0, n, g->jobs, sweep_done, &pr) : 0;
    sim_batch_free(run, n);
    return failed + pr.unsaved;
}

/* The grid, its size and the output directory; 0, or the exit status. */
static int sweep_prepare(int argc, char **argv, sweep_grid_t *g, long *points)
{
    char err[1400] = "";
    if (sweep_grid_parse(argc, argv, g, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 2;
    }
    *points = sweep_grid_points(g);
    if (*points > SWEEP_MAX_POINTS && !g->force) {
        fprintf(stderr, "sixphase-sim: %ld points is above %d: narrow the grid or add --force\n",
                *points, SWEEP_MAX_POINTS);
        return 2;
    }
    if (sim_check_out_dir(g->out, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 1;
    }
    if (sweep_points_prepare(g, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 1;
    }
    return 0;
}

static void sweep_print_summary(const sweep_grid_t *g, long points, long resumed,
                                const sweep_summary_t *sum)
{
    fprintf(stderr, "sweep: %ld points (%ld from an earlier run, %d worker processes): %ld ok, ",
            points, resumed, g->jobs, sum->ok);
    if (sum->faulted > 0) {
        fprintf(stderr, "%ld stopped by a drive fault (%s), ", sum->faulted, sum->faults);
    } else {
        fprintf(stderr, "0 stopped by a drive fault, ");
    }
    fprintf(stderr, "%ld failed; %s/sweep.csv\n", sum->failed, g->out);
}

int sim_sweep_main(int argc, char **argv)
{
    sweep_grid_t g;
    sweep_summary_t sum;
    sim_case_t *cases;
    long points = 0, resumed = 0;
    int rc = sweep_prepare(argc, argv, &g, &points);
    if (rc != 0) {
        return rc;
    }
    cases = (sim_case_t *)calloc((size_t)points, sizeof *cases);
    if (!cases) {
        fprintf(stderr, "sixphase-sim: out of memory\n");
        return 1;
    }
    rc = sweep_configure(&g, points, cases);
    if (rc == 0) {
        (void)sweep_run_missing(&g, points, cases, &resumed);
        if (sweep_table_write(&g, points, sweep_point_read, &sum) != 0) {
            fprintf(stderr, "sixphase-sim: cannot write the tables in '%s'\n", g.out);
            rc = 1;
        } else {
            if (!g.quiet) {
                sweep_print_summary(&g, points, resumed, &sum);
            }
            if (!g.no_plots && sum.ok + sum.faulted > 0 && sim_plot(SIM_PLOT_SWEEP, g.out) != 0) {
                rc = 1;
            }
            rc = (rc == 0 && sum.failed > 0) ? 1 : rc;
        }
    }
    free(cases);
    return rc;
}
