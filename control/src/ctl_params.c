#include "ctl_params.h"

#include "ctl_machine.h"
#include "ctl_predict.h"
#include "ctl_pu.h"
#include "ctl_qmath.h"

void ctl_params_default(ctl_params_t *p)
{
#define CTL_SET_DEFAULT(row, field, error, lo, hi, unit, what, value) p->field = value;
    CTL_PARAM_RANGES(CTL_SET_DEFAULT) /* the numbers: the one list, ctl_param_ranges.h */
#undef CTL_SET_DEFAULT
    p->controller = CTL_CONTROLLER_DDC;
    p->ddc_direction = CTL_DDC_DIRECTION_FLUX_ERROR;
    p->ddc_torque_guard = true;  /* improvements (docs/improvements.md); false = the paper */
    p->mid_period_angle = false; /* measured: no closed-loop gain (docs/improvements.md) */
    p->pulse_pattern = CTL_PULSE_FEWEST_PER_SET;
    p->flux_ref_mode = CTL_FLUX_REF_MTPA;
    ctl_protect_settings_default(&p->protect);
    p->open_phase = CTL_POSTFAULT_NO_LEG; /* all six phases healthy */
    p->postfault_strategy = (int16_t)CTL_POSTFAULT_MIN_LOSS;
}

float ctl_speed_gain_pu(float gain_si, int16_t pole_pairs)
{
    return gain_si * CTL_BASE_OMEGA_RAD_S_F / ((float)pole_pairs * CTL_BASE_TORQUE_NM_F);
}

void ctl_speed_gains_from_inertia(ctl_params_t *p)
{
    const float kp_max =
        CTL_SPEED_DESIGN_KP_PU_MAX / ctl_speed_gain_pu(1.0f, p->pole_pairs); /* N m s/rad */
    float wc = CTL_SPEED_DESIGN_CROSSOVER_RAD_S;
    if (p->inertia_kg_m2 * wc > kp_max) {
        wc = kp_max / p->inertia_kg_m2;
    }
    p->speed_kp_nm_per_rad_s = p->inertia_kg_m2 * wc;
    p->speed_ki_nm_per_rad = p->speed_kp_nm_per_rad_s * wc / CTL_SPEED_DESIGN_RATIO;
}

static bool params_inductance_ok(float l)
{
    return ctl_float_in_range(l, CTL_RANGE_F(CTL_INDUCTANCE_MIN), CTL_RANGE_F(CTL_INDUCTANCE_MAX));
}

#define CTL_PARAM_ERROR_TEXT(code, text) text,
static const char *const param_error_text[CTL_PARAM_ERROR_COUNT] = {
    CTL_PARAM_ERRORS(CTL_PARAM_ERROR_TEXT)};
#undef CTL_PARAM_ERROR_TEXT

#define CTL_CONTROLLER_NAME(id, number, name, what) name,
static const char *const controller_names[CTL_CONTROLLER_COUNT] = {
    CTL_CONTROLLER_LIST(CTL_CONTROLLER_NAME)};
#undef CTL_CONTROLLER_NAME

const char *ctl_controller_name(int controller)
{
    return (controller >= 0 && controller < (int)CTL_CONTROLLER_COUNT)
               ? controller_names[controller]
               : "?";
}

const char *ctl_param_error_text(ctl_param_error_t e)
{
    return ((uint32_t)e < (uint32_t)CTL_PARAM_ERROR_COUNT) ? param_error_text[e] : "unknown reason";
}

static ctl_param_error_t check_machine(const ctl_params_t *p)
{
    ctl_model_t model;
    if (!ctl_float_in_range(p->resistance_ohm, CTL_RANGE_F(CTL_RESISTANCE_MIN),
                            CTL_RANGE_F(CTL_RESISTANCE_MAX))) {
        return CTL_PARAM_RESISTANCE;
    }
    if (!params_inductance_ok(p->ld_h) || !params_inductance_ok(p->lq_h) ||
        !params_inductance_ok(p->l_xy_h)) {
        return CTL_PARAM_INDUCTANCE;
    }
    if (!ctl_float_in_range(p->pm_flux_wb, CTL_RANGE_F(CTL_PM_FLUX_MIN),
                            CTL_RANGE_F(CTL_PM_FLUX_MAX))) {
        return CTL_PARAM_PM_FLUX;
    }
    if (p->pole_pairs < CTL_POLE_PAIRS_MIN || p->pole_pairs > CTL_POLE_PAIRS_MAX) {
        return CTL_PARAM_POLE_PAIRS;
    }
    if (!ctl_float_in_range(p->inertia_kg_m2, CTL_RANGE_F(CTL_INERTIA_MIN),
                            CTL_RANGE_F(CTL_INERTIA_MAX))) {
        return CTL_PARAM_INERTIA;
    }
    if (!ctl_float_in_range(p->sample_time_s, CTL_RANGE_F(CTL_SAMPLE_TIME_MIN),
                            CTL_RANGE_F(CTL_SAMPLE_TIME_MAX))) {
        return CTL_PARAM_SAMPLE_TIME;
    }
    if (!ctl_model_init(&model, p->resistance_ohm, p->ld_h, p->lq_h, p->l_xy_h, p->pm_flux_wb,
                        p->pole_pairs, p->sample_time_s)) {
        return CTL_PARAM_MODEL;
    }
    return CTL_PARAM_OK;
}

static ctl_param_error_t check_control(const ctl_params_t *p)
{
    float kp;
    float ki_ts;
    if ((unsigned)p->controller >= (unsigned)CTL_CONTROLLER_COUNT) { /* negative: wraps above */
        return CTL_PARAM_CONTROLLER;
    }
    if (!(p->ddc_direction == CTL_DDC_DIRECTION_FLUX_ERROR ||
          p->ddc_direction == CTL_DDC_DIRECTION_XY_TABLE)) {
        return CTL_PARAM_DDC_DIRECTION;
    }
    if (p->duty_levels < CTL_DUTY_LEVELS_MIN || p->duty_levels > CTL_DUTY_LEVELS_MAX) {
        return CTL_PARAM_DUTY_LEVELS;
    }
    if (!ctl_float_in_range(p->lambda_nm_per_wb, CTL_RANGE_F(CTL_LAMBDA_MIN),
                            CTL_RANGE_F(CTL_LAMBDA_MAX))) {
        return CTL_PARAM_LAMBDA;
    }
    if (!ctl_float_in_range(p->ddc_flux_tie_band, CTL_RANGE_F(CTL_FLUX_TIE_BAND_MIN),
                            CTL_RANGE_F(CTL_FLUX_TIE_BAND_MAX))) {
        return CTL_PARAM_FLUX_TIE_BAND;
    }
    if (!(p->pulse_pattern == CTL_PULSE_BY_ONES ||
          p->pulse_pattern == CTL_PULSE_FEWEST_TRANSITIONS ||
          p->pulse_pattern == CTL_PULSE_FEWEST_PER_SET)) {
        return CTL_PARAM_PULSE_PATTERN;
    }
    if (!(p->flux_ref_mode == CTL_FLUX_REF_MTPA ||
          (p->flux_ref_mode == CTL_FLUX_REF_CONSTANT &&
           ctl_float_in_range(p->flux_ref_wb, CTL_RANGE_F(CTL_FLUX_REF_MIN),
                              CTL_RANGE_F(CTL_FLUX_REF_MAX))))) {
        return CTL_PARAM_FLUX_REF;
    }
    if (!ctl_float_in_range(p->torque_limit_nm, CTL_RANGE_F(CTL_TORQUE_LIMIT_MIN),
                            CTL_RANGE_F(CTL_TORQUE_LIMIT_MAX))) {
        return CTL_PARAM_TORQUE_LIMIT;
    }
    /* the table takes at most the current of its top (ctl_flux_ref_init) */
    if (!ctl_float_in_range(p->light_load_current_a, CTL_RANGE_F(CTL_LIGHT_LOAD_CURRENT_MIN),
                            CTL_RANGE_F(CTL_LIGHT_LOAD_CURRENT_MAX))) {
        return CTL_PARAM_LIGHT_LOAD_CURRENT;
    }
    if (!ctl_float_in_range(p->speed_kp_nm_per_rad_s, CTL_RANGE_F(CTL_SPEED_KP_MIN),
                            CTL_RANGE_F(CTL_SPEED_KP_MAX)) ||
        !ctl_float_in_range(p->speed_ki_nm_per_rad, CTL_RANGE_F(CTL_SPEED_KI_MIN),
                            CTL_RANGE_F(CTL_SPEED_KI_MAX))) {
        return CTL_PARAM_SPEED_GAINS;
    }
    /* per-unit gains must stay well inside the Q24 range (|x| < 128) */
    kp = ctl_speed_gain_pu(p->speed_kp_nm_per_rad_s, p->pole_pairs);
    ki_ts = ctl_speed_gain_pu(p->speed_ki_nm_per_rad, p->pole_pairs) * p->sample_time_s;
    if (!(kp < 100.0f && ki_ts < 100.0f)) {
        return CTL_PARAM_SPEED_GAINS;
    }
    return CTL_PARAM_OK;
}

ctl_param_error_t ctl_params_check(const ctl_params_t *p)
{
    ctl_param_error_t e = check_machine(p);
    if (e == CTL_PARAM_OK) {
        e = check_control(p);
    }
    if (e == CTL_PARAM_OK && !ctl_protect_settings_valid(&p->protect)) {
        e = CTL_PARAM_PROTECTION;
    }
    if (e == CTL_PARAM_OK && (p->open_phase < CTL_POSTFAULT_NO_LEG || p->open_phase > 5 ||
                              !(p->postfault_strategy == CTL_POSTFAULT_MIN_LOSS ||
                                p->postfault_strategy == CTL_POSTFAULT_MAX_TORQUE))) {
        e = CTL_PARAM_OPEN_PHASE;
    }
    return e;
}
