/* Control-step benchmark: operating points replayed through one arithmetic build of the
 * core. Double-only interface so the fixed and float builds link into one program (the
 * float copy's symbols carry the prefix flt_). */
#ifndef BENCH_H
#define BENCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct {
    double i_phase[6]; /* A */
    double vdc;        /* V */
    double theta_e;    /* rad */
    double omega_e;    /* electrical rad/s */
    double torque_ref; /* N*m */
} bench_point_t;

/* Converts the points to the build's measurement format (outside the measured region).
 * Returns the number kept (at most BENCH_MAX_POINTS). */
#define BENCH_MAX_POINTS 400000
size_t bench_prepare(const bench_point_t *points, size_t n);
size_t flt_bench_prepare(const bench_point_t *points, size_t n);

/* Initialises the controller (an id of CTL_CONTROLLER_LIST: 0 DDC, 1 MPTC-49, 2 MPTC-13, ...) with
 * default parameters in torque mode. 0 on success. Not measured. */
int16_t bench_setup(int16_t controller);
int16_t flt_bench_setup(int16_t controller);

/* Runs the control step over every prepared point, `reps` times, with the recorded torque
 * reference. Returns a checksum of the commands (keeps the work observable). Only this
 * function is measured. */
uint32_t bench_run(int32_t reps);
uint32_t flt_bench_run(int32_t reps);

/* Every command (vector, duty, leg duties to the last Q24 bit, enable) of one pass over the
 * prepared points after bench_setup, folded (FNV-1a): the benchmark's check that a change of
 * the core left the commands identical. Not measured. */
uint32_t bench_digest(void);
uint32_t flt_bench_digest(void);

/* The protection check (ctl_protect_check) over every prepared point, `reps` times, as the
 * drive runs it each period while running: the default settings' limits, raw ADC words
 * rebuilt from the currents with the board's scaling. Returns a checksum; only this is
 * measured. */
uint32_t bench_protect_run(int32_t reps);
uint32_t flt_bench_protect_run(int32_t reps);

/* Background work of a run-time parameter change, not measured: builds variant k of the set
 * (lambda, DDC direction reading, torque guard, flux reference mode and torque limit vary; the
 * controller stays) and publishes it; the next step takes it. Returns the ctl_param_error_t. */
int16_t bench_request_change(int16_t k);
int16_t flt_bench_request_change(int16_t k);
/* A published set waits for the next step. */
bool bench_change_pending(void);
bool flt_bench_change_pending(void);

/* One step at prepared point i (i < the prepared count) after bench_setup; for tools that
 * look at single steps (ctl-opcount). Returns a word of the command. */
uint32_t bench_step(size_t i);
uint32_t flt_bench_step(size_t i);

#endif /* BENCH_H */
