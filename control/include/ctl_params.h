/*
 * The parameter set: everything a user sets, at init or at run time, in SI units. The
 * control step never reads it; it reads the derived configuration (ctl_config.h) built
 * from it outside the ISR.
 *
 * Every set is checked before anything is derived from it: a field that is not a normal
 * number (NaN, infinite, denormal) or lies outside its stated range refuses the whole set
 * with one reason, and the set in force stays.
 */
#ifndef CTL_PARAMS_H
#define CTL_PARAMS_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_flux_ref.h"
#include "ctl_param_ranges.h"
#include "ctl_postfault_config.h"
#include "ctl_protect.h"

/* The controllers, one list (issue 26): X(id, number, name, what). The names are the tools'
 * (sixphase-sim --controller, sixphase-link controller, the reports). */
#define CTL_CONTROLLER_LIST(X)                                                                     \
    X(CTL_CONTROLLER_DDC, 0, "ddc", "the paper's discrete-duty MPTC")                              \
    X(CTL_CONTROLLER_MPTC49, 1, "mptc49", "conventional MPTC, 48 vectors + zero")                  \
    X(CTL_CONTROLLER_MPTC13, 2, "mptc13", "conventional MPTC, 12 largest + zero")                  \
    X(CTL_CONTROLLER_FOC, 3, "foc",                                                                \
      "field-oriented control in VSD coordinates: PI in d-q and x-y, carrier PWM")                 \
    X(CTL_CONTROLLER_VVMPTC, 4, "vvmptc", "virtual-vector MPTC: 12 x-y-free virtual vectors + zero")

#define CTL_CONTROLLER_ENUM(id, number, name, what) id = number,
typedef enum { CTL_CONTROLLER_LIST(CTL_CONTROLLER_ENUM) CTL_CONTROLLER_COUNT } ctl_controller_t;
#undef CTL_CONTROLLER_ENUM

/* The controller's name ("?" for none of the list). */
const char *ctl_controller_name(int controller);

/* How the discrete-duty method picks between the two alpha-beta directions
 * of a sector (see docs/design.md). */
typedef enum {
    CTL_DDC_DIRECTION_FLUX_ERROR = 0, /* DTC reading: flux error sign picks 75/105 deg */
    CTL_DDC_DIRECTION_XY_TABLE = 1    /* paper's table 2 literally: x-y sector picks one of four */
} ctl_ddc_direction_t;

/* Where the zero vector goes in a discrete-duty command (control/include/ctl_pulse.h). */
typedef enum {
    CTL_PULSE_BY_ONES = 0,            /* u77 in the middle for vectors with four or more upper
                                       * switches on, u00 at the edges otherwise */
    CTL_PULSE_FEWEST_TRANSITIONS = 1, /* u00 or u77, whichever switches fewer legs, the period
                                       * boundary included */
    CTL_PULSE_FEWEST_PER_SET = 2      /* the same over u00, u07, u70 and u77: each three-phase
                                       * set's zero state on its own (two isolated neutrals) */
} ctl_pulse_pattern_t;

typedef struct {
    /* machine */
    float resistance_ohm;
    float ld_h;
    float lq_h;
    float l_xy_h; /* x-y (leakage) inductance */
    float pm_flux_wb;
    int16_t pole_pairs;
    int16_t open_phase;  /* open-phase operation (docs/design.md): the phase (0..5, A..F) that
                          * carries no current, -1 when all six do; the drive sets it when it
                          * isolates a leg (firmware/app/drive/drive.h). (Beside pole_pairs: the two
                          * 16-bit fields keep the set's size and the healthy step's code.) */
    float inertia_kg_m2; /* used by the protection's stopped-encoder check */
    /* control */
    float sample_time_s;
    ctl_controller_t controller;
    float lambda_nm_per_wb;     /* flux weight of the cost */
    int16_t duty_levels;        /* DDC: levels k/(n-1), k = 0..n-1; paper: 6 */
    int16_t postfault_strategy; /* ctl_postfault_strategy_t, with an open phase */
    ctl_ddc_direction_t ddc_direction;
    /* improvements over the paper (docs/improvements.md); false = the paper */
    bool ddc_torque_guard; /* (default on) flux weighting moves the duty at most one level
                            * from the level that best meets the torque reference */
    bool mid_period_angle; /* every controller: each period's voltage enters the prediction
                            * at the rotor angle of the period's middle (false, the default:
                            * at its start, the paper's Eq. 17; measured no better in closed
                            * loop) */
    ctl_pulse_pattern_t pulse_pattern; /* every controller (default: fewest transitions per
                                        * set; by ones: the earlier rule) */
    float ddc_flux_tie_band; /* (default 0.5) the flux term decides only between duty levels
                              * whose predicted torque errors lie within this fraction of one
                              * level's torque step of the best one, 0..1; 0: off (the flux term
                              * weighs every level the guard leaves, the paper's search) */
    ctl_flux_ref_mode_t flux_ref_mode;
    float flux_ref_wb;          /* used when flux_ref_mode is constant */
    float light_load_current_a; /* MTPA: the current magnitude kept at light load, a d-axis
                                 * current at no load (no torque), so an open phase can be found
                                 * there (docs/faults.md); 0: plain MTPA; at most the current
                                 * of the MTPA table's top (the torque limit) takes effect */
    /* speed loop */
    float speed_kp_nm_per_rad_s; /* per mechanical rad/s */
    float speed_ki_nm_per_rad;   /* per mechanical rad */
    float torque_limit_nm;
    /* protection thresholds (docs/faults.md) */
    ctl_protect_settings_t protect;
} ctl_params_t;

/* Why a parameter set was refused: X(code, text), one list. */
#define CTL_PARAM_ERRORS(X)                                                                                                         \
    X(CTL_PARAM_OK, "accepted")                                                                                                     \
    X(CTL_PARAM_BUSY, "the previous set has not reached the control step yet")                                                      \
    X(CTL_PARAM_CONTROLLER, "unknown controller")                                                                                   \
    X(CTL_PARAM_DDC_DIRECTION, "unknown DDC direction reading")                                                                     \
    X(CTL_PARAM_DUTY_LEVELS,                                                                                                        \
      CTL_RANGE_TEXT("duty levels", CTL_DUTY_LEVELS_MIN, CTL_DUTY_LEVELS_MAX, ""))                                                  \
    X(CTL_PARAM_LAMBDA, CTL_RANGE_TEXT("flux weight", CTL_LAMBDA_MIN, CTL_LAMBDA_MAX, " N*m/Wb"))                                   \
    X(CTL_PARAM_RESISTANCE,                                                                                                         \
      CTL_RANGE_TEXT("stator resistance", CTL_RESISTANCE_MIN, CTL_RESISTANCE_MAX, " ohm"))                                          \
    X(CTL_PARAM_INDUCTANCE,                                                                                                         \
      CTL_RANGE_TEXT("an inductance", CTL_INDUCTANCE_MIN, CTL_INDUCTANCE_MAX, " H"))                                                \
    X(CTL_PARAM_PM_FLUX, CTL_RANGE_TEXT("magnet flux", CTL_PM_FLUX_MIN, CTL_PM_FLUX_MAX, " Wb"))                                    \
    X(CTL_PARAM_POLE_PAIRS,                                                                                                         \
      CTL_RANGE_TEXT("pole pairs", CTL_POLE_PAIRS_MIN, CTL_POLE_PAIRS_MAX, ""))                                                     \
    X(CTL_PARAM_INERTIA, CTL_RANGE_TEXT("inertia", CTL_INERTIA_MIN, CTL_INERTIA_MAX, " kg*m^2"))                                    \
    X(CTL_PARAM_SAMPLE_TIME,                                                                                                        \
      CTL_RANGE_TEXT("sample time", CTL_SAMPLE_TIME_MIN, CTL_SAMPLE_TIME_MAX, " s"))                                                \
    X(CTL_PARAM_MODEL, "the discrete model does not fit: sample time too long for L/R, or "                                         \
                       "currents beyond the Q24 range analysis")                                                                    \
    X(CTL_PARAM_FLUX_REF, "flux reference mode unknown or " CTL_RANGE_TEXT(                                                         \
                              "constant flux", CTL_FLUX_REF_MIN, CTL_FLUX_REF_MAX, " Wb"))                                          \
    X(CTL_PARAM_SPEED_GAINS,                                                                                                        \
      CTL_RANGE_TEXT(                                                                                                               \
          "speed gains", CTL_SPEED_KP_MIN, CTL_SPEED_KP_MAX,                                                                        \
          " N*m*s/rad") " and " CTL_RANGE_STR(CTL_SPEED_KI_MIN) ".." CTL_RANGE_STR(CTL_SPEED_KI_MAX) " N*m/rad, or too "            \
                                                                                                     "large for the number format") \
    X(CTL_PARAM_TORQUE_LIMIT,                                                                                                       \
      CTL_RANGE_TEXT("torque limit", CTL_TORQUE_LIMIT_MIN, CTL_TORQUE_LIMIT_MAX, " N*m"))                                           \
    X(CTL_PARAM_PROTECTION, "a protection threshold is out of range")                                                               \
    X(CTL_PARAM_FLUX_TIE_BAND, CTL_RANGE_TEXT("DDC flux tie band", CTL_FLUX_TIE_BAND_MIN,                                           \
                                              CTL_FLUX_TIE_BAND_MAX, " duty level"))                                                \
    X(CTL_PARAM_PULSE_PATTERN, "unknown pulse pattern")                                                                             \
    X(CTL_PARAM_OPEN_PHASE, "open phase outside -1..5 or unknown post-fault strategy")                                              \
    X(CTL_PARAM_LIGHT_LOAD_CURRENT,                                                                                                 \
      CTL_RANGE_TEXT("light-load current", CTL_LIGHT_LOAD_CURRENT_MIN, CTL_LIGHT_LOAD_CURRENT_MAX,                                  \
                     " A"))

#define CTL_PARAM_ERROR_ENUM(code, text) code,
typedef enum { CTL_PARAM_ERRORS(CTL_PARAM_ERROR_ENUM) CTL_PARAM_ERROR_COUNT } ctl_param_error_t;
#undef CTL_PARAM_ERROR_ENUM

/* The paper's machine and controller with the brief's assumed values. */
void ctl_params_default(ctl_params_t *p);

/* CTL_PARAM_OK when every field is usable, else the first reason found. */
ctl_param_error_t ctl_params_check(const ctl_params_t *p);

/* A reason's text (the list above; the ranges as ctl_param_ranges.h writes them). */
const char *ctl_param_error_text(ctl_param_error_t e);

static inline bool ctl_params_valid(const ctl_params_t *p)
{
    return ctl_params_check(p) == CTL_PARAM_OK;
}

/* A speed-loop gain (per mechanical rad/s or rad) in per unit: torque per unit per
 * electrical per-unit speed. */
float ctl_speed_gain_pu(float gain_si, int16_t pole_pairs);

/* The speed PI's design from the inertia (docs/commissioning.md, "Speed loop from the
 * inertia"): the loop L(s) = (kp + ki / s) / (J s) crosses over at w_c with kp = J w_c, and its
 * integral corner sits CTL_SPEED_DESIGN_RATIO below, ki = kp w_c / ratio: phase margin
 * atan(ratio) = 76 deg less the delay's w_c Td (the torque loop and the speed measurement, about
 * 1 ms: 9 deg), closed-loop poles a double pole at -w_c / 2. w_c is 150 rad/s, the fixed gains'
 * crossover on the reference machine (kp 1.5 N m s/rad at 0.01 kg m^2): well below the 10 kHz
 * period's and the encoder speed's bandwidth, so the speed noise stays out of the torque. On a
 * heavy rotor it comes down so that kp stays within CTL_SPEED_DESIGN_KP_PU_MAX per unit (the
 * fixed-point range ctl_params_check guards, 100). */
#define CTL_SPEED_DESIGN_CROSSOVER_RAD_S 150.0f
#define CTL_SPEED_DESIGN_RATIO 4.0f
#define CTL_SPEED_DESIGN_KP_PU_MAX 90.0f

/* p's speed gains from p's inertia and pole pairs, as above. */
void ctl_speed_gains_from_inertia(ctl_params_t *p);

#endif /* CTL_PARAMS_H */
