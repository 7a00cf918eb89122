/*
 * A sweep's point files (sweep.h): DIR/points/pNNNN.txt holds what one finished point left,
 *
 *   line 1   sixphase-sim <binary id>        the executable that ran it
 *   line 2   <the point's run arguments>
 *   line 3   ok | failed <one-line error>
 *   then     the run's metrics.json without the host timings (ok only)
 *
 * A rerun takes a point as done only when the first two lines match it exactly and it ran
 * ok, so a rebuilt binary, other arguments or a failed run run the point again.
 */
#ifndef SIM_SWEEP_POINTS_H
#define SIM_SWEEP_POINTS_H

#include <stddef.h>

#include "batch.h"
#include "sweep_grid.h"

#define SWEEP_BINARY_ID_LEN 32

/* The running executable's id: a 64-bit FNV-1a hash of its file, in hex; "" when it cannot
 * be read (then no point counts as done). */
void sweep_binary_id(char out[SWEEP_BINARY_ID_LEN]);

/* Point p's run arguments as one line of text. */
void sweep_point_args_text(const sweep_grid_t *g, long p, char *out, size_t len);

/* Writes point p's file from its finished case (ok or failed). */
void sweep_point_save(const sweep_grid_t *g, const char *binary_id, long p, const sim_case_t *c);

/* 1 when point p's file holds an ok run of this binary with these arguments. */
int sweep_point_done(const sweep_grid_t *g, const char *binary_id, long p);

/* Point p's outcome from its file: 1 ok (*json: its metrics.json, malloc'd, for the caller to
 * free), 0 failed or missing (err: why, one line). */
int sweep_point_read(const sweep_grid_t *g, long p, char **json, char *err, size_t len);

#endif /* SIM_SWEEP_POINTS_H */
