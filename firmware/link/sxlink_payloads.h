/*
 * The payloads of the serial link, one list each: X(OFFSET_NAME, TYPE, COUNT, "what"), fields in
 * wire order, TYPE one of U8 U16 U32 I16 I32, COUNT elements of it. From each list come the
 * byte offsets and the size (an enum: SXL_ST_SPEED is the offset of the status' speed,
 * SXL_ST_SIZE the block's length) and the field tables of docs/serial-protocol.md
 * (tools/protocol_doc). No offset is computed by hand: a field added in the middle moves the
 * ones after it everywhere at once. Request payloads exclude the armed session's token; reply
 * payloads start after the result byte.
 */
#ifndef SXLINK_PAYLOADS_H
#define SXLINK_PAYLOADS_H

#define SXL_STR_(x) #x
#define SXL_STR(x) SXL_STR_(x) /* a plain number's text, for help lines */

#define SXL_BYTES_U8 1
#define SXL_BYTES_U16 2
#define SXL_BYTES_U32 4
#define SXL_BYTES_I16 2
#define SXL_BYTES_I32 4

#define SXL_PF_STAGES 8u /* GET_PROFILE's stages, 0 .. 7 */
#define SXL_FR_PHASES 6u /* phase currents in a fault record */
#define SXL_CR_MAX 20u   /* samples per CAPTURE_READ reply */
#define SXL_CAPTURE_CHANNELS 4u

/* X(offset name, type, count, what) for every field of every payload below. */
#define SXL_PAYLOAD_OFFSET(name, type, count, what)                                                \
    name, name##_END_ = name + SXL_BYTES_##type * (count)-1,

/* No payload. */
#define SXL_NONE_FIELDS(X)
enum { SXL_NONE_SIZE = 0 };

/* GET_STATUS reply: the status block. Later protocol versions only append (SXL_ST_SIZE_V*). */
#define SXL_ST_FIELDS(X)                                                                           \
    X(SXL_ST_STATE, U8, 1,                                                                         \
      "drive state: 0 INIT, 1 CALIBRATE, 2 READY, 3 RUN, 4 FAULT, 5 COMMISSION")                   \
    X(SXL_ST_FAULT, U8, 1, "fault: the first since the last clear, code table below")              \
    X(SXL_ST_FLAGS, U8, 1,                                                                         \
      "flags: bit 0 encoder healthy, bit 1 PWM outputs off, bit 2 parameter "                      \
      "change pending, bit 3 a leg isolated (GET_OPEN_PHASE), bit 4 "                              \
      "torque-limited: the speed loop at its torque limit for 0.1 s or "                           \
      "more, the speed not held (docs/faults.md)")                                                 \
    X(SXL_ST_CONTROLLER, U8, 1,                                                                    \
      "controller in force (0 ddc, 1 mptc49, 2 mptc13, 3 foc, 4 vvmptc)")                          \
    X(SXL_ST_SPEED, I32, 1, "measured mechanical speed, 0.1 r/min")                                \
    X(SXL_ST_SPEED_REF, I32, 1, "speed reference, 0.1 r/min")                                      \
    X(SXL_ST_TORQUE, I32, 1, "torque estimate, mN·m")                                              \
    X(SXL_ST_TORQUE_REF, I32, 1, "torque reference, mN·m")                                         \
    X(SXL_ST_LAMBDA, U32, 1, "lambda in force, 0.001 N·m/Wb")                                      \
    X(SXL_ST_ISR_COUNT, U32, 1, "control periods since start")                                     \
    X(SXL_ST_ISR_MAX, U32, 1, "longest control ISR so far, CPU cycles (150 per µs)")               \
    X(SXL_ST_RX_ERRORS, U16, 1, "malformed frames received")                                       \
    X(SXL_ST_FAULTS, U16, 1,                                                                       \
      "faults latched since the last clear: fault bit mask, below (protocol 2)")                   \
    X(SXL_ST_RECORDS, U16, 1,                                                                      \
      "fault records in the log not yet read, GET_FAULT_RECORD (protocol 2)")                      \
    X(SXL_ST_RUN_REFUSAL, U8, 1,                                                                   \
      "reason of the last refused run: 0 NONE, 1 NOT_READY (not in READY), "                       \
      "2 ENCODER (index not seen since power-up or since an ENCODER "                              \
      "fault was cleared), 3 UNDERVOLTAGE (DC link below the limit, or "                           \
      "off) (protocol 3)")                                                                         \
    X(SXL_ST_CLEAR_BLOCKED, U16, 1,                                                                \
      "conditions that refused the last clear, as fault bits (0: none): a "                        \
      "condition active in that period, the trip pin, ADC_MISSING if "                             \
      "no fresh conversion came, a latched encoder, under-voltage or "                             \
      "stuck-ADC fault still present (protocol 3)")                                                \
    X(SXL_ST_STACK_USED, U16, 1,                                                                   \
      "the stack's high-water mark since start-up, words (protocol 6): the "                       \
      "part in use when start-up painted the stack plus the deepest use "                          \
      "since; scanned while this reply is built (background)")                                     \
    X(SXL_ST_STACK_WORDS, U16, 1,                                                                  \
      "the stack's size, words (0x700 = 1792 on the F28335); 0 = not "                             \
      "measured: the virtual board has no C28x stack and sends 0 and 0")
enum { SXL_ST_FIELDS(SXL_PAYLOAD_OFFSET) SXL_ST_SIZE };
/* What older versions' blocks ended at: readers accept the shorter block. */
enum {
    SXL_ST_SIZE_V1 = SXL_ST_FAULTS,      /* protocol 1 ended at rx_errors */
    SXL_ST_SIZE_V2 = SXL_ST_RUN_REFUSAL, /* protocol 2 ended at records */
    SXL_ST_SIZE_V5 = SXL_ST_STACK_USED   /* protocol 3 to 5 ended at the clear's conditions */
};
#define SXL_STACK_NOT_MEASURED 0u /* SXL_ST_STACK_WORDS of a platform that does not paint it */

/* GET_PROFILE request, and its reply in cycles of the ISR's counter
 * (firmware/app/measure/profile.h). */
#define SXL_PQ_FIELDS(X) X(SXL_PQ_STAGE, U8, 1, "stage, 0 .. 7")
enum { SXL_PQ_FIELDS(SXL_PAYLOAD_OFFSET) SXL_PQ_SIZE };
#define SXL_PF_FIELDS(X)                                                                           \
    X(SXL_PF_STAGE, U8, 1, "stage, echoed")                                                        \
    X(SXL_PF_LAST, U32, 1, "last, cycles")                                                         \
    X(SXL_PF_MIN, U32, 1, "minimum, cycles")                                                       \
    X(SXL_PF_MAX, U32, 1, "maximum, cycles")                                                       \
    X(SXL_PF_MEAN, U32, 1, "running mean, cycles")                                                 \
    X(SXL_PF_PERIOD, U32, 1, "control period, cycles")                                             \
    X(SXL_PF_READ_COST, U32, 1, "subtracted measurement cost, cycles")                             \
    X(SXL_PF_CYCLES_PER_US, U16, 1, "cycles per microsecond")                                      \
    X(SXL_PF_LOAD_LAST, U16, 1, "last load, per mille of the period")                              \
    X(SXL_PF_LOAD_MAX, U16, 1, "largest load, per mille of the period")                            \
    X(SXL_PF_OVERRUNS, U32, 1, "overruns")
enum { SXL_PF_FIELDS(SXL_PAYLOAD_OFFSET) SXL_PF_SIZE };

/* GET_FAULT_RECORD reply. An empty log gives PRESENT 0 and only the header's bytes. */
#define SXL_FR_FIELDS(X)                                                                           \
    X(SXL_FR_PRESENT, U8, 1,                                                                       \
      "present: 1 a record follows (now removed from the log), 0 the log is empty and the reply "  \
      "ends here")                                                                                 \
    X(SXL_FR_PENDING, U16, 1, "records still unread after this one")                               \
    X(SXL_FR_DROPPED, U16, 1,                                                                      \
      "records dropped because the log was full (since start, wraps at 65536)")                    \
    X(SXL_FR_FAULTS, U16, 1, "fault bit mask of every fault detected in that period")              \
    X(SXL_FR_PERIOD, U32, 1, "control-period count at detection")                                  \
    X(SXL_FR_I_PHASE, I16, SXL_FR_PHASES, "phase currents A, B, C, D, E, F, 10 mA")                \
    X(SXL_FR_VDC, I16, 1, "DC link voltage, 0.1 V")                                                \
    X(SXL_FR_THETA, U16, 1, "electrical angle, 1/65536 turn (0..65535 = 0..360 deg)")              \
    X(SXL_FR_SPEED, I32, 1,                                                                        \
      "mechanical speed, 0.1 r/min (electrical speed / pole pairs of the last parameter set)")     \
    X(SXL_FR_TORQUE, I32, 1, "torque estimate, mN·m")                                              \
    X(SXL_FR_TORQUE_REF, I32, 1, "torque reference, mN·m")                                         \
    X(SXL_FR_VECTOR, I16, 1, "switching vector in force (0..63)")                                  \
    X(SXL_FR_DUTY, U16, 1, "duty of that vector, Q15 (32768 = 1.0)")
enum { SXL_FR_FIELDS(SXL_PAYLOAD_OFFSET) SXL_FR_SIZE };
enum { SXL_FR_HEADER_SIZE = SXL_FR_FAULTS }; /* present, pending, dropped */

/* SET_SPEED, SET_TORQUE and SET_CONTROLLER requests; a reference beyond its limit either way
 * is refused with SXL_ERR_VALUE. */
#define SXL_SPEED_REF_MAX_RPM 20000
#define SXL_TORQUE_REF_MAX_NM 1000
#define SXL_SPEED_REF_MAX (SXL_SPEED_REF_MAX_RPM * 10L)    /* 0.1 r/min */
#define SXL_TORQUE_REF_MAX (SXL_TORQUE_REF_MAX_NM * 1000L) /* mN·m */
#define SXL_SPEED_FIELDS(X) X(SXL_SPEED_REF, I32, 1, "speed reference, 0.1 r/min")
enum { SXL_SPEED_FIELDS(SXL_PAYLOAD_OFFSET) SXL_SPEED_SIZE };
#define SXL_TORQUE_FIELDS(X) X(SXL_TORQUE_REF, I32, 1, "torque reference, mN·m")
enum { SXL_TORQUE_FIELDS(SXL_PAYLOAD_OFFSET) SXL_TORQUE_SIZE };
#define SXL_SC_FIELDS(X)                                                                           \
    X(SXL_SC_CONTROLLER, U8, 1, "controller: 0 ddc, 1 mptc49, 2 mptc13, 3 foc, 4 vvmptc")          \
    X(SXL_SC_LAMBDA, U32, 1, "lambda, 0.001 N·m/Wb")
enum { SXL_SC_FIELDS(SXL_PAYLOAD_OFFSET) SXL_SC_SIZE };

/* ARM reply. */
#define SXL_AR_FIELDS(X) X(SXL_AR_TOKEN, U32, 1, "the session's token, never 0")
enum { SXL_AR_FIELDS(SXL_PAYLOAD_OFFSET) SXL_AR_SIZE };

/* PING reply. */
#define SXL_PG_FIELDS(X) X(SXL_PG_VERSION, U8, 1, "protocol version")
enum { SXL_PG_FIELDS(SXL_PAYLOAD_OFFSET) SXL_PG_SIZE };

/* SET_TORQUE_LIMITED_ACTION request (ACTION, STOP_MS) and GET_TORQUE_LIMITED reply (all). */
#define SXL_TL_SET_FIELDS(X)                                                                       \
    X(SXL_TL_ACTION, U8, 1, "action: 0 continue, 1 stop")                                          \
    X(SXL_TL_STOP_MS, U16, 1, "ms at the limit before the stop action stops")
enum { SXL_TL_SET_FIELDS(SXL_PAYLOAD_OFFSET) SXL_TL_SET_SIZE };
#define SXL_TL_FIELDS(X)                                                                           \
    SXL_TL_SET_FIELDS(X)                                                                           \
    X(SXL_TL_STOPPED, U8, 1, "1: the stop action stopped the last run")
enum { SXL_TL_STOPPED = SXL_TL_SET_SIZE, SXL_TL_SIZE = SXL_TL_STOPPED + SXL_BYTES_U8 };

/* CAPTURE_ARM request (signals: firmware/link/capture_signals.h; unused channels 0xFF). */
#define SXL_CA_FIELDS(X)                                                                           \
    X(SXL_CA_CHANNELS, U8, 1, "channels, 1 .. 4")                                                  \
    X(SXL_CA_SIGNAL, U8, SXL_CAPTURE_CHANNELS, "signals, unused 0xFF")                             \
    X(SXL_CA_LENGTH, U16, 1, "samples per channel")                                                \
    X(SXL_CA_DECIMATION, U16, 1, "one sample every N control periods, N >= 1")                     \
    X(SXL_CA_TRIGGER, U8, 1, "trigger: 0 immediate, 1 rising, 2 falling, 3 fault")                 \
    X(SXL_CA_TRIG_SIGNAL, U8, 1, "trigger signal")                                                 \
    X(SXL_CA_TRIG_LEVEL, I16, 1, "level, in the trigger signal's sample units")                    \
    X(SXL_CA_PRE, U8, 1, "pre-trigger share, %")
enum { SXL_CA_FIELDS(SXL_PAYLOAD_OFFSET) SXL_CA_SIZE };
/* CAPTURE_STATUS reply. */
#define SXL_CS_FIELDS(X)                                                                           \
    X(SXL_CS_STATE, U8, 1, "state: 0 idle, 1 armed, 2 triggered, 3 done")                          \
    X(SXL_CS_CHANNELS, U8, 1, "channels")                                                          \
    X(SXL_CS_SIGNAL, U8, SXL_CAPTURE_CHANNELS, "signals")                                          \
    X(SXL_CS_LENGTH, U16, 1, "length, samples per channel")                                        \
    X(SXL_CS_DECIMATION, U16, 1, "decimation")                                                     \
    X(SXL_CS_COUNT, U16, 1, "valid samples per channel")                                           \
    X(SXL_CS_TRIGGER, U16, 1, "the trigger sample's index in the record")                          \
    X(SXL_CS_PERIOD, U32, 1, "control-period count of the first sample")                           \
    X(SXL_CS_TS_NS, U32, 1, "control period, ns")
enum { SXL_CS_FIELDS(SXL_PAYLOAD_OFFSET) SXL_CS_SIZE };
/* CAPTURE_READ request and reply (COUNT samples follow, 0 past the record). */
#define SXL_CQ_FIELDS(X)                                                                           \
    X(SXL_CQ_CHANNEL, U8, 1, "channel")                                                            \
    X(SXL_CQ_FIRST, U16, 1, "first sample, 0 = oldest")
enum { SXL_CQ_FIELDS(SXL_PAYLOAD_OFFSET) SXL_CQ_SIZE };
#define SXL_CR_FIELDS(X)                                                                           \
    X(SXL_CR_COUNT, U8, 1, "samples that follow, n (0 past the record)")                           \
    X(SXL_CR_SAMPLES, I16, SXL_CR_MAX, "the samples, n of them")
enum { SXL_CR_FIELDS(SXL_PAYLOAD_OFFSET) SXL_CR_SIZE };

/* COMMISSION_START request, COMMISSION_STATUS reply, COMMISSION_RESULT request and reply,
 * COMMISSION_APPLY reply (the lists: sxlink_commission.h). */
#define SXL_CC_FIELDS(X)                                                                           \
    X(SXL_CC_MASK, U8, 1, "steps, bit per step")                                                   \
    X(SXL_CC_CURRENT, U16, 1, "test current, per mille of rated")
enum { SXL_CC_FIELDS(SXL_PAYLOAD_OFFSET) SXL_CC_SIZE };
#define SXL_CT_FIELDS(X)                                                                           \
    X(SXL_CT_STATE, U8, 1, "state: 0 idle, 1 running, 2 done, 3 failed, 4 aborted")                \
    X(SXL_CT_STEP, U8, 1, "step running, or the last one run (numbers as in the mask)")            \
    X(SXL_CT_PROGRESS, U8, 1, "progress of the whole sequence, %")                                 \
    X(SXL_CT_REASON, U8, 1, "reason: of the last refused start, or of the end (list below)")       \
    X(SXL_CT_MASK, U8, 1, "the sequence's step mask")                                              \
    X(SXL_CT_CURRENT, U16, 1, "its test current, per mille of rated")                              \
    X(SXL_CT_PERIODS, U32, 1, "control periods since its start")
enum { SXL_CT_FIELDS(SXL_PAYLOAD_OFFSET) SXL_CT_SIZE };
#define SXL_CQ2_FIELDS(X) X(SXL_CQ2_QUANTITY, U8, 1, "quantity (list below)")
enum { SXL_CQ2_FIELDS(SXL_PAYLOAD_OFFSET) SXL_CQ2_SIZE };
#define SXL_CR2_FIELDS(X)                                                                          \
    X(SXL_CR2_QUANTITY, U8, 1, "quantity, echoed")                                                 \
    X(SXL_CR2_QUALITY, U8, 1,                                                                      \
      "quality: 0 not_run, 1 ok, 2 poor (a number, but its scatter or a check is beyond the "      \
      "limit), 3 failed (no number)")                                                              \
    X(SXL_CR2_REASON, U8, 1, "reason (list below)")                                                \
    X(SXL_CR2_VALUE, I32, 1, "value x the quantity's scale")                                       \
    X(SXL_CR2_SIGMA, I32, 1, "1-sigma uncertainty x the quantity's scale")                         \
    X(SXL_CR2_EXTRA, I32, 1, "the quantity's extra x its extra scale")
enum { SXL_CR2_FIELDS(SXL_PAYLOAD_OFFSET) SXL_CR2_SIZE };
#define SXL_CA2_FIELDS(X) X(SXL_CA2_APPLIED, U16, 1, "quantities applied, bit per quantity")
enum { SXL_CA2_FIELDS(SXL_PAYLOAD_OFFSET) SXL_CA2_SIZE };

/* GET_OPEN_PHASE reply, SET_OPEN_PHASE_ACTION and ISOLATE_LEG requests. */
#define SXL_OP_FIELDS(X)                                                                           \
    X(SXL_OP_ACTION, U8, 1, "what OPEN_PHASE does: 0 stop, 1 ride through")                        \
    X(SXL_OP_STRATEGY, U8, 1, "strategy: 0 minimum loss, 1 maximum torque")                        \
    X(SXL_OP_LEG, U8, 1, "isolated leg 0 .. 5 (A .. F), 0xFF none")                                \
    X(SXL_OP_CAUSE, U8, 1, "cause: 0 none, 1 an OPEN_PHASE ridden through, 2 a command")           \
    X(SXL_OP_IN_FORCE, U8, 1, "1: the parameter set for the legs as they are is in force")         \
    X(SXL_OP_TORQUE_LIMIT, I32, 1, "the speed loop's torque limit in force, mN·m")                 \
    X(SXL_OP_PERIOD, U32, 1, "control-period count at the last isolation, 0 before the first")
enum { SXL_OP_FIELDS(SXL_PAYLOAD_OFFSET) SXL_OP_SIZE };
#define SXL_OA_FIELDS(X)                                                                           \
    X(SXL_OA_ACTION, U8, 1, "action: 0 stop, 1 ride through")                                      \
    X(SXL_OA_STRATEGY, U8, 1, "strategy: 0 minimum loss, 1 maximum torque")
enum { SXL_OA_FIELDS(SXL_PAYLOAD_OFFSET) SXL_OA_SIZE };
#define SXL_IL_FIELDS(X) X(SXL_IL_LEG, U8, 1, "leg 0 .. 5 (A .. F)")
enum { SXL_IL_FIELDS(SXL_PAYLOAD_OFFSET) SXL_IL_SIZE };

/* Every payload above, by its prefix (its fields SXL_x_FIELDS, its size SXL_x_SIZE): what the
 * tools that print or check the layouts walk (tools/protocol_doc). */
#define SXL_PAYLOAD_LIST(X)                                                                        \
    X(SXL_NONE)                                                                                    \
    X(SXL_ST)                                                                                      \
    X(SXL_PQ)                                                                                      \
    X(SXL_PF)                                                                                      \
    X(SXL_FR)                                                                                      \
    X(SXL_SPEED)                                                                                   \
    X(SXL_TORQUE)                                                                                  \
    X(SXL_SC)                                                                                      \
    X(SXL_AR)                                                                                      \
    X(SXL_PG)                                                                                      \
    X(SXL_TL_SET)                                                                                  \
    X(SXL_TL)                                                                                      \
    X(SXL_CA)                                                                                      \
    X(SXL_CS)                                                                                      \
    X(SXL_CQ)                                                                                      \
    X(SXL_CR)                                                                                      \
    X(SXL_CC)                                                                                      \
    X(SXL_CT)                                                                                      \
    X(SXL_CQ2)                                                                                     \
    X(SXL_CR2)                                                                                     \
    X(SXL_CA2)                                                                                     \
    X(SXL_OP)                                                                                      \
    X(SXL_OA)                                                                                      \
    X(SXL_IL)

#endif /* SXLINK_PAYLOADS_H */
