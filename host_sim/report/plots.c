/* The figure scripts, see plots.h. */
#define _DEFAULT_SOURCE /* fork, waitpid */

#include "plots.h"

#include "run/batch.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef SIM_PLOT_PYTHON
#define SIM_PLOT_PYTHON ""
#endif
#ifndef SIM_PLOT_DIR
#define SIM_PLOT_DIR ""
#endif

static const char *const plot_scripts[] = {"plot_reproduce.py", "plot_sweep.py", "plot_run.py",
                                           "plot_pil.py"};

/* What the script wrote on stderr, the start of it when long (the rest is read and dropped). */
static void plot_collect(int fd, char *buf, size_t size)
{
    size_t used = 0;
    char sink[4096];
    ssize_t n;
    for (;;) {
        char *to = (used + 1 < size) ? buf + used : sink;
        const size_t room = (used + 1 < size) ? size - 1 - used : sizeof sink;
        n = read(fd, to, room);
        if (n <= 0) {
            break;
        }
        used += (to == sink) ? 0u : (size_t)n;
    }
    buf[used] = '\0';
}

/* The last non-empty line of text (a Python traceback ends with the error itself). */
static const char *plot_last_line(char *text)
{
    char *end = text + strlen(text);
    char *start;
    while (end > text && (end[-1] == '\n' || end[-1] == '\r' || end[-1] == ' ')) {
        *--end = '\0';
    }
    start = strrchr(text, '\n');
    return start ? start + 1 : text;
}

int sim_plot_start(sim_plot_t which, const char *dir, const char *part, sim_plot_job_t *job)
{
    int fds[2], gate[2];
    pid_t pid;
    job->pid = -1;
    job->fd = -1;
    job->gate_fd = -1;
    (void)snprintf(job->what, sizeof job->what, "%s on %s", plot_scripts[which], dir);
    if (SIM_PLOT_PYTHON[0] == '\0' || SIM_PLOT_DIR[0] == '\0') {
        fprintf(stderr, "sixphase-sim: no Python with matplotlib found at configure time; "
                        "no plot\n");
        return -1;
    }
    (void)snprintf(job->script, sizeof job->script, "%s/%s", SIM_PLOT_DIR, plot_scripts[which]);
    if (pipe(fds) != 0) {
        fprintf(stderr, "sixphase-sim: %s not started (no pipe)\n", job->what);
        return -1;
    }
    if (pipe(gate) != 0) {
        (void)close(fds[0]);
        (void)close(fds[1]);
        fprintf(stderr, "sixphase-sim: %s not started (no pipe)\n", job->what);
        return -1;
    }
    pid = fork();
    if (pid == 0) {
        (void)dup2(fds[1], 2);
        (void)dup2(gate[0], 0);
        (void)close(fds[0]);
        (void)close(fds[1]);
        (void)close(gate[0]);
        (void)close(gate[1]);
        if (part) {
            execl(SIM_PLOT_PYTHON, SIM_PLOT_PYTHON, job->script, dir, part, (char *)NULL);
        } else {
            execl(SIM_PLOT_PYTHON, SIM_PLOT_PYTHON, job->script, dir, (char *)NULL);
        }
        _exit(127);
    }
    (void)close(fds[1]);
    (void)close(gate[0]);
    if (pid < 0) {
        (void)close(fds[0]);
        (void)close(gate[1]);
        fprintf(stderr, "sixphase-sim: %s not started (no fork)\n", job->what);
        return -1;
    }
    /* the parent's ends stay out of the workers forked meanwhile: the script sees its gate
     * open when this process opens it, whatever runs then */
    (void)fcntl(fds[0], F_SETFD, FD_CLOEXEC);
    (void)fcntl(gate[1], F_SETFD, FD_CLOEXEC);
    job->pid = (int)pid;
    job->fd = fds[0];
    job->gate_fd = gate[1];
    return 0;
}

void sim_plot_open_gate(sim_plot_job_t *job)
{
    if (job->gate_fd >= 0) {
        (void)close(job->gate_fd);
        job->gate_fd = -1;
    }
}

/* The script's end: its gate opened, its stderr read to the end, its exit collected (here, or
 * by a batch of runs that reaped it while waiting for its workers, run/batch.h). True when it
 * exited with 0. */
static bool plot_end(sim_plot_job_t *job, char *output, size_t size)
{
    int status = 0;
    pid_t got;
    bool waited;
    sim_plot_open_gate(job);
    plot_collect(job->fd, output, size);
    (void)close(job->fd);
    do {
        got = waitpid((pid_t)job->pid, &status, 0);
    } while (got < 0 && errno == EINTR);
    waited = got == (pid_t)job->pid || sim_batch_reaped(job->pid, &status);
    job->pid = -1;
    return waited && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

int sim_plot_finish(sim_plot_job_t *job)
{
    char output[16384];
    if (job->pid < 0) {
        return -1;
    }
    if (!plot_end(job, output, sizeof output)) {
        /* one line: the script's own last word, not its traceback */
        fprintf(stderr, "sixphase-sim: %s failed: %s\n", job->what,
                output[0] ? plot_last_line(output) : "no message");
        return -1;
    }
    fputs(output, stderr); /* warnings of a script that worked */
    return 0;
}

void sim_plot_cancel(sim_plot_job_t *job)
{
    char output[256];
    if (job->pid < 0) {
        return;
    }
    (void)kill((pid_t)job->pid, SIGTERM);
    (void)plot_end(job, output, sizeof output);
}

int sim_plot(sim_plot_t which, const char *dir)
{
    sim_plot_job_t job;
    if (sim_plot_start(which, dir, NULL, &job) != 0) {
        return -1;
    }
    return sim_plot_finish(&job);
}
