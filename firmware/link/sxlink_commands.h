/*
 * The commands of the serial link, one list: X(NAME, code, handler, armed, REQUEST, REPLY, notes).
 *   NAME     SXL_CMD_<NAME> is the code
 *   handler  the drive's handler is on_<handler> (firmware/app/service/drive_link.c)
 *   armed    1: moves the motor, taken only with the armed session's token in front of the
 *            request (SXL_TOKEN_BYTES, uint32 little-endian)
 *   REQUEST  the request payload's field list (sxlink_payloads.h; SXL_NONE: none): its size is
 *            the only length the drive takes (after the token), anything else is SXL_ERR_LENGTH
 *   REPLY    the reply's field list after the result byte (its largest form)
 *   notes    what it does and its refusals, one line for docs/serial-protocol.md
 * From the list come the codes, the drive's dispatch and length checks, which commands need the
 * token (SXL_ARMED_COMMAND), the names the host tool prints and the command table of
 * docs/serial-protocol.md (tools/protocol_doc). The virtual board's own command is on a list of
 * its own (SXL_PLATFORM_COMMAND_LIST): a board's drive does not know it.
 */
#ifndef SXLINK_COMMANDS_H
#define SXLINK_COMMANDS_H

#include <stdbool.h>
#include <stdint.h>

#include "sxlink_payloads.h"

/* A test build appends rows to prove everything derived from the list follows them
 * (tests/firmware/test_command_row.c): the header SXL_EXTRA_COMMANDS_HEADER names defines
 * SXL_EXTRA_COMMANDS(X). The product has none. */
#ifdef SXL_EXTRA_COMMANDS_HEADER
#include SXL_EXTRA_COMMANDS_HEADER
#else
#define SXL_EXTRA_COMMANDS(X)
#endif

#define SXL_COMMAND_LIST(X)                                                                        \
    X(PING, 0x01, ping, 0, SXL_NONE, SXL_PG, "")                                                   \
    X(GET_STATUS, 0x02, get_status, 0, SXL_NONE, SXL_ST, "")                                       \
    X(GET_PROFILE, 0x03, get_profile, 0, SXL_PQ, SXL_PF, "2 for a stage above 7")                  \
    X(GET_FAULT_RECORD, 0x04, get_fault_record, 0, SXL_NONE, SXL_FR,                               \
      "the oldest unread record, removed from the drive's log; only the header when the log is "   \
      "empty")                                                                                     \
    X(SET_SPEED, 0x10, set_speed, 0, SXL_SPEED, SXL_NONE,                                          \
      "selects the speed loop; 2 beyond " SXL_STR(SXL_SPEED_REF_MAX_RPM) " r/min either way")      \
    X(SET_TORQUE, 0x11, set_torque, 0, SXL_TORQUE, SXL_NONE,                                       \
      "selects the torque loop; 2 beyond " SXL_STR(SXL_TORQUE_REF_MAX_NM) " N·m either way")       \
    X(RUN, 0x12, run, 1, SXL_NONE, SXL_NONE,                                                       \
      "4 unless READY, the encoder healthy and the DC link at or above the under-voltage limit; "  \
      "the status then says why")                                                                  \
    X(STOP, 0x13, stop, 0, SXL_NONE, SXL_NONE, "RUN or COMMISSION -> READY at the next period")    \
    X(CLEAR_FAULT, 0x14, clear_fault, 0, SXL_NONE, SXL_NONE,                                       \
      "4 unless in FAULT; the drive leaves FAULT only when healthy (below)")                       \
    X(SET_CONTROLLER, 0x15, set_controller, 0, SXL_SC, SXL_NONE,                                   \
      "checked and built in the background, taken at the next period in any state; 2 for an "      \
      "unknown controller or a set the core refuses, 5 while an earlier set still waits")          \
    X(ARM, 0x16, arm, 0, SXL_NONE, SXL_AR, "a new ARM replaces the token")                         \
    X(DISARM, 0x17, disarm, 0, SXL_NONE, SXL_NONE, "the token no longer moves the motor")          \
    X(SET_TORQUE_LIMITED_ACTION, 0x18, set_torque_limited_action, 0, SXL_TL_SET, SXL_NONE,         \
      "2 for an unknown action or a time outside " SXL_STR(SXL_TL_STOP_MS_MIN_N) " .. " SXL_STR(   \
          SXL_TL_STOP_MS_MAX_N) " ms (nothing changed); any state")                                \
    X(GET_TORQUE_LIMITED, 0x19, get_torque_limited, 0, SXL_NONE, SXL_TL, "")                       \
    X(CAPTURE_ARM, 0x20, capture_arm, 0, SXL_CA, SXL_NONE,                                         \
      "2 for a setup that is not valid, 6 when length x channels exceeds the buffer, 4 while a "   \
      "capture is armed or triggered")                                                             \
    X(CAPTURE_STATUS, 0x21, capture_status, 0, SXL_NONE, SXL_CS, "")                               \
    X(CAPTURE_READ, 0x22, capture_read, 0, SXL_CQ, SXL_CR, "2 for a channel not captured")         \
    X(CAPTURE_STOP, 0x23, capture_stop, 0, SXL_NONE, SXL_NONE,                                     \
      "back to idle, the record "                                                                  \
      "discarded")                                                                                 \
    X(COMMISSION_START, 0x40, commission_start, 1, SXL_CC, SXL_NONE,                               \
      "2 for a mask or current not valid; 4 outside READY, with the DC link low, an encoder "      \
      "error, a leg isolated or the rotor turning (the status says why)")                          \
    X(COMMISSION_STATUS, 0x41, commission_status, 0, SXL_NONE, SXL_CT, "")                         \
    X(COMMISSION_RESULT, 0x42, commission_result, 0, SXL_CQ2, SXL_CR2,                             \
      "2 for an unknown quantity")                                                                 \
    X(COMMISSION_APPLY, 0x43, commission_apply, 0, SXL_NONE, SXL_CA2,                              \
      "4 outside READY, while a sequence runs, with no result of quality ok or a mixed set; 5 "    \
      "while an earlier set waits; 2 if the core refuses the set")                                 \
    X(GET_OPEN_PHASE, 0x50, get_open_phase, 0, SXL_NONE, SXL_OP, "")                               \
    X(SET_OPEN_PHASE_ACTION, 0x51, set_open_phase_action, 0, SXL_OA, SXL_NONE,                     \
      "2 for an unknown value; what OPEN_PHASE does from now on, and the next post-fault set's "   \
      "strategy")                                                                                  \
    X(ISOLATE_LEG, 0x52, isolate_leg, 1, SXL_IL, SXL_NONE,                                         \
      "2 for a leg above 5; 4 unless READY or RUN with no leg isolated; the leg stays off, the "   \
      "drive runs on five")                                                                        \
    X(RESTORE_LEGS, 0x53, restore_legs, 1, SXL_NONE, SXL_NONE,                                     \
      "4 unless READY with a leg isolated; the healthy parameter set follows")                     \
    SXL_EXTRA_COMMANDS(X)

/* The virtual board's (sixphase-sim serve) own commands, answered by its link service before
 * the drive sees the frame; a board answers them SXL_ERR_UNKNOWN. */
#define SXL_PLATFORM_COMMAND_LIST(X)                                                               \
    X(SIM_SHUTDOWN, 0x7E, sim_shutdown, 0, SXL_NONE, SXL_NONE,                                     \
      "virtual board only: the simulator replies, then stops (exit 0)")

#define SXL_CMD_ENUM(name, code, handler, armed, request, reply, notes) SXL_CMD_##name = code,
enum { SXL_COMMAND_LIST(SXL_CMD_ENUM) SXL_PLATFORM_COMMAND_LIST(SXL_CMD_ENUM) SXL_CMD_ENUM_END_ };
#undef SXL_CMD_ENUM

#define SXL_CMD_COUNTER(name, code, handler, armed, request, reply, notes) +1
enum { SXL_COMMAND_COUNT = 0 SXL_COMMAND_LIST(SXL_CMD_COUNTER) };
#undef SXL_CMD_COUNTER

#define SXL_REPLY 0x80u /* a reply's CMD is the request's | SXL_REPLY */
#define SXL_TOKEN_BYTES 4u

/* Commands that move the motor (the list's armed column). */
#define SXL_ARMED_TERM_(name, code, handler, armed, request, reply, notes)                         \
    || ((armed) != 0 && (cmd_) == (code))
#define SXL_ARMED_COMMAND(cmd) sxl_command_armed(cmd)
static inline bool sxl_command_armed(uint16_t cmd_) { return 0 SXL_COMMAND_LIST(SXL_ARMED_TERM_); }

#endif /* SXLINK_COMMANDS_H */
