/*
 * Many simulation runs in parallel worker processes (reproduce, sweep): each case is a
 * configuration, its result comes back through memory the caller shares with the workers
 * (an anonymous shared mapping), one case per worker process.
 */
#ifndef SIM_BATCH_H
#define SIM_BATCH_H

#include "sim.h"

typedef struct {
    char name[64];
    char group[16];
    sim_config_t cfg;
    sim_result_t res;
    int ok;
    char err[320];
} sim_case_t;

/* Called in the parent as each case finishes: done of total finished so far. */
typedef void (*sim_batch_done_fn)(void *ctx, const sim_case_t *c, int done, int total);

/* Runs cases[first..last) in up to `jobs` forked workers (in this process when fork fails);
 * cases must be in memory the workers share. Returns how many failed. */
int sim_batch_run(sim_case_t *cases, int first, int last, int jobs, sim_batch_done_fn done,
                  void *ctx);

/* sim_batch_run reaps whichever child exits while it waits for its workers; one that is not a
 * worker (a plot drawn meanwhile, report/plots.c) leaves its exit status here, for its owner:
 * true, with *status, when pid was reaped so (each status is handed out once). */
bool sim_batch_reaped(int pid, int *status);

/* An anonymous shared mapping for n cases (zeroed); NULL on failure. */
sim_case_t *sim_batch_alloc(int n);
void sim_batch_free(sim_case_t *cases, int n);

#endif /* SIM_BATCH_H */
