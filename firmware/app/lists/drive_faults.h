/*
 * The drive's faults, one list, declared by the application that raises them (issue 26: it
 * was the serial link's). Every drive fault code (drive_fault_t), its protection fault bit
 * (ctl_fault_t in control/include/ctl_protect.h), the drive's bit -> code map and its severity
 * order are generated from it, and the link maps it onto the wire and into the tools' names
 * (firmware/link/sxlink_faults.h); drive.c checks at compile time that each bit number here is
 * the control core's.
 *
 *   X(code name, code, bit name, bit number, description)
 *
 * Listed from the most severe: when several faults come in one period, the first one present
 * names it. Codes and bit numbers are on the wire (docs/serial-protocol.md): never renumber.
 * Plain macros, no firmware types, so the protocol library and host tools can use it.
 */
#ifndef DRIVE_FAULTS_H
#define DRIVE_FAULTS_H

#define DRIVE_FAULT_LIST(X)                                                                        \
    X(HW_TRIP, 4, HW_TRIP, 11, "hardware over-current trip zone fired")                            \
    X(OVERCURRENT, 8, OVERCURRENT, 0, "software phase over-current")                               \
    X(ADC_RAIL, 12, ADC_RAIL, 5, "a conversion at the rail (its value unknown)")                   \
    X(DC_OVERVOLTAGE, 9, DC_OVERVOLTAGE, 1, "DC link above the limit")                             \
    X(MEASUREMENT, 16, MEASUREMENT, 13, "a scaled measurement is not a number (float build)")      \
    X(ADC_MISSING, 3, ADC_MISSING, 14, "a control period without a new conversion")                \
    X(ADC_STUCK, 13, ADC_STUCK, 6, "a current channel frozen while current flows")                 \
    X(CURRENT_SUM, 14, CURRENT_SUM, 9, "a three-phase set does not sum to zero")                   \
    X(OPEN_PHASE, 15, OPEN_PHASE, 10, "one phase carries no current while the others do")          \
    X(ENCODER, 6, ENCODER, 4, "encoder unhealthy, stopped under torque, or angle jump")            \
    X(OVERSPEED, 11, OVERSPEED, 3, "speed above the limit")                                        \
    X(DC_UNDERVOLTAGE, 10, DC_UNDERVOLTAGE, 2, "DC link below the limit while running")            \
    X(OVERRUN, 5, OVERRUN, 8, "control ISR did not finish within its period")                      \
    X(ADC_OFFSET, 2, ADC_OFFSET, 7, "current-sensor offset out of range at calibration")           \
    X(PARAMS, 1, PARAMS, 12, "controller parameters unusable (not clearable)")                     \
    X(STARTUP, 7, PLATFORM, 15, "a peripheral failed to initialise (not clearable)")

/* Codes run from NONE (0) to the largest above; bits from 0 to 15. */
#define DRIVE_FAULT_CODE_COUNT 17u
#define DRIVE_FAULT_BIT_COUNT 16u

#endif /* DRIVE_FAULTS_H */
