/* The sweep's grid: its own options, the swept axes and every point's run arguments. */
#define _DEFAULT_SOURCE /* sysconf(_SC_NPROCESSORS_ONLN) */

#include "sweep_grid.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "decimal_arg.h"

static int grid_fail(char *err, size_t len, const char *fmt, const char *a, const char *b)
{
    (void)snprintf(err, len, fmt, a, b);
    return -1;
}

/* start:stop:step into values (as text, %g); the count is checked against the cap. */
static int grid_range(sweep_axis_t *ax, const char *v, char *err, size_t len)
{
    char *e1 = NULL, *e2 = NULL, *e3 = NULL;
    const double a = strtod(v, &e1);
    const double b = (*e1 == ':') ? strtod(e1 + 1, &e2) : 0.0;
    const double s = (e2 && *e2 == ':') ? strtod(e2 + 1, &e3) : 0.0;
    double n;
    int k;
    if (!e3 || *e3 != '\0' || !isfinite(a) || !isfinite(b) || !(s > 0.0) || b < a) {
        return grid_fail(err, len,
                         "bad range for %s: '%s' (start:stop:step, step > 0, stop >= start)",
                         ax->option, v);
    }
    n = floor((b - a) / s + 1e-9) + 1.0;
    if (n > SWEEP_MAX_VALUES) {
        return grid_fail(err, len, "range for %s has too many values: '%s'", ax->option, v);
    }
    for (k = 0; k < (int)n; k++) {
        (void)snprintf(ax->value[k], sizeof ax->value[k], "%.10g", a + s * k);
    }
    ax->n = (int)n;
    return 0;
}

static int grid_list(sweep_axis_t *ax, const char *v, char *err, size_t len)
{
    const char *p = v;
    ax->n = 0;
    for (;;) {
        const char *c = strchr(p, ',');
        const size_t l = c ? (size_t)(c - p) : strlen(p);
        if (l == 0 || l >= sizeof ax->value[0] || ax->n == SWEEP_MAX_VALUES) {
            return grid_fail(err, len, "bad list for %s: '%s'", ax->option, v);
        }
        memcpy(ax->value[ax->n], p, l);
        ax->value[ax->n][l] = '\0';
        ax->n++;
        if (!c) {
            return 0;
        }
        p = c + 1;
    }
}

/* One run option (val NULL for a flag): an axis when its value is a list or a range, else
 * passed on to every point as it is. */
static int grid_option(sweep_grid_t *g, const char *opt, const char *val, char *err, size_t len)
{
    if (val && (strchr(val, ',') || strchr(val, ':'))) {
        sweep_axis_t *ax;
        if (g->n_axes == SWEEP_MAX_AXES) {
            return grid_fail(err, len, "at most 4 swept options (%s%s)", opt, "");
        }
        ax = &g->axis[g->n_axes++];
        (void)snprintf(ax->option, sizeof ax->option, "%s", opt);
        return strchr(val, ':') ? grid_range(ax, val, err, len) : grid_list(ax, val, err, len);
    }
    if (g->n_fixed == SWEEP_MAX_ARGS / 2) {
        return grid_fail(err, len, "too many options%s%s", "", "");
    }
    g->fixed_option[g->n_fixed] = opt;
    g->fixed_value[g->n_fixed++] = val;
    return 0;
}

/* The sweep's own flags, by name (issue 26: they were told apart by a character's index). */
static const struct {
    const char *name;
    size_t field; /* an int of sweep_grid_t set to 1 */
} grid_flags[] = {{"--force", offsetof(sweep_grid_t, force)},
                  {"--no-plots", offsetof(sweep_grid_t, no_plots)},
                  {"--quiet", offsetof(sweep_grid_t, quiet)}};

/* The sweep's own options, consumed here; 1 when argv[i] was one (value in *used). */
static int grid_own(sweep_grid_t *g, int argc, char **argv, int i, int *used, char *err, size_t len)
{
    const char *a = argv[i];
    double jobs;
    size_t k;
    *used = 1;
    for (k = 0; k < sizeof grid_flags / sizeof grid_flags[0]; k++) {
        if (strcmp(a, grid_flags[k].name) == 0) {
            *(int *)(void *)((char *)g + grid_flags[k].field) = 1;
            return 1;
        }
    }
    if (strcmp(a, "--plot") == 0) {
        (void)grid_fail(err, len,
                        "--plot is for run: a sweep draws DIR/plots/ (--no-plots "
                        "leaves them out)%s%s",
                        "", "");
        return -1;
    }
    if (strcmp(a, "--out") != 0 && strcmp(a, "--jobs") != 0) {
        return 0;
    }
    if (i + 1 >= argc) {
        (void)grid_fail(err, len, "%s needs a value%s", a, "");
        return -1;
    }
    *used = 2;
    if (strcmp(a, "--out") == 0) {
        g->out = argv[i + 1];
    } else if (decimal_parse(argv[i + 1], 1, 1.0, 64.0, &jobs) != 0) {
        (void)grid_fail(err, len, "bad value for --jobs: '%s' (an integer in 1..64)%s", argv[i + 1],
                        "");
        return -1;
    } else {
        g->jobs = (int)jobs;
    }
    return 1;
}

/* The number of online processors, 1..64. */
static int grid_default_jobs(void)
{
    const long n = sysconf(_SC_NPROCESSORS_ONLN);
    return (n < 1) ? 1 : ((n > 64) ? 64 : (int)n);
}

/* Whether a swept or shared option is opt. */
static int grid_has(const sweep_grid_t *g, const char *opt)
{
    int k;
    for (k = 0; k < g->n_axes; k++) {
        if (strcmp(g->axis[k].option, opt) == 0) {
            return 1;
        }
    }
    for (k = 0; k < g->n_fixed; k++) {
        if (strcmp(g->fixed_option[k], opt) == 0) {
            return 1;
        }
    }
    return 0;
}

int sweep_grid_parse(int argc, char **argv, sweep_grid_t *g, char *err, size_t len)
{
    int i = 0, used;
    memset(g, 0, sizeof *g);
    g->jobs = grid_default_jobs();
    while (i < argc) {
        const int own = grid_own(g, argc, argv, i, &used, err, len);
        if (own < 0) {
            return -1;
        }
        if (own == 0) {
            /* a number or a choice takes a value, a flag does not */
            const int kind = sim_cli_gridable(argv[i]);
            const int takes_value = kind == 1;
            if (kind < 0) {
                return grid_fail(err, len, "unknown option '%s'%s", argv[i], "");
            }
            if (strcmp(argv[i], "--pil") == 0) {
                return grid_fail(err, len,
                                 "sweep runs its points side by side: --pil is for one "
                                 "run (sixphase-sim run --pil)%s%s",
                                 "", "");
            }
            if (takes_value && i + 1 >= argc) {
                return grid_fail(err, len, "%s needs a value%s", argv[i], "");
            }
            used = takes_value ? 2 : 1;
            if (grid_option(g, argv[i], takes_value ? argv[i + 1] : NULL, err, len) != 0) {
                return -1;
            }
        }
        i += used;
    }
    if (!g->out) {
        return grid_fail(err, len, "missing %s%s", "--out", "");
    }
    if (!grid_has(g, "--scenario") && grid_option(g, "--scenario", "steady", err, len) != 0) {
        return -1;
    }
    if (g->n_axes == 0) {
        return grid_fail(err, len,
                         "nothing to sweep: give an option a list (a,b) or a range "
                         "(start:stop:step)%s%s",
                         "", "");
    }
    return 0;
}

long sweep_grid_points(const sweep_grid_t *g)
{
    long n = 1;
    int k;
    for (k = 0; k < g->n_axes; k++) {
        n *= g->axis[k].n;
    }
    return n;
}

void sweep_grid_point(const sweep_grid_t *g, long p, int index[SWEEP_MAX_AXES])
{
    int k;
    for (k = g->n_axes - 1; k >= 0; k--) { /* the first axis varies slowest */
        index[k] = (int)(p % g->axis[k].n);
        p /= g->axis[k].n;
    }
}

int sweep_grid_args(const sweep_grid_t *g, long p, char **args)
{
    int index[SWEEP_MAX_AXES];
    int n = 0, k;
    sweep_grid_point(g, p, index);
    for (k = 0; k < g->n_fixed; k++) {
        args[n++] = (char *)(uintptr_t)g->fixed_option[k];
        if (g->fixed_value[k]) {
            args[n++] = (char *)(uintptr_t)g->fixed_value[k];
        }
    }
    for (k = 0; k < g->n_axes; k++) {
        args[n++] = (char *)(uintptr_t)g->axis[k].option;
        args[n++] = (char *)(uintptr_t)g->axis[k].value[index[k]];
    }
    return n;
}
