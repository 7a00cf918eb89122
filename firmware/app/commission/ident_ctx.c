/* What the identification steps share, see ident.h. */
#include "ident.h"

#include "ctl_pu.h"
#include "ctl_q.h"
#include "ctl_qmath.h"

/* Electrical turns the output is applied after the sample, in periods: the command written in
 * period k is in force during period k + 1, on average 1.5 periods after the sample. */
#define IDENT_OUTPUT_DELAY_PERIODS 1.5f

float ident_known(const ident_ctx_t *x, comm_quantity_t q, float set)
{
    return (x->result[q].quality == COMM_QUALITY_OK) ? x->result[q].value : set;
}

void ident_still_reset(ident_still_t *w, int32_t position)
{
    w->ref = position;
    w->n = 0u;
}

uint32_t ident_still_step(ident_still_t *w, int32_t position, int32_t counts)
{
    const int32_t d = position - w->ref;
    if (d > counts || d < -counts) {
        ident_still_reset(w, position);
    } else {
        w->n++;
    }
    return w->n;
}

uint32_t ident_periods(const ident_ctx_t *x, float seconds)
{
    const float n = seconds / x->m.ts;
    return (n < 1.0f) ? 1u : (uint32_t)(n + 0.5f);
}

void ident_goto(ident_ctx_t *x, int16_t phase)
{
    x->phase = phase;
    x->t = 0u;
}

ident_status_t ident_fail(ident_ctx_t *x, int16_t reason)
{
    x->reason = reason;
    return IDENT_FAILED;
}

/* The measurement scale's share of a quantity's relative uncertainty: R and the inductances
 * are a commanded voltage (a duty times the measured DC link) over measured currents; psi_f a
 * voltage over the speed, which the encoder counts exactly; the encoder's quantities are counts;
 * inertia and friction a torque, a measured current times the flux, over a speed. */
static float ident_scale_uncertainty(const ident_machine_t *m, comm_quantity_t q)
{
    switch (q) {
    case COMM_Q_R:
    case COMM_Q_LD:
    case COMM_Q_LQ:
    case COMM_Q_LXY:
        return ctl_sqrtf(m->u_vdc * m->u_vdc + m->u_current * m->u_current);
    case COMM_Q_PSI_F:
        return m->u_vdc;
    case COMM_Q_INERTIA:
    case COMM_Q_FRICTION: /* a torque (a current times psi_f, whose share the step adds) */
        return m->u_current;
    default:
        return 0.0f;
    }
}

void ident_set_result(ident_ctx_t *x, comm_quantity_t q, float value, float sigma, float extra,
                      int16_t quality, int16_t reason)
{
    ident_result_t *r = &x->result[q];
    const float scale = value * ident_scale_uncertainty(&x->m, q);
    r->value = value;
    r->sigma = ctl_sqrtf(sigma * sigma + scale * scale);
    r->extra = extra;
    r->quality = quality;
    r->reason = reason;
}

float ident_rotor_angle(const ident_ctx_t *x, const ident_input_t *in)
{
    const float a = ident_turns_u32(in->elec_angle) + x->offset_turns;
    return a - (float)(int32_t)a;
}

void ident_speed_loop(ident_ctx_t *x, ident_pi_t *pi, float error)
{
    float iq = pi->kp * error + pi->integ + pi->ki_ts * error;
    if (iq > x->i_test) {
        iq = x->i_test;
    } else if (iq < -x->i_test) {
        iq = -x->i_test;
    } else {
        pi->integ += pi->ki_ts * error;
    }
    x->ref_dq[1] = iq;
}

float ident_ramp(uint32_t t, uint32_t n)
{
    float s, c;
    if (t >= n || n == 0u) {
        return 1.0f;
    }
    ident_sincos(0.5f * (float)t / (float)n, &s, &c);
    return 0.5f - 0.5f * c;
}

void ident_measure(ident_ctx_t *x, const ident_input_t *in)
{
    float v[4];
    float angle;
    float out_angle;
    ident_vsd(in->i_phase, v);
    x->i_ab[0] = v[0];
    x->i_ab[1] = v[1];
    x->i_xy[0] = v[2];
    x->i_xy[1] = v[3];
    x->speed_e =
        (x->enc_known && x->cpe != 0.0f) ? in->mech_rev_s * x->m.counts_per_turn / x->cpe : 0.0f;
    if (x->frame == IDENT_FRAME_ROTOR) {
        angle = ident_rotor_angle(x, in);
        out_angle = angle + IDENT_OUTPUT_DELAY_PERIODS * x->speed_e * x->m.ts;
    } else {
        angle = x->traj.angle;
        out_angle = angle;
    }
    ident_sincos(angle, &x->frame_s, &x->frame_c);
    ident_sincos(out_angle, &x->out_s, &x->out_c);
    ident_to_frame(v[0], v[1], x->frame_s, x->frame_c, x->i_dq);
    x->t++;
}

/* A phase reference below this (A) gets a proportional share of the dead-time voltage. */
#define IDENT_DEAD_BAND_A 0.02f

/* Each phase's dead-time voltage with the sign of its reference current, as a vector. */
static void ident_dead_time(ident_ctx_t *x, const float ref[2], float vdc, float comp[4])
{
    const float vd = vdc * x->m.dead_time_s / x->m.ts;
    float r[4], phase[IDENT_PHASES];
    int16_t k;
    ident_from_frame(ref[0], ref[1], x->out_s, x->out_c, r);
    r[2] = x->ref_xy[0];
    r[3] = x->ref_xy[1];
    for (k = 0; k < IDENT_PHASES; k++) {
        float share = ident_vsd_phase(r, k) * (1.0f / IDENT_DEAD_BAND_A);
        share = (share > 1.0f) ? 1.0f : ((share < -1.0f) ? -1.0f : share);
        phase[k] = vd * share;
    }
    ident_vsd(phase, comp);
}

/* The x-y harmonics' voltage added to the request (ident_xy_harmonics.h), with the machine's
 * R and L_xy as identified (else the parameter set's). */
static void ident_regulate_xy_harmonics(ident_ctx_t *x)
{
    const float err[2] = {x->ref_xy[0] - x->i_xy[0], x->ref_xy[1] - x->i_xy[1]};
    ident_xy_harmonics_in_t in;
    float u[2];
    in.s_meas = x->frame_s;
    in.c_meas = x->frame_c;
    in.s_out = x->out_s;
    in.c_out = x->out_c;
    in.w_e = CTL_TWO_PI_F * x->speed_e;
    in.r = ident_known(x, COMM_Q_R, x->m.r);
    in.l_xy = ident_known(x, COMM_Q_LXY, x->m.lxy);
    in.kp = x->reg.x.kp;
    in.ki_ts = x->reg.x.ki_ts;
    in.ts = x->m.ts;
    ident_xy_harmonics_step(&x->xy_harm, &in, err, u);
    x->reg.u[2] += u[0];
    x->reg.u[3] += u[1];
}

void ident_regulate(ident_ctx_t *x, float vdc)
{
    float ref[2], comp[4];
    int16_t k;
    ref[0] = x->ref_dq[0];
    ref[1] = x->ref_dq[1];
    if (x->frame == IDENT_FRAME_COMMAND && x->damping > 0.0f) {
        ref[1] -= x->damping * (x->speed_e - x->traj.speed);
    }
    ident_reg_step(&x->reg, x->out_s, x->out_c, ref, x->i_dq, x->ref_xy, x->i_xy);
    if (x->frame == IDENT_FRAME_ROTOR && x->xy_harm.on) {
        ident_regulate_xy_harmonics(x);
    }
    ident_dead_time(x, ref, vdc, comp);
    for (k = 0; k < 4; k++) {
        x->reg.u[k] += comp[k];
    }
    ident_to_frame(comp[0], comp[1], x->out_s, x->out_c, x->comp_dq);
    x->comp_xy[0] = comp[2];
    x->comp_xy[1] = comp[3];
}

float ident_u_frame(const ident_ctx_t *x, int16_t axis)
{
    return x->reg.u_dq[axis] + x->comp_dq[axis];
}
