/* Reading sixphase-sim trace.csv files into benchmark operating points. */
#ifndef TRACE_CSV_H
#define TRACE_CSV_H

#include <stddef.h>

#include "bench.h"

/* Appends the trace's rows to points[have..capacity); returns the new count, or -1 after a
 * one-line message on stderr prefixed with the tool's name. */
long trace_csv_read(const char *path, bench_point_t *points, size_t have, size_t capacity,
                    double vdc, const char *tool);

#endif /* TRACE_CSV_H */
