/*
 * The simulator's view of one controller build (fixed or float): a table of
 * functions with double-only arguments, implemented by
 * sim_controller_bridge.c compiled once per arithmetic. Each bridge owns a
 * static drive_t and runs the firmware's drive_control_isr against the
 * simulator HAL.
 */
#ifndef SIM_CTL_H
#define SIM_CTL_H

#include <stdbool.h>

/* The configuration of one controller build, one list: X(KIND, name), KIND INT (int), REAL
 * (double) or BOOL. The struct and its byte image for a processor-in-the-loop target
 * (sim_ctl_wire.h) come from it. */
#define SIM_CTL_CONFIG_FIELDS(X)                                                                   \
    X(INT, controller)            /* 0 ddc, 1 mptc49, 2 mptc13, 3 foc, 4 vvmptc */                 \
    X(REAL, lambda)               /* N*m/Wb */                                                     \
    X(REAL, ts_s)                 /* control period */                                             \
    X(INT, duty_levels)           /* <= 0: core default */                                         \
    X(INT, ddc_direction)         /* < 0: core default; 0 flux-error, 1 xy-table */                \
    X(INT, flux_ref_mode)         /* < 0: core default; 0 constant, 1 MTPA */                      \
    X(INT, ddc_torque_guard)      /* < 0: core default (on); 0 off (paper), 1 on */                \
    X(INT, mid_period_angle)      /* < 0: core default (off); 1 on */                              \
    X(INT, pulse_pattern)         /* < 0: core default; else a ctl_pulse_pattern_t */              \
    X(REAL, flux_tie_band)        /* < 0: core default; 0 off (paper), else a fraction */          \
    X(REAL, light_load_current_a) /* < 0: core default; 0: plain MTPA */                           \
    X(REAL, flux_ref_wb)          /* <= 0: core default */                                         \
    X(REAL, r_ohm)                /* the machine as the controller knows it */                     \
    X(REAL, ld_h)                                                                                  \
    X(REAL, lq_h)                                                                                  \
    X(REAL, lxy_h)                                                                                 \
    X(REAL, psi_f_wb)                                                                              \
    X(INT, pole_pairs)                                                                             \
    X(REAL, j_kgm2)                                                                                \
    X(REAL, speed_kp) /* speed loop; <= 0: core default */                                         \
    X(REAL, speed_ki)                                                                              \
    X(REAL, torque_limit_nm)                                                                       \
    X(BOOL, speed_gains_from_j)    /* the gains designed from j_kgm2 (speed_kp, ki unused) */      \
    X(INT, protect)                /* 1: ctl_protect_default limits; 0: out of reach */            \
    X(REAL, current_full_span_a)   /* the board's phase-current sensors, -span/2 .. +span/2 A */   \
    X(INT, open_phase_action)      /* < 0: the drive's build default; 0 stop, 1 ride through */    \
    X(INT, postfault_strategy)     /* < 0: core default (minimum loss); 1 maximum torque */        \
    X(INT, torque_limited_action)  /* < 0: drive default (continue); 1 stop */                     \
    X(REAL, torque_limited_stop_s) /* <= 0: drive default */

#define SIM_CTL_KIND_INT int
#define SIM_CTL_KIND_REAL double
#define SIM_CTL_KIND_BOOL bool
#define SIM_CTL_CONFIG_MEMBER(kind, name) SIM_CTL_KIND_##kind name;
typedef struct {
    SIM_CTL_CONFIG_FIELDS(SIM_CTL_CONFIG_MEMBER)
} sim_ctl_config_t;
#undef SIM_CTL_CONFIG_MEMBER

typedef struct {
    int state; /* drive_state_t, as a number (reported in metrics.json) */
    /* the states the simulator acts on, named by the bridge from drive.h's drive_state_t */
    bool ready;           /* DRIVE_STATE_READY: calibrated, waiting for RUN */
    bool running;         /* DRIVE_STATE_RUN */
    bool faulted;         /* DRIVE_STATE_FAULT */
    bool commissioning;   /* DRIVE_STATE_COMMISSION */
    bool phase_verifying; /* RUN, checking the phases before control (after an OPEN_PHASE) */
    int fault;            /* drive_fault_t */
    double torque_ref_nm, flux_ref_wb;
    double torque_est_nm, flux_est_wb;
    int vector;  /* commanded active state (S_A = bit 5) */
    double duty; /* commanded duty of that state */
    int enable;
    int candidates;
    int braking;
    /* effective core parameters (after defaults) */
    double p_lambda, p_speed_kp, p_speed_ki, p_torque_limit, p_flux_ref_wb;
    int p_duty_levels, p_ddc_direction, p_flux_ref_mode, p_ddc_torque_guard;
    int p_mid_period_angle, p_pulse_pattern;
    double p_flux_tie_band;
    unsigned faults_latched;    /* ctl_fault_t bits since the last clear */
    int fault_records;          /* unread records in the drive's fault log */
    int run_refusal;            /* drive_run_refusal_t of the last refused run request */
    unsigned run_refused;       /* run requests refused since init */
    int isolated_leg;           /* leg off for good (open-phase operation), -1: none */
    int postfault_in_force;     /* the parameter set of the isolated leg is in force */
    double torque_limit_nm;     /* the speed loop's limit in force (derated with an open phase) */
    int torque_limited;         /* the status flag: at the limit, the speed not held */
    int torque_limited_stopped; /* the stop action stopped the run */
} sim_ctl_status_t;

/* The commissioning sequence as the drive reports it (sxlink_commission.h lists, SI). */
#define SIM_CTL_COMM_QUANTITIES 10
typedef struct {
    int state, step, reason, progress;
    unsigned long periods;
    double value[SIM_CTL_COMM_QUANTITIES], sigma[SIM_CTL_COMM_QUANTITIES];
    double extra[SIM_CTL_COMM_QUANTITIES];
    int quality[SIM_CTL_COMM_QUANTITIES], reason_q[SIM_CTL_COMM_QUANTITIES];
} sim_comm_status_t;

/* One record of the drive's fault log, in SI units. */
typedef struct {
    unsigned faults;      /* ctl_fault_t bits detected in that period */
    unsigned long period; /* protection period count since drive_init */
    double i_phase_a[6];
    double vdc_v;
    double speed_rpm; /* mechanical */
    double torque_est_nm;
    double torque_ref_nm;
    int vector;
    double duty;
} sim_fault_record_t;

typedef struct {
    const char *arith; /* "fixed" or "float" */
    /* 0 on success; non-zero when the core refused the parameters, with why (the core's reason
     * text, or the drive setting it could not take) */
    int (*init)(const sim_ctl_config_t *cfg, const char **why);
    void (*isr)(void);
    void (*request_run)(void);
    void (*set_speed_rpm)(double rpm);
    void (*set_torque_nm)(double nm);
    void (*status)(sim_ctl_status_t *st);
    void (*report_overrun)(void); /* the platform's overrun detection fired */
    /* oldest unread fault record: 1 and removed from the log, or 0 when the log is empty */
    int (*read_fault_record)(sim_fault_record_t *r);
    /* the background loop's serial link (firmware/app/service/link_service.c) over hal_serial:
     * link_init once after init, link_step as often as the background loop would run */
    void (*link_init)(double gap_s); /* gap_s: host seconds after which a partial frame is
                                      * dropped (20 ms of the line's time, at the pacing rate) */
    void (*link_step)(void);
    unsigned long (*link_frames)(void); /* requests handled */
    /* 1 once the host asked the virtual board to stop (SXL_CMD_SIM_SHUTDOWN, answered OK) and
     * the reply has gone to the serial port */
    int (*link_shutdown)(void);
    /* status's fields the period loop reads (state and flags, fault, references, command,
     * isolated leg and whether its set is in force), without the rest's cost (the flux
     * estimate's root, the parameters); others untouched */
    void (*period_status)(sim_ctl_status_t *st);
    void (*request_clear)(void); /* a fault clear, acted on by the next ISR */
    /* the drive's background share (drive_background), once per period after the ISR, as the
     * board's background loop would run */
    void (*background)(void);
    int (*isolate_leg)(int leg); /* drive_request_isolate_leg: 1 accepted, 0 refused */
    /* commissioning, through the calls the serial commands make (drive_commission.h):
     * 0 accepted, else drive_comm_result_t */
    int (*commission_start)(unsigned mask, unsigned permille);
    void (*commission_status)(sim_comm_status_t *st);
    /* speed_gains: kp, ki of the set it handed to the core (those in force when none) */
    int (*commission_apply)(unsigned *applied, double speed_gains[2]);
    /* time each ISR and mark its stages in hal_cycles, as a board does (measure/profile.h):
     * the virtual board (link_init does it) and a processor-in-the-loop target */
    void (*profile)(void);
} sim_ctl_ops_t;

/* Defined by the two builds of the bridge. The float build's symbols are all
 * prefixed with "simflt_" at build time, so the simulator refers to its table
 * as simflt_sim_ctl_ops_float; sim_ctl_ops_float is the name inside the bridge. */
extern const sim_ctl_ops_t sim_ctl_ops_fixed;
extern const sim_ctl_ops_t sim_ctl_ops_float;
extern const sim_ctl_ops_t simflt_sim_ctl_ops_float;

#endif /* SIM_CTL_H */
