/*
 * Command-line parsing of `sixphase-sim run` (and the options `reproduce`
 * shares). No side effects: on a bad argument it returns non-zero with a
 * one-line message naming the bad value.
 */
#ifndef SIM_CLI_H
#define SIM_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "run/sim.h"

typedef struct {
    sim_config_t cfg;
    int quiet;
    int jobs;     /* reproduce: parallel workers */
    int no_plots; /* reproduce: leave the figures out */
    int plot;     /* run: draw DIR/run.png from the trace (needs --out) */
    /* serve: pacing (rate times real time; fast: as fast as possible) and the line's baud */
    double serve_rate;
    int serve_fast;
    int serve_baud;
    /* encoder offsets in electrical degrees (into cfg.plant / cfg.ctl in radians) */
    double encoder_offset_deg, ctl_encoder_offset_deg;
    const char *ctl_params_path; /* --ctl-params FILE (into cfg.ctl), NULL: none */
} sim_cli_t;

/* argv[0] is the first option (after the sub-command). 0 on success. */
int sim_cli_parse_run(int argc, char **argv, sim_cli_t *out, char *err, size_t err_len);
int sim_cli_parse_reproduce(int argc, char **argv, sim_cli_t *out, char *err, size_t err_len);
/* A run option's name: 1 when it takes a value a sweep may grid (numbers and choices), 0 for
 * the others, -1 when it is not a run option. */
int sim_cli_gridable(const char *name);

/* serve takes the run options (none required) and its own. */
int sim_cli_parse_serve(int argc, char **argv, sim_cli_t *out, char *err, size_t err_len);

/* The whole usage (every command and option), and one command's (0; -1: no such command). */
void sim_cli_usage(FILE *f);
int sim_cli_command_usage(FILE *f, const char *command);

/* The option table's entries (test_sim_cli: each is in the usage text). */
int sim_cli_option_count(void);
const char *sim_cli_option_name(int k); /* NULL out of range */

#endif /* SIM_CLI_H */
