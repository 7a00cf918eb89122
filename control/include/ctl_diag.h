/*
 * What a control step leaves for its diagnostics (ctl_diag, ctl.h): the measured currents, the
 * references and the choice. The estimates from the currents are left to their readers. Below
 * ctl.h, so the steps' shared recorder (ctl_diag_record.h) does not include the controller it
 * records for.
 */
#ifndef CTL_DIAG_H
#define CTL_DIAG_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_q.h"

typedef struct {
    ctl_q i_d, i_q, i_x, i_y; /* measured, at sample k; Te(k) and |psi_s|(k) from them:
                               * ctl_diag_torque_est, ctl_diag_flux_est (ctl.h) */
    ctl_q torque_ref;
    ctl_q flux_ref;
    ctl_q torque_pred; /* chosen candidate, at k+2 */
    ctl_q flux_pred;
    ctl_q cost;
    int16_t flux_sector; /* alpha-beta sector 0..11 at k+1 (DDC) */
    int16_t xy_sector;   /* x-y sector used by table 2 (DDC) */
    int16_t candidates;  /* candidates evaluated this step */
    bool braking;        /* DDC used the torque-lowering half of table 1 */
} ctl_diag_t;

#endif /* CTL_DIAG_H */
