/*
 * Motor identification (the drive's commissioning, docs/commissioning.md): what its steps
 * share. Each step (ident_phase.c, ident_encoder.c, ident_resistance.c, ident_inductance.c,
 * ident_flux.c, ident_mech.c) runs in the control ISR, one call per period, and leaves the machine
 * in a known state for the next (current on, rotor aligned with the commanded angle); the sequencer
 * (commission.c) calls them in order.
 *
 * Single-precision float in SI units (A, V, s, H, Wb; angles in turns) whatever the control
 * core's arithmetic; no double, no libm (the core's sine and square root); bounded work per
 * period; long averages are kept in blocks (ident_stats.h).
 */
#ifndef IDENT_H
#define IDENT_H

#include <stdbool.h>
#include <stdint.h>

#include "ident_excite.h"
#include "ident_stats.h"
#include "ident_xy_harmonics.h"
#include "lists/commission_lists.h"

/* The lists of commission_lists.h as enums. */
#define IDENT_ENUM_STEP(id, number, name, text) COMM_STEP_##id = number,
#define IDENT_ENUM_QUANTITY(id, number, name, step, unit, scale, xscale, extra)                    \
    COMM_Q_##id = number,
#define IDENT_ENUM_QUALITY(id, number, name, text) COMM_QUALITY_##id = number,
#define IDENT_ENUM_REASON(id, number, name, text) COMM_REASON_##id = number,
#define IDENT_ENUM_STATE(id, number, name, text) COMM_STATE_##id = number,
typedef enum { COMM_STEP_LIST(IDENT_ENUM_STEP) COMM_STEP_END } comm_step_t;
typedef enum { COMM_QUANTITY_LIST(IDENT_ENUM_QUANTITY) COMM_Q_COUNT } comm_quantity_t;
typedef enum { COMM_QUALITY_LIST(IDENT_ENUM_QUALITY) COMM_QUALITY_END } comm_quality_t;
typedef enum { COMM_REASON_LIST(IDENT_ENUM_REASON) COMM_REASON_END } comm_reason_t;
typedef enum { COMM_STATE_LIST(IDENT_ENUM_STATE) COMM_STATE_END } comm_state_t;
#undef IDENT_ENUM_STEP
#undef IDENT_ENUM_QUANTITY
#undef IDENT_ENUM_QUALITY
#undef IDENT_ENUM_REASON
#undef IDENT_ENUM_STATE

/* One control period's measurements, SI. */
typedef struct {
    float i_phase[IDENT_PHASES]; /* A */
    float vdc;                   /* V */
    uint32_t elec_angle;         /* the encoder HAL's angle, 2^32 = one turn */
    int32_t position;            /* the encoder's unwrapped counts */
    bool index_seen;
    float mech_rev_s; /* the encoder's speed, rev/s of its own counts */
} ident_input_t;

/* What the steps know of the machine and the drive: the parameter set in force at the start
 * (the reference machine until identified), the board's encoder and the protection. */
typedef struct {
    float ts;                             /* control period, s */
    float r, ld, lq, lxy, psi_f, inertia; /* SI */
    int16_t pole_pairs;                   /* configured */
    float rated_a;                        /* torque limit / (3 Pn psi_f) */
    float trip_a;                         /* software over-current limit */
    float counts_per_turn;                /* encoder counts per mechanical turn */
    float overspeed_e;                    /* electrical rad/s of the over-speed limit */
    float vdc;                            /* DC link at the start, V */
    float dead_time_s;                    /* the board's dead time (its voltage is fed forward) */
    float open_ratio;                     /* the protection's open-phase ratio */
    float u_current, u_vdc; /* relative 1-sigma uncertainty of the current channels' scale and
                             * of the DC link's measurement (the board's tolerances) */
    uint32_t hal_offset;    /* the encoder HAL's offset at the start */
} ident_machine_t;

/* One identified quantity. */
typedef struct {
    float value, sigma, extra; /* SI (commission_lists.h says the extra's unit) */
    int16_t quality;           /* comm_quality_t */
    int16_t reason;            /* comm_reason_t */
} ident_result_t;

typedef enum { IDENT_RUNNING = 0, IDENT_DONE = 1, IDENT_FAILED = 2 } ident_status_t;

typedef enum {
    IDENT_FRAME_COMMAND = 0, /* the regulator's d axis at the commanded angle (traj) */
    IDENT_FRAME_ROTOR = 1    /* at the rotor's d axis: encoder angle + identified offset */
} ident_frame_t;

/* The state the steps share: machine, excitation, this period's measurements, what the
 * encoder step found, the sub-phase of the running step and the results. */
typedef struct {
    ident_machine_t m;
    float i_test; /* A */
    ident_reg_t reg;
    ident_xy_harmonics_t xy_harm; /* ROTOR frame, rotor turning: the 5th and 7th in x-y */
    ident_traj_t traj;
    ident_frame_t frame;
    float ref_dq[2], ref_xy[2]; /* current references, A: in the frame, in x-y */
    float damping;              /* COMMAND frame: A of q current per turn/s of the rotor's
                                 * electrical speed above the commanded one (0: off) */
    /* this period */
    float i_ab[2], i_xy[2], i_dq[2]; /* A */
    float frame_s, frame_c;          /* sine and cosine of the frame angle */
    float out_s, out_c;              /* of the angle the output is applied at (delay) */
    float comp_dq[2];                /* the dead-time feed-forward in the frame, V */
    float comp_xy[2];                /* and in x-y */
    float speed_e;                   /* rotor, electrical turns/s (once the encoder is known) */
    /* the encoder as the encoder step found it */
    bool enc_known;      /* direction and counts per electrical turn measured */
    float cpe;           /* counts per electrical turn, signed */
    bool offset_known;   /* the d axis is at the HAL angle + offset_turns */
    float offset_turns;  /* turns */
    uint32_t offset_abs; /* the HAL offset that puts the d axis at the HAL angle (2^32 = turn) */
    /* the running step */
    int16_t phase;  /* its sub-phase */
    uint32_t t;     /* periods in the sub-phase */
    int16_t reason; /* comm_reason_t of a failure */
    ident_result_t result[COMM_Q_COUNT];
} ident_ctx_t;

/* Whether the rotor stands still: the periods it has stayed within a few counts of one position
 * (a swing's turning points, where it slows, last less than a few tens of ms). */
typedef struct {
    int32_t ref; /* the position it has stayed near */
    uint32_t n;  /* periods it has */
} ident_still_t;

void ident_still_reset(ident_still_t *w, int32_t position);

/* This period's position; the periods still so far (0: it just moved beyond `counts`). */
uint32_t ident_still_step(ident_still_t *w, int32_t position, int32_t counts);

/* A quantity as the steps take it: its result when ok, else the parameter set's value `set`. */
float ident_known(const ident_ctx_t *x, comm_quantity_t q, float set);

/* Periods in s seconds (at least 1). */
uint32_t ident_periods(const ident_ctx_t *x, float seconds);

/* Enter sub-phase p of the running step (its period count restarts). */
void ident_goto(ident_ctx_t *x, int16_t phase);

/* Fail the running step: the reason, IDENT_FAILED. */
ident_status_t ident_fail(ident_ctx_t *x, int16_t reason);

/* Record a quantity's result: sigma is the scatter of its blocks; the result's uncertainty adds
 * the share of the measurement's scale, which is the same in every block. */
void ident_set_result(ident_ctx_t *x, comm_quantity_t q, float value, float sigma, float extra,
                      int16_t quality, int16_t reason);

/* This period's currents in the stationary planes and in the frame, and the rotor's speed. */
void ident_measure(ident_ctx_t *x, const ident_input_t *in);

/* The regulator's step with the references (and the damping), plus the dead-time feed-forward
 * (each phase's dead-time voltage, Vdc Td / Ts, with the sign of its reference current), into
 * x->reg.u. */
void ident_regulate(ident_ctx_t *x, float vdc);

/* The voltage commanded along the frame's axis 0 (d) or 1 (q) this period: the regulator's
 * output and the feed-forward (what the estimators take as the applied voltage). */
float ident_u_frame(const ident_ctx_t *x, int16_t axis);

/* The HAL angle as the rotor's d axis (turns), once the offset is known. */
float ident_rotor_angle(const ident_ctx_t *x, const ident_input_t *in);

/* 0..1 raised-cosine ramp at t of n periods. */
float ident_ramp(uint32_t t, uint32_t n);
/* A speed loop's step (the flux and the mechanics steps): i_q reference = kp e + integral,
 * within the test current; the integrator moves only while i_q is within it. */
void ident_speed_loop(ident_ctx_t *x, ident_pi_t *pi, float error);

#endif /* IDENT_H */
