/*
 * `sixphase-sim reproduce`: the paper's comparison (brief §8; the runs in reproduce_cases.c)
 * run in parallel worker processes, the report beside the paper's numbers
 * (reproduce_report.c), and the plots (through the Python script found at configure time).
 */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS */

#include "reproduce.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "reproduce_cases.h"
#include "reproduce_report.h"
#include "sim.h"

#ifndef SIM_PLOT_PYTHON
#define SIM_PLOT_PYTHON ""
#endif
#ifndef SIM_PLOT_SCRIPT
#define SIM_PLOT_SCRIPT ""
#endif

static double rep_now(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Run cases[first..last) in up to `jobs` forked workers; results come back
 * through a shared anonymous mapping. */
static int rep_run_batch(rep_case_t *shared, int first, int last, int jobs, int quiet)
{
    pid_t pids[64];
    int idx[64];
    int running = 0, next = first, failures = 0, i;
    if (jobs > 64) {
        jobs = 64;
    }
    while (next < last || running > 0) {
        while (running < jobs && next < last) {
            pid_t pid = fork();
            if (pid < 0) {
                /* no fork: run in this process */
                rep_case_t *c = &shared[next];
                c->ok = (sim_run(&c->cfg, &c->res, c->err, sizeof c->err) == 0);
                next++;
                continue;
            }
            if (pid == 0) {
                rep_case_t *c = &shared[next];
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
            for (i = 0; i < running; i++) {
                if (pids[i] == done) {
                    rep_case_t *c = &shared[idx[i]];
                    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !c->ok) {
                        failures++;
                        c->ok = 0;
                        if (c->err[0] == '\0') {
                            (void)snprintf(c->err, sizeof c->err, "worker crashed");
                        }
                    }
                    if (!quiet) {
                        fprintf(stderr, "  %-28s %s  (%.0fx real time)\n", c->name,
                                c->ok ? "ok" : c->err, c->res.realtime_factor);
                    }
                    pids[i] = pids[running - 1];
                    idx[i] = idx[running - 1];
                    running--;
                    break;
                }
            }
        }
    }
    return failures;
}

static int rep_plot(const char *dir, int quiet)
{
    pid_t pid;
    int status = 0;
    if (SIM_PLOT_PYTHON[0] == '\0' || SIM_PLOT_SCRIPT[0] == '\0') {
        fprintf(stderr,
                "sixphase-sim: no Python with matplotlib found at configure time; plots skipped\n");
        return -1;
    }
    pid = fork();
    if (pid < 0) {
        return -1;
    }
    if (pid == 0) {
        char *argv[4];
        argv[0] = (char *)(uintptr_t)SIM_PLOT_PYTHON;
        argv[1] = (char *)(uintptr_t)SIM_PLOT_SCRIPT;
        argv[2] = (char *)(uintptr_t)dir;
        argv[3] = NULL;
        execv(SIM_PLOT_PYTHON, argv);
        _exit(127);
    }
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "sixphase-sim: plot script failed (status %d)\n", status);
        return -1;
    }
    if (!quiet) {
        fprintf(stderr, "plots written to %s/plots\n", dir);
    }
    return 0;
}

static void rep_write_gitignore(const char *out_dir)
{
    char path[1200];
    FILE *g;
    (void)snprintf(path, sizeof path, "%s/.gitignore", out_dir);
    g = fopen(path, "w");
    if (g) {
        fprintf(g, "# raw traces and host timings of the reproduce runs: regenerated, not "
                   "committed\nruns/\ntimings.md\n");
        (void)fclose(g);
    }
}

static int rep_write_all(const char *out_dir, const rep_case_t *cases, int n, double wall, int jobs)
{
    rep_write_gitignore(out_dir);
    if (rep_write_summary(out_dir, cases, n) != 0 || rep_write_report(out_dir, cases, n) != 0 ||
        rep_write_timings(out_dir, cases, n, wall, jobs) != 0) {
        fprintf(stderr, "sixphase-sim: cannot write the report in '%s'\n", out_dir);
        return -1;
    }
    return 0;
}

int sim_reproduce(const char *out_dir, int jobs, bool plots, int quiet)
{
    const size_t bytes = sizeof(rep_case_t) * REP_MAX_CASES;
    const double t0 = rep_now();
    rep_case_t *cases;
    int n = 0, n1, failures, rc;
    double wall;
    char err[1400];
    if (sim_check_out_dir(out_dir, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 1;
    }
    cases =
        (rep_case_t *)mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (cases == MAP_FAILED) {
        fprintf(stderr, "sixphase-sim: mmap failed\n");
        return 1;
    }
    memset(cases, 0, bytes);
    rep_cases_first_batch(cases, &n, out_dir);
    rep_cases_improvement_sweep(cases, &n, out_dir);
    n1 = n;
    if (!quiet) {
        fprintf(stderr, "reproduce: %d runs, %d workers\n", n1, jobs);
    }
    failures = rep_run_batch(cases, 0, n1, jobs, quiet);
    rep_cases_equal_switching(cases, &n, out_dir);
    failures += rep_run_batch(cases, n1, n, jobs, quiet);
    wall = rep_now() - t0;
    rc = rep_write_all(out_dir, cases, n, wall, jobs);
    if (rc == 0 && plots) {
        (void)rep_plot(out_dir, quiet);
    }
    if (rc == 0 && !quiet) {
        fprintf(stderr,
                "reproduce: %d runs, %d failed, %.1f s wall (runs %.1f s); report "
                "%s/report.md\n",
                n, failures, rep_now() - t0, wall, out_dir);
    }
    (void)munmap(cases, bytes);
    return (failures || rc != 0) ? 1 : 0;
}
