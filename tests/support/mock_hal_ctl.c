#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "mock_hal_ctl.h"

#include "hal_cycles.h"

mock_record_t mock_rec;
hal_adc_sample_t mock_adc;
hal_encoder_sample_t mock_encoder;
uint32_t mock_encoder_offset;
ctl_cmd_t mock_cmd;
ctl_diag_t mock_diag;
ctl_param_error_t mock_request_result;

void mock_reset(void)
{
    int i;
    memset(&mock_rec, 0, sizeof mock_rec);
    memset(&mock_cmd, 0, sizeof mock_cmd);
    memset(&mock_diag, 0, sizeof mock_diag);
    for (i = 0; i < HAL_ADC_PHASES; i++) {
        mock_adc.phase[i] = MOCK_ADC_ZERO;
    }
    mock_adc.vdc = MOCK_ADC_VDC_540V;
    mock_encoder.elec_angle = 0u;
    mock_encoder.mech_speed_q16 = 0;
    mock_encoder.healthy = true;
    mock_encoder.position = 0;
    mock_encoder.index_seen = true;
    mock_encoder_offset = 0u;
    mock_request_result = CTL_PARAM_OK;
}

/* ---- HAL ---- */
/* cycle counter: advances by 10 on every reading */
static uint32_t mock_cycles;
void hal_cycles_init(void) { mock_cycles = 0u; }
uint32_t hal_cycles_now(void)
{
    mock_cycles += 10u;
    return mock_cycles;
}
uint32_t hal_cycles_per_second(void) { return 150000000u; }

bool hal_adc_init(void) { return true; }

bool hal_adc_read(hal_adc_sample_t *s)
{
    const bool fresh = mock_type(bool);
    if (fresh) {
        *s = mock_adc;
    }
    return fresh;
}

bool hal_encoder_init(uint32_t lines, uint16_t pole_pairs, uint32_t elec_offset)
{
    (void)lines;
    (void)pole_pairs;
    (void)elec_offset;
    return true;
}

void hal_encoder_read(hal_encoder_sample_t *s) { *s = mock_encoder; }

/* As the HAL promises: unhealthy and not homed until the test lets the index pass
 * (mock_encoder.healthy, .index_seen). */
void hal_encoder_rehome(void)
{
    mock_rec.rehome++;
    mock_encoder.healthy = false;
    mock_encoder.index_seen = false;
}

uint32_t hal_encoder_counts_per_turn(void) { return 10000u; }

uint32_t hal_encoder_offset(void) { return mock_encoder_offset; }
void hal_encoder_set_offset(uint32_t elec_offset) { mock_encoder_offset = elec_offset; }

bool hal_pwm_init(uint32_t carrier_hz, uint32_t dead_time_ns)
{
    (void)carrier_hz;
    (void)dead_time_ns;
    return true;
}

void hal_pwm_write(const uint16_t duty[HAL_PWM_LEGS])
{
    int i;
    mock_rec.write++;
    for (i = 0; i < HAL_PWM_LEGS; i++) {
        mock_rec.duty[i] = duty[i];
    }
}

void hal_pwm_force_off(void)
{
    mock_rec.force_off++;
    mock_rec.pwm_off = true;
}

void hal_pwm_enable(void)
{
    mock_rec.enable++;
    mock_rec.pwm_off = false;
}

bool hal_pwm_is_off(void) { return mock_rec.pwm_off; }
bool hal_pwm_hw_trip_seen(void) { return mock_rec.hw_trip; }

bool hal_pwm_isolate_leg(int16_t leg)
{
    if (leg < 0 || leg >= HAL_PWM_LEGS) {
        return false;
    }
    mock_rec.isolated |= (uint16_t)(1u << leg);
    return true;
}
uint16_t hal_pwm_isolated_legs(void) { return mock_rec.isolated; }
void hal_pwm_restore_legs(void) { mock_rec.isolated = 0u; }

/* ---- control core ---- */
/* Parameter sets and their configurations are real (ctl_params.c, ctl_config.c); the hand-off
 * follows the real protocol; only the step itself is mocked. */
bool ctl_init(ctl_t *c, const ctl_params_t *p)
{
    memset(c, 0, sizeof *c);
    if (!mock_type(bool)) {
        c->params_last_error = CTL_PARAM_MODEL;
        return false;
    }
    (void)ctl_config_build(&c->config[0], p);
    ctl_postfault_config_build(&c->postfault[0], p->open_phase,
                               (ctl_postfault_strategy_t)p->postfault_strategy, p->ld_h, p->lq_h,
                               p->l_xy_h);
    c->initialised = true;
    return true;
}

void ctl_reset(ctl_t *c)
{
    (void)c;
    mock_rec.ctl_reset++;
}

void ctl_reset_command(ctl_t *c)
{
    (void)c;
    mock_rec.ctl_reset_command++;
}

ctl_param_error_t ctl_request_params(ctl_t *c, const ctl_params_t *p)
{
    mock_rec.request_params++;
    mock_rec.requested = *p;
    if (mock_request_result != CTL_PARAM_OK) {
        return mock_request_result;
    }
    if (c->config_ready != 0) {
        return CTL_PARAM_BUSY;
    }
    (void)ctl_config_build(&c->config[1 - c->config_active], p);
    ctl_postfault_config_build(&c->postfault[1 - c->config_active], p->open_phase,
                               (ctl_postfault_strategy_t)p->postfault_strategy, p->ld_h, p->lq_h,
                               p->l_xy_h);
    c->config_ready = 1;
    return CTL_PARAM_OK;
}

bool ctl_config_take(ctl_t *c)
{
    mock_rec.config_take++;
    if (c->config_ready == 0) {
        return false;
    }
    c->config_active = (int16_t)(1 - c->config_active);
    c->config_ready = 0;
    c->initialised = true;
    return true;
}

const ctl_config_t *ctl_config(const ctl_t *c) { return &c->config[c->config_active]; }
const ctl_params_t *ctl_params(const ctl_t *c) { return &ctl_config(c)->params; }
bool ctl_config_pending(const ctl_t *c) { return c->config_ready != 0; }
const ctl_postfault_config_t *ctl_postfault_config(const ctl_t *c)
{
    return &c->postfault[c->config_active];
}

void ctl_set_loop_mode(ctl_t *c, ctl_loop_mode_t mode)
{
    c->loop_mode = mode;
    mock_rec.loop_mode = mode;
}

void ctl_set_speed_ref(ctl_t *c, ctl_q omega_e_pu)
{
    c->speed_ref = omega_e_pu;
    mock_rec.speed_ref = omega_e_pu;
}

void ctl_set_torque_ref(ctl_t *c, ctl_q torque_pu)
{
    c->torque_ref_direct = torque_pu;
    mock_rec.torque_ref = torque_pu;
}

void ctl_step(ctl_t *c, const ctl_meas_t *m, ctl_cmd_t *cmd)
{
    (void)c;
    (void)m;
    mock_rec.ctl_step++;
    *cmd = mock_cmd;
}

const ctl_diag_t *ctl_diag(const ctl_t *c)
{
    (void)c;
    return &mock_diag;
}

/* The estimates from the diagnostics' currents (mock_diag's), with the model in force: the real
 * core's formulas (ctl_predict.h), pure functions of the configuration. */
ctl_q ctl_torque_estimate(const ctl_t *c, ctl_q i_d, ctl_q i_q)
{
    return ctl_torque_held(&ctl_config(c)->model, i_d, i_q);
}
ctl_q ctl_diag_torque_est(const ctl_t *c)
{
    return ctl_torque_estimate(c, mock_diag.i_d, mock_diag.i_q);
}
ctl_q ctl_diag_flux_est(const ctl_t *c)
{
    return ctl_flux_held(&ctl_config(c)->model, mock_diag.i_d, mock_diag.i_q);
}
