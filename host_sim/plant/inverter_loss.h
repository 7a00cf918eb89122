/*
 * An estimate of the inverter's semiconductor losses, to compare controllers at one operating
 * point (issue 27), not to design a heat sink: an assumed generic 1200 V / 25 A IGBT module with
 * its diodes, the IGBT's and the diode's figures taken alike.
 *   conduction: per phase V0 |i| + r_on i^2, averaged (the mean |i| of a sinusoid, 2 sqrt 2 / pi
 *               times the rms, stands for the measured one)
 *   switching:  per leg transition E_ts / 2 scaled by Vdc / V_REF and |i| / I_REF (a transition
 *               is half of an on-off cycle, whose energy E_ts is the datasheet's E_on + E_off)
 * The ranking between controllers follows their switched current and rms current; the absolute
 * watts only as far as the assumed figures hold.
 */
#ifndef SIM_INVERTER_LOSS_H
#define SIM_INVERTER_LOSS_H

#define INV_LOSS_V0_V 1.0      /* threshold voltage */
#define INV_LOSS_R_ON_OHM 0.04 /* slope resistance */
#define INV_LOSS_E_TS_J 3.5e-3 /* E_on + E_off at V_REF, I_REF */
#define INV_LOSS_V_REF_V 600.0
#define INV_LOSS_I_REF_A 25.0
#define INV_LOSS_MEAN_OVER_RMS 0.9003163161571061 /* 2 sqrt(2) / pi */

/* Conduction loss of six phases of rms current i_rms (A), W. */
static inline double inv_loss_conduction_w(double i_rms)
{
    return 6.0 *
           (INV_LOSS_V0_V * INV_LOSS_MEAN_OVER_RMS * i_rms + INV_LOSS_R_ON_OHM * i_rms * i_rms);
}

/* Switching loss of transitions commutating switched_amps in all over window_s at vdc, W. */
static inline double inv_loss_switching_w(double switched_amps, double vdc, double window_s)
{
    return 0.5 * INV_LOSS_E_TS_J * (vdc / INV_LOSS_V_REF_V) * (switched_amps / INV_LOSS_I_REF_A) /
           window_s;
}

#endif /* SIM_INVERTER_LOSS_H */
