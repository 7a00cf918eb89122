/* The simulated encoder, see sim_encoder.h. */
#include "sim_encoder.h"

#include <math.h>

#include "hal_encoder.h"
#include "hal_sim.h"

#define ENC_TWO_PI 6.28318530717958647692
/* hal/f28335: F28335_QEP_WATCHDOG_PRD (10 ms) and F28335_QEP_TIMEOUT_SPEED_Q16 (5 rev/s); that
 * header describes registers of the target and is not part of the host build */
#define ENC_WATCHDOG_S 10e-3
#define ENC_LOSS_REV_S 5.0

void sim_encoder_init(sim_encoder_t *enc, double ts)
{
    long len = lround(1e-3 / ts);
    enc->ring_len =
        (int)((len < 1) ? 1 : ((len > SIM_ENCODER_RING_MAX) ? SIM_ENCODER_RING_MAX : len));
    enc->ring_pos = 0;
    enc->first = true;
    enc->edge_speed_rev_s = 0.0;
    enc->qep_error = false;
    enc->index_seen = true;
    enc->turn_known = false;
    enc->count0 = 0;
    enc->turn_prev = 0;
    enc->turn_lo = 0;
    enc->theta_stuck = 0.0;
    enc->shaft0_rad = 0.0;
}

void sim_encoder_restart(sim_encoder_t *enc)
{
    enc->first = true;
    enc->turn_known = false;
}

/* The shaft angle as the counter sees it (rad): from the index, in the channels' direction. */
static double enc_shaft_rad(const plant_params_t *p, double theta_m)
{
    const double sign = p->encoder_reversed ? -1.0 : 1.0;
    const double index_m = p->encoder_offset_rad / (double)p->pole_pairs;
    return sign * (theta_m - index_m);
}

/* The same in counts (continuous). */
static double enc_shaft_counts(const plant_params_t *p, double theta_m)
{
    const double cpr = 4.0 * (double)p->encoder_lines;
    return enc_shaft_rad(p, theta_m) / ENC_TWO_PI * cpr;
}

static int64_t enc_floor_div(int64_t a, int64_t b)
{
    const int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

void sim_encoder_power_up(sim_encoder_t *enc, const plant_params_t *p, const plant_state_t *x,
                          bool homed)
{
    const int64_t count = (int64_t)floor(enc_shaft_counts(p, x->theta_m));
    enc->index_seen = homed;
    enc->count0 = homed ? 0 : count;
    enc->turn_prev = enc_floor_div(count, (int64_t)(4u * p->encoder_lines));
    enc->turn_lo = enc->turn_prev * (int64_t)(4u * p->encoder_lines);
    enc->turn_known = true;
    enc->theta_stuck = x->theta_m;
    enc->shaft0_rad = homed ? 0.0 : enc_shaft_rad(p, x->theta_m);
}

/* The index pulse: the count crossed a whole turn from the index since the last sample (either
 * way). It re-homes the HAL after hal_encoder_rehome (the eQEP's first-index flag) and ends a
 * slip the fault injection put into the count. Two compares per period; the turn is recomputed
 * only after a crossing. */
static void enc_index(sim_encoder_t *enc, const plant_params_t *p, int64_t count,
                      sim_fault_state_t *fs)
{
    const int64_t cpr = (int64_t)(4u * p->encoder_lines);
    int64_t turn;
    if (enc->turn_known && count >= enc->turn_lo && count < enc->turn_lo + cpr) {
        return;
    }
    turn = enc_floor_div(count, cpr);
    if (enc->turn_known && turn != enc->turn_prev) {
        enc->index_seen = true;
        if (hal_sim_bus.encoder_homing_lost) {
            sim_fault_encoder_rehomed(fs);
        }
        hal_sim_post_encoder_index();
    }
    enc->turn_prev = turn;
    enc->turn_lo = turn * cpr;
    enc->turn_known = true;
}

/* The drive's HAL configuration (the eQEP driver's constants), the plant's as a fallback. */
static uint32_t enc_hal_pole_pairs(const plant_params_t *p)
{
    return (hal_sim_bus.encoder_pole_pairs > 0u) ? (uint32_t)hal_sim_bus.encoder_pole_pairs
                                                 : (uint32_t)p->pole_pairs;
}

/* lround for |q| < 2^31 without the library call: truncate (exact), then step away from zero
 * when the exact remainder is at least one half. */
static int32_t enc_round_half_away(double q)
{
    int32_t n = (int32_t)q;
    const double rest = q - (double)n;
    if (rest >= 0.5) {
        n++;
    } else if (rest <= -0.5) {
        n--;
    }
    return n;
}

static int32_t enc_q16_clamp(double v)
{
    const double q = v * 65536.0;
    if (!(q == q)) {
        return 0;
    }
    if (q >= 2147483647.0) {
        return INT32_MAX;
    }
    if (q <= -2147483648.0) {
        return INT32_MIN;
    }
    return enc_round_half_away(q);
}

static uint32_t enc_turn_u32(double turns)
{
    const double frac = turns - floor(turns);
    double v = frac * 4294967296.0;
    if (v >= 4294967295.0) {
        v = 0.0;
    }
    return (uint32_t)v;
}

/* The window's history as if the rotor had turned at its present speed before. */
static void enc_fill_window(sim_encoder_t *enc, int64_t count, double pos, double omega_m,
                            double cpr, double t, double ts)
{
    int i;
    enc->first = false;
    enc->count_prev = count;
    enc->pos_prev = pos;
    enc->edge_t_prev = t;
    for (i = 0; i < enc->ring_len; i++) {
        const double back = (double)(enc->ring_len - i) * ts;
        enc->ring_t[i] = t - back;
        enc->ring_count[i] = (int64_t)floor(pos - omega_m / ENC_TWO_PI * cpr * back);
    }
}

/* Time of the latest edge: interpolated between the previous and this sample. */
static double enc_edge_time(const sim_encoder_t *enc, int64_t count, double pos, double t,
                            double ts)
{
    double edge, span, frac;
    if (count == enc->count_prev) {
        return enc->edge_t_prev;
    }
    edge = (count > enc->count_prev) ? (double)count : (double)(count + 1);
    span = pos - enc->pos_prev;
    frac = (span != 0.0) ? (edge - enc->pos_prev) / span : 1.0;
    frac = (frac < 0.0) ? 0.0 : ((frac > 1.0) ? 1.0 : frac);
    return (t - ts) + frac * ts;
}

/* Count change over the window divided by the time between its end edges (0 when still). */
static int32_t enc_window_speed(sim_encoder_t *enc, int64_t count, double edge_t, double cpr)
{
    const int old = enc->ring_pos; /* oldest entry */
    const int64_t dc = count - enc->ring_count[old];
    const double dt = edge_t - enc->ring_t[old];
    const int32_t speed = (dc != 0 && dt > 0.0) ? enc_q16_clamp((double)dc / cpr / dt) : 0;
    enc->ring_count[old] = count;
    enc->ring_t[old] = edge_t;
    enc->ring_pos = (enc->ring_pos + 1) % enc->ring_len;
    if (dc != 0) {
        enc->edge_speed_rev_s = (double)speed / 65536.0;
    }
    return speed;
}

/* pos: the shaft in counts (enc_shaft_counts), count: its floor. */
static void enc_quantised(sim_encoder_t *enc, const plant_params_t *p, const plant_state_t *s,
                          double pos, int64_t count, double t, double ts, hal_encoder_sample_t *e)
{
    const double cpr = 4.0 * (double)p->encoder_lines;
    const int64_t cpr_i = (int64_t)(4u * p->encoder_lines);
    int64_t in_turn = (enc->index_seen ? count : count - enc->count0) % cpr_i;
    double edge_t;
    if (in_turn < 0) {
        in_turn += cpr_i;
    }
    /* electrical angle of the counted position: (count / cpr) * Pn turns, plus the offset */
    e->elec_angle =
        (uint32_t)(((uint64_t)in_turn * (uint64_t)enc_hal_pole_pairs(p) * 4294967296ull) /
                   (uint64_t)cpr_i) +
        hal_sim_bus.encoder_elec_offset;
    if (enc->first) {
        const double sign = p->encoder_reversed ? -1.0 : 1.0;
        enc_fill_window(enc, count, pos, sign * s->omega_m, cpr, t, ts);
    }
    edge_t = enc_edge_time(enc, count, pos, t, ts);
    e->mech_speed_q16 = enc_window_speed(enc, count, edge_t, cpr);
    enc->count_prev = count;
    enc->pos_prev = pos;
    enc->edge_t_prev = edge_t;
    /* eQEP watchdog (hal/f28335 f28335_eqep.c) */
    if (t - edge_t > ENC_WATCHDOG_S && fabs(enc->edge_speed_rev_s) > ENC_LOSS_REV_S) {
        enc->qep_error = true;
    }
    e->healthy = !enc->qep_error;
}

/* Exact angle and speed (quantisation off). */
static void enc_exact(const sim_encoder_t *enc, const plant_params_t *p, const plant_state_t *s,
                      hal_encoder_sample_t *e)
{
    const double sign = p->encoder_reversed ? -1.0 : 1.0;
    const double shaft = enc_shaft_rad(p, s->theta_m) - (enc->index_seen ? 0.0 : enc->shaft0_rad);
    e->elec_angle = enc_turn_u32((double)enc_hal_pole_pairs(p) * shaft / ENC_TWO_PI +
                                 (double)hal_sim_bus.encoder_elec_offset / 4294967296.0);
    e->mech_speed_q16 = enc_q16_clamp(sign * s->omega_m / ENC_TWO_PI);
    e->healthy = true;
}

void sim_encoder_sample(sim_encoder_t *enc, const plant_params_t *p, const plant_state_t *x,
                        double t, double ts, sim_fault_state_t *fs)
{
    plant_state_t seen = *x; /* the shaft as the encoder interface sees it */
    hal_encoder_sample_t e;
    double pos;
    int64_t count;
    seen.theta_m = sim_fault_encoder_angle(fs, p->encoder_stuck ? enc->theta_stuck : x->theta_m);
    if (p->encoder_stuck) {
        seen.omega_m = 0.0;
    }
    pos = enc_shaft_counts(p, seen.theta_m);
    count = (int64_t)floor(pos);
    enc_index(enc, p, count, fs);
    e.healthy = true;
    if (!p->encoder_quant_on) {
        enc_exact(enc, p, &seen, &e);
    } else {
        enc_quantised(enc, p, &seen, pos, count, t, ts, &e);
    }
    /* before the index the eQEP reports unhealthy (QEPSTS.FIMF clear: the drive refuses RUN) */
    e.healthy = e.healthy && enc->index_seen;
    e.index_seen = enc->index_seen;
    e.position = (int32_t)(uint32_t)(uint64_t)(count - enc->count0);
    sim_fault_encoder(fs, &e);
    hal_sim_post_encoder(&e);
}
