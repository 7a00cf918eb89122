/* Identification step 2, the encoder: see ident_encoder.h. */
#include "ident_encoder.h"

#include "ctl_q.h"
#include "ctl_qmath.h"

#define ENC_ALIGN_RAMP_S 0.3f
#define ENC_ALIGN_HOLD_S 0.2f
#define ENC_ALIGN_MOVE_S 0.2f   /* then a quarter turn on: a rotor that sat opposite the field */
#define ENC_ALIGN_SETTLE_S 0.3f /* at least */
#define ENC_ALIGN_SETTLE_MAX_S 1.0f /* at most */
#define ENC_STILL_S 0.1f            /* the rotor within ENC_STILL_COUNTS this long: still */
#define ENC_STILL_COUNTS 4
#define ENC_ALIGN_ANGLE (1.0f / 24.0f) /* 15 degrees: every phase carries a quarter or more */
#define ENC_SOFT_KI_RAD_S 10.0f        /* alignment: integral gain (R + kp) times this */
#define ENC_SPEED 1.0f                 /* electrical turns/s */
#define ENC_ACCEL 4.0f                 /* turns/s^2 */
#define ENC_MIN_MOTION 0.25f           /* of the nominal counts in the first turn, else NO_MOTION */
#define ENC_SETTLE_TURNS 0.5f          /* after the index / a reversal, before measuring */
#define ENC_MEASURE_QUARTERS 8         /* counts per electrical turn: two turns */
#define ENC_CPE_TOLERANCE 0.1f         /* of the nominal counts per electrical turn */
#define ENC_OFFSET_TURNS 2.0f          /* averaged each way */
#define ENC_STOP_HOLD_S 0.2f
#define ENC_DAMPING_RATIO 0.7f
#define ENC_POOR_SIGMA_TURNS 0.0028f /* 1 electrical degree */

#define ENC_CURRENT_RAMP_S 0.2f    /* test current to half and back, for the load check */
#define ENC_LOAD_LAG_TURNS 0.0056f /* 2 electrical degrees of lag that a load torque causes */
#define ENC_RATIO_SIGMAS 10.0f     /* friction's lag this far out of its scatter: r measured */
#define ENC_RATIO_MIN 0.5f         /* a measured ratio outside these: the set's */
#define ENC_RATIO_MAX 4.0f
#define ENC_RATIO_FLAT 0.02f /* |r - 1| below this: the check cannot see a load */
/* A dragged rotor (ident_encoder.h). Until the counts per electrical turn are measured: any
 * plant's rotor (Pn >= 1) follows the field from at most half a turn away, plus the
 * quarter-turn move, less than this many mechanical turns beyond the commanded travel (the
 * first turn's count is too rough for more: 11 % off at 10 % current). Then: beyond half an
 * electrical turn from where it was, the rotor has passed the field's unstable point. */
#define ENC_DRAG_MECH_TURNS 1.0f
#define ENC_SLIP_TURNS 0.5f

enum {
    EN_ALIGN,
    EN_ALIGN2,
    EN_SPIN,
    EN_FWD,
    EN_TURN,
    EN_BWD,
    EN_STOP,
    EN_HALF,
    EN_FWD2,
    EN_TURN2,
    EN_BWD2,
    EN_STOP2
};

void ident_encoder_begin(ident_ctx_t *x, ident_encoder_t *s)
{
    x->frame = IDENT_FRAME_COMMAND;
    x->damping = 0.0f;
    x->enc_known = false;
    x->offset_known = false;
    x->ref_dq[0] = x->ref_dq[1] = 0.0f;
    x->ref_xy[0] = x->ref_xy[1] = 0.0f;
    ident_traj_reset(&x->traj, ENC_ALIGN_ANGLE);
    /* while aligning, the rotor's swing is not yet damped through the encoder (its direction is
     * unknown): a proportional gain of R and a slow integrator make the regulator nearly a
     * voltage source, whose current the back-EMF changes: the swing damps electrically */
    ident_reg_gains_dq(&x->reg, x->m.r, 2.0f * x->m.r * ENC_SOFT_KI_RAD_S, x->m.ts);
    s->travel_index = -1.0f;
    s->measuring = false;
    s->have_ref = false;
    s->have_begin = false;
    s->have_slip_ref = false;
    ident_goto(x, EN_ALIGN);
}

/* Damping of the rotor's swing about the commanded angle: q current against the speed error,
 * for a damping ratio ENC_DAMPING_RATIO with the parameter set's inertia and flux. */
static float enc_damping_gain(const ident_ctx_t *x)
{
    const float pn = (float)x->m.pole_pairs;
    const float kt = 3.0f * pn * x->m.psi_f;
    const float wn2 = kt * x->i_test * pn / x->m.inertia;
    const float kd_rad = 2.0f * ENC_DAMPING_RATIO * ctl_sqrtf(wn2) * x->m.inertia / (pn * kt);
    return kd_rad * 6.2831853f; /* per electrical turn/s */
}

static float enc_nominal_cpe(const ident_ctx_t *x)
{
    return x->m.counts_per_turn / (float)x->m.pole_pairs;
}

/* After the first commanded turn: the direction and a first counts per electrical turn. */
static ident_status_t enc_first_turn(ident_ctx_t *x, ident_encoder_t *s, const ident_input_t *in)
{
    const float moved = (float)(in->position - s->p0);
    if (moved < ENC_MIN_MOTION * enc_nominal_cpe(x) * x->traj.travel &&
        moved > -ENC_MIN_MOTION * enc_nominal_cpe(x) * x->traj.travel) {
        ident_set_result(x, COMM_Q_COUNTS, moved / x->traj.travel, 0.0f, 0.0f, COMM_QUALITY_FAILED,
                         COMM_REASON_NO_MOTION);
        return ident_fail(x, COMM_REASON_NO_MOTION);
    }
    x->cpe = moved / x->traj.travel;
    x->enc_known = true;
    x->damping = enc_damping_gain(x);
    s->travel_known = x->traj.travel;
    return IDENT_RUNNING;
}

/* The measured counts per electrical turn against the configured pole pairs. */
static ident_status_t enc_judge_counts(ident_ctx_t *x, ident_encoder_t *s)
{
    const float cpe = ident_blocks_mean(&s->cpe);
    const float mag = (cpe < 0.0f) ? -cpe : cpe;
    const float implied = (mag > 0.0f) ? x->m.counts_per_turn / mag : 0.0f;
    const float nominal = enc_nominal_cpe(x);
    int16_t reason = COMM_REASON_NONE;
    if (cpe < 0.0f) {
        reason = COMM_REASON_REVERSED;
    } else if (mag > (1.0f + ENC_CPE_TOLERANCE) * nominal ||
               mag < (1.0f - ENC_CPE_TOLERANCE) * nominal) {
        reason = COMM_REASON_POLE_PAIRS;
    }
    ident_set_result(x, COMM_Q_COUNTS, cpe, ident_blocks_sigma(&s->cpe),
                     (float)(int32_t)(implied + 0.5f),
                     (reason == COMM_REASON_NONE) ? COMM_QUALITY_OK : COMM_QUALITY_FAILED, reason);
    if (reason != COMM_REASON_NONE) {
        return ident_fail(x, reason);
    }
    /* From here on the exact count the pole pairs just confirmed, not the measurement: a
     * heavy rotor's swing about the field left it 3.4 % off (within the pole-pair check) and
     * every later speed with it, psi_f and the inertia 3.6 % high (issue 25's grid). */
    x->cpe = nominal;
    s->travel_start = x->traj.travel;
    ident_blocks_init(&s->fwd, (int32_t)ident_periods(x, 0.25f / ENC_SPEED));
    ident_goto(x, EN_FWD);
    return IDENT_RUNNING;
}

/* Quarter turns of counts per electrical turn, once the index was seen and the rotor settled. */
static ident_status_t enc_measure_counts(ident_ctx_t *x, ident_encoder_t *s,
                                         const ident_input_t *in)
{
    const float travel = x->traj.travel;
    if (!s->measuring) {
        if (x->enc_known && s->travel_index >= 0.0f &&
            travel >= ((s->travel_index > s->travel_known) ? s->travel_index : s->travel_known) +
                          ENC_SETTLE_TURNS) {
            s->measuring = true;
            s->p_mark = in->position;
            s->travel_mark = travel;
            ident_blocks_init(&s->cpe, 1);
        }
        return IDENT_RUNNING;
    }
    if (travel >= s->travel_mark + 0.25f) {
        ident_blocks_add_block(&s->cpe,
                               (float)(in->position - s->p_mark) / (travel - s->travel_mark));
        s->p_mark = in->position;
        s->travel_mark = travel;
        if (s->cpe.blocks >= ENC_MEASURE_QUARTERS) {
            return enc_judge_counts(x, s);
        }
    }
    return IDENT_RUNNING;
}

static ident_status_t enc_spin(ident_ctx_t *x, ident_encoder_t *s, const ident_input_t *in)
{
    const int32_t counted = in->position - s->p0;
    if (!x->enc_known && x->traj.travel >= 1.0f && enc_first_turn(x, s, in) != IDENT_RUNNING) {
        return IDENT_FAILED;
    }
    if (s->travel_index < 0.0f && in->index_seen) {
        s->travel_index = x->traj.travel;
    }
    if (s->travel_index < 0.0f &&
        (x->traj.travel > 2.0f * (float)x->m.pole_pairs + 3.0f ||
         (float)((counted < 0) ? -counted : counted) > 1.25f * x->m.counts_per_turn)) {
        ident_set_result(x, COMM_Q_COUNTS, x->cpe, 0.0f, 0.0f, COMM_QUALITY_FAILED,
                         COMM_REASON_NO_INDEX);
        return ident_fail(x, COMM_REASON_NO_INDEX);
    }
    return enc_measure_counts(x, s, in);
}

/* The commanded angle minus the HAL's (half a count added), unwrapped about the first one. */
static float enc_offset_sample(ident_encoder_t *s, const ident_ctx_t *x, const ident_input_t *in)
{
    const float half_count = 0.5f / x->cpe;
    const float d = x->traj.angle - ident_turns_u32(in->elec_angle) - half_count;
    if (!s->have_ref) {
        s->ref = ident_wrap_half(d);
        s->have_ref = true;
    }
    return s->ref + ident_wrap_half(d - s->ref);
}

/* How much more a constant torque lags the rotor at half the test current than at the test
 * current, from the parameter set: the stiffness about the aligned position is
 * 3 Pn I (psi_f + (L_d - L_q) I), so the ratio is 2 (psi_f + (L_d - L_q) I) /
 * (psi_f + (L_d - L_q) I / 2), 1.87 on the reference machine. */
static float enc_set_ratio(const ident_ctx_t *x)
{
    const float dl = x->m.ld - x->m.lq;
    const float k1 = x->m.psi_f + dl * x->i_test;
    const float k2 = x->m.psi_f + dl * 0.5f * x->i_test;
    const float r = (k1 > 0.0f && k2 > 0.0f) ? 2.0f * k1 / k2 : 2.0f;
    return (r > 1.1f && r < 4.0f) ? r : 2.0f;
}

/* The load check's sweeps: forward and backward at the test current (mf, mb) and at half of it
 * (m2f, m2b), each offset + a + b or offset + a - b with b friction's lag and a a load's,
 * both times r at half the current. Friction's lag gives r itself, r = (m2f - m2b) / (mf - mb),
 * when it stands out of the scatter (else the set's ratio): a weak magnet's stiffness at the
 * test current is cut by the reluctance term until r is near 1 (1.03 for 0.3 x psi_f on two
 * pole pairs against the set's 1.80, which read friction's lag as a 4.7 degree load: issue 25's
 * grid). Then a = ((m2f + m2b) - (mf + mb)) / (2 (r - 1)). */
typedef struct {
    float mf, mb, m2f, m2b; /* turns */
    float sf, sb, s2f, s2b;
} enc_sweeps_t;

typedef struct {
    float r;         /* the ratio used */
    bool measured;   /* r from friction's lag, else the set's */
    float a, s_a;    /* the load's lag and its scatter, turns */
    float ratio_err; /* a's uncertainty from r's, turns */
} enc_load_t;

static float enc_abs(float v) { return (v < 0.0f) ? -v : v; }

static void enc_load_lag(const ident_ctx_t *x, const enc_sweeps_t *w, enc_load_t *l)
{
    const float d1 = w->mf - w->mb, d2 = w->m2f - w->m2b;
    const float s_d1 = ctl_sqrtf(w->sf * w->sf + w->sb * w->sb);
    const float s_d2 = ctl_sqrtf(w->s2f * w->s2f + w->s2b * w->s2b);
    const float rm = (d1 != 0.0f) ? d2 / d1 : 0.0f;
    const float sum = (w->m2f + w->m2b) - (w->mf + w->mb);
    const float s_sum = ctl_sqrtf(s_d1 * s_d1 + s_d2 * s_d2);
    float rm1;
    l->measured = enc_abs(d1) > ENC_RATIO_SIGMAS * s_d1 && rm > ENC_RATIO_MIN && rm < ENC_RATIO_MAX;
    l->r = l->measured ? rm : enc_set_ratio(x);
    rm1 = l->r - 1.0f;
    if (enc_abs(rm1) < ENC_RATIO_FLAT) { /* a load would lag both currents alike: unseen */
        l->a = 0.0f;
        l->s_a = 1.0f;
        l->ratio_err = 0.0f;
        return;
    }
    l->a = sum / (2.0f * rm1);
    l->s_a = s_sum / (2.0f * enc_abs(rm1));
    if (l->measured) { /* r's own scatter, through a = sum / (2 (r - 1)) */
        const float s_r =
            enc_abs(l->r) * ctl_sqrtf((s_d1 * s_d1) / (d1 * d1) +
                                      ((d2 != 0.0f) ? (s_d2 * s_d2) / (d2 * d2) : 0.0f));
        l->ratio_err = enc_abs(l->a) * s_r / enc_abs(rm1);
    } else { /* the set's L_d, L_q and psi_f, not yet measured: the reluctance term's whole effect
              */
        l->ratio_err = enc_abs(l->a) * enc_abs(2.0f - l->r) / enc_abs(rm1);
    }
}

/* The offset from the sweeps, into the result and the context. A load's lag that stands out of
 * its scatter (3 sigma) is taken out of the offset and above ENC_LOAD_LAG_TURNS fails the step
 * (the later steps would be dragged too); one that does not is left in. */
static ident_status_t enc_finish(ident_ctx_t *x, ident_encoder_t *s)
{
    const enc_sweeps_t w = {ident_blocks_mean(&s->fwd),   ident_blocks_mean(&s->bwd),
                            ident_blocks_mean(&s->fwd2),  ident_blocks_mean(&s->bwd2),
                            ident_blocks_sigma(&s->fwd),  ident_blocks_sigma(&s->bwd),
                            ident_blocks_sigma(&s->fwd2), ident_blocks_sigma(&s->bwd2)};
    enc_load_t l;
    bool significant, loaded;
    float sigma, absolute;
    enc_load_lag(x, &w, &l);
    significant = enc_abs(l.a) > 3.0f * l.s_a;
    loaded = significant && enc_abs(l.a) > ENC_LOAD_LAG_TURNS;
    if (significant) {
        sigma = ctl_sqrtf(l.s_a * l.s_a + l.ratio_err * l.ratio_err);
        x->offset_turns = 0.5f * (w.mf + w.mb) - l.a;
    } else { /* no load to be seen (one below 3 s_a may hide: docs/commissioning.md 2.2) */
        sigma = 0.5f * ctl_sqrtf(w.sf * w.sf + w.sb * w.sb);
        x->offset_turns = 0.5f * (w.mf + w.mb);
    }
    x->offset_known = true;
    x->offset_abs = x->m.hal_offset +
                    (uint32_t)(int32_t)(ident_wrap_half(x->offset_turns) * 2147483648.0f) * 2u;
    absolute = ident_turns_u32(x->m.hal_offset) + x->offset_turns;
    absolute -= (float)(int32_t)absolute;
    if (absolute < 0.0f) {
        absolute += 1.0f;
    }
    if (loaded) { /* the offset is off by the load's lag, and every later step with it */
        ident_set_result(x, COMM_Q_OFFSET, 360.0f * absolute, 360.0f * sigma, 360.0f * l.a,
                         COMM_QUALITY_FAILED, COMM_REASON_LOAD_TORQUE);
        return ident_fail(x, COMM_REASON_LOAD_TORQUE);
    }
    ident_set_result(x, COMM_Q_OFFSET, 360.0f * absolute, 360.0f * sigma,
                     360.0f * 0.5f * (w.mf - w.mb),
                     (sigma > ENC_POOR_SIGMA_TURNS) ? COMM_QUALITY_POOR : COMM_QUALITY_OK,
                     (sigma > ENC_POOR_SIGMA_TURNS) ? COMM_REASON_SCATTER : COMM_REASON_NONE);
    return IDENT_DONE;
}

/* Forward, reverse, backward, stop: the offset's sweeps. */
static ident_status_t enc_sweep(ident_ctx_t *x, ident_encoder_t *s, const ident_input_t *in)
{
    const float travel = x->traj.travel;
    switch (x->phase) {
    case EN_FWD:
        ident_blocks_add(&s->fwd, enc_offset_sample(s, x, in));
        if (travel >= s->travel_start + ENC_OFFSET_TURNS) {
            x->traj.target = -ENC_SPEED;
            ident_goto(x, EN_TURN);
        }
        break;
    case EN_TURN:
        if (x->traj.speed > -ENC_SPEED) {
            s->travel_start = travel;
        } else if (travel <= s->travel_start - ENC_SETTLE_TURNS) {
            s->travel_start = travel;
            ident_blocks_init(&s->bwd, s->fwd.length);
            ident_goto(x, EN_BWD);
        }
        break;
    case EN_BWD:
        ident_blocks_add(&s->bwd, enc_offset_sample(s, x, in));
        if (travel <= s->travel_start - ENC_OFFSET_TURNS) {
            x->traj.target = 0.0f;
            ident_goto(x, EN_STOP);
        }
        break;
    default: /* EN_STOP */
        if (x->traj.speed != 0.0f) {
            x->t = 0u;
        } else if (x->t >= ident_periods(x, ENC_STOP_HOLD_S)) {
            ident_goto(x, EN_HALF);
        }
        break;
    }
    return IDENT_RUNNING;
}

/* The load check: forward and backward again at half the current. A lag that does not change
 * sign with the direction (a load torque) grows at half the current by the stiffness ratio r, as
 * friction's does, which gives r (enc_load_lag). */
static ident_status_t enc_half(ident_ctx_t *x, ident_encoder_t *s, const ident_input_t *in)
{
    const uint32_t ramp = ident_periods(x, ENC_CURRENT_RAMP_S);
    switch (x->phase) {
    case EN_HALF:
        x->ref_dq[0] = x->i_test * (1.0f - 0.5f * ident_ramp(x->t, ramp));
        if (x->t == ramp) {
            x->traj.target = ENC_SPEED;
        }
        if (x->traj.speed < ENC_SPEED) {
            s->travel_start = x->traj.travel;
        } else if (x->traj.travel >= s->travel_start + ENC_SETTLE_TURNS) {
            s->travel_start = x->traj.travel;
            ident_blocks_init(&s->fwd2, s->fwd.length);
            ident_goto(x, EN_FWD2);
        }
        break;
    case EN_FWD2:
        ident_blocks_add(&s->fwd2, enc_offset_sample(s, x, in));
        if (x->traj.travel >= s->travel_start + ENC_OFFSET_TURNS) {
            x->traj.target = -ENC_SPEED;
            ident_goto(x, EN_TURN2);
        }
        break;
    case EN_TURN2:
        if (x->traj.speed > -ENC_SPEED) {
            s->travel_start = x->traj.travel;
        } else if (x->traj.travel <= s->travel_start - ENC_SETTLE_TURNS) {
            s->travel_start = x->traj.travel;
            ident_blocks_init(&s->bwd2, s->fwd.length);
            ident_goto(x, EN_BWD2);
        }
        break;
    case EN_BWD2:
        ident_blocks_add(&s->bwd2, enc_offset_sample(s, x, in));
        if (x->traj.travel <= s->travel_start - ENC_OFFSET_TURNS) {
            x->traj.target = 0.0f;
            ident_goto(x, EN_STOP2);
        }
        break;
    default: /* EN_STOP2: stop, the current back up */
        if (x->traj.speed != 0.0f) {
            x->t = 0u;
        }
        x->ref_dq[0] = x->i_test * (0.5f + 0.5f * ident_ramp(x->t, ramp));
        if (x->t >= ramp + ident_periods(x, ENC_STOP_HOLD_S)) {
            return enc_finish(x, s);
        }
        break;
    }
    return IDENT_RUNNING;
}

/* The current rises at angle 0 and holds; then the angle moves a quarter turn and holds: a
 * rotor that sat at the first angle's unstable point (the field opposite its d axis) is pulled
 * off it by the second. */
static void enc_align(ident_ctx_t *x, ident_encoder_t *s, const ident_input_t *in)
{
    const uint32_t ramp = ident_periods(x, ENC_ALIGN_RAMP_S);
    const uint32_t move = ident_periods(x, ENC_ALIGN_MOVE_S);
    if (x->phase == EN_ALIGN) {
        x->ref_dq[0] = x->i_test * ident_ramp(x->t, ramp);
        if (x->t >= ramp + ident_periods(x, ENC_ALIGN_HOLD_S)) {
            ident_goto(x, EN_ALIGN2);
        }
        return;
    }
    ident_traj_reset(&x->traj, ENC_ALIGN_ANGLE + 0.25f * ident_ramp(x->t, move));
    if (x->t == 0u) {
        ident_still_reset(&s->still, in->position);
    }
    /* until the swing has died away: at a tenth of rated current a weak magnet's rotor still
     * swung through whole turns after 0.3 s, and the spin then read its swing as a reversed
     * encoder (issue 25). At most ENC_ALIGN_SETTLE_MAX_S: the spin's damping takes over. */
    if (x->t >= move + ident_periods(x, ENC_ALIGN_SETTLE_S) &&
        (ident_still_step(&s->still, in->position, ENC_STILL_COUNTS) >=
             ident_periods(x, ENC_STILL_S) ||
         x->t >= move + ident_periods(x, ENC_ALIGN_SETTLE_MAX_S))) {
        ident_reg_gains_nominal(&x->reg);
        s->p0 = in->position;
        x->traj.target = ENC_SPEED;
        x->traj.accel = ENC_ACCEL;
        ident_goto(x, EN_SPIN);
    }
}

/* A load the field cannot hold drags the rotor through its poles (ident_encoder.h): the slip
 * in electrical turns beyond what the field can have pulled, > 0 when dragged. */
static float enc_slip(const ident_ctx_t *x, const ident_encoder_t *s, const ident_input_t *in)
{
    float slip;
    if (!s->have_slip_ref) { /* counts per electrical turn not yet measured */
        const int32_t moved = in->position - s->p_begin;
        const float travel = (x->traj.travel < 0.0f) ? -x->traj.travel : x->traj.travel;
        slip = (float)((moved < 0) ? -moved : moved) / x->m.counts_per_turn - travel -
               ENC_DRAG_MECH_TURNS;
        return slip * (float)x->m.pole_pairs;
    }
    slip = x->traj.travel - s->travel_slip - (float)(in->position - s->p_slip) / x->cpe;
    return ((slip < 0.0f) ? -slip : slip) - ENC_SLIP_TURNS;
}

/* The first period of the step and the first with the counts measured: the references. */
static void enc_slip_refs(const ident_ctx_t *x, ident_encoder_t *s, const ident_input_t *in)
{
    if (!s->have_begin) {
        s->p_begin = in->position;
        s->have_begin = true;
    }
    if (!s->have_slip_ref && x->phase >= EN_FWD) {
        s->p_slip = in->position;
        s->travel_slip = x->traj.travel;
        s->have_slip_ref = true;
    }
}

static ident_status_t enc_dragged(ident_ctx_t *x, const ident_encoder_t *s, const ident_input_t *in)
{
    const float limit =
        s->have_slip_ref ? ENC_SLIP_TURNS : ENC_DRAG_MECH_TURNS * (float)x->m.pole_pairs;
    ident_set_result(x, COMM_Q_OFFSET, 0.0f, 0.0f, 360.0f * (enc_slip(x, s, in) + limit),
                     COMM_QUALITY_FAILED, COMM_REASON_LOAD_TORQUE);
    return ident_fail(x, COMM_REASON_LOAD_TORQUE);
}

ident_status_t ident_encoder_step(ident_ctx_t *x, ident_encoder_t *s, const ident_input_t *in)
{
    enc_slip_refs(x, s, in);
    if (enc_slip(x, s, in) > 0.0f) {
        return enc_dragged(x, s, in);
    }
    if (x->phase == EN_ALIGN || x->phase == EN_ALIGN2) {
        enc_align(x, s, in);
        return IDENT_RUNNING;
    }
    ident_traj_step(&x->traj, x->m.ts);
    if (x->phase == EN_SPIN) {
        return enc_spin(x, s, in);
    }
    return (x->phase >= EN_HALF) ? enc_half(x, s, in) : enc_sweep(x, s, in);
}
