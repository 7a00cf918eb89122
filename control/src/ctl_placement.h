/*
 * The control core's RAM placement marks (sixphase_placement.h), with the two that depend on
 * the arithmetic: code a control period runs in the float build only (the Q24 image runs
 * ctl_mptc_select from flash, docs/porting.md section 7, and no period calls ctl_sqrtf there),
 * and a table only the Q24 build's period reads (the square root's seed).
 */
#ifndef CTL_PLACEMENT_H
#define CTL_PLACEMENT_H

#include "ctl_q.h"
#include "sixphase_placement.h"

#if CTL_MATH_FLOAT
#define CTL_RAMFUNC_FLOAT SIXPHASE_RAMFUNC
#define CTL_RAMCONST_FIXED
#else
#define CTL_RAMFUNC_FLOAT
#define CTL_RAMCONST_FIXED SIXPHASE_RAMCONST
#endif

#endif /* CTL_PLACEMENT_H */
