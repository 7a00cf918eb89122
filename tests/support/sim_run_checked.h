/* A simulator run (sim.h) that must succeed: on an error the test fails with sim_run's
 * message. */
#ifndef SIM_RUN_CHECKED_H
#define SIM_RUN_CHECKED_H

#include "run/sim.h"

void sim_run_checked(const sim_config_t *c, sim_result_t *r);
/* The same without output files: c->out_dir cleared first. */
void sim_run_quiet(sim_config_t *c, sim_result_t *r);

#endif /* SIM_RUN_CHECKED_H */
