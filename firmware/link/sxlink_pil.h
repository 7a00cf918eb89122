/*
 * Processor-in-the-loop (PIL) frames of the serial link: the host (sixphase-sim run --pil)
 * runs the plant and a build of the controller of its own; a target runs the firmware's control
 * period on inputs that come in a frame instead of from its peripherals, and answers each
 * period with what it wrote to them and its own cycle counts. Same framing as every sxlink frame
 * (sxlink.h: start byte, length, command, payload, CRC-32C; a reply's command is the request's
 * | SXL_REPLY, its first payload byte the result). A product image answers these commands
 * SXL_ERR_UNKNOWN; a PIL image (firmware/pil) answers only these. docs/profiling.md.
 *
 * One session: HELLO (what the target is), CONFIG frames carrying the configuration's byte
 * image (host_sim/bridge/sim_ctl_wire.h), INIT, then one STEP per control period. Calls the
 * host made on its drive between two periods (a run request, a speed reference, the background
 * loop's share, ...) travel in front of the next period, in order: in the STEP frame itself when
 * they fit, else in CALLS frames before it.
 */
#ifndef SXLINK_PIL_H
#define SXLINK_PIL_H

#define SXL_PIL_VERSION 1u

/* The commands, one list: X(NAME, code, notes). */
#define SXL_PIL_COMMAND_LIST(X)                                                                    \
    X(PIL_HELLO, 0x60, "reply: version, arithmetic, target, cycles per second")                    \
    X(PIL_CONFIG, 0x61, "offset u16, then bytes of the configuration image at that offset")        \
    X(PIL_INIT, 0x62, "the peripherals set up, the drive configured from the image; reply: i16")   \
    X(PIL_CALLS, 0x63, "call records (SXL_PIL_CALL_LIST), run in order")                           \
    X(PIL_STEP, 0x64, "one control period: its inputs, then call records run before it")

#define SXL_PIL_CMD_ENUM(name, code, notes) SXL_CMD_##name = code,
enum { SXL_PIL_COMMAND_LIST(SXL_PIL_CMD_ENUM) SXL_PIL_CMD_END_ };
#undef SXL_PIL_CMD_ENUM

/* Calls on the drive (the simulator's bridge, host_sim/bridge/sim_ctl.h), one list:
 * X(NAME, code, argument bytes). A record is the code, then its arguments (little-endian; a
 * REAL as the IEEE single bits). */
#define SXL_PIL_CALL_LIST(X)                                                                       \
    X(RUN, 0, 0)               /* request_run */                                                   \
    X(CLEAR, 1, 0)             /* request_clear */                                                 \
    X(SET_SPEED, 2, 4)         /* set_speed_rpm, REAL */                                           \
    X(SET_TORQUE, 3, 4)        /* set_torque_nm, REAL */                                           \
    X(OVERRUN, 4, 0)           /* report_overrun */                                                \
    X(BACKGROUND, 5, 0)        /* background */                                                    \
    X(ISOLATE_LEG, 6, 1)       /* isolate_leg, leg 0..5 */                                         \
    X(COMMISSION_START, 7, 4)  /* commission_start, mask u16, permille u16 */                      \
    X(COMMISSION_APPLY, 8, 0)  /* commission_apply */                                              \
    X(READ_FAULT_RECORD, 9, 0) /* read_fault_record: the record taken off the target's log */

#define SXL_PIL_CALL_ENUM(name, code, bytes) SXL_PIL_CALL_##name = code,
enum { SXL_PIL_CALL_LIST(SXL_PIL_CALL_ENUM) SXL_PIL_CALL_COUNT };
#undef SXL_PIL_CALL_ENUM

/* HELLO reply, after the result byte: version u8, arithmetic u8 (0 fixed, 1 float), target u8,
 * cycles per second of the target's counter u32. */
#define SXL_PIL_HELLO_BYTES 7u
#define SXL_PIL_ARITH_FIXED 0u
#define SXL_PIL_ARITH_FLOAT 1u
#define SXL_PIL_TARGET_MPS2 1u   /* an Arm MPS2 AN386, Cortex-M4F (under QEMU here) */
#define SXL_PIL_TARGET_F28335 2u /* a TMS320F28335 board */

/* CONFIG request: offset u16, then at most SXL_PIL_CONFIG_CHUNK bytes of the image. */
#define SXL_PIL_CONFIG_CHUNK 40u

/* INIT request: the peripherals as the host's main set them up before the drive's init (the
 * PWM's carrier and dead time, the encoder's lines, pole pairs and offset). Reply after the result
 * byte: the init's result i16 (the bridge's: 0 ok, 1 refused, 2 configured in FAULT). */
#define SXL_PIL_INIT_CARRIER 0u     /* u32 Hz */
#define SXL_PIL_INIT_DEAD_TIME 4u   /* u32 ns */
#define SXL_PIL_INIT_LINES 8u       /* u32 */
#define SXL_PIL_INIT_POLE_PAIRS 12u /* u16 */
#define SXL_PIL_INIT_OFFSET 14u     /* u32, electrical, 2^32 a turn */
#define SXL_PIL_INIT_BYTES 18u

/* STEP request: the period's inputs as the plant left them on the peripheral bus (hal_sim.h),
 * then call records up to the payload's end. */
#define SXL_PIL_IN_SEQ 0u       /* u16, echoed */
#define SXL_PIL_IN_ADC 2u       /* 6 phase currents then the DC link, u16 counts each */
#define SXL_PIL_IN_ANGLE 16u    /* encoder electrical angle u32 */
#define SXL_PIL_IN_SPEED 20u    /* encoder mechanical speed i32, Q16 rev/s */
#define SXL_PIL_IN_POSITION 24u /* encoder position i32, counts */
#define SXL_PIL_IN_FLAGS 28u    /* u8: SXL_PIL_IN_* bits */
#define SXL_PIL_IN_BYTES 29u    /* the inputs; call records follow */
#define SXL_PIL_IN_ADC_FRESH 0x01u
#define SXL_PIL_IN_ENC_HEALTHY 0x02u
#define SXL_PIL_IN_ENC_INDEX_SEEN 0x04u
#define SXL_PIL_IN_HW_TRIP 0x08u
#define SXL_PIL_IN_FORCED_OFF 0x10u  /* the plant's hardware trip forces the outputs off too */
#define SXL_PIL_IN_HOMING_LOST 0x20u /* the plant posts the index: homing back */

/* STEP reply, after the result byte: what the period wrote to the bus and how long it took on
 * the target's counter. */
#define SXL_PIL_OUT_SEQ 1u       /* u16 */
#define SXL_PIL_OUT_DUTY 3u      /* 6 legs, u16 (hal_pwm.h's Q15 duty) */
#define SXL_PIL_OUT_FLAGS 15u    /* u8: SXL_PIL_OUT_* bits */
#define SXL_PIL_OUT_ISOLATED 16u /* u8: bit k leg k off for good */
#define SXL_PIL_OUT_OFFSET 17u   /* u32: the encoder's electrical offset in force */
#define SXL_PIL_OUT_STATE 21u    /* u8: the drive's state */
#define SXL_PIL_OUT_FAULTS 22u   /* u16: faults latched (ctl_fault_t bits) */
#define SXL_PIL_OUT_CYCLES 24u   /* u32: the ISR, entry to end (the profile's TOTAL) */
#define SXL_PIL_OUT_STAGES 28u   /* u24 each: the profile's stages ADC .. PWM (6) */
#define SXL_PIL_OUT_STAGE_COUNT 6u
#define SXL_PIL_OUT_BYTES 46u
#define SXL_PIL_OUT_FORCED_OFF 0x01u
#define SXL_PIL_OUT_ADC_FRESH 0x02u
#define SXL_PIL_OUT_HOMING_LOST 0x04u
#define SXL_PIL_OUT_PWM_INIT 0x08u
#define SXL_PIL_OUT_HW_TRIP 0x10u

#endif /* SXLINK_PIL_H */
