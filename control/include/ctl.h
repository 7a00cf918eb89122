/*
 * The control step: the one API the firmware ISR, the simulator and the tests
 * all call. Measurements in, a switching command and diagnostics out.
 *
 * Timing contract (as on the target): ctl_step() is called once per control
 * period with the sample taken at the start of that period. The command it
 * returns takes effect at the start of the NEXT period; the command in force
 * during the current period is the previous call's output, which the core
 * remembers for its delay compensation.
 *
 * Command semantics: leg_duty[i] is the fraction of the period that the upper
 * switch of leg i is on, as one pulse centred in the period (centre-aligned
 * up-down carrier). A discrete-duty command (vector v, duty d) therefore puts
 * v in the middle of the period for d*Ts and a zero vector (u00 or u77) at the
 * edges, or v at the edges and the zero vector in the middle; both give the
 * same period average.
 */
#ifndef CTL_H
#define CTL_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_flux_ref.h"
#include "ctl_predict.h"
#include "ctl_q.h"
#include "ctl_speed_pi.h"

#define CTL_PHASES 6

/* Stage boundaries of ctl_step reported to an optional hook (execution-time profiling).
 * CTL_PROFILE=0 compiles the calls away; otherwise an unset hook costs one test per stage. */
#ifndef CTL_PROFILE
#define CTL_PROFILE 1
#endif

typedef enum {
    CTL_STAGE_TRANSFORMS = 0, /* VSD, Park, speed loop, flux reference done */
    CTL_STAGE_PREDICT = 1,    /* k+1 prediction and the k+2 free response done */
    CTL_STAGE_TABLE = 2,      /* sectors and lookup tables done (immediate for MPTC) */
    CTL_STAGE_SEARCH = 3      /* search and command done */
} ctl_stage_t;

typedef void (*ctl_stage_hook_t)(int16_t stage);

#if CTL_PROFILE
#define CTL_STAGE_MARK(hook, stage)                                                                \
    do {                                                                                           \
        if ((hook) != 0) {                                                                         \
            (hook)((int16_t)(stage));                                                              \
        }                                                                                          \
    } while (0)
#else
#define CTL_STAGE_MARK(hook, stage) ((void)0)
#endif
#define CTL_DUTY_LEVELS_MAX 11 /* = CTL_DDC_LEVELS_MAX */

typedef enum {
    CTL_CONTROLLER_DDC = 0,    /* the paper's discrete-duty MPTC */
    CTL_CONTROLLER_MPTC49 = 1, /* conventional MPTC, 48 vectors + zero */
    CTL_CONTROLLER_MPTC13 = 2  /* conventional MPTC, 12 largest + zero */
} ctl_controller_t;

/* How the discrete-duty method picks between the two alpha-beta directions
 * of a sector (see docs/design.md). */
typedef enum {
    CTL_DDC_DIRECTION_FLUX_ERROR = 0, /* DTC reading: flux error sign picks 75/105 deg */
    CTL_DDC_DIRECTION_XY_TABLE = 1    /* paper's table 2 literally: x-y sector picks one of four */
} ctl_ddc_direction_t;

typedef enum {
    CTL_LOOP_SPEED = 0, /* speed PI produces the torque reference */
    CTL_LOOP_TORQUE = 1 /* torque reference given directly */
} ctl_loop_mode_t;

/* Everything that can be set at init or changed at run time, in SI units.
 * Converted to per-unit coefficients once when applied, never per step. */
typedef struct {
    /* machine */
    float resistance_ohm;
    float ld_h;
    float lq_h;
    float l_xy_h; /* x-y (leakage) inductance */
    float pm_flux_wb;
    int16_t pole_pairs;
    float inertia_kg_m2; /* used by the protection's stopped-encoder check */
    /* control */
    float sample_time_s;
    ctl_controller_t controller;
    float lambda_nm_per_wb; /* flux weight of the cost */
    int16_t duty_levels;    /* DDC: levels k/(n-1), k = 0..n-1; paper: 6 */
    ctl_ddc_direction_t ddc_direction;
    /* improvement over the paper (docs/improvements.md), on by default; false = the paper */
    bool ddc_torque_guard; /* flux weighting moves the duty at most one level from the
                            * level that best meets the torque reference */
    ctl_flux_ref_mode_t flux_ref_mode;
    float flux_ref_wb; /* used when flux_ref_mode is constant */
    /* speed loop */
    float speed_kp_nm_per_rad_s; /* per mechanical rad/s */
    float speed_ki_nm_per_rad;   /* per mechanical rad */
    float torque_limit_nm;
} ctl_params_t;

typedef struct {
    ctl_q i_phase[CTL_PHASES]; /* A B C D E F, per unit */
    ctl_q vdc;                 /* per unit */
    ctl_q theta_e;             /* electrical angle, per unit turn */
    ctl_q omega_e;             /* electrical speed, per unit */
} ctl_meas_t;

typedef struct {
    ctl_q leg_duty[CTL_PHASES]; /* upper-switch on fraction, centred, [0, 1] */
    int16_t vector;             /* active switching state 0..63 (S_A is bit 5) */
    ctl_q duty;                 /* fraction of the period the active vector is applied */
    bool enable;                /* false: all switches off */
} ctl_cmd_t;

typedef struct {
    ctl_q i_d, i_q, i_x, i_y; /* measured, at sample k */
    ctl_q torque_est;         /* Te(k) from measured currents */
    ctl_q flux_est;           /* |psi_s|(k) */
    ctl_q torque_ref;
    ctl_q flux_ref;
    ctl_q torque_pred; /* chosen candidate, at k+2 */
    ctl_q flux_pred;
    ctl_q cost;
    int16_t flux_sector;      /* alpha-beta sector 0..11 at k+1 (DDC) */
    int16_t xy_sector;        /* x-y sector used by table 2 (DDC) */
    int16_t candidates;       /* candidates evaluated this step */
    bool braking;             /* DDC used the torque-lowering half of table 1 */
    uint16_t params_rejected; /* shadow parameter sets refused as invalid */
} ctl_diag_t;

typedef struct {
    ctl_params_t params; /* in force */
    ctl_params_t shadow; /* written by ctl_request_params, applied at a step start */
    volatile bool shadow_pending;
    ctl_model_t model;
    ctl_speed_pi_t speed_pi;
    ctl_flux_ref_t flux_ref;
    ctl_q lambda_pu;
    ctl_q duty_level[CTL_DUTY_LEVELS_MAX];
    ctl_q torque_limit_pu;
    ctl_loop_mode_t loop_mode;
    ctl_q speed_ref; /* electrical, per unit */
    ctl_q torque_ref_direct;
    int16_t applied_vector; /* command in force during the current period */
    ctl_q applied_duty;
    ctl_diag_t diag;
    bool initialised;            /* false: parameters were never valid, every command is all-off */
    ctl_stage_hook_t stage_hook; /* 0: none */
} ctl_t;

/* Paper's machine and controller with the brief's assumed values. */
void ctl_params_default(ctl_params_t *p);

/* True when every field is usable (positive inductances, levels in range...). */
bool ctl_params_valid(const ctl_params_t *p);

/* Returns false (and leaves c unusable, ctl_step commands all-off) on invalid parameters. */
bool ctl_init(ctl_t *c, const ctl_params_t *p);

/* Clears integrators and the remembered command (call before enabling PWM). */
void ctl_reset(ctl_t *c);

/* Queue a parameter change; it is applied at the start of the next ctl_step.
 * On the target call it from the background loop only. */
void ctl_request_params(ctl_t *c, const ctl_params_t *p);

void ctl_set_loop_mode(ctl_t *c, ctl_loop_mode_t mode);
void ctl_set_speed_ref(ctl_t *c, ctl_q omega_e_pu);
void ctl_set_torque_ref(ctl_t *c, ctl_q torque_pu);

/* One control period. */
void ctl_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd);

const ctl_diag_t *ctl_diag(const ctl_t *c);

/* Stage boundaries of every following ctl_step go to hook (0 removes it). */
void ctl_set_stage_hook(ctl_t *c, ctl_stage_hook_t hook);

#endif /* CTL_H */
