/*
 * A PIL session's record: each period's comparison of the target's outputs with the
 * reference's, its cycle counts (pil.csv, a row each), and the statistics sim_pil_close gives.
 */
#ifndef PIL_STATS_H
#define PIL_STATS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "bridge/sim_ctl_wire.h"
#include "hal_sim.h"
#include "pil.h"

typedef struct {
    uint32_t cycles;
    uint32_t stage[SXL_PIL_OUT_STAGE_COUNT];
    bool running;
} pil_period_t;

typedef struct {
    sim_pil_summary_t summary;
    bool float_image;
    FILE *csv;
    pil_period_t *periods;
    size_t steps, cap; /* periods seen; room for */
    bool full;         /* a growth failed: periods from then on are compared, not kept */
} pil_stats_t;

/* csv_path NULL: no file. 0, or -1 with the reason in err. */
int pil_stats_open(pil_stats_t *st, const char *csv_path, char *err, size_t len);

/* One period: in the inputs both sides had, mine the reference's outputs, theirs the target's,
 * t_s its time from the first period. */
void pil_stats_add(pil_stats_t *st, const hal_sim_bus_t *in, const sim_ctl_wire_out_t *mine,
                   const sim_ctl_wire_out_t *theirs, double t_s);

/* The statistics into s (wall_s: from the first period's reply to the last's). */
void pil_stats_close(pil_stats_t *st, double wall_s, sim_pil_summary_t *s);

/* The outputs agree: every field equal, a float image's duties within tolerance counts (the
 * largest duty difference into *duty_diff). */
bool pil_outputs_agree(const sim_ctl_wire_out_t *a, const sim_ctl_wire_out_t *b, unsigned tolerance,
                       unsigned *duty_diff);

#endif /* PIL_STATS_H */
