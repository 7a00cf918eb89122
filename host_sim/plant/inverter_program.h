/*
 * The switching program of one carrier period: its constant-voltage intervals in time order,
 * each with the commanded leg states and the legs in a dead interval (whose state follows the
 * sign of their current, known only when the plant gets there), and the sampling instants the
 * caller asked for. Everything in it follows from the duties, the legs' commanded state at the
 * period start and any dead interval carried over from the last period; none of it from the
 * plant. So a period with the duties, start state and samples of an earlier one repeats that
 * program exactly, and the inverter keeps recent programs (a cache keyed by those inputs)
 * instead of sorting edges and merging breakpoints again: the drives repeat a few hundred duty
 * patterns over and over.
 *
 * The rules (inverter.h): leg k with duty d is commanded on in [(1-d)/2 Ts, (1+d)/2 Ts); after
 * every commanded transition the leg is dead for td; instants closer than eps = Ts 1e-12 are one.
 */
#ifndef SIM_INVERTER_PROGRAM_H
#define SIM_INVERTER_PROGRAM_H

#include <stdbool.h>

#include "plant.h"
#include "plant_exact.h"

/* Transition instants per period: the start, the rising and the falling edges of six legs. */
#define INV_MAX_EDGES (1 + 2 * PLANT_PHASES)
/* Instants the voltage may change at: the edges, their dead-interval ends, the ends carried
 * over from the last period and the period end. */
#define INV_MAX_BREAKS (2 * INV_MAX_EDGES + PLANT_PHASES + 1)

#define INV_LEG_BIT(k) (1u << (5 - (k))) /* S_A = bit 5 */

/* The legs' switching state carried from period to period. Times are relative to the start of
 * the period about to run. */
typedef struct {
    unsigned nominal_bits;           /* commanded state (gate signals before the dead band) */
    double dead_until[PLANT_PHASES]; /* end of each leg's latest dead interval */
    double dead_last;                /* the latest of dead_until[]: > 0 carries into the period */
} inv_legs_t;

/* One constant-voltage interval. */
typedef struct {
    double t, h;           /* start (relative to the period start) and length, s */
    plant_exact_span_t sp; /* the integrator's length-only coefficients (the inverter's) */
    unsigned nominal;      /* commanded leg states */
    unsigned dead;         /* legs in a dead interval at t */
    bool sample;           /* the caller's sample is taken at t */
} inv_interval_t;

/* Where the caller samples the plant within the period (sorted, in [0, Ts)). */
typedef struct {
    const double *t;
    int n;
} inv_sample_times_t;

/* Builds a period's intervals one at a time (no limit on their number). */
typedef struct {
    inv_legs_t legs; /* as they evolve through the period */
    double ts, td, eps, t;
    unsigned changed; /* legs that started a dead interval in this period */
    struct {
        double t;
        unsigned set, clear; /* legs commanded to 1, to 0 */
    } edge[INV_MAX_EDGES];
    double br[INV_MAX_BREAKS];
    int n_edges, n_br, i_edge, i_br, i_smp;
    inv_sample_times_t smp;
} inv_builder_t;

/* Start the period: duties (fractions, clamped to 0..1) from the carried state `legs`. */
void inv_builder_start(inv_builder_t *b, const inv_legs_t *legs, const double duty[PLANT_PHASES],
                       double ts, double td, const inv_sample_times_t *smp);

/* The next interval into *iv (its sp left alone); false after the last. */
bool inv_builder_next(inv_builder_t *b, inv_interval_t *iv);

/* The carried state at the end of the built period, as the next period sees it. */
void inv_builder_finish(const inv_builder_t *b, inv_legs_t *legs);

/* A cached program: the intervals of one period and what it leaves for the next. */
#define INV_PROGRAM_MAX_INTERVALS 40
typedef struct {
    double duty[PLANT_PHASES]; /* key: the duties as given, */
    unsigned nominal_in;       /* the commanded state at the start (no dead interval carried in) */
    bool valid;
    bool recent;              /* the more recently used of its set's two */
    unsigned span_generation; /* the integrator's coefficients the spans were made with */
    int n;
    unsigned nominal_out, changed; /* changed: legs whose dead interval ends at dead_until_out */
    double dead_until_out[PLANT_PHASES], dead_last_out;
    inv_interval_t iv[INV_PROGRAM_MAX_INTERVALS];
} inv_program_t;

/* Recent programs of one inverter with one set of sample instants. */
typedef struct {
    inv_program_t *slot; /* INV_CACHE_SLOTS in sets of two; allocated on first use */
    double *sample_t;    /* the sample instants the programs were built with */
    int n_samples;
    bool off;                  /* build every period as it runs (tests compare the two) */
    unsigned long hits, built; /* periods run from a cached program, programs built */
} inv_cache_t;

/* The program of a period with these inputs from the cache, built into it first when it is not
 * there (programs made with other sample instants are dropped first); NULL when the period cannot
 * be cached (a dead interval carried in, more intervals than a program holds, no memory): the
 * caller then builds it as it runs. */
inv_program_t *inv_cache_program(inv_cache_t *c, const inv_legs_t *legs,
                                 const double duty[PLANT_PHASES], double ts, double td,
                                 const inv_sample_times_t *smp);

/* The carried state after a cached program (legs as it started from). */
void inv_program_finish(const inv_program_t *pr, double ts, inv_legs_t *legs);

void inv_cache_free(inv_cache_t *c);

#endif /* SIM_INVERTER_PROGRAM_H */
