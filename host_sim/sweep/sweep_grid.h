/* The grid of `sixphase-sim sweep` (sweep.h): its own options and the swept axes. */
#ifndef SIM_SWEEP_GRID_H
#define SIM_SWEEP_GRID_H

#include <stddef.h>

/* A grid's limits: swept options, values of one, run arguments */
#define SWEEP_MAX_AXES 4
#define SWEEP_MAX_VALUES 256
#define SWEEP_MAX_ARGS 96

typedef struct {
    char option[32];
    int n;
    char value[SWEEP_MAX_VALUES][32];
} sweep_axis_t;

typedef struct {
    const char *out;
    int jobs, force, no_plots, quiet;
    int n_axes;
    sweep_axis_t axis[SWEEP_MAX_AXES];
    int n_fixed; /* the run options every point shares, a flag's value NULL */
    const char *fixed_option[SWEEP_MAX_ARGS / 2];
    const char *fixed_value[SWEEP_MAX_ARGS / 2];
} sweep_grid_t;

/* 0, or -1 with a one-line message (bad range or list, missing --out, nothing swept). Without
 * --scenario every point runs the steady scenario (`--scenario steady` is added); --jobs
 * defaults to the number of online processors (at least 1, at most 64). */
int sweep_grid_parse(int argc, char **argv, sweep_grid_t *g, char *err, size_t len);

long sweep_grid_points(const sweep_grid_t *g);

/* Point p's value index on each axis (the first axis varies slowest). */
void sweep_grid_point(const sweep_grid_t *g, long p, int index[SWEEP_MAX_AXES]);

/* Point p's run arguments into args (room for SWEEP_MAX_ARGS + 2 * SWEEP_MAX_AXES); returns
 * their count. */
int sweep_grid_args(const sweep_grid_t *g, long p, char **args);

#endif /* SIM_SWEEP_GRID_H */
