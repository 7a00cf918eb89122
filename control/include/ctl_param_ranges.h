/*
 * The parameter set's numeric ranges, written once (issue 26). ctl_params_check tests them and
 * its refusal texts print them; the motor parameter file's reader, the simulator's --ctl-* and
 * controller options, the serial link's lambda and the host tool take their bounds from here.
 *
 * Each bound is a plain decimal (no suffix), so that it can be printed as written; CTL_RANGE_F
 * makes it a float. None relies on a 64-bit double.
 */
#ifndef CTL_PARAM_RANGES_H
#define CTL_PARAM_RANGES_H

#include "ctl_machine.h"
#include "ctl_pu.h"

#define CTL_LAMBDA_MIN 0
#define CTL_LAMBDA_MAX 2000 /* an integer: the link carries lambda in thousandths */
#define CTL_RESISTANCE_MIN 0
#define CTL_RESISTANCE_MAX 1000
#define CTL_INDUCTANCE_MIN 1e-6
#define CTL_INDUCTANCE_MAX 10
#define CTL_PM_FLUX_MIN 1e-4
#define CTL_PM_FLUX_MAX 10
#define CTL_POLE_PAIRS_MIN 1
#define CTL_POLE_PAIRS_MAX 64
#define CTL_INERTIA_MIN 1e-6
#define CTL_INERTIA_MAX 1000
#define CTL_SAMPLE_TIME_MIN 1e-6
#define CTL_SAMPLE_TIME_MAX 1e-2
#define CTL_FLUX_REF_MIN 1e-3
#define CTL_FLUX_REF_MAX 10
#define CTL_TORQUE_LIMIT_MIN 1e-3
#define CTL_TORQUE_LIMIT_MAX 500
#define CTL_FLUX_TIE_BAND_MIN 0
#define CTL_FLUX_TIE_BAND_MAX 1
#define CTL_LIGHT_LOAD_CURRENT_MIN 0
#define CTL_LIGHT_LOAD_CURRENT_MAX 1000
#define CTL_SPEED_KP_MIN 0
#define CTL_SPEED_KP_MAX 1e4
#define CTL_SPEED_KI_MIN 0
#define CTL_SPEED_KI_MAX 1e6
#define CTL_DUTY_LEVELS_MIN 2
#define CTL_DUTY_LEVELS_MAX 11 /* = CTL_DDC_LEVELS_MAX */

/* The list: X(row, field, error, min, max, unit, what, default). One row per field; rows sharing
 * an error (the three inductances, the two speed gains) share its bounds. Integer fields:
 * pole_pairs and duty_levels (int16_t), the rest float. The defaults are ctl_params_default's
 * (the reference machine of ctl_machine.h, the settings measured in docs/improvements.md). */
#define CTL_PARAM_RANGES(X)                                                                        \
    X(R, resistance_ohm, CTL_PARAM_RESISTANCE, CTL_RESISTANCE_MIN, CTL_RESISTANCE_MAX, "ohm",      \
      "stator resistance", CTL_FLOAT_LITERAL(CTL_MACHINE_R_OHM))                                   \
    X(LD, ld_h, CTL_PARAM_INDUCTANCE, CTL_INDUCTANCE_MIN, CTL_INDUCTANCE_MAX, "H",                 \
      "d-axis inductance", CTL_FLOAT_LITERAL(CTL_MACHINE_LD_H))                                    \
    X(LQ, lq_h, CTL_PARAM_INDUCTANCE, CTL_INDUCTANCE_MIN, CTL_INDUCTANCE_MAX, "H",                 \
      "q-axis inductance", CTL_FLOAT_LITERAL(CTL_MACHINE_LQ_H))                                    \
    X(LXY, l_xy_h, CTL_PARAM_INDUCTANCE, CTL_INDUCTANCE_MIN, CTL_INDUCTANCE_MAX, "H",              \
      "x-y inductance", CTL_FLOAT_LITERAL(CTL_MACHINE_LXY_H))                                      \
    X(PSI_F, pm_flux_wb, CTL_PARAM_PM_FLUX, CTL_PM_FLUX_MIN, CTL_PM_FLUX_MAX, "Wb", "magnet flux", \
      CTL_FLOAT_LITERAL(CTL_MACHINE_PSI_F_WB))                                                     \
    X(POLE_PAIRS, pole_pairs, CTL_PARAM_POLE_PAIRS, CTL_POLE_PAIRS_MIN, CTL_POLE_PAIRS_MAX, "",    \
      "pole pairs", CTL_MACHINE_POLE_PAIRS)                                                        \
    X(INERTIA, inertia_kg_m2, CTL_PARAM_INERTIA, CTL_INERTIA_MIN, CTL_INERTIA_MAX, "kg*m^2",       \
      "inertia", CTL_FLOAT_LITERAL(CTL_MACHINE_INERTIA_KG_M2))                                     \
    X(SAMPLE_TIME, sample_time_s, CTL_PARAM_SAMPLE_TIME, CTL_SAMPLE_TIME_MIN, CTL_SAMPLE_TIME_MAX, \
      "s", "sample time", 1.0e-4f)                                                                 \
    X(LAMBDA, lambda_nm_per_wb, CTL_PARAM_LAMBDA, CTL_LAMBDA_MIN, CTL_LAMBDA_MAX, "N*m/Wb",        \
      "flux weight", 100.0f)                                                                       \
    X(DUTY_LEVELS, duty_levels, CTL_PARAM_DUTY_LEVELS, CTL_DUTY_LEVELS_MIN, CTL_DUTY_LEVELS_MAX,   \
      "", "duty levels", 6)                                                                        \
    X(FLUX_TIE_BAND, ddc_flux_tie_band, CTL_PARAM_FLUX_TIE_BAND, CTL_FLUX_TIE_BAND_MIN,            \
      CTL_FLUX_TIE_BAND_MAX, "duty level", "DDC flux tie band", 0.5f)                              \
    X(FLUX_REF, flux_ref_wb, CTL_PARAM_FLUX_REF, CTL_FLUX_REF_MIN, CTL_FLUX_REF_MAX, "Wb",         \
      "constant flux reference", 0.26f)                                                            \
    X(TORQUE_LIMIT, torque_limit_nm, CTL_PARAM_TORQUE_LIMIT, CTL_TORQUE_LIMIT_MIN,                 \
      CTL_TORQUE_LIMIT_MAX, "N*m", "torque limit", 7.0f)                                           \
    X(LIGHT_LOAD_CURRENT, light_load_current_a, CTL_PARAM_LIGHT_LOAD_CURRENT,                      \
      CTL_LIGHT_LOAD_CURRENT_MIN, CTL_LIGHT_LOAD_CURRENT_MAX, "A", "light-load current", 0.5f)     \
    X(SPEED_KP, speed_kp_nm_per_rad_s, CTL_PARAM_SPEED_GAINS, CTL_SPEED_KP_MIN, CTL_SPEED_KP_MAX,  \
      "N*m*s/rad", "speed PI gain", 1.5f)                                                          \
    X(SPEED_KI, speed_ki_nm_per_rad, CTL_PARAM_SPEED_GAINS, CTL_SPEED_KI_MIN, CTL_SPEED_KI_MAX,    \
      "N*m/rad", "speed PI integral gain", 60.0f)

/* A bound as a float (a constant expression). */
#define CTL_RANGE_F(x) ((float)(x))

/* A bound as text, as written above. */
#define CTL_RANGE_STR(x) CTL_RANGE_STR_(x)
#define CTL_RANGE_STR_(x) #x

/* "<what> outside <min>..<max><unit>": a refusal's text (unit: "" or " ohm"). */
#define CTL_RANGE_TEXT(what, lo, hi, unit)                                                         \
    what " outside " CTL_RANGE_STR(lo) ".." CTL_RANGE_STR(hi) unit

#endif /* CTL_PARAM_RANGES_H */
