/* The figure scripts, see plots.h. */
#define _DEFAULT_SOURCE /* fork, waitpid */

#include "plots.h"

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

static const char *const plot_scripts[] = {"plot_reproduce.py", "plot_sweep.py", "plot_run.py"};

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

int sim_plot(sim_plot_t which, const char *dir)
{
    char script[1200], output[16384];
    int fds[2], status = 0;
    pid_t pid;
    if (SIM_PLOT_PYTHON[0] == '\0' || SIM_PLOT_DIR[0] == '\0') {
        fprintf(stderr, "sixphase-sim: no Python with matplotlib found at configure time; "
                        "no plot\n");
        return -1;
    }
    (void)snprintf(script, sizeof script, "%s/%s", SIM_PLOT_DIR, plot_scripts[which]);
    if (pipe(fds) != 0) {
        fprintf(stderr, "sixphase-sim: %s not started on %s (no pipe)\n", plot_scripts[which], dir);
        return -1;
    }
    pid = fork();
    if (pid == 0) {
        (void)dup2(fds[1], 2);
        (void)close(fds[0]);
        (void)close(fds[1]);
        execl(SIM_PLOT_PYTHON, SIM_PLOT_PYTHON, script, dir, (char *)NULL);
        _exit(127);
    }
    (void)close(fds[1]);
    plot_collect(fds[0], output, sizeof output);
    (void)close(fds[0]);
    if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        /* one line: the script's own last word, not its traceback */
        fprintf(stderr, "sixphase-sim: %s failed on %s: %s\n", plot_scripts[which], dir,
                output[0] ? plot_last_line(output) : "no message");
        return -1;
    }
    fputs(output, stderr); /* warnings of a script that worked */
    return 0;
}
