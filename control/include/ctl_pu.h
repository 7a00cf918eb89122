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
 * Every base is a literal, never an expression: on the C28x (COFF) double is
 * 32 bits, so an expression of doubles would be folded with other roundings
 * than on the host. The derived values are written out to 17 digits (the test
 * suite checks them against their definitions). Host code uses the double
 * literals; target code uses the _F forms, float literals that every compiler
 * rounds once, to the nearest float.
 */
#ifndef CTL_PU_H
#define CTL_PU_H

#define CTL_BASE_VOLTAGE_V 540.0
#define CTL_BASE_CURRENT_A 10.0
#define CTL_BASE_OMEGA_RAD_S 942.47779607693797    /* electrical, 2 pi 150 */
#define CTL_BASE_TIME_S 1.0610329539459689e-3      /* 1 / w_b */
#define CTL_BASE_FLUX_WB 0.57295779513082321       /* V_b / w_b */
#define CTL_BASE_IMPEDANCE_OHM 54.0                /* V_b / I_b */
#define CTL_BASE_INDUCTANCE_H 0.057295779513082325 /* Z_b / w_b */
#define CTL_BASE_TORQUE_NM 17.188733853924696      /* 3 psi_b I_b */

#define CTL_TWO_PI 6.2831853071795865

/* A float literal from a double literal above: 0.5 -> 0.5f. */
#define CTL_FLOAT_LITERAL(x) CTL_FLOAT_LITERAL_(x)
#define CTL_FLOAT_LITERAL_(x) x##f

#define CTL_BASE_VOLTAGE_V_F CTL_FLOAT_LITERAL(CTL_BASE_VOLTAGE_V)
#define CTL_BASE_CURRENT_A_F CTL_FLOAT_LITERAL(CTL_BASE_CURRENT_A)
#define CTL_BASE_OMEGA_RAD_S_F CTL_FLOAT_LITERAL(CTL_BASE_OMEGA_RAD_S)
#define CTL_BASE_TIME_S_F CTL_FLOAT_LITERAL(CTL_BASE_TIME_S)
#define CTL_BASE_FLUX_WB_F CTL_FLOAT_LITERAL(CTL_BASE_FLUX_WB)
#define CTL_BASE_IMPEDANCE_OHM_F CTL_FLOAT_LITERAL(CTL_BASE_IMPEDANCE_OHM)
#define CTL_BASE_INDUCTANCE_H_F CTL_FLOAT_LITERAL(CTL_BASE_INDUCTANCE_H)
#define CTL_BASE_TORQUE_NM_F CTL_FLOAT_LITERAL(CTL_BASE_TORQUE_NM)
#define CTL_TWO_PI_F CTL_FLOAT_LITERAL(CTL_TWO_PI)

#endif
