/* Identification step 3, the stator resistance: see ident_resistance.h. */
#include "ident_resistance.h"

#include "ctl_q.h"
#include "ctl_qmath.h"

#define RES_MOVE_S 0.3f
#define RES_SETTLE_S 0.3f
#define RES_MEASURE_S 0.5f
#define RES_BLOCK_S 0.05f
#define RES_RAMP_S 0.05f
#define RES_LOW_FRACTION 0.5f
#define RES_POOR_RELATIVE 0.01f /* 1-sigma above 1 % of R: POOR */
#define RES_MIN_PHASE_A 0.05f   /* a phase's mean this close to zero at the low level: POOR */

enum { RS_MOVE, RS_RAMP, RS_SETTLE, RS_MEASURE };

void ident_resistance_begin(ident_ctx_t *x, ident_resistance_t *s)
{
    int16_t k;
    /* the nearest 15 + 30 k degrees: (2 k + 1) / 24 turn */
    const float a = x->traj.angle;
    const float sector = (float)(int32_t)(a * 12.0f); /* a in [0, 1): the 30-degree sector */
    s->from = a;
    s->to = (2.0f * sector + 1.0f) / 24.0f;
    s->level = 0;
    for (k = 0; k < IDENT_PHASES; k++) {
        s->low_phase_sum[k] = 0.0f;
    }
    s->low_n = 0;
    x->frame = IDENT_FRAME_COMMAND;
    x->traj.target = 0.0f;
    ident_goto(x, RS_MOVE);
}

static float res_level_current(const ident_ctx_t *x, int16_t level)
{
    return (level == 1) ? RES_LOW_FRACTION * x->i_test : x->i_test;
}

/* The smallest |mean phase current| at the low level: a phase whose current averages near zero
 * changes sign between the levels, and its dead-time voltage no longer cancels. The mean, not
 * the smallest sample: the switching ripple may touch zero on a low-inductance or many-pole
 * machine for an instant without moving the mean voltage (issue 25's grid: R +0.55 % there,
 * +0.53 % on the reference machine, reported poor by the smallest sample). */
static float res_smallest_phase_mean(const ident_resistance_t *s)
{
    float smallest = 1.0e9f;
    int16_t k;
    for (k = 0; k < IDENT_PHASES && s->low_n > 0; k++) {
        const float m = s->low_phase_sum[k] / (float)s->low_n;
        const float a = (m < 0.0f) ? -m : m;
        smallest = (a < smallest) ? a : smallest;
    }
    return smallest;
}

/* R and its uncertainty from the three levels, into the result. */
static ident_status_t res_finish(ident_ctx_t *x, ident_resistance_t *s)
{
    const float uh = 0.5f * (ident_blocks_mean(&s->u[0]) + ident_blocks_mean(&s->u[2]));
    const float ih = 0.5f * (ident_blocks_mean(&s->i[0]) + ident_blocks_mean(&s->i[2]));
    const float ul = ident_blocks_mean(&s->u[1]);
    const float il = ident_blocks_mean(&s->i[1]);
    const float di = ih - il;
    float r, su2, si2, sigma;
    int16_t k;
    if (!(di > 0.1f * x->i_test)) {
        ident_set_result(x, COMM_Q_R, 0.0f, 0.0f, 0.0f, COMM_QUALITY_FAILED,
                         COMM_REASON_NO_CURRENT);
        return ident_fail(x, COMM_REASON_NO_CURRENT);
    }
    r = (uh - ul) / di;
    su2 = 0.0f;
    si2 = 0.0f;
    for (k = 0; k < 3; k++) {
        const float w = (k == 1) ? 1.0f : 0.25f; /* the highs enter halved */
        const float su = ident_blocks_sigma(&s->u[k]);
        const float si = ident_blocks_sigma(&s->i[k]);
        su2 += w * su * su;
        si2 += w * si * si;
    }
    sigma = ctl_sqrtf(su2 + r * r * si2) / di;
    if (!(r > 0.0f && r < 1000.0f)) {
        ident_set_result(x, COMM_Q_R, r, sigma, 0.0f, COMM_QUALITY_FAILED,
                         COMM_REASON_OUT_OF_RANGE);
        return IDENT_DONE; /* later steps do not need R to run */
    }
    {
        const bool poor =
            sigma > RES_POOR_RELATIVE * r || res_smallest_phase_mean(s) < RES_MIN_PHASE_A;
        ident_set_result(x, COMM_Q_R, r, sigma, 0.0f, poor ? COMM_QUALITY_POOR : COMM_QUALITY_OK,
                         poor ? COMM_REASON_SCATTER : COMM_REASON_NONE);
    }
    return IDENT_DONE;
}

static void res_sample(ident_ctx_t *x, ident_resistance_t *s, const ident_input_t *in)
{
    ident_blocks_add(&s->u[s->level], ident_u_frame(x, 0));
    ident_blocks_add(&s->i[s->level], x->i_dq[0]);
    if (s->level == 1) {
        int16_t k;
        for (k = 0; k < IDENT_PHASES; k++) {
            s->low_phase_sum[k] += in->i_phase[k];
        }
        s->low_n++;
    }
}

ident_status_t ident_resistance_step(ident_ctx_t *x, ident_resistance_t *s, const ident_input_t *in)
{
    const uint32_t n_move = ident_periods(x, RES_MOVE_S);
    const uint32_t n_ramp = ident_periods(x, RES_RAMP_S);
    switch (x->phase) {
    case RS_MOVE: { /* a raised-cosine move of at most 15 degrees */
        const float d = ident_wrap_half(s->to - s->from);
        ident_traj_reset(&x->traj, s->from + d * ident_ramp(x->t, n_move));
        if (x->t >= n_move) {
            ident_goto(x, RS_SETTLE);
        }
        break;
    }
    case RS_RAMP: {
        const float from = res_level_current(x, (int16_t)(s->level - 1));
        const float to = res_level_current(x, s->level);
        x->ref_dq[0] = from + (to - from) * ident_ramp(x->t, n_ramp);
        if (x->t >= n_ramp) {
            ident_goto(x, RS_SETTLE);
        }
        break;
    }
    case RS_SETTLE:
        if (x->t >= ident_periods(x, RES_SETTLE_S)) {
            ident_blocks_init(&s->u[s->level], (int32_t)ident_periods(x, RES_BLOCK_S));
            ident_blocks_init(&s->i[s->level], (int32_t)ident_periods(x, RES_BLOCK_S));
            ident_goto(x, RS_MEASURE);
        }
        break;
    default: /* RS_MEASURE */
        res_sample(x, s, in);
        if (x->t < ident_periods(x, RES_MEASURE_S)) {
            break;
        }
        if (s->level == 2) {
            return res_finish(x, s);
        }
        s->level++;
        ident_goto(x, RS_RAMP);
        break;
    }
    return IDENT_RUNNING;
}
