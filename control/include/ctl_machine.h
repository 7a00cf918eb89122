/*
 * The reference machine: the paper's asymmetrical six-phase PMSM with the brief's assumed
 * values where the paper gives none (method-notes §6). One table, used by the controller's
 * default parameters (ctl_params_default) and by the simulator's plant
 * (plant_params_default), so the model the controller assumes and the machine it drives in
 * the simulator cannot drift apart by accident. SI units.
 */
#ifndef CTL_MACHINE_H
#define CTL_MACHINE_H

#define CTL_MACHINE_R_OHM 2.0
#define CTL_MACHINE_LD_H 0.035
#define CTL_MACHINE_LQ_H 0.055
#define CTL_MACHINE_LXY_H 0.010 /* x-y (leakage) inductance */
#define CTL_MACHINE_PSI_F_WB 0.225
#define CTL_MACHINE_POLE_PAIRS 3
#define CTL_MACHINE_INERTIA_KG_M2 0.01
#define CTL_MACHINE_VDC_V 540.0

#endif /* CTL_MACHINE_H */
