/* Identification steps 4 and 5, the inductances: see ident_inductance.h. */
#include "ident_inductance.h"

#define IND_SETTLE_S 0.1f
#define IND_HALF_PERIODS 10u    /* control periods per half square wave (500 Hz at 10 kHz) */
#define IND_BLOCK_WAVES 10u     /* square waves per estimate */
#define IND_WAVES 200           /* square waves per axis */
#define IND_RIPPLE_D 0.5f       /* peak-to-peak ripple over the bias, d axis */
#define IND_RIPPLE_OTHER 0.25f  /* q, x, y */
#define IND_POOR_RELATIVE 0.02f /* 1-sigma above 2 %: POOR */
#define IND_MOVED_TURNS 0.003f  /* electrical turns of rotor motion (about 1 degree): POOR */

enum { IN_SETTLE, IN_INJECT };

/* The axis' regulator output this period (the one computed last period). */
static float ind_output(const ident_ctx_t *x, int16_t axis)
{
    return (axis < IDENT_AXIS_X) ? x->reg.u_dq[axis] : x->reg.u_xy[axis - IDENT_AXIS_X];
}

static float ind_inductance(const ident_ctx_t *x, int16_t axis)
{
    return (axis == IDENT_AXIS_D) ? x->m.ld : ((axis == IDENT_AXIS_Q) ? x->m.lq : x->m.lxy);
}

/* The injected axis' current this period. */
static float ind_current(const ident_ctx_t *x, int16_t axis)
{
    return (axis < IDENT_AXIS_X) ? x->i_dq[axis] : x->i_xy[axis - IDENT_AXIS_X];
}

static void ind_inject(ident_ctx_t *x, int16_t axis, float u)
{
    if (axis < IDENT_AXIS_X) {
        x->reg.inject_dq[axis] = u;
    } else {
        x->reg.inject_xy[axis - IDENT_AXIS_X] = u;
    }
}

/* The block store of an axis: x and y share one. */
static ident_blocks_t *ind_store(ident_inductance_t *s, int16_t axis)
{
    return &s->l[(axis < IDENT_AXIS_X) ? axis : 2];
}

static void ind_start_axis(ident_ctx_t *x, ident_inductance_t *s, const ident_input_t *in)
{
    const float ripple = (s->axis == IDENT_AXIS_D) ? IND_RIPPLE_D : IND_RIPPLE_OTHER;
    s->amplitude =
        ripple * x->i_test * ind_inductance(x, s->axis) / ((float)IND_HALF_PERIODS * x->m.ts);
    s->sign[0] = s->sign[1] = 0;
    s->sum_pos = s->sum_neg = 0.0f;
    s->n_pos = s->n_neg = 0;
    s->waves = 0;
    s->last_i = ind_current(x, s->axis);
    if (s->axis != IDENT_AXIS_Y) { /* y adds to x's blocks and motion */
        ident_blocks_init(ind_store(s, s->axis), 1);
        s->p_start = in->position;
        s->moved = 0;
    }
    /* the axis held at its mean output of the settling (the bias voltage, without the noise
     * of a single period's proportional part); the other axes keep regulating (and damping) */
    ident_reg_hold(&x->reg, (uint16_t)(1u << s->axis), s->u_sum / (float)s->u_n);
    ident_goto(x, IN_INJECT);
}

void ident_inductance_begin(ident_ctx_t *x, ident_inductance_t *s, ident_axis_t first,
                            ident_axis_t last)
{
    s->axis = (int16_t)first;
    s->last_axis = (int16_t)last;
    x->frame = IDENT_FRAME_COMMAND;
    x->traj.target = 0.0f;
    ident_goto(x, IN_SETTLE);
}

/* One period's change of the axis current, filed by the sign that caused it: the command of
 * two periods ago acted over the last period. */
static void ind_accumulate(ident_ctx_t *x, ident_inductance_t *s)
{
    const float i = ind_current(x, s->axis);
    const float di = i - s->last_i;
    s->last_i = i;
    if (s->sign[1] > 0) {
        s->sum_pos += di;
        s->n_pos++;
    } else if (s->sign[1] < 0) {
        s->sum_neg += di;
        s->n_neg++;
    }
    if (s->n_pos + s->n_neg >= (int32_t)(2u * IND_HALF_PERIODS * IND_BLOCK_WAVES) && s->n_pos > 0 &&
        s->n_neg > 0) {
        const float slope = s->sum_pos / (float)s->n_pos - s->sum_neg / (float)s->n_neg;
        if (slope > 0.0f) {
            ident_blocks_add_block(ind_store(s, s->axis), 2.0f * s->amplitude * x->m.ts / slope);
        }
        s->sum_pos = s->sum_neg = 0.0f;
        s->n_pos = s->n_neg = 0;
    }
}

/* The square wave: the first half period half long, so the ripple is centred on the bias; t
 * counts from 0. */
static int16_t ind_next_sign(ident_inductance_t *s, uint32_t t)
{
    const uint32_t phase = (t + IND_HALF_PERIODS / 2u) % (2u * IND_HALF_PERIODS);
    if (phase == 0u) {
        s->waves++;
    }
    return (phase < IND_HALF_PERIODS) ? 1 : -1;
}

static void ind_track_motion(ident_inductance_t *s, const ident_input_t *in)
{
    const int32_t d = in->position - s->p_start;
    const int32_t a = (d < 0) ? -d : d;
    s->moved = (a > s->moved) ? a : s->moved;
}

static void ind_result(ident_ctx_t *x, comm_quantity_t q, const ident_blocks_t *b, int32_t moved)
{
    const float l = ident_blocks_mean(b);
    const float sigma = ident_blocks_sigma(b);
    const float turns =
        (x->cpe != 0.0f) ? (float)moved / ((x->cpe > 0.0f) ? x->cpe : -x->cpe) : 0.0f;
    int16_t quality = COMM_QUALITY_OK;
    int16_t reason = COMM_REASON_NONE;
    if (b->blocks < 2 || !(l > 1.0e-6f && l < 10.0f)) {
        quality = COMM_QUALITY_FAILED;
        reason = COMM_REASON_OUT_OF_RANGE;
    } else if (turns > IND_MOVED_TURNS) {
        quality = COMM_QUALITY_POOR;
        reason = COMM_REASON_ROTOR_MOVED;
    } else if (sigma > IND_POOR_RELATIVE * l) {
        quality = COMM_QUALITY_POOR;
        reason = COMM_REASON_SCATTER;
    }
    ident_set_result(x, q, l, sigma, (float)moved, quality, reason);
}

/* The axis is done: back to regulation, the next axis or the results. */
static ident_status_t ind_end_axis(ident_ctx_t *x, ident_inductance_t *s)
{
    ind_inject(x, s->axis, 0.0f);
    x->reg.hold = 0u;
    if (s->axis == IDENT_AXIS_D) {
        ind_result(x, COMM_Q_LD, ind_store(s, s->axis), s->moved);
    } else if (s->axis == IDENT_AXIS_Q) {
        ind_result(x, COMM_Q_LQ, ind_store(s, s->axis), s->moved);
    } else if (s->axis == IDENT_AXIS_Y) {
        ind_result(x, COMM_Q_LXY, ind_store(s, s->axis), s->moved);
    }
    if (s->axis >= s->last_axis) {
        return IDENT_DONE;
    }
    s->axis++;
    ident_goto(x, IN_SETTLE);
    return IDENT_RUNNING;
}

ident_status_t ident_inductance_step(ident_ctx_t *x, ident_inductance_t *s, const ident_input_t *in)
{
    if (x->phase == IN_SETTLE) {
        const uint32_t n = ident_periods(x, IND_SETTLE_S);
        if (x->t <= n / 2u) {
            s->u_sum = 0.0f;
            s->u_n = 0;
        } else {
            s->u_sum += ind_output(x, s->axis);
            s->u_n++;
        }
        if (x->t >= n) {
            ind_start_axis(x, s, in);
        }
        return IDENT_RUNNING;
    }
    ind_track_motion(s, in);
    ind_accumulate(x, s);
    s->sign[1] = s->sign[0];
    if (s->waves >= IND_WAVES) {
        s->sign[0] = 0;
        ind_inject(x, s->axis, 0.0f);
        return (s->sign[1] == 0) ? ind_end_axis(x, s) : IDENT_RUNNING;
    }
    s->sign[0] = ind_next_sign(s, x->t - 1u);
    if (s->waves >= IND_WAVES) {
        s->sign[0] = 0;
    }
    ind_inject(x, s->axis, (float)s->sign[0] * s->amplitude);
    return IDENT_RUNNING;
}
