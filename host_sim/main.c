/* sixphase-sim: host plant simulator front end (issue 3). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "reproduce.h"
#include "serve.h"
#include "sim.h"

int main(int argc, char **argv)
{
    char err[256];
    sim_cli_t cli;
    sim_result_t res;
    err[0] = '\0';
    if (argc < 2) {
        sim_cli_usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "help") == 0 || strcmp(argv[1], "--help") == 0 ||
        strcmp(argv[1], "-h") == 0) {
        sim_cli_usage(stdout);
        return 0;
    }
    if (strcmp(argv[1], "run") == 0) {
        if (sim_cli_parse_run(argc - 2, argv + 2, &cli, err, sizeof err) != 0) {
            fprintf(stderr, "sixphase-sim: %s\n", err);
            return 2;
        }
        if (sim_run(&cli.cfg, &res, err, sizeof err) != 0) {
            fprintf(stderr, "sixphase-sim: %s\n", err);
            return 1;
        }
        if (!cli.quiet) {
            sim_print_metrics_json(stdout, &cli.cfg, &res);
        }
        return 0;
    }
    if (strcmp(argv[1], "reproduce") == 0) {
        if (sim_cli_parse_reproduce(argc - 2, argv + 2, &cli, err, sizeof err) != 0) {
            fprintf(stderr, "sixphase-sim: %s\n", err);
            return 2;
        }
        return sim_reproduce(cli.cfg.out_dir, cli.jobs, !cli.no_plots, cli.quiet);
    }
    if (strcmp(argv[1], "serve") == 0) {
        sim_serve_options_t so;
        if (sim_cli_parse_serve(argc - 2, argv + 2, &cli, err, sizeof err) != 0) {
            fprintf(stderr, "sixphase-sim: %s\n", err);
            return 2;
        }
        so.rate = cli.serve_rate;
        so.fast = cli.serve_fast != 0;
        so.baud = cli.serve_baud;
        so.quiet = cli.quiet != 0;
        return sim_serve(&cli.cfg, &so);
    }
    fprintf(stderr, "sixphase-sim: unknown command '%s' (expected run, reproduce or serve)\n",
            argv[1]);
    return 2;
}
