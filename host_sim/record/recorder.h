/*
 * The run's output files, written while the run goes (memory does not grow with the
 * duration): trace.csv, one row per control period, and fine.csv, the plant samples of the
 * analysis window. The text is what the earlier fprintf formats gave, byte for byte
 * (csv_format.h; tests/sim/test_sim_recorder.c compares whole files with fprintf's).
 */
#ifndef SIM_RECORDER_H
#define SIM_RECORDER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* One control period: the plant at the period start, the drive's references and the command
 * in force during the period. */
typedef struct {
    double t, speed_rpm, theta_e;
    double i_phase[6];
    double i_d, i_q, i_x, i_y;
    double te, te_avg, psi_s; /* torque at the start, period-average torque, stator flux */
    double tref, psi_ref;
    int vector; /* S_A = bit 5 */
    double duty;
} sim_trace_row_t;

/* One plant sample of the analysis window. */
typedef struct {
    double t, i_a, theta_e_unwrapped, i_x, i_y, te, speed_rpm;
} sim_fine_row_t;

#define SIM_CSV_BUFFER_BYTES 65536

typedef struct {
    FILE *f;
    char path[1200];
    size_t used;
    bool failed;
    char buf[SIM_CSV_BUFFER_BYTES];
} sim_csv_file_t;

typedef struct {
    sim_csv_file_t trace, fine;
    bool trace_on, fine_on;
    double limit_bytes; /* both files together */
    double bytes;       /* written so far (headers and whole rows) */
    bool limit_reached; /* a row did not fit: nothing more is written */
} sim_recorder_t;

/* Creates the files that are on (their headers written); nothing when dir is NULL. Together
 * they stop at limit_mb (1e6 bytes): the row that would pass it and every later one are left
 * out, and limit_reached is set. 0 on success, else a one-line message in err. */
int sim_recorder_open(sim_recorder_t *r, const char *dir, bool trace, bool fine, double limit_mb,
                      char *err, size_t err_len);

void sim_recorder_trace(sim_recorder_t *r, const sim_trace_row_t *row);
void sim_recorder_fine(sim_recorder_t *r, const sim_fine_row_t *row);

/* Flush and close; 0 when everything reached the files, else a one-line message in err. */
int sim_recorder_close(sim_recorder_t *r, char *err, size_t err_len);

/* Close and delete the files (a failed run leaves no partial output). */
void sim_recorder_discard(sim_recorder_t *r);

/* The row texts themselves (no newline handling beyond the row's own), for the tests. */
char *sim_trace_row_text(char *out, const sim_trace_row_t *row);
char *sim_fine_row_text(char *out, const sim_fine_row_t *row);

/* Longest row text. */
#define SIM_ROW_MAX_CHARS (24 * 340)

#endif /* SIM_RECORDER_H */
