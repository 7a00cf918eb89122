/* The reference model of the vector space decomposition, in double, from the defining formulas
 * of the method notes (§2 VSD matrix and phase-voltage formula, §3 switching states): what the
 * tests compare the control core's fixed-point and float transforms and tables with. */
#ifndef VSD_REFERENCE_H
#define VSD_REFERENCE_H

#include <stdint.h>

/* Amplitude-invariant alpha-beta-x-y components. */
typedef struct {
    double alpha;
    double beta;
    double x;
    double y;
} vsd_d;

/* Phase axes A B C D E F in degrees (method notes §2). */
extern const double vsd_ref_phase_deg[6];

/* The VSD of six phase quantities: sum_k p_k (cos th_k, sin th_k, cos 5th_k, sin 5th_k) / 3. */
vsd_d vsd_ref_forward(const double p[6]);

/* Switch state (0 or 1) of leg 0..5 (A..F) from the paper's octal name u_ab of a state 0..63:
 * a = [S_A S_B S_C] = v / 8, b = [S_D S_E S_F] = v % 8, most significant first. */
int32_t vsd_ref_state_leg(int32_t v, int32_t leg);

/* Voltage of switching state v per unit of Vdc (two isolated neutrals:
 * v_A = S_A - (S_A + S_B + S_C) / 3 etc.), then the VSD. */
vsd_d vsd_ref_state(int32_t v);

double vsd_ref_mag_ab(vsd_d u);
double vsd_ref_mag_xy(vsd_d u);

#endif /* VSD_REFERENCE_H */
