/*
 * A sweep's table (sweep.h): DIR/sweep.csv and DIR/sweep.json, one row per point, built from
 * the point files (sweep_points.h). Columns, in order:
 *
 *   point          the point's number
 *   --OPTION ...   every run option given to the sweep, the swept ones first, as given
 *                  (a flag: true)
 *   outcome        ok; fault (the drive stopped in a fault: its metrics describe a stopped
 *                  drive, the plots leave the point out); failed (the run did not finish)
 *   error          why a run failed (empty otherwise)
 *   the rest       the run's metrics.json without the host timings, flattened: a nested
 *                  object's fields as OBJECT_FIELD, an array's elements (per phase) as
 *                  NAME_A .. NAME_F
 *
 * In the CSV null is empty and true / false are 1 / 0; a column a row lacks (a fault record
 * only a faulted run has, say) is empty there (null in the JSON).
 */
#ifndef SIM_SWEEP_TABLE_H
#define SIM_SWEEP_TABLE_H

#include "sweep_grid.h"

typedef struct {
    long ok, faulted, failed;
    char faults[256]; /* the faults that stopped points, with their counts: "OVERCURRENT 30" */
} sweep_summary_t;

/* 1 when json is one whole metrics object the table can flatten (nothing but white space
 * after it), 0 when it is cut short or malformed. */
int sweep_table_metrics_whole(const char *json);

/* Point p's outcome as sweep_point_read gives it: 1 ok (*json: its whole metrics.json, malloc'd,
 * for the caller to free), 0 not (err: why, one line). */
typedef int (*sweep_table_read_fn)(const sweep_grid_t *g, long p, char **json, char *err,
                                   size_t len);

/* Writes both tables from the points' outcomes (read); 0, or -1 when they cannot be written. */
int sweep_table_write(const sweep_grid_t *g, long points, sweep_table_read_fn read,
                      sweep_summary_t *sum);

#endif /* SIM_SWEEP_TABLE_H */
