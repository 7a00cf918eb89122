/* Reading sixphase-sim trace.csv files into benchmark operating points. */
#define _POSIX_C_SOURCE 200809L

#include "trace_csv.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_COLUMNS 64
#define POLE_PAIRS 3.0
#define PI 3.14159265358979323846

static int column_index(char *header, const char *name)
{
    int index = 0;
    char *save = NULL;
    char *tok = strtok_r(header, ",\n\r", &save);
    while (tok) {
        if (strcmp(tok, name) == 0) {
            return index;
        }
        index++;
        tok = strtok_r(NULL, ",\n\r", &save);
    }
    return -1;
}

/* Appends the trace's points; returns the new count or -1 with a message. */
long trace_csv_read(const char *path, bench_point_t *points, size_t have, size_t capacity,
                    double vdc, const char *tool)
{
    /* column names of sixphase-sim's trace.csv (phase currents i_A..i_F; i_d is the d axis) */
    static const char *names[9] = {"theta_e", "speed_rpm", "i_A", "i_B", "i_C",
                                   "i_D",     "i_E",       "i_F", "Tref"};
    int col[9];
    char line[4096];
    char copy[4096];
    FILE *f = fopen(path, "r");
    int k;
    size_t n = have;
    if (!f) {
        fprintf(stderr, "%s: cannot open trace '%s': %s\n", tool, path, strerror(errno));
        return -1;
    }
    if (!fgets(line, sizeof line, f)) {
        fprintf(stderr, "%s: trace '%s' is empty\n", tool, path);
        fclose(f);
        return -1;
    }
    for (k = 0; k < 9; k++) {
        memcpy(copy, line, sizeof line);
        col[k] = column_index(copy, names[k]);
        if (col[k] < 0) {
            fprintf(stderr, "%s: trace '%s' has no column '%s'\n", tool, path, names[k]);
            fclose(f);
            return -1;
        }
    }
    while (fgets(line, sizeof line, f) && n < capacity) {
        double v[MAX_COLUMNS];
        int c = 0;
        char *save = NULL;
        char *tok = strtok_r(line, ",\n\r", &save);
        while (tok && c < MAX_COLUMNS) {
            char *end;
            v[c] = strtod(tok, &end);
            if (end == tok) {
                v[c] = 0.0; /* non-numeric column (leg bit string) */
            }
            c++;
            tok = strtok_r(NULL, ",\n\r", &save);
        }
        for (k = 0; k < 9; k++) {
            if (col[k] >= c) {
                fprintf(stderr, "%s: short row in trace '%s'\n", tool, path);
                fclose(f);
                return -1;
            }
        }
        points[n].theta_e = v[col[0]];
        points[n].omega_e = v[col[1]] * PI / 30.0 * POLE_PAIRS;
        for (k = 0; k < 6; k++) {
            points[n].i_phase[k] = v[col[2 + k]];
        }
        points[n].torque_ref = v[col[8]];
        points[n].vdc = vdc;
        n++;
    }
    fclose(f);
    return (long)n;
}
