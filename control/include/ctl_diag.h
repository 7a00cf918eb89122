/*
 * What a control step leaves for its diagnostics (ctl_diag, ctl.h): the measured currents and
 * the estimates from them, the references and the choice. Below ctl.h, so the steps' shared
 * recorder (ctl_diag_record.h) does not include the controller it records for.
 */
#ifndef CTL_DIAG_H
#define CTL_DIAG_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_q.h"

typedef struct {
    ctl_q i_d, i_q, i_x, i_y;   /* measured, at sample k */
    ctl_q torque_est;           /* Te(k) from measured currents */
    ctl_q psi_d_est, psi_q_est; /* psi_s(k) in the rotor frame; |psi_s|: ctl_diag_flux_est */
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
