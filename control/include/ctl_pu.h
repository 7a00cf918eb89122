/*
 * Per-unit base table: the single place that says what 1.0 means for every
 * quantity the control core handles. Every file that converts between SI and
 * per unit (ADC scaling in the firmware, the simulator bridge, parameter init)
 * uses these and nothing else.
 *
 *   quantity          base                         value
 *   voltage           V_b                          540 V (nominal DC link)
 *   current           I_b                          10 A
 *   electrical speed  w_b                          2*pi*150 rad/s (3000 r/min at Pn = 3)
 *   time              t_b = 1 / w_b                1.061 ms
 *   flux linkage      psi_b = V_b / w_b            0.5730 Wb
 *   impedance         Z_b = V_b / I_b              54 ohm
 *   inductance        L_b = Z_b / w_b              57.30 mH
 *   torque            T_b = 3 * psi_b * I_b        17.19 N*m per pole pair
 *
 * Torque in per unit is therefore Pn * (psi_d i_q - psi_q i_d) with every
 * factor in per unit; Pn stays an integer multiplier.
 * Angles are in per unit of one electrical turn (1.0 = 360 deg).
 *
 * The constants are plain literals so that host code may use them in double
 * and target code in float; convert with an explicit cast.
 */
#ifndef CTL_PU_H
#define CTL_PU_H

#define CTL_BASE_VOLTAGE_V 540.0
#define CTL_BASE_CURRENT_A 10.0
#define CTL_BASE_OMEGA_RAD_S 942.47779607693797 /* electrical */
#define CTL_BASE_TIME_S (1.0 / CTL_BASE_OMEGA_RAD_S)
#define CTL_BASE_FLUX_WB (CTL_BASE_VOLTAGE_V / CTL_BASE_OMEGA_RAD_S)
#define CTL_BASE_IMPEDANCE_OHM (CTL_BASE_VOLTAGE_V / CTL_BASE_CURRENT_A)
#define CTL_BASE_INDUCTANCE_H (CTL_BASE_IMPEDANCE_OHM / CTL_BASE_OMEGA_RAD_S)
#define CTL_BASE_TORQUE_NM (3.0 * CTL_BASE_FLUX_WB * CTL_BASE_CURRENT_A)

#define CTL_TWO_PI 6.28318530717958648

#endif
