/* A period's switching program and the cache of recent ones, see inverter_program.h. */
#include "inverter_program.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Two-way sets of slots: the drives use a few hundred duty patterns per electrical turn (DDC about
 * 420, MPTC-49 about 1,000 with the start state), revisited every turn. */
#define INV_CACHE_SET_BITS 9
#define INV_CACHE_SLOTS (2u << INV_CACHE_SET_BITS)

/* Inserts v into the sorted a[0..n) (n + 1 entries after). */
static void inv_insert_sorted(double *a, int n, double v)
{
    while (n > 0 && a[n - 1] > v) {
        a[n] = a[n - 1];
        n--;
    }
    a[n] = v;
}

/* Appends the legs commanded at t, merged into the last edge when that is at the same instant. */
static void inv_add_edge(inv_builder_t *b, double t, unsigned set, unsigned clear)
{
    const int n = b->n_edges;
    if (n > 0 && b->edge[n - 1].t == t) {
        b->edge[n - 1].set |= set;
        b->edge[n - 1].clear |= clear;
    } else {
        b->edge[n].t = t;
        b->edge[n].set = set;
        b->edge[n].clear = clear;
        b->n_edges = n + 1;
    }
}

/* Edges in time order without a general sort: the transitions at the period start first, then
 * the rising edges (the longest pulse first) and the falling edges (the shortest first), since
 * a duty d rises at (1 - d) Ts / 2 and falls at (1 + d) Ts / 2. Legs with equal duties switch
 * together: one edge per distinct instant. A leg whose pulse is too short to separate its edges
 * in floating point is in both masks: set first, then cleared. */
static void inv_schedule_edges(inv_builder_t *b, const double duty[PLANT_PHASES])
{
    int by_duty[PLANT_PHASES], n_mid = 0, k;
    double d_of[PLANT_PHASES];
    unsigned start_set = 0u, start_clear = 0u;
    for (k = 0; k < PLANT_PHASES; k++) {
        const unsigned bit = INV_LEG_BIT(k);
        const double d = (duty[k] < 0.0) ? 0.0 : ((duty[k] > 1.0) ? 1.0 : duty[k]);
        if (duty[k] >= 1.0) {
            start_set |= bit & ~b->legs.nominal_bits;
        } else {
            start_clear |= bit & b->legs.nominal_bits;
        }
        d_of[k] = d;
        if (d > 0.0 && d < 1.0) { /* insertion by falling duty */
            int i = n_mid++;
            while (i > 0 && d_of[by_duty[i - 1]] < d) {
                by_duty[i] = by_duty[i - 1];
                i--;
            }
            by_duty[i] = k;
        }
    }
    b->n_edges = 0;
    if ((start_set | start_clear) != 0u) {
        inv_add_edge(b, 0.0, start_set, start_clear);
    }
    for (k = 0; k < n_mid; k++) {
        inv_add_edge(b, 0.5 * (1.0 - d_of[by_duty[k]]) * b->ts, INV_LEG_BIT(by_duty[k]), 0u);
    }
    for (k = n_mid - 1; k >= 0; k--) {
        inv_add_edge(b, 0.5 * (1.0 + d_of[by_duty[k]]) * b->ts, 0u, INV_LEG_BIT(by_duty[k]));
    }
}

/* Breakpoints: the edges and the ends of their dead intervals (two sorted lists, the second the
 * first shifted by the dead time) merged, the ends carried over from the last period inserted,
 * the period end last. */
static void inv_schedule_breaks(inv_builder_t *b)
{
    const double ts = b->ts;
    int i = 0, j = 0, n = 0, k;
    while (i < b->n_edges) {
        const double end = b->edge[j].t + b->td;
        if (b->edge[i].t <= end) {
            b->br[n++] = b->edge[i++].t;
        } else {
            b->br[n++] = end; /* below the next edge, so below ts */
            j++;
        }
    }
    for (; j < b->n_edges && b->edge[j].t + b->td < ts; j++) {
        b->br[n++] = b->edge[j].t + b->td;
    }
    if (b->legs.dead_last > 0.0) { /* a dead interval runs into this period */
        for (k = 0; k < PLANT_PHASES; k++) {
            if (b->legs.dead_until[k] > 0.0 && b->legs.dead_until[k] < ts) {
                inv_insert_sorted(b->br, n++, b->legs.dead_until[k]);
            }
        }
    }
    b->br[n++] = ts;
    b->n_br = n;
}

void inv_builder_start(inv_builder_t *b, const inv_legs_t *legs, const double duty[PLANT_PHASES],
                       double ts, double td, const inv_sample_times_t *smp)
{
    b->legs = *legs;
    b->ts = ts;
    b->td = td;
    b->eps = ts * 1e-12;
    b->t = 0.0;
    b->changed = 0u;
    b->i_edge = b->i_br = b->i_smp = 0;
    b->smp = *smp;
    inv_schedule_edges(b, duty);
    inv_schedule_breaks(b);
}

/* Apply the edges due at t: the commanded state, and a dead interval for every leg that
 * changes. */
static void inv_apply_edges(inv_builder_t *b)
{
    inv_legs_t *l = &b->legs;
    while (b->i_edge < b->n_edges && b->edge[b->i_edge].t <= b->t + b->eps) {
        const unsigned rising = b->edge[b->i_edge].set & ~l->nominal_bits;
        const unsigned falling = b->edge[b->i_edge].clear & (l->nominal_bits | rising);
        const unsigned changed = rising | falling;
        l->nominal_bits = (l->nominal_bits | rising) & ~falling;
        if (changed != 0u) {
            const double end = b->edge[b->i_edge].t + b->td;
            int k;
            for (k = 0; k < PLANT_PHASES; k++) {
                if ((changed & INV_LEG_BIT(k)) != 0u) {
                    l->dead_until[k] = end;
                }
            }
            l->dead_last = (end > l->dead_last) ? end : l->dead_last;
            b->changed |= changed;
        }
        b->i_edge++;
    }
}

/* The legs in a dead interval at t. */
static unsigned inv_dead_legs(const inv_builder_t *b)
{
    unsigned dead = 0u;
    int k;
    if (!(b->t < b->legs.dead_last - b->eps)) {
        return 0u;
    }
    for (k = 0; k < PLANT_PHASES; k++) {
        if (b->t < b->legs.dead_until[k] - b->eps) {
            dead |= INV_LEG_BIT(k);
        }
    }
    return dead;
}

/* Whether the caller's next sample is due at t; returns t_next or the next sample instant before
 * it. */
static double inv_sample_due(inv_builder_t *b, bool *due, double t_next)
{
    const inv_sample_times_t *s = &b->smp;
    *due = false;
    while (b->i_smp < s->n && s->t[b->i_smp] < b->t - b->eps) {
        b->i_smp++;
    }
    if (b->i_smp < s->n && s->t[b->i_smp] <= b->t + b->eps) {
        *due = true;
        b->i_smp++;
    }
    if (b->i_smp < s->n && s->t[b->i_smp] < t_next) {
        t_next = s->t[b->i_smp];
    }
    return t_next;
}

bool inv_builder_next(inv_builder_t *b, inv_interval_t *iv)
{
    double t_next = b->ts;
    if (!(b->t < b->ts - b->eps)) {
        return false;
    }
    inv_apply_edges(b);
    iv->nominal = b->legs.nominal_bits;
    iv->dead = inv_dead_legs(b);
    /* next breakpoint: leg edge, dead end or sample */
    while (b->i_br < b->n_br && b->br[b->i_br] <= b->t + b->eps) {
        b->i_br++;
    }
    if (b->i_br < b->n_br) {
        t_next = b->br[b->i_br];
    }
    iv->sample = false;
    if (b->smp.n > 0) {
        t_next = inv_sample_due(b, &iv->sample, t_next);
    }
    iv->t = b->t;
    iv->h = t_next - b->t;
    b->t = t_next;
    return true;
}

void inv_builder_finish(const inv_builder_t *b, inv_legs_t *legs)
{
    int k;
    legs->nominal_bits = b->legs.nominal_bits;
    for (k = 0; k < PLANT_PHASES; k++) {
        legs->dead_until[k] = b->legs.dead_until[k] - b->ts;
    }
    legs->dead_last = b->legs.dead_last - b->ts;
}

/* After a period that carried no dead interval in, the legs it did not switch keep their (past)
 * dead ends moved one period back; the others get the program's. */
void inv_program_finish(const inv_program_t *pr, double ts, inv_legs_t *legs)
{
    int k;
    legs->nominal_bits = pr->nominal_out;
    for (k = 0; k < PLANT_PHASES; k++) {
        legs->dead_until[k] = ((pr->changed & INV_LEG_BIT(k)) != 0u) ? pr->dead_until_out[k]
                                                                     : legs->dead_until[k] - ts;
    }
    legs->dead_last = (pr->changed != 0u) ? pr->dead_last_out : legs->dead_last - ts;
}

static uint64_t inv_key_hash(const double duty[PLANT_PHASES], unsigned nominal)
{
    uint64_t h = (uint64_t)nominal;
    int k;
    for (k = 0; k < PLANT_PHASES; k++) {
        uint64_t bits;
        memcpy(&bits, &duty[k], sizeof bits);
        h = (h ^ bits) * 0x9E3779B97F4A7C15ull;
        h ^= h >> 29;
    }
    return h >> (64 - INV_CACHE_SET_BITS);
}

/* The cache holds programs for the sample instants smp: allocated, and emptied when they change. */
static bool inv_cache_ready(inv_cache_t *c, const inv_sample_times_t *smp)
{
    const size_t n_bytes = (size_t)smp->n * sizeof(double);
    if (c->slot && smp->n == c->n_samples &&
        (smp->n == 0 || !memcmp(smp->t, c->sample_t, n_bytes))) {
        return true;
    }
    inv_cache_free(c);
    c->slot = (inv_program_t *)calloc(INV_CACHE_SLOTS, sizeof(inv_program_t));
    c->sample_t = (double *)malloc(n_bytes + sizeof(double));
    if (!c->slot || !c->sample_t) {
        inv_cache_free(c);
        return false;
    }
    if (smp->n > 0) {
        memcpy(c->sample_t, smp->t, n_bytes);
    }
    c->n_samples = smp->n;
    return true;
}

/* Build the whole period into pr; false when it holds too many intervals. */
static bool inv_program_build(inv_program_t *pr, const inv_legs_t *legs,
                              const double duty[PLANT_PHASES], double ts, double td,
                              const inv_sample_times_t *smp)
{
    inv_builder_t b;
    inv_interval_t iv;
    int k;
    inv_builder_start(&b, legs, duty, ts, td, smp);
    pr->n = 0;
    while (inv_builder_next(&b, &iv)) {
        if (pr->n >= INV_PROGRAM_MAX_INTERVALS) {
            return false;
        }
        pr->iv[pr->n++] = iv;
    }
    memcpy(pr->duty, duty, sizeof pr->duty);
    pr->nominal_in = legs->nominal_bits;
    pr->nominal_out = b.legs.nominal_bits;
    pr->changed = b.changed;
    for (k = 0; k < PLANT_PHASES; k++) {
        pr->dead_until_out[k] = b.legs.dead_until[k] - ts;
    }
    pr->dead_last_out = b.legs.dead_last - ts;
    pr->span_generation = 0u; /* no spans yet */
    return true;
}

static bool inv_program_is(const inv_program_t *pr, const inv_legs_t *legs,
                           const double duty[PLANT_PHASES])
{
    return pr->valid && pr->nominal_in == legs->nominal_bits &&
           !memcmp(pr->duty, duty, sizeof pr->duty);
}

inv_program_t *inv_cache_program(inv_cache_t *c, const inv_legs_t *legs,
                                 const double duty[PLANT_PHASES], double ts, double td,
                                 const inv_sample_times_t *smp)
{
    inv_program_t *set, *pr;
    if (c->off || legs->dead_last > 0.0 || !inv_cache_ready(c, smp)) {
        return NULL;
    }
    set = &c->slot[2u * inv_key_hash(duty, legs->nominal_bits)];
    if (inv_program_is(&set[0], legs, duty)) {
        set[1].recent = false;
        set[0].recent = true;
        c->hits++;
        return &set[0];
    }
    if (inv_program_is(&set[1], legs, duty)) {
        set[0].recent = false;
        set[1].recent = true;
        c->hits++;
        return &set[1];
    }
    pr = set[0].recent ? &set[1] : &set[0]; /* the least recently used way */
    pr->valid = inv_program_build(pr, legs, duty, ts, td, smp);
    c->built++;
    set[0].recent = set[1].recent = false;
    pr->recent = true;
    return pr->valid ? pr : NULL;
}

void inv_cache_free(inv_cache_t *c)
{
    free(c->slot);
    free(c->sample_t);
    c->slot = NULL;
    c->sample_t = NULL;
    c->n_samples = 0;
}
