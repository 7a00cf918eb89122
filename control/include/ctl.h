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

#include "ctl_config.h"
#include "ctl_diag.h"
#include "ctl_params.h"
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
typedef enum {
    CTL_LOOP_SPEED = 0, /* speed PI produces the torque reference */
    CTL_LOOP_TORQUE = 1 /* torque reference given directly */
} ctl_loop_mode_t;

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

/*
 * Parameter hand-off (C2000Ware's init/run split, double-buffered): the background builds
 * the whole derived configuration (ctl_config.h) of a new set into the standby buffer, then
 * publishes it; the ISR switches to it at the start of a period, which costs a flag test
 * and an index flip. Single producer (background), single consumer (ISR), no lock:
 *   background  ctl_request_params: refused while a published set waits (config_ready);
 *               else builds into config[1 - active], barrier, config_ready = 1
 *   ISR         ctl_config_take: if config_ready: barrier, active flips, barrier,
 *               config_ready = 0; from then on the old buffer is the background's
 * The background never writes the buffer the ISR reads, and the ISR never reads a buffer
 * before it is published (ctl_barrier.h says why the barriers are needed).
 */
typedef struct {
    ctl_config_t config[2];
    volatile int16_t config_active; /* buffer in force: written by ctl_init and the ISR only */
    volatile int16_t config_ready;  /* 1: the other buffer is published and waits for the ISR */
    bool initialised;               /* false: no valid set was ever in force, commands all-off */
    /* a valid set without an open phase is in force: the healthy step runs; else
     * ctl_postfault.h's step, or all-off while none was ever valid (in initialised's padding) */
    bool healthy_step;
    /* the healthy step of the DDC, which holds the x-y currents near zero: the protection's fast
     * open-phase check may judge (ctl_protect_input_t.xy_held) */
    bool xy_held;
    bool foc_step; /* the healthy step is FOC-VSD's (ctl_foc.h), which ctl_step calls itself */
    uint16_t params_rejected;            /* sets refused by ctl_request_params (background) */
    ctl_param_error_t params_last_error; /* reason of the last refusal */
    ctl_speed_pi_t speed_pi;             /* gains copied from the configuration in force */
    ctl_loop_mode_t loop_mode;
    ctl_q speed_ref; /* electrical, per unit */
    ctl_q torque_ref_direct;
    int16_t applied_vector; /* command in force during the current period */
    ctl_q applied_duty;
    int16_t applied_edges; /* its legs' states at the period boundary (S_A = bit 5) */
    /* the virtual vector in force (VV-MPTC, 0..CTL_VV_COUNT - 1; applied_vector is then its
     * large state, applied_duty 1), CTL_VV_NONE for a switching state with a duty */
    int16_t applied_virtual;
    ctl_diag_t diag;
    ctl_stage_hook_t stage_hook; /* 0: none */
    /* the open-phase part of each configuration (ctl_postfault_config.h), built and taken with
     * it; a separate array keeps the healthy configuration's layout as it was */
    ctl_postfault_config_t postfault[2];
    ctl_foc_state_t foc; /* FOC-VSD's integrators and voltage in force (ctl_foc.h) */
} ctl_t;

/* Builds the first configuration from p (background, before the ISR runs). Returns false,
 * with the reason in params_last_error, on an unusable set: ctl_step then commands all-off
 * until a valid set is taken. */
bool ctl_init(ctl_t *c, const ctl_params_t *p);

/* Clears integrators and the remembered command (call before enabling PWM). */
void ctl_reset(ctl_t *c);

/* Clears the remembered command only (the outputs were off): the speed loop keeps its state. */
void ctl_reset_command(ctl_t *c);

/* Background: check p, build its configuration into the standby buffer and publish it; the
 * ISR takes it at the start of its next period. CTL_PARAM_BUSY while an earlier set still
 * waits (try again after a period); any other refusal is counted, and the set in force
 * stays. Never call from the ISR: building takes milliseconds. */
ctl_param_error_t ctl_request_params(ctl_t *c, const ctl_params_t *p);

/* ISR, at the start of a period, before anything reads the configuration: switches to a
 * published set. True if it switched. ctl_step calls it too; calling it twice is harmless. */
bool ctl_config_take(ctl_t *c);

/* The configuration in force (ISR side), and its parameter set. */
const ctl_config_t *ctl_config(const ctl_t *c);
const ctl_params_t *ctl_params(const ctl_t *c);

/* The open-phase configuration in force (open_leg CTL_POSTFAULT_NO_LEG: all six phases healthy). */
const ctl_postfault_config_t *ctl_postfault_config(const ctl_t *c);

/* A published set waits for the ISR. */
bool ctl_config_pending(const ctl_t *c);

void ctl_set_loop_mode(ctl_t *c, ctl_loop_mode_t mode);
void ctl_set_speed_ref(ctl_t *c, ctl_q omega_e_pu);
void ctl_set_torque_ref(ctl_t *c, ctl_q torque_pu);

/* One control period. */
void ctl_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd);
/* One control period with all six legs (ctl.c), the step ctl_step (ctl_step.c) hands the period
 * to when no phase is open (ctl_postfault_step, ctl_postfault.h, otherwise). */
void ctl_healthy_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd);

const ctl_diag_t *ctl_diag(const ctl_t *c);

/* Te and |psi_s| of rotor-frame currents with the model in force, and those of the diagnostics'
 * measured currents at k: computed by whoever reads them (background, capture, the protection's
 * encoder check when it needs one, the simulator), not in every control period (issue 28). */
ctl_q ctl_torque_estimate(const ctl_t *c, ctl_q i_d, ctl_q i_q);
ctl_q ctl_diag_torque_est(const ctl_t *c);
ctl_q ctl_diag_flux_est(const ctl_t *c);

/* Stage boundaries of every following ctl_step go to hook (0 removes it). */
void ctl_set_stage_hook(ctl_t *c, ctl_stage_hook_t hook);

#endif /* CTL_H */
