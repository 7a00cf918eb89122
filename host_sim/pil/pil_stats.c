/* A PIL session's record, see pil_stats.h. */
#include "pil_stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sxlink_states.h"

#define PIL_STATE_NUMBER(id, number, name) id##_NUMBER_ = number,
enum { DRIVE_STATE_LIST(PIL_STATE_NUMBER) PIL_STATES_END_ };
#undef PIL_STATE_NUMBER

int pil_stats_open(pil_stats_t *st, const char *csv_path, char *err, size_t len)
{
    int k;
    memset(st, 0, sizeof *st);
    st->summary.on = true;
    st->summary.first_diff = -1;
    if (!csv_path) {
        return 0;
    }
    st->csv = fopen(csv_path, "w");
    if (!st->csv) {
        (void)snprintf(err, len, "PIL: cannot write %s", csv_path);
        return -1;
    }
    fprintf(st->csv, "step,t_s,state,cycles");
    for (k = 0; k < (int)SXL_PIL_OUT_STAGE_COUNT; k++) {
        fprintf(st->csv, ",%s", sim_pil_stage_names[k]);
    }
    fprintf(st->csv, ",agrees\n");
    return 0;
}

bool pil_outputs_agree(const sim_ctl_wire_out_t *a, const sim_ctl_wire_out_t *b, unsigned tolerance,
                       unsigned *duty_diff)
{
    unsigned worst = 0u;
    int k;
    for (k = 0; k < HAL_PWM_LEGS; k++) {
        const unsigned d = (a->duty[k] > b->duty[k]) ? (unsigned)(a->duty[k] - b->duty[k])
                                                     : (unsigned)(b->duty[k] - a->duty[k]);
        worst = (d > worst) ? d : worst;
    }
    *duty_diff = worst;
    return worst <= tolerance && a->flags == b->flags && a->isolated == b->isolated &&
           a->encoder_offset == b->encoder_offset && a->state == b->state && a->faults == b->faults;
}

static int describe_outputs(char *out, size_t cap, const char *who, const sim_ctl_wire_out_t *o)
{
    return snprintf(out, cap,
                    "%s: duty [%u %u %u %u %u %u], flags 0x%02x, isolated 0x%02x, "
                    "state %u, faults latched 0x%04x; ",
                    who, o->duty[0], o->duty[1], o->duty[2], o->duty[3], o->duty[4], o->duty[5],
                    o->flags, o->isolated, o->state, o->faults);
}

/* The first differing period, its inputs and both sides' outputs. */
static void describe_difference(pil_stats_t *st, const hal_sim_bus_t *in,
                                const sim_ctl_wire_out_t *mine, const sim_ctl_wire_out_t *theirs,
                                double t_s)
{
    char *p = st->summary.first_diff_text;
    const size_t cap = sizeof st->summary.first_diff_text;
    int n =
        snprintf(p, cap,
                 "period %lu (t = %.6f s): inputs ADC [%u %u %u %u %u %u] vdc %u, angle %lu, "
                 "speed %ld, fresh %d, forced off %d; ",
                 (unsigned long)st->steps, t_s, in->adc.phase[0], in->adc.phase[1],
                 in->adc.phase[2], in->adc.phase[3], in->adc.phase[4], in->adc.phase[5],
                 in->adc.vdc, (unsigned long)in->encoder.elec_angle,
                 (long)in->encoder.mech_speed_q16, in->adc_fresh ? 1 : 0, in->forced_off ? 1 : 0);
    if (n > 0 && (size_t)n < cap) {
        n += describe_outputs(p + n, cap - (size_t)n, "host", mine);
    }
    if (n > 0 && (size_t)n < cap) {
        (void)describe_outputs(p + n, cap - (size_t)n, "target", theirs);
    }
    st->summary.first_diff = (long)st->steps;
}

static void keep_period(pil_stats_t *st, const sim_ctl_wire_out_t *theirs)
{
    pil_period_t *pp;
    int k;
    if (st->full) {
        return; /* out of memory once: the statistics end there, the comparison goes on */
    }
    if (st->steps == st->cap) {
        const size_t cap = st->cap ? 2u * st->cap : 4096u;
        pil_period_t *grown = realloc(st->periods, cap * sizeof *grown);
        if (!grown) {
            st->full = true;
            return;
        }
        st->periods = grown;
        st->cap = cap;
    }
    pp = &st->periods[st->steps];
    pp->cycles = theirs->cycles;
    pp->running = theirs->state == (uint16_t)DRIVE_STATE_RUN_NUMBER_;
    for (k = 0; k < (int)SXL_PIL_OUT_STAGE_COUNT; k++) {
        pp->stage[k] = theirs->stage[k];
    }
}

void pil_stats_add(pil_stats_t *st, const hal_sim_bus_t *in, const sim_ctl_wire_out_t *mine,
                   const sim_ctl_wire_out_t *theirs, double t_s)
{
    unsigned diff = 0u;
    const bool agree =
        pil_outputs_agree(mine, theirs, st->float_image ? SIM_PIL_FLOAT_DUTY_TOL : 0u, &diff);
    int k;
    st->summary.max_duty_diff =
        (diff > st->summary.max_duty_diff) ? diff : st->summary.max_duty_diff;
    if (!agree) {
        if (st->summary.differing == 0u) {
            describe_difference(st, in, mine, theirs, t_s);
        }
        st->summary.differing++;
    }
    if (st->csv) {
        fprintf(st->csv, "%lu,%.6f,%u,%lu", (unsigned long)st->steps, t_s, theirs->state,
                (unsigned long)theirs->cycles);
        for (k = 0; k < (int)SXL_PIL_OUT_STAGE_COUNT; k++) {
            fprintf(st->csv, ",%lu", (unsigned long)theirs->stage[k]);
        }
        fprintf(st->csv, ",%d\n", agree ? 1 : 0);
    }
    keep_period(st, theirs);
    st->steps++;
}

static void stat_add(sim_pil_stat_t *s, double v, unsigned long *n)
{
    s->mean += v;
    s->worst = (v > s->worst) ? v : s->worst;
    (*n)++;
}

static void stat_end(sim_pil_stat_t *s, unsigned long n)
{
    s->mean = n ? s->mean / (double)n : 0.0;
}

/* Mean and worst over every period, over those in RUN, per stage; the histogram. */
static void summarise(pil_stats_t *st, size_t kept)
{
    sim_pil_summary_t *s = &st->summary;
    unsigned long n_all = 0u, n_run = 0u, n_stage[SXL_PIL_OUT_STAGE_COUNT] = {0};
    double lo = INFINITY;
    size_t i;
    int k;
    for (i = 0u; i < kept; i++) {
        const pil_period_t *pp = &st->periods[i];
        if (pp->cycles > s->cycles.worst) {
            s->worst_step = (unsigned long)i;
        }
        stat_add(&s->cycles, (double)pp->cycles, &n_all);
        if (pp->running) {
            stat_add(&s->cycles_run, (double)pp->cycles, &n_run);
        }
        for (k = 0; k < (int)SXL_PIL_OUT_STAGE_COUNT; k++) {
            stat_add(&s->stage[k], (double)pp->stage[k], &n_stage[k]);
        }
        lo = fmin(lo, (double)pp->cycles);
    }
    stat_end(&s->cycles, n_all);
    stat_end(&s->cycles_run, n_run);
    for (k = 0; k < (int)SXL_PIL_OUT_STAGE_COUNT; k++) {
        stat_end(&s->stage[k], n_stage[k]);
    }
    s->hist_lo = kept ? lo : 0.0;
    s->hist_width = fmax(1.0, ceil((s->cycles.worst - s->hist_lo + 1.0) / SIM_PIL_HIST_BINS));
    for (i = 0u; i < kept; i++) {
        const int bin = (int)(((double)st->periods[i].cycles - s->hist_lo) / s->hist_width);
        s->hist[(bin < SIM_PIL_HIST_BINS) ? bin : SIM_PIL_HIST_BINS - 1]++;
    }
}

void pil_stats_close(pil_stats_t *st, double wall_s, sim_pil_summary_t *s)
{
    const size_t kept = (st->steps < st->cap) ? st->steps : st->cap;
    st->summary.steps = (unsigned long)st->steps;
    summarise(st, kept);
    st->summary.wall_s = wall_s;
    st->summary.steps_per_s =
        (wall_s > 0.0 && st->steps > 1u) ? (double)(st->steps - 1u) / wall_s : 0.0;
    if (st->csv) {
        (void)fclose(st->csv);
        st->csv = NULL;
    }
    free(st->periods);
    st->periods = NULL;
    *s = st->summary;
}
