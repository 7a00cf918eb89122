/*
 * One simulation run: plant + inverter + simulator HAL around the firmware's
 * drive ISR, a paper scenario, metrics (brief §7) and output files.
 */
#ifndef SIM_SIM_H
#define SIM_SIM_H

#include <stddef.h>
#include <stdio.h>

#include "sim_config.h"

/* Run; 0 on success, else non-zero with a one-line message in err. */
int sim_run(const sim_config_t *c, sim_result_t *r, char *err, size_t err_len);

/* Write metrics.json for a result (with parameters) to path. 0 on success. */
int sim_write_metrics_json(const char *path, const sim_config_t *c, const sim_result_t *r);

/* The same JSON to an open stream. */
void sim_print_metrics_json(FILE *f, const sim_config_t *c, const sim_result_t *r);
/* The same without the host timings (realtime_factor, wall_s, isr_mean_us): what depends only
 * on the binary and the configuration (a sweep's table). */
void sim_print_metrics_json_no_timings(FILE *f, const sim_config_t *c, const sim_result_t *r);

/* mkdir -p; 0 on success. */
int sim_make_dirs(const char *path);
/* Creates dir and proves a file can be written in it; else non-zero with a one-line message.
 * Called before any simulation, so a bad --out costs nothing. */
int sim_check_out_dir(const char *dir, char *err, size_t err_len);

#endif /* SIM_SIM_H */
