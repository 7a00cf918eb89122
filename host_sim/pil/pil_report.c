/* A PIL session's statistics in metrics.json, see pil.h. */
#include <stdio.h>

#include "pil.h"

const char *const sim_pil_stage_names[SXL_PIL_OUT_STAGE_COUNT] = {"adc",   "transforms", "predict",
                                                                  "table", "search",     "pwm"};

/* Counter ticks of the emulator as instructions: 2^shift ns of virtual time per instruction. */
static double report_instructions(const sim_pil_summary_t *s, double ticks)
{
    return ticks * 1e9 / (s->counter_hz * (double)(1u << s->icount_shift));
}

/* A board's counter ticks are its cycles, shown in us too; the emulator's are virtual time,
 * shown as the instructions they stand for. */
static void report_stat(FILE *f, const char *name, const sim_pil_summary_t *s,
                        const sim_pil_stat_t *st, const char *end)
{
    fprintf(f, "    \"%s\": {\"mean\": %.1f, \"worst\": %.0f", name, st->mean, st->worst);
    if (s->emulated) {
        fprintf(f, ", \"mean_instructions\": %.1f, \"worst_instructions\": %.0f",
                report_instructions(s, st->mean), report_instructions(s, st->worst));
    } else {
        fprintf(f, ", \"mean_us\": %.3f, \"worst_us\": %.3f", 1e6 * st->mean / s->counter_hz,
                1e6 * st->worst / s->counter_hz);
    }
    fprintf(f, "}%s\n", end);
}

void sim_pil_print_json(FILE *f, const sim_pil_summary_t *s)
{
    int k;
    fprintf(f, "  \"pil\": {\n    \"target\": \"%s\",\n    \"emulated\": %s,\n", s->target,
            s->emulated ? "true" : "false");
    fprintf(f, "    \"counter_hz\": %.0f,\n", s->counter_hz);
    if (s->emulated) {
        fprintf(f, "    \"icount_shift\": %u,\n", s->icount_shift);
    }
    fprintf(f, "    \"steps\": %lu,\n    \"identical\": %s,\n    \"differing_steps\": %lu,\n",
            s->steps, (s->differing == 0u) ? "true" : "false", s->differing);
    fprintf(f, "    \"largest_duty_difference_counts\": %u,\n", s->max_duty_diff);
    if (s->first_diff < 0) {
        fprintf(f, "    \"first_difference\": null,\n");
    } else {
        fprintf(f, "    \"first_difference\": \"%s\",\n", s->first_diff_text);
    }
    report_stat(f, "cycles", s, &s->cycles, ",");
    fprintf(f, "    \"worst_step\": %lu,\n", s->worst_step);
    report_stat(f, "cycles_in_run", s, &s->cycles_run, ",");
    for (k = 0; k < (int)SXL_PIL_OUT_STAGE_COUNT; k++) {
        report_stat(f, sim_pil_stage_names[k], s, &s->stage[k], ",");
    }
    fprintf(f, "    \"histogram\": {\"from\": %.0f, \"bin_width\": %.0f, \"counts\": [", s->hist_lo,
            s->hist_width);
    for (k = 0; k < SIM_PIL_HIST_BINS; k++) {
        fprintf(f, "%s%lu", k ? ", " : "", s->hist[k]);
    }
    fprintf(f, "]},\n    \"wall_s\": %.3f,\n    \"steps_per_s\": %.1f\n  },\n", s->wall_s,
            s->steps_per_s);
}
