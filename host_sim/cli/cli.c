/* Command-line parsing, see cli.h. One table of options; each option is parsed, range-checked
 * and stored the same way, and checked once against the others at the end. */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ctl_params.h"
#include "decimal_arg.h"
#include "motor_params_file.h"
#include "pil/pil_port.h"
#include "run/scenario.h"
#include "sxlink_commission.h"

#define CLI_DEG_TO_RAD (3.14159265358979323846 / 180.0)

typedef enum {
    OPT_SET_BOOL,  /* flag: the bool field := flag_value */
    OPT_SET_INT,   /* flag: the int field := flag_value */
    OPT_IDEAL,     /* flag: every non-ideality off */
    OPT_PAPER,     /* flag: the paper's DDC, every improvement off */
    OPT_NUMBER,    /* decimal number in [lo, hi] into a double */
    OPT_INTEGER,   /* decimal integer in [lo, hi] into an int */
    OPT_SEED,      /* unsigned 64-bit integer */
    OPT_CHOICE,    /* one of choices[], its index into an int */
    OPT_SCENARIO,  /* a scenario or fault-<name> */
    OPT_DIRECTORY, /* a path */
    OPT_FILE,      /* a file to read once the options are parsed (a const char * field) */
    OPT_PIL        /* a processor-in-the-loop target (pil/pil_port.h's spelling) */
} opt_kind_t;

#define OPT_RUN 1u
#define OPT_REPRODUCE 2u
#define OPT_SERVE 4u

typedef struct {
    const char *name;
    opt_kind_t kind;
    unsigned where; /* OPT_RUN and/or OPT_REPRODUCE */
    size_t field;   /* offset in sim_cli_t */
    int group;      /* options of one group set the same thing: at most one of them */
    double lo, hi;  /* OPT_NUMBER, OPT_INTEGER */
    int flag_value; /* OPT_SET_BOOL, OPT_SET_INT */
    const char *const *choices;
    int section;         /* the usage's heading (cli_sections) */
    const char *metavar; /* the value's name in the usage (NULL: a flag, or the choices) */
    const char *help;    /* one line for the usage */
} opt_t;

#define CLI_CONTROLLER_NAME(id, number, name, what) name,
static const char *const controllers[] = {CTL_CONTROLLER_LIST(CLI_CONTROLLER_NAME) NULL};
#undef CLI_CONTROLLER_NAME
static const char *const ariths[] = {"fixed", "float", NULL};
static const char *const directions[] = {"flux-error", "xy-table", NULL};
static const char *const flux_refs[] = {"constant", "mtpa", NULL};
static const char *const integrators[] = {"exact", "rk4", NULL}; /* plant_integrator_t order */
static const char *const delay_angles[] = {"period-start", "mid-period", NULL};
/* ctl_pulse_pattern_t order */
static const char *const pulse_patterns[] = {"by-ones", "fewest-transitions", "fewest-per-set",
                                             NULL};
static const char *const phases[] = {"A", "B", "C", "D", "E", "F", NULL};
static const char *const postfault_strategies[] = {"min-loss", "max-torque", NULL};
static const char *const torque_limited_actions[] = {"continue", "stop", NULL};
static const char *const open_models[] = {"resistor", "open", NULL};

/* The usage's headings, in order (an option's section). */
enum {
    SEC_0,  /* what runs */
    SEC_1,  /* the controller's settings */
    SEC_2,  /* faults, open phase, torque limit */
    SEC_3,  /* the plant's machine (the controller keeps the reference machine) */
    SEC_4,  /* the controller's machine (the plant stays) */
    SEC_5,  /* commissioning (--scenario commission) */
    SEC_6,  /* the board and the plant's non-idealities */
    SEC_7,  /* the plant's numerics */
    SEC_8,  /* output */
    SEC_9,  /* serve */
    SEC_10, /* processor in the loop */
    SEC_COUNT
};
static const char *const cli_sections[SEC_COUNT] = {
    "what runs",
    "the controller's settings",
    "faults, open phase, torque limit",
    "the plant's machine (the controller keeps the reference machine)",
    "the controller's machine (the plant stays)",
    "commissioning (--scenario commission)",
    "the board and the plant's non-idealities",
    "the plant's numerics",
    "output",
    "serve",
    "processor in the loop (docs/profiling.md)"};

#define F(member) offsetof(sim_cli_t, member)
#define FLAG(n, k, m, g, v, sec, arg, help)                                                        \
    {                                                                                              \
        n, k, OPT_RUN, F(m), g, 0.0, 0.0, v, NULL, sec, arg, help                                  \
    }
#define NUM(n, m, g, lo, hi, sec, arg, help)                                                       \
    {                                                                                              \
        n, OPT_NUMBER, OPT_RUN, F(m), g, lo, hi, 0, NULL, sec, arg, help                           \
    }
#define CHOICE(n, m, g, list, sec, help)                                                           \
    {                                                                                              \
        n, OPT_CHOICE, OPT_RUN, F(m), g, 0.0, 0.0, 0, list, sec, NULL, help                        \
    }

enum {
    G_QUIET = 1,
    G_OUT,
    G_OUT_LIMIT,
    G_JOBS,
    G_CONTROLLER,
    G_SCENARIO,
    G_ARITH,
    G_DIRECTION,
    G_FLUX_REF,
    G_GUARD,
    G_DELAY_ANGLE,
    G_PULSE_PATTERN,
    G_TIE_BAND,
    G_LAMBDA,
    G_FS,
    G_SPEED,
    G_LOAD,
    G_DURATION,
    G_SEED,
    G_LEVELS,
    G_TORQUE_LIMIT,
    G_LIGHT_LOAD_CURRENT,
    G_FAULT_TIME,
    G_TRIP,
    G_FINE_RATE,
    G_LXY,
    G_VDC,
    G_DEAD_TIME,
    G_PSI5,
    G_PSI7,
    G_STEP,
    G_INTEGRATOR,
    G_SPAN,
    G_PROTECT,
    G_TRACE,
    G_FINE,
    G_PLOTS,
    G_PACING,
    G_RUN_PLOT,
    G_BAUD,
    G_RIDE_THROUGH,
    G_POSTFAULT,
    G_OPEN_PHASE,
    G_OPEN_MODEL,
    G_SECOND_FAULT,
    G_SECOND_FAULT_TIME,
    G_ISOLATE_LEG,
    G_ISOLATE_TIME,
    G_HANDOFF_DELAY,
    G_TORQUE_LIMITED,
    G_TORQUE_LIMITED_STOP,
    G_MOTOR_R, /* the plant's machine, the controller's left alone */
    G_MOTOR_LD,
    G_MOTOR_LQ,
    G_MOTOR_LXY,
    G_MOTOR_PSI_F,
    G_MOTOR_POLES,
    G_MOTOR_J,
    G_MOTOR_B,
    G_ENC_OFFSET,
    G_ENC_REVERSED,
    G_ENC_STUCK,
    G_CTL_R, /* the controller's machine, the plant left alone */
    G_CTL_LD,
    G_CTL_LQ,
    G_CTL_LXY,
    G_CTL_PSI_F,
    G_CTL_POLES,
    G_CTL_ENC_OFFSET,
    G_CTL_PARAMS,
    G_COMM_STEPS,
    G_COMM_CURRENT,
    G_PIL,
    G_IDEAL
};

static const opt_t options[] = {
    CHOICE("--controller", cfg.controller, G_CONTROLLER, controllers, SEC_0, "the controller"),
    {"--scenario", OPT_SCENARIO, OPT_RUN, F(cfg.scenario), G_SCENARIO, 0.0, 0.0, 0, NULL, SEC_0,
     "NAME", "steady, load-step, accel, reversal, commission or fault-<name> (list below)"},
    CHOICE("--arith", cfg.arith, G_ARITH, ariths, SEC_0, "the control core's arithmetic"),
    NUM("--lambda", cfg.lambda, G_LAMBDA, CTL_LAMBDA_MIN, CTL_LAMBDA_MAX, SEC_0, "X",
        "the cost's flux weight, N*m/Wb"),
    NUM("--fs", cfg.fs_hz, G_FS, 1000.0, 100000.0, SEC_0, "HZ",
        "sampling (and switching period) frequency"),
    NUM("--speed", cfg.speed_rpm, G_SPEED, -6000.0, 6000.0, SEC_0, "RPM",
        "speed reference (serve: the initial one)"),
    NUM("--load", cfg.load_nm, G_LOAD, -50.0, 50.0, SEC_0, "NM", "load torque on the shaft"),
    NUM("--duration", cfg.duration_s, G_DURATION, 0.01, SIM_MAX_DURATION_S, SEC_0, "S",
        "simulated time"),
    {"--seed", OPT_SEED, OPT_RUN, F(cfg.seed), G_SEED, 0.0, 0.0, 0, NULL, SEC_0, "N",
     "noise seed (an unsigned 64-bit integer)"},
    CHOICE("--ddc-direction", cfg.ddc_direction, G_DIRECTION, directions, SEC_1,
           "how the DDC reads its table 2 (flux-error: the core's default)"),
    CHOICE("--flux-ref", cfg.flux_ref_mode, G_FLUX_REF, flux_refs, SEC_1,
           "the flux reference: constant or MTPA"),
    FLAG("--ddc-torque-guard", OPT_SET_INT, cfg.ddc_torque_guard, G_GUARD, 1, SEC_1, NULL,
         "the DDC keeps a candidate only where it does not worsen the torque"),
    {"--paper-ddc", OPT_PAPER, OPT_RUN, 0u, G_GUARD, 0.0, 0.0, 0, NULL, SEC_1, NULL,
     "the paper's DDC: every improvement off (not with the four options it sets)"},
    CHOICE("--delay-angle", cfg.mid_period_angle, G_DELAY_ANGLE, delay_angles, SEC_1,
           "the angle the delay compensation rotates by"),
    CHOICE("--pulse-pattern", cfg.pulse_pattern, G_PULSE_PATTERN, pulse_patterns, SEC_1,
           "how the duty's zero vector is arranged in the period"),
    NUM("--flux-tie-band", cfg.flux_tie_band, G_TIE_BAND, CTL_FLUX_TIE_BAND_MIN,
        CTL_FLUX_TIE_BAND_MAX, SEC_1, "LEVELS", "the flux tie band, in duty levels (0 = off)"),
    {"--duty-levels", OPT_INTEGER, OPT_RUN, F(cfg.duty_levels), G_LEVELS, CTL_DUTY_LEVELS_MIN,
     CTL_DUTY_LEVELS_MAX, 0, NULL, SEC_1, "N", "the DDC's duty levels"},
    NUM("--torque-limit", cfg.torque_limit_nm, G_TORQUE_LIMIT, CTL_TORQUE_LIMIT_MIN,
        CTL_TORQUE_LIMIT_MAX, SEC_1, "NM", "the speed loop's torque limit"),
    NUM("--light-load-current", cfg.light_load_current_a, G_LIGHT_LOAD_CURRENT,
        CTL_LIGHT_LOAD_CURRENT_MIN, CTL_LIGHT_LOAD_CURRENT_MAX, SEC_1, "A",
        "the d-axis current the MTPA reference keeps at no load"),
    FLAG("--no-protect", OPT_SET_BOOL, cfg.protect, G_PROTECT, 0, SEC_1, NULL,
         "the drive's protection off (faults are not detected)"),
    NUM("--fault-time", cfg.fault_time_s, G_FAULT_TIME, 0.001, SIM_MAX_DURATION_S, SEC_2, "S",
        "when a fault-<name> scenario or --open-phase injects its fault"),
    NUM("--trip-current", cfg.trip_current_a, G_TRIP, 0.1, 1000.0, SEC_2, "A",
        "the board's hardware over-current trip level"),
    FLAG("--ride-through", OPT_SET_INT, cfg.open_phase_action, G_RIDE_THROUGH, 1, SEC_2, NULL,
         "an open phase is ridden through on five legs instead of stopping"),
    CHOICE("--postfault", cfg.postfault_strategy, G_POSTFAULT, postfault_strategies, SEC_2,
           "the five-leg strategy"),
    CHOICE("--open-phase", cfg.fault_phase, G_OPEN_PHASE, phases, SEC_2,
           "the phase that opens (fault-open-phase, or in a motion scenario)"),
    CHOICE("--open-model", cfg.open_model, G_OPEN_MODEL, open_models, SEC_2,
           "the open connection's model: 2 kohm in series or open"),
    CHOICE("--second-fault", cfg.second_fault_phase, G_SECOND_FAULT, phases, SEC_2,
           "a second phase opening later (needs --ride-through)"),
    NUM("--second-fault-time", cfg.second_fault_s, G_SECOND_FAULT_TIME, 0.001, 100.0, SEC_2, "S",
        "when the second phase opens (default 0.3 s after the first)"),
    CHOICE("--isolate-leg", cfg.isolate_leg, G_ISOLATE_LEG, phases, SEC_2,
           "the isolation command sent to a healthy drive"),
    NUM("--isolate-time", cfg.isolate_s, G_ISOLATE_TIME, 0.001, 100.0, SEC_2, "S",
        "when the isolation command is sent"),
    NUM("--handoff-delay", cfg.handoff_delay_s, G_HANDOFF_DELAY, 0.0, 0.1, SEC_2, "S",
        "delay of the post-fault set's hand-off to the ISR"),
    CHOICE("--torque-limited", cfg.torque_limited_action, G_TORQUE_LIMITED, torque_limited_actions,
           SEC_2, "what the drive does when the speed loop stays at its torque limit"),
    NUM("--torque-limited-stop", cfg.torque_limited_stop_s, G_TORQUE_LIMITED_STOP, 0.001, 60.0,
        SEC_2, "S", "time at the limit before the stop action stops"),
    NUM("--lxy", cfg.plant.lxy_h, G_LXY, 1e-4, 1.0, SEC_3, "H",
        "the machine's L_xy, the plant's and the controller's together (not with --motor-lxy)"),
    NUM("--motor-r", cfg.plant.r_ohm, G_MOTOR_R, 1e-3, 999.0, SEC_3, "OHM", "stator resistance"),
    NUM("--motor-ld", cfg.plant.ld_h, G_MOTOR_LD, 1e-5, 9.0, SEC_3, "H", "d-axis inductance"),
    NUM("--motor-lq", cfg.plant.lq_h, G_MOTOR_LQ, 1e-5, 9.0, SEC_3, "H", "q-axis inductance"),
    NUM("--motor-lxy", cfg.plant.lxy_h, G_MOTOR_LXY, 1e-5, 9.0, SEC_3, "H", "x-y inductance"),
    NUM("--motor-psi-f", cfg.plant.psi_f_wb, G_MOTOR_PSI_F, 1e-3, 5.0, SEC_3, "WB",
        "permanent-magnet flux linkage"),
    {"--motor-pole-pairs", OPT_INTEGER, OPT_RUN, F(cfg.plant.pole_pairs), G_MOTOR_POLES, 1.0, 64.0,
     0, NULL, SEC_3, "N", "pole pairs"},
    NUM("--motor-j", cfg.plant.j_kgm2, G_MOTOR_J, 1e-5, 100.0, SEC_3, "KGM2", "inertia"),
    NUM("--motor-b", cfg.plant.b_nms, G_MOTOR_B, 0.0, 10.0, SEC_3, "NMS", "viscous friction"),
    NUM("--encoder-offset-deg", encoder_offset_deg, G_ENC_OFFSET, -360.0, 360.0, SEC_3, "DEG",
        "the encoder's index offset, electrical degrees"),
    FLAG("--encoder-reversed", OPT_SET_BOOL, cfg.plant.encoder_reversed, G_ENC_REVERSED, 1, SEC_3,
         NULL, "the encoder counts backwards (A and B swapped)"),
    FLAG("--encoder-stuck", OPT_SET_BOOL, cfg.plant.encoder_stuck, G_ENC_STUCK, 1, SEC_3, NULL,
         "the count never moves (a seized coupling or a dead encoder)"),
    NUM("--ctl-r", cfg.ctl.r_ohm, G_CTL_R, CTL_RESISTANCE_MIN, CTL_RESISTANCE_MAX, SEC_4, "OHM",
        "stator resistance"),
    NUM("--ctl-ld", cfg.ctl.ld_h, G_CTL_LD, CTL_INDUCTANCE_MIN, CTL_INDUCTANCE_MAX, SEC_4, "H",
        "d-axis inductance"),
    NUM("--ctl-lq", cfg.ctl.lq_h, G_CTL_LQ, CTL_INDUCTANCE_MIN, CTL_INDUCTANCE_MAX, SEC_4, "H",
        "q-axis inductance"),
    NUM("--ctl-lxy", cfg.ctl.lxy_h, G_CTL_LXY, CTL_INDUCTANCE_MIN, CTL_INDUCTANCE_MAX, SEC_4, "H",
        "x-y inductance"),
    NUM("--ctl-psi-f", cfg.ctl.psi_f_wb, G_CTL_PSI_F, CTL_PM_FLUX_MIN, CTL_PM_FLUX_MAX, SEC_4, "WB",
        "permanent-magnet flux linkage"),
    {"--ctl-pole-pairs", OPT_INTEGER, OPT_RUN, F(cfg.ctl.pole_pairs), G_CTL_POLES,
     CTL_POLE_PAIRS_MIN, CTL_POLE_PAIRS_MAX, 0, NULL, SEC_4, "N",
     "pole pairs (also the encoder HAL's)"},
    NUM("--ctl-encoder-offset-deg", ctl_encoder_offset_deg, G_CTL_ENC_OFFSET, -360.0, 360.0, SEC_4,
        "DEG", "the encoder HAL's offset, electrical degrees"),
    {"--ctl-params", OPT_FILE, OPT_RUN, F(ctl_params_path), G_CTL_PARAMS, 0.0, 0.0, 0, NULL, SEC_4,
     "FILE",
     "a motor parameter file (sixphase-link identify --out), instead of the --ctl-* options"},
    {"--commission-steps", OPT_INTEGER, OPT_RUN, F(cfg.commission_steps), G_COMM_STEPS, 1.0, 127.0,
     0, NULL, SEC_5, "MASK", "the steps, bit per step (docs/commissioning.md)"},
    {"--commission-current", OPT_INTEGER, OPT_RUN, F(cfg.commission_permille), G_COMM_CURRENT,
     100.0, 800.0, 0, NULL, SEC_5, "PERMILLE", "the test current, per mille of rated"},
    NUM("--vdc", cfg.plant.vdc_v, G_VDC, 50.0, 1500.0, SEC_6, "V", "DC link voltage"),
    NUM("--dead-time", cfg.plant.dead_time_s, G_DEAD_TIME, 0.0, 20e-6, SEC_6, "S",
        "the inverter's dead time"),
    NUM("--psi5", cfg.plant.psi5_wb, G_PSI5, 0.0, 0.1, SEC_6, "WB",
        "the PM flux's 5th harmonic (x-y)"),
    NUM("--psi7", cfg.plant.psi7_wb, G_PSI7, 0.0, 0.1, SEC_6, "WB",
        "the PM flux's 7th harmonic (x-y)"),
    NUM("--sensor-span", cfg.plant.current_sensor_span_a, G_SPAN, PLANT_SENSOR_SPAN_MIN_A,
        PLANT_SENSOR_SPAN_MAX_A, SEC_6, "A", "the phase-current sensors' full span"),
    FLAG("--no-dead-time", OPT_SET_BOOL, cfg.plant.dead_time_on, G_IDEAL + 1, 0, SEC_6, NULL,
         "no dead time"),
    FLAG("--no-harmonics", OPT_SET_BOOL, cfg.plant.harmonics_on, G_IDEAL + 2, 0, SEC_6, NULL,
         "no PM flux harmonics"),
    FLAG("--no-adc-offset", OPT_SET_BOOL, cfg.plant.adc_offset_on, G_IDEAL + 3, 0, SEC_6, NULL,
         "no ADC offsets"),
    FLAG("--no-adc-gain", OPT_SET_BOOL, cfg.plant.adc_gain_on, G_IDEAL + 4, 0, SEC_6, NULL,
         "no ADC gain errors"),
    FLAG("--no-adc-noise", OPT_SET_BOOL, cfg.plant.adc_noise_on, G_IDEAL + 5, 0, SEC_6, NULL,
         "no ADC noise"),
    FLAG("--no-encoder-quant", OPT_SET_BOOL, cfg.plant.encoder_quant_on, G_IDEAL + 6, 0, SEC_6,
         NULL, "no encoder quantisation"),
    {"--ideal", OPT_IDEAL, OPT_RUN, 0u, G_IDEAL, 0.0, 0.0, 0, NULL, SEC_6, NULL,
     "every non-ideality above off"},
    NUM("--fine-rate", cfg.fine_rate_hz, G_FINE_RATE, 10000.0, 10e6, SEC_7, "HZ",
        "the plant samples' rate for the metrics"),
    NUM("--plant-step", cfg.plant.max_step_s, G_STEP, 1e-7, 1e-4, SEC_7, "S",
        "the integrator's largest step"),
    CHOICE("--integrator", cfg.plant.integrator, G_INTEGRATOR, integrators, SEC_7,
           "the plant's integrator"),
    {"--quiet", OPT_SET_INT, OPT_RUN | OPT_REPRODUCE | OPT_SERVE, F(quiet), G_QUIET, 0.0, 0.0, 1,
     NULL, SEC_8, NULL, "no metrics on stdout, no progress"},
    {"--out", OPT_DIRECTORY, OPT_RUN | OPT_REPRODUCE, F(cfg.out_dir), G_OUT, 0.0, 0.0, 0, NULL,
     SEC_8, "DIR", "write the run's files here (reproduce, sweep: the report)"},
    NUM("--out-limit-mb", cfg.out_limit_mb, G_OUT_LIMIT, 0.01, 1e6, SEC_8, "MB",
        "stop when the files in --out reach this (default 512; 1 MB = 1e6 bytes)"),
    {"--jobs", OPT_INTEGER, OPT_REPRODUCE, F(jobs), G_JOBS, 1.0, 64.0, 0, NULL, SEC_8, "N",
     "reproduce: parallel workers"},
    {"--plot", OPT_SET_INT, OPT_RUN, F(plot), G_RUN_PLOT, 0.0, 0.0, 1, NULL, SEC_8, NULL,
     "draw DIR/run.png from the trace (needs --out)"},
    FLAG("--no-trace", OPT_SET_BOOL, cfg.write_trace, G_TRACE, 0, SEC_8, NULL,
         "no trace.csv in --out"),
    FLAG("--no-fine", OPT_SET_BOOL, cfg.write_fine, G_FINE, 0, SEC_8, NULL,
         "no fine-rate file in --out"),
    {"--no-plots", OPT_SET_INT, OPT_REPRODUCE, F(no_plots), G_PLOTS, 0.0, 0.0, 1, NULL, SEC_8, NULL,
     "reproduce: leave the figures out"},
    {"--rate", OPT_NUMBER, OPT_SERVE, F(serve_rate), G_PACING, 0.01, 1000.0, 0, NULL, SEC_9, "N",
     "pacing: N times real time"},
    {"--fast", OPT_SET_INT, OPT_SERVE, F(serve_fast), G_PACING, 0.0, 0.0, 1, NULL, SEC_9, NULL,
     "pacing: as fast as possible"},
    {"--baud", OPT_INTEGER, OPT_SERVE, F(serve_baud), G_BAUD, 1200.0, 4000000.0, 0, NULL, SEC_9,
     "B", "the virtual line's baud"},
    {"--pil", OPT_PIL, OPT_RUN, F(cfg.pil_target), G_PIL, 0.0, 0.0, 0, NULL, SEC_10, "TARGET",
     "each control period on a target over its serial line: qemu (the emulated Cortex-M4) or "
     "serial:PATH[@BAUD] (a board running the PIL image)"},
};

#define OPTION_COUNT ((int)(sizeof options / sizeof options[0]))
#define GROUP_LIMIT (G_IDEAL + 8)

static int cli_fail(char *err, size_t len, const char *fmt, const char *a, const char *b)
{
    (void)snprintf(err, len, fmt, a, b ? b : "(missing)");
    return -1;
}

/* A number or integer option's value outside its range: the range in the message. */
static int cli_fail_range(char *err, size_t len, const opt_t *opt, const char *v, int integer)
{
    (void)snprintf(err, len, "bad value for %s: '%s' (%s in %g..%g)", opt->name,
                   v ? v : "(missing)", integer ? "an integer" : "a number", opt->lo, opt->hi);
    return -1;
}

static int parse_number(const char *s, double lo, double hi, double *out)
{
    return decimal_parse(s, 0, lo, hi, out);
}

static int parse_seed(const char *s, uint64_t *out)
{
    char *end;
    unsigned long long v;
    if (!decimal_is_plain(s, 1) || s[0] == '-' || s[0] == '+') {
        return -1;
    }
    errno = 0;
    v = strtoull(s, &end, 10);
    if (errno != 0 || *end != '\0') {
        return -1;
    }
    *out = (uint64_t)v;
    return 0;
}

static int parse_choice(const char *s, const char *const *choices, int *out)
{
    int k;
    for (k = 0; s && choices[k]; k++) {
        if (strcmp(s, choices[k]) == 0) {
            *out = k;
            return 0;
        }
    }
    return -1;
}

static int parse_scenario(const char *s, sim_config_t *c)
{
    static const char *const scenarios[] = {"steady",   "load-step",  "accel",
                                            "reversal", "commission", NULL};
    static const sim_scenario_t values[] = {SIM_SCEN_STEADY, SIM_SCEN_LOAD_STEP, SIM_SCEN_ACCEL,
                                            SIM_SCEN_REVERSAL, SIM_SCEN_COMMISSION};
    int k;
    if (parse_choice(s, scenarios, &k) == 0) {
        c->scenario = values[k];
        return 0;
    }
    if (s && sim_fault_from_scenario(s) != SIM_FAULT_NONE) {
        c->scenario = SIM_SCEN_STEADY; /* rated operation, then the fault */
        c->fault = sim_fault_from_scenario(s);
        return 0;
    }
    return -1;
}

static void set_ideal(plant_params_t *p)
{
    p->dead_time_on = p->harmonics_on = p->adc_offset_on = p->adc_gain_on = false;
    p->adc_noise_on = p->encoder_quant_on = false;
}

/* Stores one option's value. Returns the number of arguments consumed (1 or 2), -1 on error. */
static int apply_option(const opt_t *opt, const char *v, sim_cli_t *o, char *err, size_t len)
{
    char *base = (char *)o;
    double x;
    int k;
    switch (opt->kind) {
    case OPT_SET_BOOL:
        *(bool *)(void *)(base + opt->field) = opt->flag_value != 0;
        return 1;
    case OPT_SET_INT:
        *(int *)(void *)(base + opt->field) = opt->flag_value;
        return 1;
    case OPT_IDEAL:
        set_ideal(&o->cfg.plant);
        return 1;
    case OPT_PAPER:
        o->cfg.ddc_torque_guard = 0;
        o->cfg.mid_period_angle = 0;
        o->cfg.pulse_pattern = 0;
        o->cfg.flux_tie_band = 0.0;
        o->cfg.light_load_current_a = 0.0;
        return 1;
    case OPT_NUMBER:
        if (parse_number(v, opt->lo, opt->hi, (double *)(void *)(base + opt->field)) != 0) {
            return cli_fail_range(err, len, opt, v, 0);
        }
        return 2;
    case OPT_INTEGER:
        if (decimal_parse(v, 1, opt->lo, opt->hi, &x) != 0) {
            return cli_fail_range(err, len, opt, v, 1);
        }
        *(int *)(void *)(base + opt->field) = (int)x;
        return 2;
    case OPT_SEED:
        if (parse_seed(v, &o->cfg.seed) != 0) {
            return cli_fail(err, len, "bad value for %s: '%s'", opt->name, v);
        }
        return 2;
    case OPT_CHOICE:
        if (parse_choice(v, opt->choices, &k) != 0) {
            return cli_fail(err, len, "bad value for %s: '%s'", opt->name, v);
        }
        *(int *)(void *)(base + opt->field) = k;
        return 2;
    case OPT_SCENARIO:
        if (parse_scenario(v, &o->cfg) != 0) {
            return cli_fail(err, len, "bad value for %s: '%s'", opt->name, v);
        }
        return 2;
    case OPT_FILE:
        if (!v || !*v || strlen(v) > 900 || v[0] == '-') {
            return cli_fail(err, len, "bad value for %s: '%s'", opt->name, v);
        }
        *(const char **)(void *)(base + opt->field) = v;
        return 2;
    case OPT_PIL:
        if (!v || pil_port_check_spec(v, err, len) != 0) {
            return -1;
        }
        o->cfg.pil_target = v;
        return 2;
    case OPT_DIRECTORY:
    default:
        if (!v || !*v || strlen(v) > 900 || v[0] == '-') {
            return cli_fail(err, len, "bad value for %s: '%s'", opt->name, v);
        }
        o->cfg.out_dir = v;
        return 2;
    }
}

/* One option's line: name, value (its metavar or choices), help, range, where it applies. */
static void usage_option(FILE *f, const opt_t *o)
{
    char value[160] = "";
    int k, n = 0;
    if (o->kind == OPT_CHOICE) {
        for (k = 0; o->choices[k] && n < (int)sizeof value; k++) {
            n += snprintf(&value[n], sizeof value - (size_t)n, "%s%s", (k == 0) ? " {" : ",",
                          o->choices[k]);
        }
        (void)snprintf(&value[n], sizeof value - (size_t)n, "}");
    } else if (o->metavar) {
        (void)snprintf(value, sizeof value, " %s", o->metavar);
    }
    fprintf(f, "  %s%s\n      %s", o->name, value, o->help);
    if (o->kind == OPT_NUMBER || o->kind == OPT_INTEGER) {
        fprintf(f, " (%g..%g)", o->lo, o->hi);
    }
    fprintf(f, "%s%s\n", (o->where & OPT_RUN) ? "" : " [",
            (o->where & OPT_RUN)          ? ""
            : (o->where == OPT_SERVE)     ? "serve]"
            : (o->where == OPT_REPRODUCE) ? "reproduce]"
                                          : "reproduce, serve]");
}

/* The options a command takes (where), under their headings. */
static void usage_options(FILE *f, unsigned where)
{
    int sec, k;
    for (sec = 0; sec < SEC_COUNT; sec++) {
        int heading = 0;
        for (k = 0; k < OPTION_COUNT; k++) {
            if (options[k].section != sec || (options[k].where & where) == 0u) {
                continue;
            }
            if (!heading) {
                fprintf(f, "%s:\n", cli_sections[sec]);
                heading = 1;
            }
            usage_option(f, &options[k]);
        }
    }
}

static void usage_notes(FILE *f)
{
    int k;
    fprintf(f, "numbers are plain decimals (1500, -0.5, 2e-6); each option at most once; "
               "--name=value or --name value\n"
               "--duration: memory stays flat, trace.csv grows by about 1.7 MB per simulated "
               "second at 10 kHz (--no-trace leaves it out)\n"
               "fault scenarios (rated operation, the fault at 0.25 s; docs/faults.md):\n");
    for (k = 1; k < (int)SIM_FAULT_COUNT; k++) {
        const sim_fault_info_t *fi = sim_fault_info((sim_fault_t)k);
        fprintf(f, "  fault-%-16s %s\n", fi->name, fi->injection);
    }
}

/* The commands, one list: name, synopsis, what it does, the options it takes (0: its own). */
static const struct {
    const char *name, *synopsis, *what;
    unsigned where;
} cli_commands[] = {
    {"run", "[options]", "one simulation; its metrics as JSON on stdout", OPT_RUN},
    {"reproduce", "--out DIR [--jobs N] [--no-plots] [--quiet]",
     "the paper's comparison: the report and figures in DIR", OPT_REPRODUCE},
    {"sweep", "--out DIR [--jobs N] [--force] [--no-plots] [--quiet] [run options]",
     "run options as lists (a,b,c) or ranges (start:stop:step), every point run; --scenario "
     "defaults to steady, --jobs to the online processors",
     OPT_RUN},
    {"serve", "[run options] [--rate N | --fast] [--baud B]",
     "the firmware on a virtual board behind a pseudo-terminal (its path on stdout); --scenario "
     "steady, commission or fault-<name>, --speed the initial reference; until --duration, a "
     "signal or `sixphase-link shutdown`",
     OPT_RUN | OPT_SERVE},
    {"plot", "DIR", "the figure of an earlier run --out DIR (DIR/run.png)", 0u},
};
#define CLI_COMMAND_COUNT ((int)(sizeof cli_commands / sizeof cli_commands[0]))

int sim_cli_command_usage(FILE *f, const char *command)
{
    int k;
    for (k = 0; k < CLI_COMMAND_COUNT; k++) {
        if (strcmp(cli_commands[k].name, command) == 0) {
            fprintf(f, "usage: sixphase-sim %s %s\n  %s\n", cli_commands[k].name,
                    cli_commands[k].synopsis, cli_commands[k].what);
            if (cli_commands[k].where != 0u) {
                usage_options(f, cli_commands[k].where);
                usage_notes(f);
            }
            return 0;
        }
    }
    return -1;
}

void sim_cli_usage(FILE *f)
{
    int k;
    fprintf(f, "usage:\n");
    for (k = 0; k < CLI_COMMAND_COUNT; k++) {
        fprintf(f, "  sixphase-sim %s %s\n      %s\n", cli_commands[k].name,
                cli_commands[k].synopsis, cli_commands[k].what);
    }
    fprintf(f, "  sixphase-sim COMMAND --help: that command's options; sixphase-sim --version\n"
               "options (run, sweep and serve take the run options; [..] names the only commands "
               "taking one):\n");
    usage_options(f, OPT_RUN | OPT_REPRODUCE | OPT_SERVE);
    usage_notes(f);
}

int sim_cli_option_count(void) { return (int)(sizeof options / sizeof options[0]); }

const char *sim_cli_option_name(int k)
{
    return (k >= 0 && k < sim_cli_option_count()) ? options[k].name : NULL;
}

static const opt_t *find_option(const char *a, unsigned where)
{
    int k;
    for (k = 0; k < OPTION_COUNT; k++) {
        if (strcmp(a, options[k].name) == 0 && (options[k].where & where) != 0u) {
            return &options[k];
        }
    }
    return NULL;
}

static void cli_defaults(sim_cli_t *o)
{
    memset(o, 0, sizeof *o);
    sim_config_default(&o->cfg);
    o->jobs = 2;
    o->serve_rate = 1.0;
    o->serve_baud = 115200;
}

/* serve has no scenario timeline (the host commands the drive) and draws nothing itself;
 * commission only powers the board up as a new machine (serve_config). */
static int check_serve(const sim_cli_t *o, unsigned where, char *err, size_t len)
{
    if ((where & OPT_SERVE) == 0u) {
        return 0;
    }
    if (o->cfg.scenario != SIM_SCEN_STEADY && o->cfg.scenario != SIM_SCEN_COMMISSION) {
        return cli_fail(err, len,
                        "serve takes --scenario steady, commission or fault-<name>, not '%s' (the "
                        "host commands speed and load steps)%s",
                        sim_scenario_name(o->cfg.scenario), "");
    }
    if (o->plot) {
        return cli_fail(err, len,
                        "serve has no --plot: `sixphase-sim plot DIR` draws the session's --out "
                        "DIR afterwards%s%s",
                        "", "");
    }
    if (o->cfg.pil_target) {
        return cli_fail(err, len,
                        "serve has no --pil: the virtual board is the drive itself (a target runs "
                        "the periods of `sixphase-sim run --pil`)%s%s",
                        "", "");
    }
    return 0;
}

/* The open-phase options: each belongs to its scenario or to another option. */
static int check_open_phase_options(const sim_config_t *c, const int *seen, char *err, size_t len)
{
    const bool open_fault = c->fault == SIM_FAULT_OPEN_PHASE;
    const int first = (c->fault_phase >= 0) ? c->fault_phase : 2;
    if ((seen[G_OPEN_PHASE] || seen[G_SECOND_FAULT] || seen[G_OPEN_MODEL]) && !open_fault) {
        return cli_fail(
            err, len,
            "%s needs an open phase (fault-open-phase, or --open-phase in a motion scenario)%s",
            seen[G_OPEN_PHASE]   ? "--open-phase"
            : seen[G_OPEN_MODEL] ? "--open-model"
                                 : "--second-fault",
            "");
    }
    if (seen[G_TORQUE_LIMITED_STOP] && c->torque_limited_action != 1) {
        return cli_fail(err, len, "%s needs --torque-limited stop%s", "--torque-limited-stop", "");
    }
    if (seen[G_SECOND_FAULT_TIME] && !seen[G_SECOND_FAULT]) {
        return cli_fail(err, len, "%s needs --second-fault%s", "--second-fault-time", "");
    }
    if (seen[G_SECOND_FAULT] && c->second_fault_phase == first) {
        return cli_fail(err, len, "%s names the phase that is already open%s", "--second-fault",
                        "");
    }
    if (seen[G_ISOLATE_TIME] && !seen[G_ISOLATE_LEG]) {
        return cli_fail(err, len, "%s needs --isolate-leg%s", "--isolate-time", "");
    }
    if (seen[G_ISOLATE_LEG] && c->fault != SIM_FAULT_NONE && !open_fault) {
        return cli_fail(err, len,
                        "%s runs on a healthy machine, not with a fault-<name> scenario%s",
                        "--isolate-leg", "");
    }
    if (seen[G_ISOLATE_LEG] && open_fault && c->isolate_leg != first) {
        (void)snprintf(err, len, "--isolate-leg with fault-open-phase names the open phase (%c)",
                       'A' + first);
        return -1;
    }
    return 0;
}

/* In a run the strategy and the hand-off act only in five-leg operation, and after a stop the
 * second fault finds the drive off; serve takes them (the host may turn the ride-through on). */
static int check_ride_through_options(const sim_config_t *c, const int *seen, unsigned where,
                                      char *err, size_t len)
{
    const bool five_legs = c->open_phase_action == 1 || seen[G_ISOLATE_LEG];
    if ((where & OPT_SERVE) != 0u) {
        return 0;
    }
    if ((seen[G_POSTFAULT] || seen[G_HANDOFF_DELAY]) && !five_legs) {
        return cli_fail(err, len, "%s needs --ride-through or --isolate-leg%s",
                        seen[G_POSTFAULT] ? "--postfault" : "--handoff-delay", "");
    }
    if (seen[G_SECOND_FAULT] && c->open_phase_action != 1) {
        return cli_fail(err, len,
                        "%s needs --ride-through (with stop the first open phase ends the run)%s",
                        "--second-fault", "");
    }
    return 0;
}

/* --fault-time inside the run: up to its duration (serve: 10 h unless --duration). */
static int check_fault_time(const sim_config_t *c, unsigned where, char *err, size_t len)
{
    char text[160];
    sim_plan_t plan;
    double duration = (c->duration_s > 0.0) ? c->duration_s : SIM_MAX_DURATION_S;
    if ((where & OPT_SERVE) == 0u) {
        sim_plan(c, &plan);
        duration = plan.duration;
    }
    if (c->fault_time_s < duration) {
        return 0;
    }
    (void)snprintf(text, sizeof text,
                   "%g s is not inside the run's %g s (0.001 s up to the "
                   "duration)",
                   c->fault_time_s, duration);
    return cli_fail(err, len, "bad value for %s: %s", "--fault-time", text);
}

/* What no single option can see: combinations that cannot work. */
static int check_combination(const sim_cli_t *o, const int *seen, unsigned where, char *err,
                             size_t len)
{
    const sim_config_t *c = &o->cfg;
    char text[160];
    if (check_serve(o, where, err, len) != 0) {
        return -1;
    }
    if (where == OPT_RUN && !seen[G_CONTROLLER]) {
        return cli_fail(err, len, "missing %s%s", "--controller", "");
    }
    if (where == OPT_RUN && !seen[G_SCENARIO]) {
        return cli_fail(err, len, "missing %s%s", "--scenario", "");
    }
    if (seen[G_OUT_LIMIT] && !c->out_dir) {
        return cli_fail(err, len, "%s needs --out (it limits the files written there)%s",
                        "--out-limit-mb", "");
    }
    if (o->plot && !c->out_dir) {
        return cli_fail(err, len, "--plot needs --out (the figure is drawn from trace.csv)%s%s", "",
                        "");
    }
    if (o->plot && !c->write_trace) {
        return cli_fail(err, len, "--plot draws trace.csv, which --no-trace leaves out%s%s", "",
                        "");
    }
    if (where == OPT_REPRODUCE && !c->out_dir) {
        return cli_fail(err, len, "missing %s%s", "--out", "");
    }
    if ((seen[G_COMM_STEPS] || seen[G_COMM_CURRENT]) && c->scenario != SIM_SCEN_COMMISSION) {
        return cli_fail(err, len, "%s needs --scenario commission%s", "--commission-...", "");
    }
    if (seen[G_COMM_STEPS] && !SXL_COMM_STEPS_VALID((unsigned)c->commission_steps)) {
        return cli_fail(err, len,
                        "%s needs bit 0 (phases), and bit 1 (encoder) with any of bits "
                        "2..5%s",
                        "--commission-steps", "");
    }
    if (seen[G_FAULT_TIME] && c->fault == SIM_FAULT_NONE) {
        return cli_fail(err, len, "%s needs a fault-<name> scenario%s", "--fault-time", "");
    }
    if (c->fault != SIM_FAULT_NONE && sim_fault_at_power_up(c->fault) && seen[G_FAULT_TIME]) {
        (void)snprintf(err, len, "fault-%s is present from power-up: no --fault-time",
                       sim_fault_info(c->fault)->name);
        return -1;
    }
    if (seen[G_FAULT_TIME] && check_fault_time(c, where, err, len) != 0) {
        return -1;
    }
    if (check_open_phase_options(c, seen, err, len) != 0 ||
        check_ride_through_options(c, seen, where, err, len) != 0) {
        return -1;
    }
    /* Both switches of a leg are off for the dead time at every edge: it must leave room for
     * pulses, a quarter of the period at most. */
    if (c->plant.dead_time_on && c->plant.dead_time_s >= 0.25 / c->fs_hz) {
        (void)snprintf(text, sizeof text, "%g us is not below a quarter of the %g us PWM period",
                       c->plant.dead_time_s * 1e6, 1e6 / c->fs_hz);
        return cli_fail(err, len, "bad value for %s: %s", "--dead-time", text);
    }
    {
        const char *chk = plant_params_check(&c->plant);
        if (chk[0] != '\0') {
            return cli_fail(err, len, "%s%s", chk, "");
        }
    }
    return 0;
}

/* The inertia and the speed gains of a motor parameter file (the friction is the plant's). */
static int cli_read_ctl_speed_loop(const motor_params_t *m, sim_ctl_machine_t *c)
{
    if (m->have & (1u << MOTOR_PARAM_INERTIA)) {
        c->j_kgm2 = m->value[MOTOR_PARAM_INERTIA];
    }
    if (m->have & (1u << MOTOR_PARAM_SPEED_KP)) {
        c->speed_kp = m->value[MOTOR_PARAM_SPEED_KP];
    }
    if (m->have & (1u << MOTOR_PARAM_SPEED_KI)) {
        c->speed_ki = m->value[MOTOR_PARAM_SPEED_KI];
    }
    return 0;
}

/* The controller's machine from a motor parameter file (firmware/tools/motor_params_file.h). */
static int cli_read_ctl_params(sim_cli_t *o, char *err, size_t len)
{
    motor_params_t m;
    sim_ctl_machine_t *c = &o->cfg.ctl;
    char why[600];
    if (motor_params_read(o->ctl_params_path, &m, why, sizeof why) != 0) {
        return cli_fail(err, len, "bad value for --ctl-params: %s%s", why, "");
    }
    if (m.have & (1u << MOTOR_PARAM_R)) {
        c->r_ohm = m.value[MOTOR_PARAM_R];
    }
    if (m.have & (1u << MOTOR_PARAM_LD)) {
        c->ld_h = m.value[MOTOR_PARAM_LD];
    }
    if (m.have & (1u << MOTOR_PARAM_LQ)) {
        c->lq_h = m.value[MOTOR_PARAM_LQ];
    }
    if (m.have & (1u << MOTOR_PARAM_LXY)) {
        c->lxy_h = m.value[MOTOR_PARAM_LXY];
    }
    if (m.have & (1u << MOTOR_PARAM_PSI_F)) {
        c->psi_f_wb = m.value[MOTOR_PARAM_PSI_F];
    }
    if (m.have & (1u << MOTOR_PARAM_POLE_PAIRS)) {
        c->pole_pairs = (int)m.value[MOTOR_PARAM_POLE_PAIRS];
    }
    if (m.have & (1u << MOTOR_PARAM_ENCODER_OFFSET)) {
        c->encoder_offset_rad =
            m.value[MOTOR_PARAM_ENCODER_OFFSET] / 4294967296.0 * 360.0 * CLI_DEG_TO_RAD;
    }
    return cli_read_ctl_speed_loop(&m, c);
}

/* What follows from the options once they are all known: --lxy sets the controller's L_xy too
 * (as it always has), the offsets in radians, the controller's machine from a file. */
static int cli_derive(sim_cli_t *o, const int *seen, char *err, size_t len)
{
    int g;
    if (seen[G_LXY] && seen[G_MOTOR_LXY]) {
        return cli_fail(err, len, "%s and %s set the same thing", "--lxy", "--motor-lxy");
    }
    if (seen[G_LXY] && !seen[G_CTL_LXY]) {
        o->cfg.ctl.lxy_h = o->cfg.plant.lxy_h;
    }
    if (seen[G_OPEN_PHASE] && o->cfg.fault == SIM_FAULT_NONE) {
        o->cfg.fault = SIM_FAULT_OPEN_PHASE; /* --open-phase X opens X in any scenario too */
    }
    o->cfg.plant.encoder_offset_rad = o->encoder_offset_deg * CLI_DEG_TO_RAD;
    o->cfg.ctl.encoder_offset_rad = o->ctl_encoder_offset_deg * CLI_DEG_TO_RAD;
    if (!seen[G_CTL_PARAMS]) {
        return 0;
    }
    for (g = G_CTL_R; g <= G_CTL_ENC_OFFSET; g++) {
        if (seen[g] || (g == G_CTL_LXY && seen[G_LXY])) {
            return cli_fail(err, len, "%s and %s set the same thing", "--ctl-params",
                            "a --ctl-... or --lxy option");
        }
    }
    return cli_read_ctl_params(o, err, len);
}

/* getopt_long's table of the options a command takes (where): val = CLI_OPT_BASE + the option's
 * index in options[]. */
#define CLI_OPT_BASE 256
#define CLI_MAX_ARGS 1024
static void cli_long_options(struct option *lo, unsigned where)
{
    int k, n = 0;
    for (k = 0; k < OPTION_COUNT; k++) {
        const opt_kind_t kind = options[k].kind;
        const int flag =
            kind == OPT_SET_BOOL || kind == OPT_SET_INT || kind == OPT_IDEAL || kind == OPT_PAPER;
        if ((options[k].where & where) == 0u) {
            continue;
        }
        lo[n].name = options[k].name + 2;
        lo[n].has_arg = flag ? no_argument : required_argument;
        lo[n].flag = NULL;
        lo[n].val = CLI_OPT_BASE + k;
        n++;
    }
    memset(&lo[n], 0, sizeof lo[n]);
}

/* The --paper-ddc and --ideal options set what other options set: one group each. */
static int cli_claim_groups(const opt_t *opt, const char *a, int *seen, char *err, size_t len)
{
    if (seen[opt->group]) {
        return cli_fail(err, len,
                        "%s given more than once (or with an option that sets the same thing)%s", a,
                        "");
    }
    seen[opt->group] = 1;
    if (opt->kind == OPT_PAPER) { /* it also sets what these four set */
        if (seen[G_DELAY_ANGLE] || seen[G_PULSE_PATTERN] || seen[G_TIE_BAND] ||
            seen[G_LIGHT_LOAD_CURRENT]) {
            return cli_fail(err, len,
                            "%s repeats --delay-angle, --pulse-pattern, --flux-tie-band or "
                            "--light-load-current%s",
                            a, "");
        }
        seen[G_DELAY_ANGLE] = seen[G_PULSE_PATTERN] = seen[G_TIE_BAND] = 1;
        seen[G_LIGHT_LOAD_CURRENT] = 1;
    }
    if (opt->kind == OPT_IDEAL) {
        int g;
        for (g = G_IDEAL + 1; g <= G_IDEAL + 6; g++) {
            if (seen[g]) {
                return cli_fail(err, len, "%s repeats a --no-... option given with it%s", a, "");
            }
            seen[g] = 1;
        }
    }
    return 0;
}

/* One getopt_long result: the option found (its full name given, no abbreviation), or -1
 * after a one-line error. */
static int cli_option_of(int c, const char *token, const opt_t **opt, char *err, size_t len)
{
    size_t n;
    if (c == '?' || c < CLI_OPT_BASE || c >= CLI_OPT_BASE + OPTION_COUNT) {
        return cli_fail(err, len, "unknown option '%s'%s", token, "");
    }
    *opt = &options[c - CLI_OPT_BASE];
    n = strcspn(token, "=");
    if (strlen((*opt)->name) != n || strncmp(token, (*opt)->name, n) != 0) {
        return cli_fail(err, len, "unknown option '%s' (did you mean %s?)", token, (*opt)->name);
    }
    return 0;
}

static int cli_parse(int argc, char **argv, sim_cli_t *o, char *err, size_t len, unsigned where)
{
    static struct option lo[OPTION_COUNT + 1];
    char *av[CLI_MAX_ARGS + 1];
    int seen[GROUP_LIMIT] = {0};
    cli_defaults(o);
    if (argc > CLI_MAX_ARGS) {
        return cli_fail(err, len, "too many arguments (at most %s)%s", "1024", "");
    }
    av[0] = (char *)"sixphase-sim";
    memcpy(&av[1], argv, (size_t)argc * sizeof av[0]);
    cli_long_options(lo, where);
    optind = 0; /* getopt_long starts afresh (glibc) */
    opterr = 0;
    for (;;) {
        const int first = (optind == 0) ? 1 : optind;
        const opt_t *opt = NULL;
        const int c = getopt_long(argc + 1, av, "+:", lo, NULL);
        if (c == -1) {
            break;
        }
        if (c == ':') { /* a value missing at the end: the option's own message */
            opt = &options[optopt - CLI_OPT_BASE];
            return (apply_option(opt, NULL, o, err, len) < 0)
                       ? -1
                       : cli_fail(err, len, "%s needs a value%s", opt->name, "");
        }
        if (cli_option_of(c, av[first], &opt, err, len) != 0 ||
            cli_claim_groups(opt, opt->name, seen, err, len) != 0 ||
            apply_option(opt, optarg, o, err, len) < 0) {
            return -1;
        }
    }
    if (optind < argc + 1) {
        return cli_fail(err, len, "unknown option '%s'%s", av[optind], "");
    }
    if (cli_derive(o, seen, err, len) != 0) {
        return -1;
    }
    return check_combination(o, seen, where, err, len);
}

int sim_cli_parse_run(int argc, char **argv, sim_cli_t *out, char *err, size_t err_len)
{
    return cli_parse(argc, argv, out, err, err_len, OPT_RUN);
}

int sim_cli_parse_reproduce(int argc, char **argv, sim_cli_t *out, char *err, size_t err_len)
{
    return cli_parse(argc, argv, out, err, err_len, OPT_REPRODUCE);
}

int sim_cli_gridable(const char *name)
{
    const opt_t *o = find_option(name, OPT_RUN);
    if (!o) {
        return -1;
    }
    return (o->kind == OPT_NUMBER || o->kind == OPT_INTEGER || o->kind == OPT_SEED ||
            o->kind == OPT_CHOICE || o->kind == OPT_SCENARIO)
               ? 1
               : 0;
}

int sim_cli_parse_serve(int argc, char **argv, sim_cli_t *out, char *err, size_t err_len)
{
    return cli_parse(argc, argv, out, err, err_len, OPT_RUN | OPT_SERVE);
}
