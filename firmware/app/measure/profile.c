#include "profile.h"

#include "ctl.h"
#include "hal_cycles.h"
#include "sixphase_placement.h"

prof_t drive_profile;

uint32_t prof_mean(const prof_stat_t *s) { return (s->mean_x256 + 128u) >> 8; }

SIXPHASE_RAMFUNC void prof_ctl_stage(int16_t ctl_stage)
{
#if PROFILE_ENABLE
    if (ctl_stage >= 0 && ctl_stage <= (int16_t)CTL_STAGE_SEARCH) {
        prof_mark((prof_stage_t)((int16_t)PROF_TRANSFORMS + ctl_stage));
    }
#else
    (void)ctl_stage;
#endif
}

#if PROFILE_ENABLE

#define PROF_MEAN_MAX_CYCLES 0x00FFFFFFu

SIXPHASE_RAMFUNC static void prof_record(prof_stat_t *s, uint32_t cycles)
{
    s->last = cycles;
    if (s->count == 0u) {
        s->min = cycles;
        s->max = cycles;
        s->mean_x256 = ((cycles < PROF_MEAN_MAX_CYCLES) ? cycles : PROF_MEAN_MAX_CYCLES) << 8;
    } else {
        if (cycles < s->min) {
            s->min = cycles;
        }
        if (cycles > s->max) {
            s->max = cycles;
        }
        /* mean += (x - mean) / 64 in x256 units, the quotient truncated toward zero; 32-bit
         * only (x below 2^24 cycles, 0.11 s at 150 MHz, in the mean; min, max and last keep x) */
        const uint32_t x256 = ((cycles < PROF_MEAN_MAX_CYCLES) ? cycles : PROF_MEAN_MAX_CYCLES)
                              << 8;
        if (x256 >= s->mean_x256) {
            s->mean_x256 += (x256 - s->mean_x256) >> 6;
        } else {
            s->mean_x256 -= (s->mean_x256 - x256) >> 6;
        }
    }
    if (s->count < UINT32_MAX) {
        s->count++;
    }
}

void prof_init(uint32_t period_cycles, uint32_t cycles_per_second)
{
    prof_t *p = &drive_profile;
    uint32_t best = UINT32_MAX;
    int16_t k;
    for (k = 0; k < (int16_t)PROF_STAGES; k++) {
        p->stage[k] = (prof_stat_t){0u, 0u, 0u, 0u, 0u};
    }
    /* the cheapest of several back-to-back readings is the cost of one reading */
    for (k = 0; k < 16; k++) {
        const uint32_t a = hal_cycles_now();
        const uint32_t b = hal_cycles_now();
        if ((uint32_t)(b - a) < best) {
            best = (uint32_t)(b - a);
        }
    }
    p->read_cost = best;
    /* load = busy / period, in permille, without a division per ISR (prof_permille) */
    p->period_cycles = (period_cycles >= PROF_MIN_PERIOD_CYCLES) ? period_cycles : 0u;
    p->permille_k = (p->period_cycles != 0u) ? (uint32_t)65536000u / p->period_cycles : 0u;
    p->cycles_per_us = cycles_per_second / 1000000u;
    p->load_permille_last = 0u;
    p->load_permille_max = 0u;
    p->overruns = 0u;
    p->t_start = hal_cycles_now();
    p->t_prev = p->t_start;
}

SIXPHASE_RAMFUNC void prof_begin(uint32_t latency_cycles)
{
    prof_t *p = &drive_profile;
    prof_record(&p->stage[PROF_LATENCY], latency_cycles);
    p->t_start = hal_cycles_now();
    p->t_prev = p->t_start;
}

SIXPHASE_RAMFUNC static uint32_t prof_elapsed(uint32_t from, uint32_t to)
{
    const uint32_t dt = (uint32_t)(to - from);
    const uint32_t cost = drive_profile.read_cost;
    return (dt > cost) ? dt - cost : 0u;
}

SIXPHASE_RAMFUNC void prof_mark(prof_stage_t stage)
{
    prof_t *p = &drive_profile;
    const uint32_t now = hal_cycles_now();
    if ((int16_t)stage >= 0 && stage < PROF_STAGES) {
        prof_record(&p->stage[stage], prof_elapsed(p->t_prev, now));
    }
    p->t_prev = hal_cycles_now(); /* the bookkeeping above is not charged to the next stage */
}

/* busy * 1000 / period, rounded down, from k = floor(1000 2^16 / period) <= 2^16: busy k / 2^16
 * is at most one below it while busy < 2^16 (one comparison corrects that), and within
 * busy / 2^16 + 1 of it beyond (an overrun of over four periods); saturated at 65535. */
SIXPHASE_RAMFUNC static uint16_t prof_permille(uint32_t busy, uint32_t period, uint32_t k)
{
    const uint32_t hi = busy >> 16;
    uint32_t est;
    if (hi != 0u) {
        if (hi * k > 65535u) {
            return 65535u;
        }
        est = hi * k + (((busy & 0xFFFFu) * k) >> 16);
    } else {
        est = (busy * k) >> 16;
        if ((est + 1u) * period <= busy * 1000u) {
            est++;
        }
    }
    return (uint16_t)((est > 65535u) ? 65535u : est);
}

SIXPHASE_RAMFUNC void prof_end(void)
{
    prof_t *p = &drive_profile;
    const uint32_t now = hal_cycles_now();
    uint32_t busy;
    prof_record(&p->stage[PROF_TOTAL], prof_elapsed(p->t_start, now));
    busy = p->stage[PROF_TOTAL].last + p->stage[PROF_LATENCY].last;
    if (p->period_cycles != 0u) {
        p->load_permille_last = prof_permille(busy, p->period_cycles, p->permille_k);
        if (p->load_permille_last > p->load_permille_max) {
            p->load_permille_max = p->load_permille_last;
        }
    }
}

void prof_count_overrun(void)
{
    if (drive_profile.overruns < UINT32_MAX) {
        drive_profile.overruns++;
    }
}

#endif /* PROFILE_ENABLE */
