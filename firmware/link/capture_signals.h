/*
 * The signals the drive's capture buffer can record: one list, shared by the firmware
 * (firmware/app/capture/capture.c), the serial protocol and the host tool (sixphase-link capture).
 *
 * X(id, name, unit, base, exponent): a sample is the signal in per unit of `base` (SI units
 * per unit) scaled by 2^(15 - exponent) into a signed 16-bit word, so |value| < 2^exponent
 * per unit fits; SI = sample * base / 2^(15 - exponent). Integer signals (the vector) use
 * base 1 and exponent 15: the sample is the value. The bases are the control core's per-unit
 * bases (control/include/ctl_pu.h), taken from there; only the host uses them.
 */
#ifndef CAPTURE_SIGNALS_H
#define CAPTURE_SIGNALS_H

#include "ctl_pu.h" /* the bases, defined once */

#define CAPTURE_SIGNAL_LIST(X)                                                                     \
    X(CAPTURE_I_A, "i_a", "A", CTL_BASE_CURRENT_A, 3)                                              \
    X(CAPTURE_I_B, "i_b", "A", CTL_BASE_CURRENT_A, 3)                                              \
    X(CAPTURE_I_C, "i_c", "A", CTL_BASE_CURRENT_A, 3)                                              \
    X(CAPTURE_I_D_PHASE, "i_D", "A", CTL_BASE_CURRENT_A, 3)                                        \
    X(CAPTURE_I_E, "i_E", "A", CTL_BASE_CURRENT_A, 3)                                              \
    X(CAPTURE_I_F, "i_F", "A", CTL_BASE_CURRENT_A, 3)                                              \
    X(CAPTURE_ID, "id", "A", CTL_BASE_CURRENT_A, 3)                                                \
    X(CAPTURE_IQ, "iq", "A", CTL_BASE_CURRENT_A, 3)                                                \
    X(CAPTURE_IX, "ix", "A", CTL_BASE_CURRENT_A, 3)                                                \
    X(CAPTURE_IY, "iy", "A", CTL_BASE_CURRENT_A, 3)                                                \
    X(CAPTURE_TORQUE, "torque", "N*m", CTL_BASE_TORQUE_NM, 2)                                      \
    X(CAPTURE_TORQUE_REF, "torque_ref", "N*m", CTL_BASE_TORQUE_NM, 2)                              \
    X(CAPTURE_FLUX, "flux", "Wb", CTL_BASE_FLUX_WB, 1)                                             \
    X(CAPTURE_FLUX_REF, "flux_ref", "Wb", CTL_BASE_FLUX_WB, 1)                                     \
    X(CAPTURE_SPEED, "speed_e", "rad/s", CTL_BASE_OMEGA_RAD_S, 2)                                  \
    X(CAPTURE_SPEED_REF, "speed_ref_e", "rad/s", CTL_BASE_OMEGA_RAD_S, 2)                          \
    X(CAPTURE_VECTOR, "vector", "state", 1.0, 15)                                                  \
    X(CAPTURE_DUTY, "duty", "1", 1.0, 0)                                                           \
    X(CAPTURE_COST, "cost", "pu", 1.0, 4)                                                          \
    X(CAPTURE_VDC, "vdc", "V", CTL_BASE_VOLTAGE_V, 1)

#define CAPTURE_SIGNAL_ENUM(id, name, unit, base, exponent) id,
enum { CAPTURE_SIGNAL_LIST(CAPTURE_SIGNAL_ENUM) CAPTURE_SIGNAL_COUNT };
#undef CAPTURE_SIGNAL_ENUM

#endif /* CAPTURE_SIGNALS_H */
