/* Identification step 1, the phase check: see ident_phase.h. */
#include "ident_phase.h"

#define PHASE_RAMP_S 0.004f
#define PHASE_SETTLE_S 0.012f
#define PHASE_MEASURE_S 0.004f
#define PHASE_JUDGED_SHARE 0.5f /* phases with at least this share of the test are judged */
#define PHASE_LIMIT_FACTOR 2.0f /* a phase above this times the test current ends the check */

enum { PH_RAMP, PH_SETTLE, PH_MEASURE, PH_DOWN };

/* Phase k's share of a current along the x (axis 0) or y (axis 1) axis. */
static float phase_share(int16_t axis, int16_t k)
{
    float v[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    v[2 + axis] = 1.0f;
    return ident_vsd_phase(v, k);
}

void ident_phase_begin(ident_ctx_t *x, ident_phase_t *s)
{
    int16_t k;
    s->axis = 0;
    s->n = 0;
    s->min_ratio = 1.0e9f;
    s->max_ratio = -1.0e9f;
    s->min_phase = -1;
    for (k = 0; k < IDENT_PHASES; k++) {
        s->sum[k] = 0.0f;
    }
    x->ref_dq[0] = x->ref_dq[1] = 0.0f;
    x->ref_xy[0] = x->ref_xy[1] = 0.0f;
    ident_goto(x, PH_RAMP);
}

/* Ratio of each judged phase's current (sum over n samples) to its share of the reference. */
static void phase_judge(ident_phase_t *s, const float *sum, float n, float ref)
{
    int16_t k;
    for (k = 0; k < IDENT_PHASES; k++) {
        const float share = phase_share(s->axis, k);
        if (share >= PHASE_JUDGED_SHARE || share <= -PHASE_JUDGED_SHARE) {
            const float ratio = (sum[k] / n) / (share * ref);
            if (ratio < s->min_ratio) {
                s->min_ratio = ratio;
                s->min_phase = k;
            }
            if (ratio > s->max_ratio) {
                s->max_ratio = ratio;
            }
        }
    }
}

/* The verdict once judged: OK, or why not. */
static ident_status_t phase_verdict(ident_ctx_t *x, ident_phase_t *s, bool limit)
{
    const bool open = s->min_ratio < x->m.open_ratio;
    int16_t reason = COMM_REASON_NONE;
    if (open) {
        reason = (s->max_ratio < x->m.open_ratio) ? COMM_REASON_NO_CURRENT : COMM_REASON_OPEN_PHASE;
    } else if (limit) {
        reason = COMM_REASON_CURRENT_LIMIT;
    }
    ident_set_result(x, COMM_Q_PHASES, s->min_ratio, 0.0f,
                     (reason == COMM_REASON_OPEN_PHASE) ? (float)s->min_phase : -1.0f,
                     (reason == COMM_REASON_NONE) ? COMM_QUALITY_OK : COMM_QUALITY_FAILED, reason);
    return (reason == COMM_REASON_NONE) ? IDENT_DONE : ident_fail(x, reason);
}

/* A phase far above the test current: judge on this sample and stop. */
static bool phase_over_limit(const ident_ctx_t *x, const ident_input_t *in)
{
    const float limit = PHASE_LIMIT_FACTOR * x->i_test;
    int16_t k;
    for (k = 0; k < IDENT_PHASES; k++) {
        if (in->i_phase[k] > limit || in->i_phase[k] < -limit) {
            return true;
        }
    }
    return false;
}

static void phase_measure(ident_ctx_t *x, ident_phase_t *s, const ident_input_t *in)
{
    int16_t k;
    for (k = 0; k < IDENT_PHASES; k++) {
        s->sum[k] = (s->n == 0) ? in->i_phase[k] : s->sum[k] + in->i_phase[k];
    }
    s->n++;
    if (x->t >= ident_periods(x, PHASE_MEASURE_S)) {
        phase_judge(s, s->sum, (float)s->n, x->i_test);
        s->n = 0;
        ident_goto(x, PH_DOWN);
    }
}

ident_status_t ident_phase_step(ident_ctx_t *x, ident_phase_t *s, const ident_input_t *in)
{
    const uint32_t ramp = ident_periods(x, PHASE_RAMP_S);
    if (phase_over_limit(x, in)) {
        phase_judge(s, in->i_phase, 1.0f, x->ref_xy[s->axis]);
        return phase_verdict(x, s, true);
    }
    switch (x->phase) {
    case PH_RAMP:
        x->ref_xy[s->axis] = x->i_test * ident_ramp(x->t, ramp);
        if (x->t >= ramp) {
            ident_goto(x, PH_SETTLE);
        }
        break;
    case PH_SETTLE:
        if (x->t >= ident_periods(x, PHASE_SETTLE_S)) {
            ident_goto(x, PH_MEASURE);
        }
        break;
    case PH_MEASURE:
        phase_measure(x, s, in);
        break;
    default: /* PH_DOWN */
        x->ref_xy[s->axis] = x->i_test * (1.0f - ident_ramp(x->t, ramp));
        if (x->t < ramp) {
            break;
        }
        x->ref_xy[s->axis] = 0.0f;
        if (s->axis == 1) {
            return phase_verdict(x, s, false);
        }
        s->axis = 1;
        ident_goto(x, PH_RAMP);
        break;
    }
    return IDENT_RUNNING;
}
