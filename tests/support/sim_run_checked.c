/* A simulator run that must succeed (sim_run_checked.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "sim_run_checked.h"

void sim_run_checked(const sim_config_t *c, sim_result_t *r)
{
    char err[256] = "";
    if (sim_run(c, r, err, sizeof err) != 0) {
        print_error("sim_run failed: %s\n", err);
        fail();
    }
}

void sim_run_quiet(sim_config_t *c, sim_result_t *r)
{
    c->out_dir = NULL;
    sim_run_checked(c, r);
}
