/*
 * The signals the drive's capture buffer can record: one list, shared by the firmware
 * (firmware/app/capture.c), the serial protocol and the host tool (sixphase-link capture).
 *
 * X(id, name, unit, base, exponent): a sample is the signal in per unit of `base` (SI units
 * per unit) scaled by 2^(15 - exponent) into a signed 16-bit word, so |value| < 2^exponent
 * per unit fits; SI = sample * base / 2^(15 - exponent). Integer signals (the vector) use
 * base 1 and exponent 15: the sample is the value. The bases are the control core's per-unit
 * bases (control/include/ctl_pu.h); only the host uses them.
 */
#ifndef CAPTURE_SIGNALS_H
#define CAPTURE_SIGNALS_H

#define CAPTURE_SIGNAL_LIST(X)                                                                     \
    X(CAPTURE_I_A, "i_a", "A", 10.0, 3)                                                            \
    X(CAPTURE_I_B, "i_b", "A", 10.0, 3)                                                            \
    X(CAPTURE_I_C, "i_c", "A", 10.0, 3)                                                            \
    X(CAPTURE_I_D_PHASE, "i_D", "A", 10.0, 3)                                                      \
    X(CAPTURE_I_E, "i_E", "A", 10.0, 3)                                                            \
    X(CAPTURE_I_F, "i_F", "A", 10.0, 3)                                                            \
    X(CAPTURE_ID, "id", "A", 10.0, 3)                                                              \
    X(CAPTURE_IQ, "iq", "A", 10.0, 3)                                                              \
    X(CAPTURE_IX, "ix", "A", 10.0, 3)                                                              \
    X(CAPTURE_IY, "iy", "A", 10.0, 3)                                                              \
    X(CAPTURE_TORQUE, "torque", "N*m", 17.188733853924696, 2)                                      \
    X(CAPTURE_TORQUE_REF, "torque_ref", "N*m", 17.188733853924696, 2)                              \
    X(CAPTURE_FLUX, "flux", "Wb", 0.57295779513082321, 1)                                          \
    X(CAPTURE_FLUX_REF, "flux_ref", "Wb", 0.57295779513082321, 1)                                  \
    X(CAPTURE_SPEED, "speed_e", "rad/s", 942.47779607693797, 2)                                    \
    X(CAPTURE_SPEED_REF, "speed_ref_e", "rad/s", 942.47779607693797, 2)                            \
    X(CAPTURE_VECTOR, "vector", "state", 1.0, 15)                                                  \
    X(CAPTURE_DUTY, "duty", "1", 1.0, 0)                                                           \
    X(CAPTURE_COST, "cost", "pu", 1.0, 4)                                                          \
    X(CAPTURE_VDC, "vdc", "V", 540.0, 1)

#define CAPTURE_SIGNAL_ENUM(id, name, unit, base, exponent) id,
enum { CAPTURE_SIGNAL_LIST(CAPTURE_SIGNAL_ENUM) CAPTURE_SIGNAL_COUNT };
#undef CAPTURE_SIGNAL_ENUM

#endif /* CAPTURE_SIGNALS_H */
