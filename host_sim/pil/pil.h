/*
 * Processor-in-the-loop for one run (README.md): sim_pil_open wraps the run's drive (the
 * reference) in a function table whose periods run on the target; sim_pil_close ends the
 * session and gives its statistics.
 */
#ifndef SIM_PIL_H
#define SIM_PIL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "bridge/sim_ctl.h"
#include "sxlink_pil.h"

#define SIM_PIL_HIST_BINS 16
/* Float images: a leg's duty may differ from the reference's by this many counts of the HAL's
 * Q15 duty (1/32768 of the period); everything else must be equal. Fixed: nothing may differ. */
#define SIM_PIL_FLOAT_DUTY_TOL 1

/* The profile's stages a STEP reply carries (SXL_PIL_OUT_STAGES: ADC .. PWM), as the report,
 * pil.csv and its figure name them. */
extern const char *const sim_pil_stage_names[SXL_PIL_OUT_STAGE_COUNT];

typedef struct {
    double mean, worst;
} sim_pil_stat_t;

typedef struct {
    bool on;
    char target[128];
    bool emulated;
    unsigned icount_shift;
    double counter_hz;
    unsigned long steps, differing;
    long first_diff; /* step of the first difference, -1: none */
    char first_diff_text[1024];
    unsigned max_duty_diff;            /* counts */
    sim_pil_stat_t cycles, cycles_run; /* every period; the periods in RUN */
    unsigned long worst_step;
    sim_pil_stat_t stage[SXL_PIL_OUT_STAGE_COUNT];
    double hist_lo, hist_width; /* counter ticks */
    unsigned long hist[SIM_PIL_HIST_BINS];
    double wall_s, steps_per_s;
} sim_pil_summary_t;

/* The table the run uses instead of ref, its periods on target ("qemu" or "serial:PATH[@BAUD]");
 * csv_path (NULL: none) gets a row per period. NULL, with a one-line reason in err. */
const sim_ctl_ops_t *sim_pil_open(const sim_ctl_ops_t *ref, const char *target, double ts_s,
                                  const char *csv_path, char *err, size_t err_len);

/* NULL while the session is sound, else why it ended (the run stops at the next period). */
const char *sim_pil_error(void);

/* Ends the session (the emulator stopped), the statistics into s. */
void sim_pil_close(sim_pil_summary_t *s);

/* The statistics as a "pil" object of metrics.json (a line each, indent two spaces). */
void sim_pil_print_json(FILE *f, const sim_pil_summary_t *s);

#endif /* SIM_PIL_H */
