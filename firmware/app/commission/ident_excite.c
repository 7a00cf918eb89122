/* Excitation of the motor identification, see ident_excite.h. */
#include "ident_excite.h"

#include "ctl_q.h"
#include "ctl_qmath.h"

#define IDENT_H3 0.8660254f /* sqrt(3) / 2 */

/* cos th_k, sin th_k, cos 5th_k, sin 5th_k for th = 0, 120, 240, 30, 150, 270 deg. */
static const float vsd_row[4][IDENT_PHASES] = {
    {1.0f, -0.5f, -0.5f, IDENT_H3, -IDENT_H3, 0.0f},
    {0.0f, IDENT_H3, -IDENT_H3, 0.5f, 0.5f, -1.0f},
    {1.0f, -0.5f, -0.5f, -IDENT_H3, IDENT_H3, 0.0f},
    {0.0f, -IDENT_H3, IDENT_H3, 0.5f, 0.5f, -1.0f},
};

void ident_sincos(float turns, float *s, float *c)
{
    ctl_q sq, cq;
    ctl_sincos_pu(ctl_from_float(turns - (float)(int32_t)turns), &sq, &cq);
    *s = ctl_to_float(sq);
    *c = ctl_to_float(cq);
}

float ident_wrap_half(float turns)
{
    float w = turns - (float)(int32_t)turns; /* (-1, 1) */
    if (w > 0.5f) {
        w -= 1.0f;
    } else if (w <= -0.5f) {
        w += 1.0f;
    }
    return w;
}

float ident_turns_u32(uint32_t angle) { return (float)(angle >> 8) * (1.0f / 16777216.0f); }

void ident_vsd(const float phase[IDENT_PHASES], float out[4])
{
    int16_t a, k;
    for (a = 0; a < 4; a++) {
        float sum = 0.0f;
        for (k = 0; k < IDENT_PHASES; k++) {
            sum += vsd_row[a][k] * phase[k];
        }
        out[a] = sum * (1.0f / 3.0f);
    }
}

float ident_vsd_phase(const float v[4], int16_t k)
{
    return v[0] * vsd_row[0][k] + v[1] * vsd_row[1][k] + v[2] * vsd_row[2][k] +
           v[3] * vsd_row[3][k];
}

void ident_to_frame(float a, float b, float s, float c, float out[2])
{
    out[0] = a * c + b * s;
    out[1] = b * c - a * s;
}

void ident_from_frame(float d, float q, float s, float c, float out[2])
{
    out[0] = d * c - q * s;
    out[1] = d * s + q * c;
}

void ident_reg_init(ident_reg_t *r, float l_dq, float l_xy, float bw_rad_s, float ts,
                    float limit_dq, float limit_xy)
{
    const ident_pi_t zero = {0.0f, 0.0f, 0.0f};
    r->d = r->q = r->x = r->y = zero;
    r->d.kp = r->q.kp = l_dq * bw_rad_s;
    r->x.kp = r->y.kp = l_xy * bw_rad_s;
    r->d.ki_ts = r->q.ki_ts = r->d.kp * (bw_rad_s / 3.0f) * ts;
    r->x.ki_ts = r->y.ki_ts = r->x.kp * (bw_rad_s / 3.0f) * ts;
    r->kp_dq = r->d.kp;
    r->ki_ts_dq = r->d.ki_ts;
    r->limit_dq = limit_dq;
    r->limit_xy = limit_xy;
    r->hold = 0u;
    r->u_dq[0] = r->u_dq[1] = r->u_xy[0] = r->u_xy[1] = 0.0f;
    r->inject_dq[0] = r->inject_dq[1] = r->inject_xy[0] = r->inject_xy[1] = 0.0f;
    r->u[0] = r->u[1] = r->u[2] = r->u[3] = 0.0f;
    r->saturated = false;
}

/* The PI's output for an error; the integrator moves only while the output is within limit
 * (conditional integration: no wind-up at a voltage limit). */
static float pi_out(ident_pi_t *pi, float error, float limit, bool *clipped)
{
    const float integ = pi->integ + pi->ki_ts * error;
    const float u = pi->kp * error + integ;
    if (u > limit || u < -limit) {
        *clipped = true;
        return (u > limit) ? limit : -limit;
    }
    pi->integ = integ;
    return u;
}

void ident_reg_gains_dq(ident_reg_t *r, float kp, float ki, float ts)
{
    r->d.kp = r->q.kp = kp;
    r->d.ki_ts = r->q.ki_ts = ki * ts;
}

void ident_reg_gains_nominal(ident_reg_t *r)
{
    r->d.kp = r->q.kp = r->kp_dq;
    r->d.ki_ts = r->q.ki_ts = r->ki_ts_dq;
}

void ident_reg_hold(ident_reg_t *r, uint16_t axis, float u)
{
    ident_pi_t *const pis[4] = {&r->d, &r->q, &r->x, &r->y};
    float *const outs[4] = {&r->u_dq[0], &r->u_dq[1], &r->u_xy[0], &r->u_xy[1]};
    int16_t k;
    for (k = 0; k < 4; k++) {
        if ((axis & (1u << k)) != 0u) {
            *outs[k] = u;
            pis[k]->integ = u;
        }
    }
    r->hold |= axis;
}

static void reg_dq(ident_reg_t *r, const float ref[2], const float i[2])
{
    bool clipped = false;
    float d = r->u_dq[0];
    float q = r->u_dq[1];
    float mag2;
    if ((r->hold & IDENT_HOLD_D) == 0u) {
        d = pi_out(&r->d, ref[0] - i[0], r->limit_dq, &clipped);
    }
    if ((r->hold & IDENT_HOLD_Q) == 0u) {
        q = pi_out(&r->q, ref[1] - i[1], r->limit_dq, &clipped);
    }
    mag2 = d * d + q * q;
    if (r->hold == 0u && mag2 > r->limit_dq * r->limit_dq) {
        const float k = r->limit_dq / ctl_sqrtf(mag2);
        d *= k;
        q *= k;
        clipped = true;
    }
    r->u_dq[0] = d;
    r->u_dq[1] = q;
    r->saturated = r->saturated || clipped;
}

static void reg_xy(ident_reg_t *r, const float ref[2], const float i[2])
{
    bool clipped = false;
    if ((r->hold & IDENT_HOLD_X) == 0u) {
        r->u_xy[0] = pi_out(&r->x, ref[0] - i[0], r->limit_xy, &clipped);
    }
    if ((r->hold & IDENT_HOLD_Y) == 0u) {
        r->u_xy[1] = pi_out(&r->y, ref[1] - i[1], r->limit_xy, &clipped);
    }
    r->saturated = r->saturated || clipped;
}

void ident_reg_step(ident_reg_t *r, float s, float c, const float ref_dq[2], const float i_dq[2],
                    const float ref_xy[2], const float i_xy[2])
{
    float ab[2];
    r->saturated = false;
    reg_dq(r, ref_dq, i_dq);
    reg_xy(r, ref_xy, i_xy);
    ident_from_frame(r->u_dq[0] + r->inject_dq[0], r->u_dq[1] + r->inject_dq[1], s, c, ab);
    r->u[0] = ab[0];
    r->u[1] = ab[1];
    r->u[2] = r->u_xy[0] + r->inject_xy[0];
    r->u[3] = r->u_xy[1] + r->inject_xy[1];
}

void ident_modulate(const float u[4], float vdc, uint16_t duty[IDENT_PHASES])
{
    const float inv = (vdc > 1.0f) ? 1.0f / vdc : 0.0f;
    int16_t k;
    for (k = 0; k < IDENT_PHASES; k++) {
        float d = 0.5f + ident_vsd_phase(u, k) * inv;
        d = (d < 0.0f) ? 0.0f : ((d > 1.0f) ? 1.0f : d);
        duty[k] = (uint16_t)(d * (float)HAL_PWM_DUTY_ONE + 0.5f);
    }
}

void ident_traj_reset(ident_traj_t *t, float angle)
{
    t->angle = angle - (float)(int32_t)angle;
    if (t->angle < 0.0f) {
        t->angle += 1.0f;
    }
    t->travel = 0.0f;
    t->speed = 0.0f;
    t->target = 0.0f;
    t->accel = 1.0f;
}

void ident_traj_step(ident_traj_t *t, float ts)
{
    const float dv = t->accel * ts;
    const float before = t->speed;
    if (t->speed < t->target - dv) {
        t->speed += dv;
    } else if (t->speed > t->target + dv) {
        t->speed -= dv;
    } else {
        t->speed = t->target;
    }
    {
        const float step = 0.5f * (before + t->speed) * ts;
        t->travel += step;
        t->angle += step;
        if (t->angle >= 1.0f) {
            t->angle -= 1.0f;
        } else if (t->angle < 0.0f) {
            t->angle += 1.0f;
        }
    }
}
