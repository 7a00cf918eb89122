/* The figure scripts, see plots.h. */
#define _DEFAULT_SOURCE /* fork, waitpid */

#include "plots.h"

#include <stdint.h>
#include <stdio.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef SIM_PLOT_PYTHON
#define SIM_PLOT_PYTHON ""
#endif
#ifndef SIM_PLOT_DIR
#define SIM_PLOT_DIR ""
#endif

static const char *const plot_scripts[] = {"plot_reproduce.py", "plot_sweep.py", "plot_run.py"};

int sim_plot(sim_plot_t which, const char *dir)
{
    char script[1200];
    pid_t pid;
    int status = 0;
    if (SIM_PLOT_PYTHON[0] == '\0' || SIM_PLOT_DIR[0] == '\0') {
        fprintf(stderr, "sixphase-sim: no Python with matplotlib found at configure time; "
                        "no plot\n");
        return -1;
    }
    (void)snprintf(script, sizeof script, "%s/%s", SIM_PLOT_DIR, plot_scripts[which]);
    pid = fork();
    if (pid == 0) {
        execl(SIM_PLOT_PYTHON, SIM_PLOT_PYTHON, script, dir, (char *)NULL);
        _exit(127);
    }
    if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "sixphase-sim: %s failed on %s\n", plot_scripts[which], dir);
        return -1;
    }
    return 0;
}
