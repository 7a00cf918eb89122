/*
 * A sweep's point files (sweep.h): DIR/points/KEY.txt holds what one finished point left, KEY
 * the 64-bit FNV-1a hash (16 hex digits) of the point's run arguments as one line of text, so
 * a file belongs to the content of its options, not to a position in the grid:
 *
 *   line 1   sixphase-sim <binary id>        the executable that ran it
 *   line 2   <the point's run arguments>     (the text KEY is the hash of)
 *   line 3   ok | failed <one-line error>
 *   then     the run's metrics.json without the host timings (ok only)
 *
 * A file is written whole or not at all: into KEY.tmp in the same folder, then renamed. A
 * rerun takes a point as done only when its file's first two lines match it exactly, it ran
 * ok and its JSON parses whole (one object, nothing but white space after it), so a rebuilt
 * binary, other arguments, a failed run or a file cut anywhere run the point again.
 */
#ifndef SIM_SWEEP_POINTS_H
#define SIM_SWEEP_POINTS_H

#include <stddef.h>

#include "run/batch.h"
#include "sweep_grid.h"

#define SWEEP_BINARY_ID_LEN 32

/* The running executable's id: a 64-bit FNV-1a hash of its file, in hex; "" when it cannot
 * be read (then no point counts as done). */
void sweep_binary_id(char out[SWEEP_BINARY_ID_LEN]);

/* Point p's run arguments as one line of text. */
void sweep_point_args_text(const sweep_grid_t *g, long p, char *out, size_t len);

/* DIR/points made if missing and checked writable; 0, or -1 with a one-line message
 * ("cannot write DIR/points/: Permission denied"). */
int sweep_points_prepare(const sweep_grid_t *g, char *err, size_t len);

/* Writes point p's file from its finished case (ok or failed); 0, or -1 with a one-line
 * message naming the file and the system's reason. */
int sweep_point_save(const sweep_grid_t *g, const char *binary_id, long p, const sim_case_t *c,
                     char *err, size_t len);

/* 1 when point p's file holds a whole ok run of this binary with these arguments. */
int sweep_point_done(const sweep_grid_t *g, const char *binary_id, long p);

/* Point p's outcome from its file: 1 ok (*json: its whole metrics.json, malloc'd, for the
 * caller to free), 0 failed, missing, unreadable or damaged (err: why, one line). */
int sweep_point_read(const sweep_grid_t *g, long p, char **json, char *err, size_t len);

#endif /* SIM_SWEEP_POINTS_H */
