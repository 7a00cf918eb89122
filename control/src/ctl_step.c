/*
 * ctl_step (ctl.h): the published parameter set taken, then the period handed to the healthy
 * step (ctl.c), FOC-VSD's (ctl_foc.c) or the open-phase step (ctl_postfault.c). A file of its
 * own so that no step is inlined here: their frames are never on the stack at once, and the larger
 * one sets the control interrupt's depth (tools/check_stack_bound.sh).
 */
#include "ctl.h"
#include "ctl_foc.h"
#include "ctl_placement.h"
#include "ctl_postfault.h"

SIXPHASE_RAMFUNC void ctl_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd)
{
    if (c->config_ready != 0) { /* the common case decided here: ctl_config_take is in ctl.c */
        (void)ctl_config_take(c);
    }
    if (c->healthy_step) { /* one test on the healthy path, as before open phases */
        if (c->foc_step) { /* and one for FOC-VSD, whose frame is not nested in the MPC's */
            ctl_foc_healthy_step(c, m, cmd);
        } else {
            ctl_healthy_step(c, m, cmd);
        }
    } else {
        ctl_postfault_step(c, m, cmd);
    }
}
