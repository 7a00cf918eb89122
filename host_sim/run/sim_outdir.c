/* Output directories of runs and of reproduce, see sim.h. */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "sim.h"

int sim_make_dirs(const char *path)
{
    char buf[1024];
    size_t i, n = strlen(path);
    if (n == 0 || n >= sizeof buf) {
        return -1;
    }
    memcpy(buf, path, n + 1);
    for (i = 1; i <= n; i++) {
        if (buf[i] == '/' || buf[i] == '\0') {
            const char save = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
                return -1;
            }
            buf[i] = save;
        }
    }
    return 0;
}

int sim_check_out_dir(const char *dir, char *err, size_t err_len)
{
    char probe[1200];
    FILE *f;
    if (sim_make_dirs(dir) != 0) {
        (void)snprintf(err, err_len, "cannot create the output directory '%s': %s", dir,
                       strerror(errno));
        return -1;
    }
    (void)snprintf(probe, sizeof probe, "%s/.sixphase-sim-write-test", dir);
    f = fopen(probe, "w");
    if (!f) {
        (void)snprintf(err, err_len, "cannot write to the output directory '%s': %s", dir,
                       strerror(errno));
        return -1;
    }
    (void)fclose(f);
    (void)remove(probe);
    return 0;
}
