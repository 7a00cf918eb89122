/*
 * The commissioning's lists, declared by the application that runs the sequence (issue 26: they
 * were the serial link's): the steps, the quantities it identifies, each result's quality and
 * reason, the sequence's states, the apply rule and the test current's range. ident.h makes the
 * firmware's enums of them; the link maps them onto the wire and into the tools' names
 * (firmware/link/sxlink_commission.h, the same lists under SXL_COMM_ names). Numbers are on the
 * wire: never renumber. Plain macros, no firmware types, so host programs can use them.
 */
#ifndef COMMISSION_LISTS_H
#define COMMISSION_LISTS_H

/* Steps, in the order they run: X(id, number, name, what it does). A step mask has bit
 * (1 << number) per step. */
#define COMM_STEP_LIST(X)                                                                          \
    X(PHASES, 0, "phases", "phase check: each phase carries its share of a test current")          \
    X(ENCODER, 1, "encoder", "encoder direction, counts per electrical turn and index offset")     \
    X(RESISTANCE, 2, "r", "stator resistance from DC current at two levels")                       \
    X(INDUCTANCE, 3, "ldq", "L_d and L_q from a square wave at standstill")                        \
    X(LXY, 4, "lxy", "L_xy from a square wave in the x-y plane")                                   \
    X(FLUX, 5, "psi_f", "magnet flux at steady speed")                                             \
    X(MECH, 6, "mech", "friction at steady speeds, inertia from acceleration-deceleration runs")

#define COMM_STEP_COUNT 7u
#define COMM_STEPS_ALL 0x7Fu
/* The phase check always runs first, and every step after the encoder's needs it: a mask
 * without bit PHASES, or with any of bits 2..6 but not ENCODER, is refused. The rule, for the
 * drive (comm_mask_valid) and the host tools alike; mask an unsigned value. */
#define COMM_STEPS_VALID(mask)                                                                     \
    (((mask) & ~COMM_STEPS_ALL) == 0u && ((mask)&0x1u) != 0u &&                                    \
     (((mask)&0x7Cu) == 0u || ((mask)&0x2u) != 0u))

/* Quantities: X(id, number, name, the step that identifies it, unit, scale, extra scale, extra's
 * meaning). The reply carries value and uncertainty as int32 of the SI value times scale, the
 * extra times its own scale. */
#define COMM_QUANTITY_LIST(X)                                                                      \
    X(PHASES, 0, "phases", PHASES, "", 1000.0, 1.0,                                                \
      "smallest phase current over its share (value); the phase that failed, 0..5 = A..F, or -1")  \
    X(COUNTS, 1, "counts_per_elec_turn", ENCODER, "counts", 1000.0, 1.0,                           \
      "pole pairs the count implies")                                                              \
    X(OFFSET, 2, "encoder_offset", ENCODER, "deg", 1000.0, 1000.0,                                 \
      "friction's lag (half the forward-backward difference), or a load's, deg")                   \
    X(R, 3, "r", RESISTANCE, "ohm", 1.0e6, 1.0, "-")                                               \
    X(LD, 4, "ld", INDUCTANCE, "H", 1.0e9, 1.0, "rotor motion during the test, encoder counts")    \
    X(LQ, 5, "lq", INDUCTANCE, "H", 1.0e9, 1.0, "rotor motion during the test, encoder counts")    \
    X(LXY, 6, "lxy", LXY, "H", 1.0e9, 1.0, "rotor motion during the test, encoder counts")         \
    X(PSI_F, 7, "psi_f", FLUX, "Wb", 1.0e6, 10.0, "test speed, r/min")                             \
    X(INERTIA, 8, "inertia", MECH, "kg m^2", 1.0e6, 1.0, "acceleration runs measured")             \
    X(FRICTION, 9, "friction", MECH, "N m s/rad", 1.0e7, 1.0e6, "Coulomb friction, N m")

#define COMM_QUANTITY_COUNT 10u

/* What an apply (the drive's COMMISSION_APPLY, the host tool's parameter file) may not mix
 * (docs/commissioning.md section 3.1). Each of R, L_d, L_q, L_xy and psi_f is taken when its
 * quality is ok, else kept (the drive's set in force, the file's reference machine). Refused:
 *  - a kept quantity whose measurement (poor: a number) lies more than 3 of its sigmas from
 *    the kept value: the set would hold a value the machine was just measured to contradict;
 *  - the flux group L_d, L_q, psi_f (the torque and flux model: one flux linkage map) with a
 *    member taken and another one selected but without a number (failed or skipped): the
 *    measured members would be paired with one the sequence could not confirm.
 * The reason is MIXED_SET. COMM_KEPT_CONTRADICTS works on float and double alike. */
#define COMM_MODEL_QUANTITIES 0xF8u /* R, L_d, L_q, L_xy, psi_f */
#define COMM_FLUX_GROUP 0xB0u       /* L_d, L_q, psi_f */
#define COMM_KEPT_CONTRADICTS(value, sigma, kept)                                                  \
    ((value) - (kept) > 3 * (sigma) || (kept) - (value) > 3 * (sigma))

/* Quality of a result: X(id, number, name, meaning). */
#define COMM_QUALITY_LIST(X)                                                                       \
    X(NOT_RUN, 0, "not_run", "not selected, or an earlier step failed")                            \
    X(OK, 1, "ok", "within its quality limit")                                                     \
    X(POOR, 2, "poor", "a number, but its scatter or a check is beyond the limit")                 \
    X(FAILED, 3, "failed", "no number: the reason says why")

#define COMM_QUALITY_COUNT 4u

/* Why: a refused start, the end of the sequence, a result that failed or is poor.
 * X(id, number, name, text). */
#define COMM_REASON_LIST(X)                                                                        \
    X(NONE, 0, "none", "none")                                                                     \
    X(ABORTED, 1, "aborted", "stopped by a stop command")                                          \
    X(FAULT, 2, "fault", "a protection fault ended the sequence (the drive is in FAULT)")          \
    X(NOT_READY, 3, "not_ready", "the drive is not READY")                                         \
    X(UNDERVOLTAGE, 4, "undervoltage", "DC link below the under-voltage limit")                    \
    X(ENCODER_ERROR, 5, "encoder_error", "encoder counter or signal error (after its index)")      \
    X(OPEN_PHASE, 6, "open_phase", "a phase carries less than its share of the test current")      \
    X(CURRENT_LIMIT, 7, "current_limit", "a phase current above twice the test current")           \
    X(NO_CURRENT, 8, "no_current", "the test current was not reached within the voltage limit")    \
    X(NO_MOTION, 9, "no_motion", "the encoder did not count while the field turned the rotor")     \
    X(REVERSED, 10, "reversed", "the encoder counts backwards: channels A and B swapped")          \
    X(POLE_PAIRS, 11, "pole_pairs",                                                                \
      "counts per electrical turn do not match the configured pole pairs")                         \
    X(NO_INDEX, 12, "no_index", "no index pulse within the search")                                \
    X(ROTOR_MOVED, 13, "rotor_moved", "the rotor turned during a standstill test")                 \
    X(NO_SPEED, 14, "no_speed", "the speed did not settle at its reference")                       \
    X(SCATTER, 15, "scatter", "the blocks disagree: their scatter above the quality limit")        \
    X(SKIPPED, 16, "skipped", "not run: an earlier step failed")                                   \
    X(OUT_OF_RANGE, 17, "out_of_range",                                                            \
      "the estimate lies outside the range the controller accepts")                                \
    X(TIMEOUT, 18, "timeout", "the step ran past its time bound (a stalled rotor, a load)")        \
    X(LOAD_TORQUE, 19, "load_torque",                                                              \
      "a load torque on the shaft biases the offset: commission with the shaft free")              \
    X(ROTOR_TURNING, 20, "rotor_turning",                                                          \
      "the rotor turns faster than the sequence's spin: wait until it stands still")               \
    X(MIXED_SET, 21, "mixed_set",                                                                  \
      "the set would keep a value its measurement contradicts, or take L_d, L_q, psi_f in part")

#define COMM_REASON_COUNT 22u

/* State of the sequence (COMMISSION_STATUS): X(id, number, name, meaning). */
#define COMM_STATE_LIST(X)                                                                         \
    X(IDLE, 0, "idle", "never started since power-up")                                             \
    X(RUNNING, 1, "running", "the drive is in COMMISSION")                                         \
    X(DONE, 2, "done", "every selected step ran; results readable")                                \
    X(FAILED, 3, "failed", "a step failed; the results so far readable")                           \
    X(ABORTED, 4, "aborted", "stopped by a stop command or a fault")

#define COMM_STATE_COUNT 5u

/* Test current of COMMISSION_START, per mille of the rated current (torque limit over
 * 3 Pn psi_f of the parameter set in force). */
#define COMM_CURRENT_MIN_PERMILLE 100u
#define COMM_CURRENT_MAX_PERMILLE 800u
#define COMM_CURRENT_DEFAULT_PERMILLE 400u

#endif /* COMMISSION_LISTS_H */
