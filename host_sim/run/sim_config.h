/*
 * What a run takes and what it gives: the configuration (sim_config_t, its defaults and names)
 * and the result (sim_result_t), and what an observer of a run sees. sim.h runs one.
 */
#ifndef SIM_SIM_CONFIG_H
#define SIM_SIM_CONFIG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "bridge/sim_ctl.h"
#include "plant/fault_inject.h"
#include "pil/pil.h"
#include "plant/plant.h"
#include "record/recorder.h"

typedef enum {
    SIM_SCEN_STEADY = 0,    /* 1500 r/min, rated load */
    SIM_SCEN_LOAD_STEP = 1, /* rated load step at 1500 r/min */
    SIM_SCEN_ACCEL = 2,     /* 0 -> 800 r/min, no load */
    SIM_SCEN_REVERSAL = 3,  /* 800 -> -800 r/min, no load */
    SIM_SCEN_COMMISSION = 4 /* the drive's commissioning sequence (sim_commission.c) */
} sim_scenario_t;

/* The machine as the controller's parameter set and the encoder HAL describe it: the firmware's
 * defaults (the reference machine, control/include/ctl_machine.h) for every field left unset,
 * whatever the plant is. Set by --ctl-* or --ctl-params FILE (and by --lxy, which sets the
 * plant's and the controller's L_xy together, as before). */
typedef struct {
    double r_ohm, ld_h, lq_h, lxy_h, psi_f_wb; /* < 0: the reference machine's */
    int pole_pairs;                            /* <= 0: the reference machine's */
    double encoder_offset_rad; /* the HAL's index offset (FW_ENCODER_OFFSET), electrical */
    double j_kgm2;             /* <= 0: the reference machine's (not the plant's) */
    double speed_kp, speed_ki; /* the speed PI's gains; <= 0: the core's defaults */
    bool speed_gains_from_j;   /* the gains designed from j_kgm2 (ctl_speed_gains_from_inertia),
                                * as the drive's APPLY of an identified inertia does */
} sim_ctl_machine_t;

typedef struct {
    int controller; /* an id of CTL_CONTROLLER_LIST: 0 ddc, 1 mptc49, 2 mptc13, 3 foc, 4 vvmptc */
    int arith;      /* 0 fixed, 1 float */
    sim_scenario_t scenario;
    double lambda;     /* N*m/Wb */
    double fs_hz;      /* sampling (= carrier) frequency */
    double speed_rpm;  /* <= -1e9: scenario default */
    double load_nm;    /* < -1e9: scenario default */
    double duration_s; /* <= 0: scenario default */
    uint64_t seed;
    int duty_levels;      /* <= 0: core default */
    int ddc_direction;    /* < 0: core default */
    int flux_ref_mode;    /* < 0: core default */
    int ddc_torque_guard; /* < 0: core default (on); 0: the paper's method */
    int mid_period_angle; /* < 0: core default (off: the paper's Eq. 17, period start); 1 on */
    double flux_tie_band; /* < 0: core default (0.5 of a duty level); 0: off (the paper) */
    double light_load_current_a; /* < 0: core default; 0: plain MTPA (docs/faults.md) */
    int pulse_pattern;           /* < 0: core default (fewest transitions per set); else a
                                    ctl_pulse_pattern_t (0: by ones, the paper's DDC here) */
    double torque_limit_nm; /* <= 0: scenario default (rated 7 N*m; 1.2x rated with rated load) */
    double trip_current_a;  /* > 0: simulated hardware over-current comparator (trip zone) */
    sim_fault_t fault;      /* injected fault (scenario fault-<name>): steady scenario */
    double fault_time_s;    /* injection time; <= 0: SIM_FAULT_INJECT_S */
    /* open-phase operation (sim_open_phase.h, docs/faults.md) */
    int open_phase_action;     /* < 0: the drive's default (stop); 1: ride through */
    int postfault_strategy;    /* < 0: the core's default (minimum loss); 1: maximum torque */
    int fault_phase;           /* fault-open-phase: the phase that opens (0..5); < 0: C */
    int open_model;            /* fault-open-phase: 0 2 kohm in series (default), 1 open circuit */
    int second_fault_phase;    /* a second phase that opens later, < 0: none */
    double second_fault_s;     /* when; <= 0: 0.3 s after the first */
    double handoff_delay_s;    /* the background's build of the post-fault set takes this long
                                * (the target's hand-off latency, docs/faults.md); 0: one period */
    int torque_limited_action; /* < 0: the drive's default (continue); 1: stop after
                                * torque_limited_stop_s at the limit (docs/faults.md) */
    double torque_limited_stop_s; /* <= 0: the drive's default (0.5 s) */
    int isolate_leg;              /* a leg isolated by command (a healthy machine), < 0: none */
    double isolate_s;             /* when; <= 0: SIM_FAULT_INJECT_S */
    bool protect;        /* the firmware's software protection at its default limits; false:
                          * thresholds out of reach (comparing controllers that overload the
                          * drive, e.g. MPTC-49 peaks near 30 A) */
    double fine_rate_hz; /* plant sampling for the metrics in the analysis window */
    bool passive_load;   /* the load only opposes motion (serve): a rotor at rest stays at
                            rest; false: an ideal torque source (the scenarios) */
    plant_params_t plant;
    sim_ctl_machine_t ctl; /* the controller's machine (the reference one unless set) */
    /* scenario commission: the steps (sxlink_commission.h bits) and the test current (per mille
     * of rated), as COMMISSION_START takes them */
    int commission_steps;
    int commission_permille;
    const char *out_dir;    /* NULL: write nothing */
    const char *pil_target; /* NULL: the drive runs here; else its periods on this target (pil.h) */
    bool write_trace;
    bool write_fine;
    double out_limit_mb; /* trace.csv and fine.csv together stop at this size (MB, 1e6 bytes) */
    const struct sim_observer *observer; /* NULL: none (tests watch a run through it) */
} sim_config_t;

#define SIM_UNSET (-1e30)
#define SIM_DEFAULT_FINE_RATE_HZ 100000.0
/* Longest run: 10 h of simulated time (at 10 kHz, 3.6e8 periods; memory does not grow with the
 * duration, trace.csv does: about 1.7 MB per simulated second at 10 kHz). */
#define SIM_MAX_DURATION_S 36000.0
/* The output files' default size limit: a 10 h run's trace would be about 61 GB, a `serve --fast`
 * session writes about 116 MB/s; 512 MB is about 300 s of a run's trace. */
#define SIM_DEFAULT_OUT_LIMIT_MB 512.0

/* What the inverter applied in one control period, to the plant as it then was. */
typedef struct {
    double duty[6];  /* leg duties, fractions of the period */
    bool forced_off; /* every switch open */
    double t_load_nm;
    const plant_params_t *plant; /* as any injected fault leaves it */
} sim_period_input_t;

/* Sees every trace row and fine sample of a run (whether or not files are written) and what
 * the inverter applied in each period: the tests replay a run's commands through the plant
 * with another integrator, and compare the files with a reference writer. */
typedef struct sim_observer {
    void *ctx;
    /* after each control period, with its complete trace row */
    void (*period)(void *ctx, const sim_trace_row_t *row, const sim_period_input_t *in);
    /* each plant sample of the analysis window */
    void (*fine)(void *ctx, const sim_fine_row_t *row);
} sim_observer_t;

/* The commissioning scenario's outcome: the drive's results beside the plant's values. */
#define SIM_COMM_QUANTITIES 10
typedef struct {
    bool ran;
    int state, reason, step; /* sxlink_commission.h lists */
    double duration_s;       /* from the start to the end of the sequence */
    double value[SIM_COMM_QUANTITIES], sigma[SIM_COMM_QUANTITIES], extra[SIM_COMM_QUANTITIES];
    int quality[SIM_COMM_QUANTITIES], reason_q[SIM_COMM_QUANTITIES];
    double truth[SIM_COMM_QUANTITIES]; /* the plant's (NaN where there is none) */
    int apply_result; /* drive_commission_apply's, after a DONE sequence or one failed on an open
                         phase */
    unsigned applied; /* quantities applied */
    double speed_kp, speed_ki; /* the speed gains of the set applied (N m s/rad, N m/rad) */
    double phase_peak_a;       /* largest |phase current| of the plant, at each period's end */
} sim_commission_result_t;

typedef struct {
    char controller[8];
    char arith[8];
    char scenario[32];
    double lambda, fs_hz, speed_ref_rpm, load_nm, duration_s;
    double window_start_s, window_end_s;
    int thd_periods;
    double stats_from_s; /* start of the whole fundamental periods THD, ripple and x-y rms use
                            (the analysis window's start when it holds no whole period) */
    double thd_phase_percent[6]; /* each phase current, all frequencies; < 0: not meaningful */
    double thd_percent;          /* mean of the six phases' THD (brief §7); < 0: n/a */
    double thd50_percent;        /* harmonics 2..50, six-phase mean */
    double torque_ripple_nm;     /* std of plant torque at fine resolution */
    double torque_ripple_pp_nm;
    double torque_ripple_sampled_nm; /* std of plant torque at the control samples */
    double torque_mean_nm;
    double torque_ref_mean_nm; /* the controller's reference, mean over the analysis window */
    double speed_mean_rpm;
    double xy_current_rms_a;
    double phase_current_rms_a; /* six-phase mean, without DC */
    double switching_freq_hz;
    /* the inverter's semiconductor losses over the window, estimated (plant/inverter_loss.h) */
    double switching_loss_w, inverter_loss_w;
    double phase_current_peak_a; /* max |i| of the six phases at the control samples, analysis
                                    window */
    long adc_clipped;    /* phase-current conversions at 0 or 4095 counts (sensor range +-20 A) */
    double transient_ms; /* < 0: null */
    /* motion scenarios: the speed's last exit from 2 % of its final reference after the event,
     * and its largest error once it first came within that band; < 0: null */
    double speed_settle_ms, speed_peak_error_rpm;
    /* host timing: machine-dependent, kept out of the committed reproduce report */
    double realtime_factor;
    double wall_s;
    double isr_mean_us; /* host wall time per drive ISR call (mean over every 8th call) */
    int final_state, fault;
    double fault_time_s; /* first period the drive was in FAULT; < 0: never */
    double trip_time_s;  /* simulated hardware trip; < 0: never */
    /* fault injection (scenario fault-<name>) and the drive's answer */
    double fault_inject_s;   /* < 0: no injection; power-up faults: 0 = calibration start */
    double fault_detect_ms;  /* injection to the first period in FAULT; < 0: not detected */
    bool outputs_off;        /* every leg off in every period from detection on */
    unsigned faults_latched; /* ctl_fault_t bits latched at the end */
    int fault_records;       /* records in the drive's fault log at the end */
    bool have_first_record;
    sim_fault_record_t first_record; /* the oldest, i.e. the detection */
    double first_record_t_s;         /* its time on the scenario clock */
    /* open-phase operation (sim_open_phase.h): after a fault-open-phase injection or an
     * isolation command (the event) */
    double open_phase_event_s; /* < 0: no such event */
    int isolated_leg;          /* at the end; -1: none */
    double isolation_ms;       /* event to the leg's isolation; < 0: never */
    double postfault_start_ms; /* event to the first period on five legs; < 0: never */
    double speed_dip_rpm;      /* deepest fall below the reference from the event on */
    double peak_after_event_a; /* largest |i| of any phase from the event on (period starts) */
    /* torque-limited operation (the drive's status flag, docs/faults.md) */
    double torque_limited_s;       /* periods the flag was set, in seconds */
    double torque_limited_first_s; /* first period it was, scenario clock; < 0: never */
    bool torque_limited_stopped;   /* the stop action stopped the run */
    double recover_ms;             /* event until the speed stays within 2 % of its reference */
    double torque_limit_end_nm;    /* the speed loop's limit in force at the end */
    double phase_rms_a[6];         /* each phase over the analysis window (plant samples) */
    double phase_peak_a[6];
    double phase_limit_peak_a; /* the peak the healthy torque limit allows: T_lim / (3 Pn psi_f) */
    double diode_conduction;   /* share of the analysis window in which an isolated leg whose
                                * phase is still connected conducted through a diode */
    /* the machine the controller was told (sim_ctl_machine_t resolved) */
    double ctl_r_ohm, ctl_ld_h, ctl_lq_h, ctl_lxy_h, ctl_psi_f_wb, ctl_encoder_offset_deg;
    int ctl_pole_pairs;
    sim_commission_result_t comm; /* scenario commission */
    /* core parameters in force */
    double p_speed_kp, p_speed_ki, p_torque_limit, p_flux_ref_wb;
    int p_duty_levels, p_ddc_direction, p_flux_ref_mode, p_ddc_torque_guard;
    int p_mid_period_angle, p_pulse_pattern;
    double p_flux_tie_band;
    sim_pil_summary_t pil; /* processor in the loop (pil.on) */
} sim_result_t;

/* Scenario defaults: speed, load, duration, event time. */
void sim_config_default(sim_config_t *c);

const char *sim_controller_name(int controller);
const char *sim_scenario_name(sim_scenario_t s);

#endif /* SIM_SIM_CONFIG_H */
