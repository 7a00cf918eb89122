/* sixphase-sim: host plant simulator front end: run, reproduce, sweep, serve, plot. */
#define _POSIX_C_SOURCE 200809L /* isatty, clock_gettime */

#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli.h"
#include "report/plots.h"
#include "report/reproduce.h"
#include "run/scenario.h"
#include "run/serve.h"
#include "run/sim.h"
#include "sweep/sweep.h"

/* A long run's progress on a terminal (the run's observer, every 1,000 periods). */
typedef struct {
    double total_s, wall0, last_print;
    long periods;
} run_progress_t;

static double wall_now(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void run_progress(void *ctx, const sim_trace_row_t *row, const sim_period_input_t *in)
{
    run_progress_t *p = (run_progress_t *)ctx;
    double now, done;
    (void)in;
    if (++p->periods % 1000 != 0) {
        return;
    }
    now = wall_now();
    done = row->t / p->total_s;
    if (now - p->wall0 > 2.0 && now - p->last_print > 0.5 && done > 0.0) {
        fprintf(stderr, "\rrun: %.0f %% of %.4g s simulated, about %.0f s left   ", 100.0 * done,
                p->total_s, (now - p->wall0) / done * (1.0 - done));
        p->last_print = now;
    }
}

static int cmd_run(int argc, char **argv)
{
    char err[256] = "";
    sim_cli_t cli;
    sim_result_t res;
    run_progress_t prog = {0.0, 0.0, 0.0, 0};
    sim_observer_t obs = {&prog, run_progress, NULL};
    sim_plan_t plan;
    int rc;
    if (sim_cli_parse_run(argc, argv, &cli, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 2;
    }
    if (!cli.quiet && isatty(2)) {
        sim_plan(&cli.cfg, &plan);
        prog.total_s = plan.duration;
        prog.wall0 = wall_now();
        cli.cfg.observer = &obs;
    }
    rc = sim_run(&cli.cfg, &res, err, sizeof err);
    if (prog.last_print > 0.0) {
        fprintf(stderr, "\n");
    }
    if (rc != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 1;
    }
    if (!cli.quiet) {
        sim_print_metrics_json(stdout, &cli.cfg, &res);
    }
    if (cli.plot && sim_plot(SIM_PLOT_RUN, cli.cfg.out_dir) != 0) {
        return 1;
    }
    return (cli.plot && res.pil.on && sim_plot(SIM_PLOT_PIL, cli.cfg.out_dir) != 0) ? 1 : 0;
}

static int cmd_serve(int argc, char **argv)
{
    char err[256] = "";
    sim_cli_t cli;
    sim_serve_options_t so;
    if (sim_cli_parse_serve(argc, argv, &cli, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 2;
    }
    so.rate = cli.serve_rate;
    so.fast = cli.serve_fast != 0;
    so.baud = cli.serve_baud;
    so.quiet = cli.quiet != 0;
    return sim_serve(&cli.cfg, &so);
}

static int cmd_reproduce(int argc, char **argv)
{
    char err[256] = "";
    sim_cli_t cli;
    if (sim_cli_parse_reproduce(argc, argv, &cli, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 2;
    }
    return sim_reproduce(cli.cfg.out_dir, cli.jobs, !cli.no_plots, cli.quiet);
}

/* plot DIR: the figure of an earlier `run --out DIR`. */
static int cmd_plot(int argc, char **argv)
{
    char trace[1200];
    if (argc != 1 || argv[0][0] == '-') {
        fprintf(stderr, "sixphase-sim: usage: sixphase-sim plot DIR (a run's --out directory)\n");
        return 2;
    }
    (void)snprintf(trace, sizeof trace, "%s/trace.csv", argv[0]);
    if (access(trace, R_OK) != 0) {
        fprintf(stderr,
                "sixphase-sim: no trace.csv in '%s' (plot takes the --out directory of a run "
                "without --no-trace)\n",
                argv[0]);
        return 1;
    }
    return (sim_plot(SIM_PLOT_RUN, argv[0]) == 0) ? 0 : 1;
}

/* COMMAND --help, help COMMAND: that command's usage (exit 0), or a one-line error. */
static int cli_command_help(const char *command)
{
    if (sim_cli_command_usage(stdout, command) != 0) {
        fprintf(stderr, "sixphase-sim: no command '%s' (run, reproduce, sweep, serve or plot)\n",
                command);
        return 2;
    }
    return 0;
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        int (*fn)(int argc, char **argv);
    } commands[] = {{"run", cmd_run},
                    {"reproduce", cmd_reproduce},
                    {"sweep", sim_sweep_main},
                    {"serve", cmd_serve},
                    {"plot", cmd_plot}};
    size_t k;
    if (argc < 2) {
        sim_cli_usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "help") == 0 || strcmp(argv[1], "--help") == 0 ||
        strcmp(argv[1], "-h") == 0) {
        return (argc == 3) ? cli_command_help(argv[2]) : (sim_cli_usage(stdout), 0);
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("sixphase-sim %s\n", SIXPHASE_VERSION);
        return 0;
    }
    for (k = 0; k < sizeof commands / sizeof commands[0]; k++) {
        if (strcmp(argv[1], commands[k].name) == 0) {
            if (argc == 3 && (strcmp(argv[2], "--help") == 0 || strcmp(argv[2], "-h") == 0)) {
                return cli_command_help(argv[1]);
            }
            return commands[k].fn(argc - 2, argv + 2);
        }
    }
    fprintf(stderr,
            "sixphase-sim: unknown command '%s' (expected run, reproduce, sweep, serve or plot)\n",
            argv[1]);
    return 2;
}
