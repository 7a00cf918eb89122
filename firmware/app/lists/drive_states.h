/*
 * The drive's states and the reasons a run is refused, one list each, declared by the
 * application (issue 26: the link kept its own name tables, checked by count only). drive.h
 * builds drive_state_t and drive_run_refusal_t from them; the link maps them onto the wire and
 * into the tools' names (firmware/link/sxlink_states.h, sxlink_names.c).
 *
 *   X(enum name, number, name as the tools print it)
 *
 * Numbers are on the wire (docs/serial-protocol.md): never renumber. Plain macros, no firmware
 * types, so the protocol library and host tools can use them.
 */
#ifndef DRIVE_STATES_H
#define DRIVE_STATES_H

#define DRIVE_STATE_LIST(X)                                                                        \
    X(DRIVE_STATE_INIT, 0, "INIT")                                                                 \
    X(DRIVE_STATE_CALIBRATE, 1, "CALIBRATE")                                                       \
    X(DRIVE_STATE_READY, 2, "READY")                                                               \
    X(DRIVE_STATE_RUN, 3, "RUN")                                                                   \
    X(DRIVE_STATE_FAULT, 4, "FAULT")                                                               \
    X(DRIVE_STATE_COMMISSION, 5, "COMMISSION") /* identification and encoder alignment */

/* Why a run request was refused (the last reason is kept and reported over the link). */
#define DRIVE_RUN_REFUSAL_LIST(X)                                                                  \
    X(DRIVE_RUN_ACCEPTED, 0, "NONE")                                                               \
    X(DRIVE_RUN_REFUSED_STATE, 1, "NOT_READY") /* not in READY: calibrating, faulted, running */   \
    X(DRIVE_RUN_REFUSED_ENCODER, 2, "ENCODER") /* encoder not healthy: index not seen yet */       \
    X(DRIVE_RUN_REFUSED_UNDERVOLTAGE, 3, "UNDERVOLTAGE") /* DC link below the limit (or off) */

#define DRIVE_LIST_COUNT_(id, number, name) +1
enum {
    DRIVE_STATE_COUNT = 0 DRIVE_STATE_LIST(DRIVE_LIST_COUNT_),
    DRIVE_RUN_REFUSAL_COUNT = 0 DRIVE_RUN_REFUSAL_LIST(DRIVE_LIST_COUNT_)
};
#undef DRIVE_LIST_COUNT_

#endif /* DRIVE_STATES_H */
