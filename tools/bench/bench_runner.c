/* The measured loop of the benchmark, compiled once per arithmetic. */
#include "bench.h"
#include "ctl.h"
#include "ctl_protect.h"
#include "ctl_pu.h"
#include "ctl_qmath.h"

static ctl_meas_t meas[BENCH_MAX_POINTS];
static ctl_q torque_ref[BENCH_MAX_POINTS];
static size_t count;
static ctl_t controller_state;
static int16_t raw_phase[BENCH_MAX_POINTS][6];
static int16_t raw_vdc[BENCH_MAX_POINTS];
static ctl_protect_t protect_state;

/* Board scaling (hal_board.h): +-20 A over 4096 counts around 2048, 800 V full scale. */
static int16_t raw_counts(double value, double per_count, double zero)
{
    const double c = zero + value / per_count + 0.5;
    return (int16_t)((c < 0.0) ? 0.0 : ((c > 4095.0) ? 4095.0 : c));
}

static ctl_q pu(double si, double base) { return ctl_from_float((float)(si / base)); }

size_t bench_prepare(const bench_point_t *points, size_t n)
{
    size_t i;
    count = (n < BENCH_MAX_POINTS) ? n : BENCH_MAX_POINTS;
    for (i = 0; i < count; i++) {
        int16_t k;
        for (k = 0; k < 6; k++) {
            meas[i].i_phase[k] = pu(points[i].i_phase[k], CTL_BASE_CURRENT_A);
        }
        meas[i].vdc = pu(points[i].vdc, CTL_BASE_VOLTAGE_V);
        meas[i].theta_e = ctl_wrap_turn(pu(points[i].theta_e, CTL_TWO_PI));
        meas[i].omega_e = pu(points[i].omega_e, CTL_BASE_OMEGA_RAD_S);
        torque_ref[i] = pu(points[i].torque_ref, CTL_BASE_TORQUE_NM);
        for (k = 0; k < 6; k++) {
            raw_phase[i][k] = raw_counts(points[i].i_phase[k], 40.0 / 4096.0, 2048.0);
        }
        raw_vdc[i] = raw_counts(points[i].vdc, 800.0 / 4096.0, 0.0);
    }
    return count;
}

static ctl_params_t setup_params;

int16_t bench_setup(int16_t controller)
{
    ctl_params_default(&setup_params);
    setup_params.controller = (ctl_controller_t)controller;
    if (!ctl_init(&controller_state, &setup_params)) {
        return -1;
    }
    ctl_set_loop_mode(&controller_state, CTL_LOOP_TORQUE);
    return 0;
}

int16_t bench_request_change(int16_t k)
{
    static const float lambdas[4] = {20.0f, 100.0f, 200.0f, 50.0f};
    ctl_params_t p = setup_params;
    p.lambda_nm_per_wb = lambdas[k % 4];
    p.ddc_direction =
        ((k / 4) % 2 == 0) ? CTL_DDC_DIRECTION_FLUX_ERROR : CTL_DDC_DIRECTION_XY_TABLE;
    p.ddc_torque_guard = ((k / 8) % 2) == 0;
    p.flux_ref_mode = ((k / 16) % 2 == 0) ? CTL_FLUX_REF_MTPA : CTL_FLUX_REF_CONSTANT;
    p.torque_limit_nm = 7.0f + 0.25f * (float)(k % 5); /* rebuilds the MTPA table's span */
    return (int16_t)ctl_request_params(&controller_state, &p);
}

bool bench_change_pending(void) { return ctl_config_pending(&controller_state); }

/* One control step at prepared point i; a word of its command for the checksum (cheap: this
 * is the measured loop). */
static uint32_t step_at(size_t i, ctl_cmd_t *cmd)
{
    ctl_set_torque_ref(&controller_state, torque_ref[i]);
    ctl_step(&controller_state, &meas[i], cmd);
    return (uint32_t)(uint16_t)cmd->vector + (uint32_t)ctl_to_qn(cmd->duty, 8);
}

uint32_t bench_digest(void)
{
    uint32_t digest = 2166136261u;
    size_t i;
    ctl_reset(&controller_state);
    for (i = 0; i < count; i++) {
        ctl_cmd_t cmd;
        int16_t leg;
        (void)step_at(i, &cmd);
        digest = (digest ^ (uint32_t)(uint16_t)cmd.vector) * 16777619u;
        digest = (digest ^ (uint32_t)ctl_to_qn(cmd.duty, 24)) * 16777619u;
        digest = (digest ^ (cmd.enable ? 1u : 0u)) * 16777619u;
        for (leg = 0; leg < CTL_PHASES; leg++) {
            digest = (digest ^ (uint32_t)ctl_to_qn(cmd.leg_duty[leg], 24)) * 16777619u;
        }
    }
    return digest;
}

uint32_t bench_step(size_t i)
{
    ctl_cmd_t cmd;
    return (i < count) ? step_at(i, &cmd) : 0u;
}

uint32_t bench_run(int32_t reps)
{
    uint32_t checksum = 0u;
    int32_t r;
    size_t i;
    for (r = 0; r < reps; r++) {
        ctl_reset(&controller_state);
        for (i = 0; i < count; i++) {
            ctl_cmd_t cmd;
            checksum = checksum * 31u + step_at(i, &cmd);
        }
    }
    return checksum;
}

uint32_t bench_protect_run(int32_t reps)
{
    ctl_protect_settings_t settings;
    ctl_protect_limits_t l;
    ctl_protect_input_t in;
    uint32_t checksum = 0u;
    int32_t r;
    size_t i;
    int16_t k;
    ctl_model_t model;
    ctl_protect_settings_default(&settings);
    (void)ctl_model_init(&model, 2.0f, 0.035f, 0.055f, 0.01f, 0.225f, 3, 1e-4f);
    ctl_protect_limits_build(&l, &settings, 1e-4f, 3, 0.01f);
    in.model = &model;
    in.encoder_healthy = true;
    in.overrun = false;
    in.hw_trip = false;
    in.running = true;
    in.currents_calibrated = true;
    in.xy_held = true; /* the DDC's six-leg step: the fast open-phase check runs too */
    for (r = 0; r < reps; r++) {
        ctl_protect_init(&protect_state);
        for (i = 0; i < count; i++) {
            for (k = 0; k < 6; k++) {
                in.i_phase[k] = meas[i].i_phase[k];
                in.raw_phase[k] = raw_phase[i][k];
            }
            in.vdc = meas[i].vdc;
            in.raw_vdc = raw_vdc[i];
            in.theta_e = meas[i].theta_e;
            in.omega_e = meas[i].omega_e;
            in.i_d = CTL_Q(0.0); /* the encoder check's torque: the point's reference, as i_q */
            in.i_q = torque_ref[i];
            checksum = checksum * 31u +
                       ctl_protect_check(&protect_state, &l, &in, torque_ref[i], 0, CTL_Q(0.0));
        }
    }
    return checksum;
}
