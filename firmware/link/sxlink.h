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

#include "sxlink_commission.h"
#include "sxlink_faults.h"

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

/* Commands (host -> drive). A reply carries CMD | SXL_REPLY and starts with
 * a result byte. */
#define SXL_CMD_PING 0x01u
#define SXL_CMD_GET_STATUS 0x02u
#define SXL_CMD_GET_PROFILE 0x03u      /* uint8 stage (0..7) -> SXL_PF_* reply */
#define SXL_CMD_GET_FAULT_RECORD 0x04u /* none -> SXL_FR_* reply; removes the record read */
#define SXL_CMD_SET_SPEED 0x10u        /* int32 speed reference, 0.1 r/min */
#define SXL_CMD_SET_TORQUE 0x11u       /* int32 torque reference, mN*m */
#define SXL_CMD_RUN 0x12u
#define SXL_CMD_STOP 0x13u
#define SXL_CMD_CLEAR_FAULT 0x14u
#define SXL_CMD_SET_CONTROLLER 0x15u /* uint8 controller, uint32 lambda in 0.001 N*m/Wb */
/* none -> uint32 session token (never 0): arms the session, a new ARM replaces the token */
#define SXL_CMD_ARM 0x16u
#define SXL_CMD_DISARM 0x17u /* none -> result only: the token no longer moves the motor */
/* The speed loop at its torque limit (docs/faults.md, "When the speed cannot be held"):
 * SXL_TL_SET_SIZE bytes (SXL_TL_ACTION, SXL_TL_STOP_MS) -> result only */
#define SXL_CMD_SET_TORQUE_LIMITED_ACTION 0x18u
#define SXL_CMD_GET_TORQUE_LIMITED 0x19u /* none -> SXL_TL_* */
#define SXL_CMD_CAPTURE_ARM 0x20u        /* SXL_CA_* setup -> result only */
#define SXL_CMD_CAPTURE_STATUS 0x21u     /* none -> SXL_CS_* */
#define SXL_CMD_CAPTURE_READ 0x22u       /* uint8 channel, uint16 first sample -> SXL_CR_* */
#define SXL_CMD_CAPTURE_STOP 0x23u       /* none -> result only; the record is discarded */
/* Commissioning (sxlink_commission.h, docs/serial-protocol.md). */
#define SXL_CMD_COMMISSION_START 0x40u  /* SXL_CC_* -> result only */
#define SXL_CMD_COMMISSION_STATUS 0x41u /* none -> SXL_CT_* */
#define SXL_CMD_COMMISSION_RESULT 0x42u /* uint8 quantity -> SXL_CR2_* */
#define SXL_CMD_COMMISSION_APPLY 0x43u  /* none -> SXL_CA2_* */
/* Open-phase operation (docs/faults.md): ids 0x50..0x5F. */
#define SXL_CMD_GET_OPEN_PHASE 0x50u /* none -> SXL_OP_* */
/* uint8 action 0 stop, 1 ride through; uint8 strategy 0 minimum loss, 1 maximum torque */
#define SXL_CMD_SET_OPEN_PHASE_ACTION 0x51u
/* uint8 leg 0..5 (A..F): in READY or RUN with no leg isolated, else SXL_ERR_REFUSED */
#define SXL_CMD_ISOLATE_LEG 0x52u
/* none: in READY with a leg isolated, else SXL_ERR_REFUSED */
#define SXL_CMD_RESTORE_LEGS 0x53u
/* Virtual board only (sixphase-sim serve): none -> result only, then the simulator stops. A
 * board does not know it: SXL_ERR_UNKNOWN. */
#define SXL_CMD_SIM_SHUTDOWN 0x7Eu
#define SXL_REPLY 0x80u

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

/* Commands that move the motor: accepted only with the armed session's token in front of their
 * own payload (SXL_TOKEN_BYTES, uint32 little-endian). */
#define SXL_TOKEN_BYTES 4u
#define SXL_ARMED_COMMAND(cmd)                                                                     \
    ((cmd) == SXL_CMD_RUN || (cmd) == SXL_CMD_COMMISSION_START || (cmd) == SXL_CMD_ISOLATE_LEG ||  \
     (cmd) == SXL_CMD_RESTORE_LEGS)

/* Capture setup (SXL_CMD_CAPTURE_ARM payload). Signals: firmware/link/capture_signals.h;
 * unused channels 0xFF. Results: SXL_ERR_VALUE for an unknown signal, no channel, decimation
 * or length 0, pre-trigger above 100 % or an unknown trigger; SXL_ERR_NO_ROOM when length x
 * channels exceeds the buffer; SXL_ERR_REFUSED while a capture is armed or triggered. */
#define SXL_CA_CHANNELS 0u     /* uint8 1..4 */
#define SXL_CA_SIGNAL 1u       /* uint8 x 4 */
#define SXL_CA_LENGTH 5u       /* uint16 samples per channel */
#define SXL_CA_DECIMATION 7u   /* uint16 one sample every N control periods (N >= 1) */
#define SXL_CA_TRIGGER 9u      /* uint8 0 immediate, 1 rising, 2 falling, 3 fault */
#define SXL_CA_TRIG_SIGNAL 10u /* uint8 */
#define SXL_CA_TRIG_LEVEL 11u  /* int16 in the trigger signal's sample units */
#define SXL_CA_PRE 13u         /* uint8 pre-trigger share, % */
#define SXL_CA_SIZE 14u
/* Capture status (reply to SXL_CMD_CAPTURE_STATUS, after the result byte). */
#define SXL_CS_STATE 0u      /* uint8 0 idle, 1 armed, 2 triggered, 3 done */
#define SXL_CS_CHANNELS 1u   /* uint8 */
#define SXL_CS_SIGNAL 2u     /* uint8 x 4 */
#define SXL_CS_LENGTH 6u     /* uint16 */
#define SXL_CS_DECIMATION 8u /* uint16 */
#define SXL_CS_COUNT 10u     /* uint16 valid samples per channel */
#define SXL_CS_TRIGGER 12u   /* uint16 the trigger sample's index in the record */
#define SXL_CS_PERIOD 14u    /* uint32 control-period count of the first sample */
#define SXL_CS_TS_NS 18u     /* uint32 control period, ns */
#define SXL_CS_SIZE 22u
/* Capture read (reply to SXL_CMD_CAPTURE_READ, after the result byte). */
#define SXL_CR_COUNT 0u   /* uint8 samples that follow (0 past the record) */
#define SXL_CR_SAMPLES 1u /* int16 x count */
#define SXL_CR_MAX 20u    /* samples per read */

/* Controller ids of SXL_CMD_SET_CONTROLLER (same values as ctl_controller_t). */
#define SXL_CONTROLLER_DDC 0u
#define SXL_CONTROLLER_MPTC49 1u
#define SXL_CONTROLLER_MPTC13 2u

/* Status payload (after the result byte), offsets in bytes. */
#define SXL_ST_STATE 0u       /* uint8 drive_state_t */
#define SXL_ST_FAULT 1u       /* uint8 drive_fault_t */
#define SXL_ST_FLAGS 2u       /* uint8 SXL_FLAG_* */
#define SXL_ST_CONTROLLER 3u  /* uint8 controller in force */
#define SXL_ST_SPEED 4u       /* int32 measured speed, 0.1 r/min */
#define SXL_ST_SPEED_REF 8u   /* int32 speed reference, 0.1 r/min */
#define SXL_ST_TORQUE 12u     /* int32 torque estimate, mN*m */
#define SXL_ST_TORQUE_REF 16u /* int32 torque reference, mN*m */
#define SXL_ST_LAMBDA 20u     /* uint32 lambda in force, 0.001 N*m/Wb */
#define SXL_ST_ISR_COUNT 24u  /* uint32 control periods since start */
#define SXL_ST_ISR_MAX 28u    /* uint32 longest ISR, CPU cycles */
#define SXL_ST_RX_ERRORS 32u  /* uint16 malformed frames received */
#define SXL_ST_FAULTS 34u     /* uint16 latched ctl_fault_t mask (protocol 2) */
#define SXL_ST_RECORDS 36u    /* uint16 fault records not yet read (protocol 2) */
/* protocol 3: uint8 drive_run_refusal_t of the last refused run; uint16 ctl_fault_t conditions
 * that refused the last clear */
#define SXL_ST_RUN_REFUSAL 38u
#define SXL_ST_CLEAR_BLOCKED 39u
/* protocol 6: uint16 the stack's high-water mark since start-up, words; uint16 the stack's size,
 * words, or SXL_STACK_NOT_MEASURED where the platform does not paint its stack (the virtual
 * board; the mark is then 0) */
#define SXL_ST_STACK_USED 41u
#define SXL_ST_STACK_WORDS 43u
#define SXL_STACK_NOT_MEASURED 0u
#define SXL_ST_SIZE 45u
#define SXL_ST_SIZE_V5 41u /* protocol 3 to 5 ended at the clear's conditions */
#define SXL_ST_SIZE_V2 38u /* protocol 2 ended at records */
#define SXL_ST_SIZE_V1 34u /* protocol 1 ended at rx_errors: readers accept the shorter block */
/* Profile payload (reply to SXL_CMD_GET_PROFILE, after the result byte); cycles of the
 * ISR's counter, see firmware/app/profile.h. */
#define SXL_PF_STAGE 0u          /* uint8 stage echoed */
#define SXL_PF_LAST 1u           /* uint32 */
#define SXL_PF_MIN 5u            /* uint32 */
#define SXL_PF_MAX 9u            /* uint32 */
#define SXL_PF_MEAN 13u          /* uint32 running mean */
#define SXL_PF_PERIOD 17u        /* uint32 control period, cycles */
#define SXL_PF_READ_COST 21u     /* uint32 subtracted measurement cost, cycles */
#define SXL_PF_CYCLES_PER_US 25u /* uint16 */
#define SXL_PF_LOAD_LAST 27u     /* uint16 per mille of the period */
#define SXL_PF_LOAD_MAX 29u      /* uint16 per mille */
#define SXL_PF_OVERRUNS 31u      /* uint32 */
#define SXL_PF_SIZE 35u
#define SXL_PF_STAGES 8u
/* Fault record payload (reply to SXL_CMD_GET_FAULT_RECORD, after the result byte). An
 * empty log gives PRESENT 0 and only the first SXL_FR_HEADER_SIZE bytes. */
#define SXL_FR_PRESENT 0u /* uint8 1: a record follows (now removed from the log), 0: none */
#define SXL_FR_PENDING 1u /* uint16 records still unread after this one */
#define SXL_FR_DROPPED 3u /* uint16 records dropped because the log was full */
#define SXL_FR_HEADER_SIZE 5u
#define SXL_FR_FAULTS 5u      /* uint16 ctl_fault_t mask detected in that period */
#define SXL_FR_PERIOD 7u      /* uint32 control-period count at detection */
#define SXL_FR_I_PHASE 11u    /* int16 x 6, phase currents A..F, 10 mA */
#define SXL_FR_VDC 23u        /* int16 DC link, 0.1 V */
#define SXL_FR_THETA 25u      /* uint16 electrical angle, 1/65536 turn */
#define SXL_FR_SPEED 27u      /* int32 mechanical speed, 0.1 r/min */
#define SXL_FR_TORQUE 31u     /* int32 torque estimate, mN*m */
#define SXL_FR_TORQUE_REF 35u /* int32 torque reference, mN*m */
#define SXL_FR_VECTOR 39u     /* int16 switching vector in force */
#define SXL_FR_DUTY 41u       /* uint16 duty of that vector, Q15 (32768 = 1.0) */
#define SXL_FR_SIZE 43u
#define SXL_FR_PHASES 6u

/* Open-phase details (reply to SXL_CMD_GET_OPEN_PHASE, after the result byte). */
#define SXL_OP_ACTION 0u       /* uint8 0 stop, 1 ride through (what OPEN_PHASE does) */
#define SXL_OP_STRATEGY 1u     /* uint8 0 minimum loss, 1 maximum torque */
#define SXL_OP_LEG 2u          /* uint8 isolated leg 0..5 (A..F), 0xFF none */
#define SXL_OP_CAUSE 3u        /* uint8 0 none, 1 an OPEN_PHASE ridden through, 2 a command */
#define SXL_OP_IN_FORCE 4u     /* uint8 1: the parameter set for the legs as they are is in force */
#define SXL_OP_TORQUE_LIMIT 5u /* int32 the speed loop's torque limit in force, mN*m */
#define SXL_OP_PERIOD 9u       /* uint32 control-period count at the isolation */
#define SXL_OP_SIZE 13u

/* What the drive does when the speed loop is at its torque limit: the request of
 * SXL_CMD_SET_TORQUE_LIMITED_ACTION (ACTION and STOP_MS) and the reply to
 * SXL_CMD_GET_TORQUE_LIMITED (all, after the result byte). An unknown action or a time outside
 * STOP_MS_MIN..STOP_MS_MAX is refused with SXL_ERR_VALUE and changes nothing. */
#define SXL_TL_ACTION 0u  /* uint8 SXL_TL_CONTINUE or SXL_TL_STOP */
#define SXL_TL_STOP_MS 1u /* uint16 ms at the limit before the stop action stops */
#define SXL_TL_SET_SIZE 3u
#define SXL_TL_STOPPED 3u /* uint8 1: the stop action stopped the last run */
#define SXL_TL_SIZE 4u
#define SXL_TL_CONTINUE 0u /* run on at the limit: the load sets the speed */
#define SXL_TL_STOP 1u     /* at the limit for STOP_MS: RUN -> READY, no fault */
/* The time is kept with continue too, for a later stop. */
#define SXL_TL_STOP_MS_MIN 1u
#define SXL_TL_STOP_MS_MAX 60000u   /* the drive's DRIVE_TORQUE_LIMITED_STOP_MAX_S */
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
#define SXL_STATE_NAME_COUNT 6u       /* drive_state_t: INIT .. COMMISSION */
#define SXL_RUN_REFUSAL_NAME_COUNT 4u /* drive_run_refusal_t: NONE .. UNDERVOLTAGE */
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
