/*
 * Serial commands of the drive: one sixphase-link request frame in, one
 * reply frame out. Portable (no registers); the firmware's background loop
 * feeds it, host tests drive it directly.
 */
#ifndef DRIVE_LINK_H
#define DRIVE_LINK_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive.h"
#include "sxlink.h"

#define DRIVE_LINK_MAX_SPEED_01RPM ((int32_t)SXL_SPEED_REF_MAX) /* |speed reference|, 0.1 r/min */
#define DRIVE_LINK_MAX_TORQUE_MNM ((int32_t)SXL_TORQUE_REF_MAX) /* |torque reference|, mN*m */
#define DRIVE_LINK_MAX_LAMBDA_MILLI ((uint32_t)CTL_LAMBDA_MAX * 1000u) /* lambda, 0.001 N*m/Wb */

/* Handle req and fill reply (always a reply for a well-formed frame).
 * rx_errors: malformed frames seen by the receiver, reported in the status.
 * A command that moves the motor (SXL_ARMED_COMMAND) is refused with SXL_ERR_NOT_ARMED unless
 * its payload starts with the armed session's token, which is taken off req's payload. */
void drive_link_handle(drive_t *d, sxl_frame_t *req, sxl_frame_t *reply, uint16_t rx_errors);

/* Profile payload of one stage (SXL_PF_*); out must hold SXL_PF_SIZE bytes. */
void drive_link_profile(uint16_t stage, uint16_t *out);

/* Status payload as sent in the reply to SXL_CMD_GET_STATUS (after the
 * result byte); out must hold SXL_ST_SIZE bytes. */
void drive_link_status(const drive_t *d, uint16_t rx_errors, uint16_t *out);

/* Open-phase details (SXL_OP_*) as sent in the reply to SXL_CMD_GET_OPEN_PHASE; out must hold
 * SXL_OP_SIZE bytes. */
void drive_link_open_phase(const drive_t *d, uint16_t *out);

/* Fault record payload (SXL_FR_*) as sent in the reply to SXL_CMD_GET_FAULT_RECORD: the
 * oldest unread record, removed from the log. out must hold SXL_FR_SIZE bytes; returns the
 * payload length (SXL_FR_HEADER_SIZE when the log is empty). Background side. */
uint16_t drive_link_fault_record(drive_t *d, uint16_t *out);

#endif
