/* Parallel simulation runs, see batch.h. */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS */

#include "batch.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

sim_case_t *sim_batch_alloc(int n)
{
    void *p = mmap(NULL, sizeof(sim_case_t) * (size_t)n, PROT_READ | PROT_WRITE,
                   MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) {
        return NULL;
    }
    memset(p, 0, sizeof(sim_case_t) * (size_t)n);
    return (sim_case_t *)p;
}

void sim_batch_free(sim_case_t *cases, int n)
{
    if (cases) {
        (void)munmap(cases, sizeof(sim_case_t) * (size_t)n);
    }
}

/* Children reaped here that were not workers: their statuses until their owner asks. */
#define BATCH_OTHERS 8
static struct {
    pid_t pid;
    int status;
} batch_others[BATCH_OTHERS];

static void batch_note_other(pid_t pid, int status)
{
    int k;
    for (k = 0; k < BATCH_OTHERS; k++) {
        if (batch_others[k].pid == 0) {
            batch_others[k].pid = pid;
            batch_others[k].status = status;
            return;
        }
    }
}

bool sim_batch_reaped(int pid, int *status)
{
    int k;
    for (k = 0; k < BATCH_OTHERS; k++) {
        if (batch_others[k].pid == (pid_t)pid && pid > 0) {
            *status = batch_others[k].status;
            batch_others[k].pid = 0;
            return true;
        }
    }
    return false;
}

/* Run cases[first..last) in up to `jobs` forked workers; results come back
 * through a shared anonymous mapping. */
int sim_batch_run(sim_case_t *shared, int first, int last, int jobs, sim_batch_done_fn done_fn,
                  void *ctx)
{
    pid_t pids[64];
    int idx[64];
    int running = 0, next = first, failures = 0, finished = 0, i;
    if (jobs > 64) {
        jobs = 64;
    }
    while (next < last || running > 0) {
        while (running < jobs && next < last) {
            pid_t pid = fork();
            if (pid < 0) {
                /* no fork: run in this process */
                sim_case_t *c = &shared[next];
                c->ok = (sim_run(&c->cfg, &c->res, c->err, sizeof c->err) == 0);
                failures += c->ok ? 0 : 1;
                next++;
                finished++;
                if (done_fn) {
                    done_fn(ctx, c, finished, last - first);
                }
                continue;
            }
            if (pid == 0) {
                sim_case_t *c = &shared[next];
                c->ok = (sim_run(&c->cfg, &c->res, c->err, sizeof c->err) == 0);
                _exit(c->ok ? 0 : 1);
            }
            pids[running] = pid;
            idx[running] = next;
            running++;
            next++;
        }
        if (running > 0) {
            int status = 0;
            const pid_t done = wait(&status);
            if (done < 0) {
                if (errno == EINTR) {
                    continue;
                }
                break;
            }
            for (i = 0; i < running && pids[i] != done; i++) {
            }
            if (i == running) {
                batch_note_other(done, status); /* not a worker: a plot drawn meanwhile */
                continue;
            }
            {
                sim_case_t *c = &shared[idx[i]];
                if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !c->ok) {
                    failures++;
                    c->ok = 0;
                    if (c->err[0] == '\0') {
                        (void)snprintf(c->err, sizeof c->err, "worker crashed");
                    }
                }
                finished++;
                if (done_fn) {
                    done_fn(ctx, c, finished, last - first);
                }
                pids[i] = pids[running - 1];
                idx[i] = idx[running - 1];
                running--;
            }
        }
    }
    return failures;
}
