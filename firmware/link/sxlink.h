/*
 * sixphase link: the framed binary protocol of the serial port (SCI-A on the
 * target, a tty on the host). Pure, portable C shared by the firmware and the
 * host tool. Bytes are held in uint16_t (0..255) because a char is 16 bits on
 * the C28x; nothing here assumes 8-bit storage.
 *
 * Frame:  0xA5 | LEN | CMD | PAYLOAD (LEN - 1 bytes) | CRC (4 bytes, most significant first)
 *   LEN   number of bytes of CMD + PAYLOAD, 1 .. 1 + SXL_MAX_PAYLOAD
 *   CRC   CRC-32C (Castagnoli: poly 0x1EDC6F41 reflected, init and final xor 0xFFFFFFFF) over
 *         LEN, CMD and PAYLOAD. Since protocol 7; CRC-16 before let 13 of 300,000 noise frames
 *         with a start byte and a valid length through, any of which could be a command.
 * Commands that move the motor (SXL_ARMED_COMMAND) also carry the token of an armed session
 * (SXL_CMD_ARM) as their first four payload bytes.
 * Multi-byte payload fields are little-endian. See docs/serial-protocol.md.
 */
#ifndef SXLINK_H
#define SXLINK_H

#include <stdbool.h>
#include <stdint.h>

#include "sxlink_commands.h"
#include "sxlink_commission.h"
#include "sxlink_faults.h"
#include "sxlink_states.h"

#define SXL_SOF 0xA5u
#define SXL_MAX_PAYLOAD 48u
#define SXL_CRC_BYTES 4u
#define SXL_CRC32C_POLY_REFLECTED 0x82F63B78u
#define SXL_FRAME_OVERHEAD (3u + SXL_CRC_BYTES) /* start byte, LEN, CMD, CRC */
#define SXL_MAX_FRAME (SXL_MAX_PAYLOAD + SXL_FRAME_OVERHEAD)
/* Protocol version. 2: fault fields in the status, SXL_CMD_GET_FAULT_RECORD; 3: why the last
 * run or clear was refused, in the status, and the result SXL_ERR_BUSY; 4: the capture buffer
 * (SXL_CMD_CAPTURE_*, SXL_ERR_NO_ROOM); 5: commissioning (SXL_CMD_COMMISSION_*, the drive state
 * COMMISSION) and open-phase operation (SXL_CMD_GET_OPEN_PHASE .. SXL_CMD_RESTORE_LEGS, status
 * flag bit 3); 6: the stack's high-water mark and size in the status (SXL_ST_STACK_USED);
 * 7: CRC-32C instead of CRC-16, and the armed session (SXL_CMD_ARM, SXL_ERR_NOT_ARMED) that
 * commands moving the motor need; 8: what the drive does when the speed cannot be held, set and
 * read over the link (SXL_CMD_SET_TORQUE_LIMITED_ACTION, SXL_CMD_GET_TORQUE_LIMITED). */
#define SXL_VERSION 8u

/* Result byte of every reply. */
/* A reply's result byte, one list: X(id, number, text); the host tool prints the text. */
#define SXL_RESULT_LIST(X)                                                                         \
    X(SXL_OK, 0, "ok")                                                                             \
    X(SXL_ERR_LENGTH, 1, "bad length") /* payload length wrong for the command */                  \
    X(SXL_ERR_VALUE, 2, "bad value")   /* out of range or parameters rejected */                   \
    X(SXL_ERR_UNKNOWN, 3, "unknown command")                                                       \
    X(SXL_ERR_REFUSED, 4, "refused")  /* not allowed in the present state */                       \
    X(SXL_ERR_BUSY, 5, "busy, retry") /* the previous parameter set is still applied */            \
    X(SXL_ERR_NO_ROOM, 6, "no room in the capture buffer") /* length x channels above it */        \
    X(SXL_ERR_NOT_ARMED, 7, "not armed (the session's token is missing)") /* moves the motor */

#define SXL_RESULT_ENUM(id, number, text) id = number##u,
enum { SXL_RESULT_LIST(SXL_RESULT_ENUM) SXL_RESULT_COUNT };
#undef SXL_RESULT_ENUM

/* Controller ids of SXL_CMD_SET_CONTROLLER (same values as ctl_controller_t). */
#define SXL_CONTROLLER_DDC 0u
#define SXL_CONTROLLER_MPTC49 1u
#define SXL_CONTROLLER_MPTC13 2u
#define SXL_CONTROLLER_FOC 3u

/* What the drive does when the speed loop is at its torque limit: the request of
 * SXL_CMD_SET_TORQUE_LIMITED_ACTION (ACTION and STOP_MS) and the reply to
 * SXL_CMD_GET_TORQUE_LIMITED (all, after the result byte). An unknown action or a time outside
 * STOP_MS_MIN..STOP_MS_MAX is refused with SXL_ERR_VALUE and changes nothing. */
#define SXL_TL_CONTINUE 0u /* run on at the limit: the load sets the speed */
#define SXL_TL_STOP 1u     /* at the limit for STOP_MS: RUN -> READY, no fault */
/* The time is kept with continue too, for a later stop. */
#define SXL_TL_STOP_MS_MIN_N 1
#define SXL_TL_STOP_MS_MAX_N 60000 /* the drive's DRIVE_TORQUE_LIMITED_STOP_MAX_S */
#define SXL_TL_STOP_MS_MIN ((uint16_t)SXL_TL_STOP_MS_MIN_N)
#define SXL_TL_STOP_MS_MAX ((uint16_t)SXL_TL_STOP_MS_MAX_N)
#define SXL_TL_STOP_MS_DEFAULT 500u /* the drive's DRIVE_TORQUE_LIMITED_STOP_S */

#define SXL_FLAG_ENCODER_OK 0x01u
#define SXL_FLAG_PWM_OFF 0x02u
#define SXL_FLAG_PARAMS_PENDING 0x04u
#define SXL_FLAG_LEG_ISOLATED 0x08u /* a leg is off for good (SXL_CMD_GET_OPEN_PHASE) */
#define SXL_FLAG_TORQUE_LIMITED                                                                    \
    0x10u /* the speed loop at its torque limit for 0.1 s or more:                                 \
           * the speed is not held (docs/faults.md) */

typedef struct {
    uint16_t cmd;
    uint16_t len; /* payload bytes */
    uint16_t payload[SXL_MAX_PAYLOAD];
} sxl_frame_t;

typedef enum {
    SXL_RX_NONE = 0,       /* byte consumed, no frame yet */
    SXL_RX_FRAME = 1,      /* a complete, valid frame is in *out */
    SXL_RX_ERR_CRC = 2,    /* frame dropped: CRC mismatch */
    SXL_RX_ERR_LENGTH = 3, /* frame dropped: LEN 0 or too long */
    SXL_RX_ERR_BYTE = 4    /* value above 255 pushed: decoder reset */
} sxl_rx_t;

/* Receiver. It holds the bytes from the earliest start byte that may still begin a frame
 * on, and never commits to a start: a frame is recognised the moment its last byte arrives,
 * wherever it starts in what is held (its length field and CRC check), so noise before a
 * frame, a stray start byte or a bad length never costs the frame that follows. A start
 * whose frame is complete but fails its CRC, or whose length field is impossible, is given
 * up (counted in errors) and the search goes on from the byte after it. */
typedef struct {
    uint16_t held[SXL_MAX_FRAME]; /* held[0] is a start byte when n > 0 */
    uint16_t n;
    uint16_t errors; /* saturates at 65535 */
} sxl_decoder_t;

/* CRC-32C of n bytes (init and final xor included), and one byte's step (neither). */
uint32_t sxl_crc32(const uint16_t *bytes, uint16_t n);
uint32_t sxl_crc32_byte(uint32_t crc, uint16_t byte);

/* Encode a frame into out (capacity cap bytes). Returns the frame length, or 0
 * if the payload is too long, a byte is above 255 or out is too small. */
uint16_t sxl_encode(uint16_t cmd, const uint16_t *payload, uint16_t len, uint16_t *out,
                    uint16_t cap);

void sxl_decoder_init(sxl_decoder_t *d);
/* Drop a partial frame (e.g. after an inter-byte gap). */
void sxl_decoder_reset(sxl_decoder_t *d);
/* True while no frame is partially received. */
bool sxl_decoder_idle(const sxl_decoder_t *d);
/* Give up a partial frame (the line went quiet in the middle of it): counted as a receive
 * error, the decoder hunts for the next start. Nothing to give up: nothing happens. */
void sxl_decoder_abandon(sxl_decoder_t *d);
/* One received byte. SXL_RX_FRAME: a frame ended with this byte, in *out. Otherwise the
 * last start given up with this byte (SXL_RX_ERR_*), or SXL_RX_NONE. Bounded work per byte:
 * at most SXL_MAX_FRAME starts are looked at, and only one whose length ends here is
 * checksummed. */
sxl_rx_t sxl_decoder_push(sxl_decoder_t *d, uint16_t byte, sxl_frame_t *out);

/* Little-endian payload fields (the caller checks the payload length). */
void sxl_put_u16(uint16_t *p, uint16_t v);
void sxl_put_u32(uint16_t *p, uint32_t v);
uint16_t sxl_get_u16(const uint16_t *p);
uint32_t sxl_get_u32(const uint16_t *p);
int32_t sxl_get_i32(const uint16_t *p);
void sxl_put_i32(uint16_t *p, int32_t v);
void sxl_put_i16(uint16_t *p, int16_t v);
int16_t sxl_get_i16(const uint16_t *p);

/* Names (sxlink_names.c), upper case as in the firmware's enums; "?" out of range. Plain
 * numbers, no firmware headers, so host programs can use them. */
const char *sxl_run_refusal_name(uint16_t reason);
const char *sxl_state_name(uint16_t state);
const char *sxl_fault_name(uint16_t code);
const char *sxl_result_name(uint16_t result);
/* One line on what a drive fault code means (the fault list's description; "" for NONE). */
const char *sxl_fault_description(uint16_t code);
/* Commissioning's lists (sxlink_commission.h): names as the tool prints them; "?" out of range. */
const char *sxl_comm_step_name(uint16_t step);
const char *sxl_comm_quantity_name(uint16_t quantity);
const char *sxl_comm_quantity_unit(uint16_t quantity);
double sxl_comm_quantity_scale(uint16_t quantity); /* wire value = SI value x scale */
double sxl_comm_quantity_extra_scale(uint16_t quantity);
/* The quantities a step identifies, bit (1 << quantity) each (the quantity list's step). */
uint16_t sxl_comm_step_quantities(uint16_t step);
const char *sxl_comm_quality_name(uint16_t quality);
const char *sxl_comm_reason_name(uint16_t reason);
const char *sxl_comm_reason_text(uint16_t reason);
const char *sxl_comm_state_name(uint16_t state);
/* Name of ctl_fault_t bit number bit (0 = OVERCURRENT .. 15 = PLATFORM), not of a mask. */
const char *sxl_fault_bit_name(uint16_t bit);
/* The names of the bits set in mask joined by '|' ("NONE" for 0) into out (cap chars incl.
 * the terminator, cap > 0); cut short if out is too small. Returns the length written. */
uint16_t sxl_fault_mask_str(uint16_t mask, char *out, uint16_t cap);

#endif /* SXLINK_H */
