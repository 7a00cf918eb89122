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

#include "batch.h"
#include "cli.h"
#include "plots.h"
#include "sweep_grid.h"

/* The metrics of a row, one list: X(field of sim_result_t, null when negative). */
#define SWEEP_METRICS(X)                                                                           \
    X(thd_percent, 1)                                                                              \
    X(thd50_percent, 1)                                                                            \
    X(torque_ripple_nm, 0)                                                                         \
    X(torque_ripple_pp_nm, 0)                                                                      \
    X(torque_mean_nm, 0)                                                                           \
    X(speed_mean_rpm, 0)                                                                           \
    X(xy_current_rms_a, 0)                                                                         \
    X(switching_freq_hz, 0)                                                                        \
    X(phase_current_peak_a, 0)                                                                     \
    X(transient_ms, 1)

typedef struct {
    const sweep_grid_t *grid;
    double t0; /* wall clock at the start, for the time left */
} sweep_progress_t;

static double sweep_now(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void sweep_point_args_text(const sweep_grid_t *g, long p, char *out, size_t len)
{
    char *args[SWEEP_MAX_ARGS + 2 * SWEEP_MAX_AXES];
    const int n = sweep_grid_args(g, p, args);
    size_t used = 0;
    int k;
    out[0] = '\0';
    for (k = 0; k < n && used < len; k++) {
        used += (size_t)snprintf(out + used, len - used, "%s%s", k ? " " : "", args[k]);
    }
}

static void sweep_point_path(const sweep_grid_t *g, long p, char *out, size_t len)
{
    (void)snprintf(out, len, "%s/points/p%04ld.txt", g->out, p);
}

/* The finished point's arguments and metrics, so a rerun can skip it. */
static void sweep_save_point(const sweep_grid_t *g, long p, const sim_case_t *c)
{
    char path[1200], args[4096];
    FILE *f;
    sweep_point_path(g, p, path, sizeof path);
    sweep_point_args_text(g, p, args, sizeof args);
    f = fopen(path, "w");
    if (!f) {
        return;
    }
    fprintf(f, "%s\n%d %d", args, c->ok, c->res.fault);
#define SWEEP_SAVE(field, null_if_negative) fprintf(f, " %.17g", c->res.field);
    SWEEP_METRICS(SWEEP_SAVE)
#undef SWEEP_SAVE
    fprintf(f, "\n");
    (void)fclose(f);
}

/* 1 when the point was finished by an earlier run with the same arguments (metrics loaded). */
static int sweep_load_point(const sweep_grid_t *g, long p, sim_case_t *c)
{
    char path[1200], args[4096], line[4096];
    FILE *f;
    int ok = 0;
    sweep_point_path(g, p, path, sizeof path);
    sweep_point_args_text(g, p, args, sizeof args);
    f = fopen(path, "r");
    if (!f) {
        return 0;
    }
    if (fgets(line, sizeof line, f) && strncmp(line, args, strlen(args)) == 0 &&
        line[strlen(args)] == '\n' && fscanf(f, "%d %d", &c->ok, &c->res.fault) == 2 &&
        c->ok) { /* a point that failed runs again */
        ok = 1;
#define SWEEP_LOAD(field, null_if_negative) ok = ok && fscanf(f, "%lf", &c->res.field) == 1;
        SWEEP_METRICS(SWEEP_LOAD)
#undef SWEEP_LOAD
    }
    (void)fclose(f);
    return ok;
}

static void sweep_done(void *ctx, const sim_case_t *c, int done, int total)
{
    sweep_progress_t *pr = (sweep_progress_t *)ctx;
    const long p = strtol(c->name + 1, NULL, 10);
    sweep_save_point(pr->grid, p, c);
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

/* Runs the points no earlier sweep finished; returns how many failed. */
static int sweep_run_missing(const sweep_grid_t *g, long points, sim_case_t *cases, long *resumed)
{
    sim_case_t *run;
    sweep_progress_t pr;
    long p;
    int n = 0, k, failed;
    *resumed = 0;
    for (p = 0; p < points; p++) {
        if (sweep_load_point(g, p, &cases[p])) {
            (*resumed)++;
        } else {
            n++;
        }
    }
    run = (n > 0) ? sim_batch_alloc(n) : NULL;
    if (n > 0 && !run) {
        return n;
    }
    for (p = 0, k = 0; p < points; p++) {
        if (!sweep_load_point(g, p, &cases[p])) {
            run[k++] = cases[p];
        }
    }
    pr.grid = g;
    pr.t0 = sweep_now();
    failed = (n > 0) ? sim_batch_run(run, 0, n, g->jobs, sweep_done, &pr) : 0;
    for (k = 0; k < n; k++) {
        cases[strtol(run[k].name + 1, NULL, 10)] = run[k];
    }
    sim_batch_free(run, n);
    return failed;
}

static void sweep_write_value(FILE *f, double v, int null_if_negative, int json)
{
    if (!(v == v) || (null_if_negative && v < 0.0)) {
        fprintf(f, json ? "null" : "");
    } else {
        fprintf(f, "%.6g", v);
    }
}

static void sweep_row(FILE *f, const sweep_grid_t *g, long p, const sim_case_t *c, int json)
{
    int index[SWEEP_MAX_AXES];
    int k;
    sweep_grid_point(g, p, index);
    fprintf(f, json ? "  {\"point\": %ld" : "%ld", p);
    for (k = 0; k < g->n_axes; k++) {
        const char *v = g->axis[k].value[index[k]];
        char *end = NULL;
        const double x = strtod(v, &end);
        if (json && end != v && *end == '\0') {
            fprintf(f, ", \"%s\": %.17g", g->axis[k].option + 2, x);
        } else if (json) {
            fprintf(f, ", \"%s\": \"%s\"", g->axis[k].option + 2, v);
        } else {
            fprintf(f, ",%s", v);
        }
    }
#define SWEEP_COLUMN(field, null_if_negative)                                                      \
    fprintf(f, json ? ", \"" #field "\": " : ",");                                                 \
    sweep_write_value(f, c->res.field, null_if_negative, json);
    SWEEP_METRICS(SWEEP_COLUMN)
#undef SWEEP_COLUMN
    if (json) {
        fprintf(f, ", \"drive_fault\": %d, \"ok\": %s}", c->res.fault, c->ok ? "true" : "false");
    } else {
        fprintf(f, ",%d,%d", c->res.fault, c->ok);
    }
}

static int sweep_write_tables(const sweep_grid_t *g, long points, const sim_case_t *cases)
{
    char path[1200];
    FILE *csv, *json;
    long p;
    int k, rc;
    (void)snprintf(path, sizeof path, "%s/sweep.csv", g->out);
    csv = fopen(path, "w");
    (void)snprintf(path, sizeof path, "%s/sweep.json", g->out);
    json = fopen(path, "w");
    if (!csv || !json) {
        if (csv) {
            (void)fclose(csv);
        }
        if (json) {
            (void)fclose(json);
        }
        return -1;
    }
    fprintf(csv, "point");
    for (k = 0; k < g->n_axes; k++) {
        fprintf(csv, ",%s", g->axis[k].option + 2);
    }
#define SWEEP_HEADER(field, null_if_negative) fprintf(csv, "," #field);
    SWEEP_METRICS(SWEEP_HEADER)
#undef SWEEP_HEADER
    fprintf(csv, ",drive_fault,ok\n");
    fprintf(json, "[\n");
    for (p = 0; p < points; p++) {
        sweep_row(csv, g, p, &cases[p], 0);
        fprintf(csv, "\n");
        sweep_row(json, g, p, &cases[p], 1);
        fprintf(json, "%s\n", (p + 1 < points) ? "," : "");
    }
    fprintf(json, "]\n");
    rc = (fclose(csv) == 0) ? 0 : -1;
    return (fclose(json) == 0) ? rc : -1;
}

/* The grid, its size and the output directory; 0, or the exit status. */
static int sweep_prepare(int argc, char **argv, sweep_grid_t *g, long *points)
{
    char err[1400] = "", dir[1300];
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
    (void)snprintf(dir, sizeof dir, "%s/points", g->out);
    (void)mkdir(dir, 0777);
    return 0;
}

int sim_sweep_main(int argc, char **argv)
{
    sweep_grid_t g;
    sim_case_t *cases;
    long points = 0, resumed = 0;
    int rc = sweep_prepare(argc, argv, &g, &points), failed;
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
        failed = sweep_run_missing(&g, points, cases, &resumed);
        if (sweep_write_tables(&g, points, cases) != 0) {
            fprintf(stderr, "sixphase-sim: cannot write the tables in '%s'\n", g.out);
            rc = 1;
        } else if (!g.no_plots && sim_plot(SIM_PLOT_SWEEP, g.out) != 0) {
            rc = 1;
        }
        if (!g.quiet) {
            fprintf(stderr,
                    "sweep: %ld points (%ld from an earlier run), %d failed; %s/sweep.csv\n",
                    points, resumed, failed, g.out);
        }
        rc = (rc == 0 && failed > 0) ? 1 : rc;
    }
    free(cases);
    return rc;
}
