/*
 * FOC-VSD's configuration (ctl_foc_types.h), built with the rest of a set's outside the ISR
 * (ctl_config_build).
 */
#ifndef CTL_FOC_CONFIG_H
#define CTL_FOC_CONFIG_H

#include "ctl_foc_types.h"
#include "ctl_params.h"

/* The bandwidth from p (SI); the current references come with the flux table
 * (ctl_flux_ref_init's id_pu, ctl_config_build). Background only. */
void ctl_foc_config_build(ctl_foc_config_t *f, const ctl_params_t *p);

#endif /* CTL_FOC_CONFIG_H */
