/* Identification steps 4 and 5, the inductances: see ident_inductance.h. */
#include "ident_inductance.h"

#define IND_SETTLE_S 0.1f     /* at least */
#define IND_SETTLE_MAX_S 2.0f /* at most: a rotor still swinging is then measured anyway */
#define IND_STILL_S 0.05f     /* the rotor within IND_STILL_COUNTS this long: still */
#define IND_STILL_COUNTS 2
#define IND_HALF_PERIODS 10u    /* control periods per half square wave (500 Hz at 10 kHz) */
#define IND_BLOCK_WAVES 10u     /* square waves per estimate */
#define IND_WAVES 200           /* square waves per axis */
#define IND_RIPPLE_D 0.5f       /* peak-to-peak ripple over the bias, d axis */
#define IND_RIPPLE_OTHER 0.25f  /* q, x, y */
#define IND_POOR_RELATIVE 0.02f /* 1-sigma above 2 %: POOR */
#define IND_MOTION_BIAS 0.01f   /* what the rotor's motion can have biased, relative: POOR */
#define IND_TWO_PI 6.2831853f
#define IND_ATANH_TERMS 24 /* terms of the series of atanh(y) / y */
#define IND_SIZE_MIN 0.2f  /* the measured amplitude: within these of the set's */
#define IND_SIZE_MAX 5.0f
#define IND_DROOP_Y_MAX 0.9f /* R N T / (2 L_raw) beyond this: taken as this */

/* 1 / (2k + 1), k = 0..IND_ATANH_TERMS - 1: the series atanh(y) / y = sum y^2k / (2k + 1). */
static const float ind_odd_inverse[IND_ATANH_TERMS] = {
    1.0f,         1.0f / 3.0f,  1.0f / 5.0f,  1.0f / 7.0f,  1.0f / 9.0f,  1.0f / 11.0f,
    1.0f / 13.0f, 1.0f / 15.0f, 1.0f / 17.0f, 1.0f / 19.0f, 1.0f / 21.0f, 1.0f / 23.0f,
    1.0f / 25.0f, 1.0f / 27.0f, 1.0f / 29.0f, 1.0f / 31.0f, 1.0f / 33.0f, 1.0f / 35.0f,
    1.0f / 37.0f, 1.0f / 39.0f, 1.0f / 41.0f, 1.0f / 43.0f, 1.0f / 45.0f, 1.0f / 47.0f};

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

/* The square wave's amplitude for the ripple of the axis with inductance l. */
static float ind_amplitude(const ident_ctx_t *x, const ident_inductance_t *s, float l)
{
    const float ripple = (s->axis == IDENT_AXIS_D) ? IND_RIPPLE_D : IND_RIPPLE_OTHER;
    return ripple * x->i_test * l / ((float)IND_HALF_PERIODS * x->m.ts);
}

static void ind_start_axis(ident_ctx_t *x, ident_inductance_t *s, const ident_input_t *in)
{
    const ident_blocks_t *xy = ind_store(s, IDENT_AXIS_X);
    /* y is sized from x's estimate; every other axis first probes with the set's inductance */
    s->sized = s->axis == IDENT_AXIS_Y && xy->blocks >= 2;
    s->amplitude =
        ind_amplitude(x, s, s->sized ? ident_blocks_mean(xy) : ind_inductance(x, s->axis));
    s->resize = 0.0f;
    s->skip = 0;
    s->sign[0] = s->sign[1] = 0;
    s->sum_pos = s->sum_neg = 0.0f;
    s->n_pos = s->n_neg = 0;
    s->waves = 0;
    s->last_i = ind_current(x, s->axis);
    s->p_last = in->position;
    if (s->axis != IDENT_AXIS_Y) { /* y adds to x's blocks and motion */
        ident_blocks_init(ind_store(s, s->axis), 1);
        s->p_start = in->position;
        s->moved = 0;
        s->misalign = 0.0f;
        s->sync_counts[0] = s->sync_counts[1] = 0;
        s->sync_n[0] = s->sync_n[1] = 0;
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
    /* the droop's resistance: the resistance step's when it is ok, else the set's */
    s->r = ident_known(x, COMM_Q_R, x->m.r);
    x->frame = IDENT_FRAME_COMMAND;
    x->traj.target = 0.0f;
    ident_goto(x, IN_SETTLE);
}

/* The resistive droop taken out of a block's raw estimate l_raw = 2 U T / (mean change in +
 * periods - mean change in - periods) (docs/commissioning.md section 2.4): over a half period of
 * N periods the current relaxes towards its end value with the time constant L / R, so the
 * ripple's periodic steady state gives l_raw = L x / tanh x with x = R N T / (2 L); with
 * c = R N T / 2 that is tanh x = c / l_raw, so L = c / atanh(c / l_raw) = l_raw / (atanh(y) / y),
 * y = c / l_raw. R: the resistance step's (s->r). A fixed number of series terms: bounded. */
static float ind_droop(const ident_ctx_t *x, const ident_inductance_t *s, float l_raw)
{
    float y = 0.5f * s->r * (float)IND_HALF_PERIODS * x->m.ts / l_raw;
    float z, sum = 0.0f;
    int16_t k;
    if (!(y > 0.0f)) {
        return l_raw;
    }
    y = (y > IND_DROOP_Y_MAX) ? IND_DROOP_Y_MAX : y;
    z = y * y;
    for (k = IND_ATANH_TERMS - 1; k >= 0; k--) {
        sum = sum * z + ind_odd_inverse[k];
    }
    return l_raw / sum;
}

/* A block's estimate: filed, or while probing, the amplitude the axis' measured inductance
 * asks for (the probe's block dropped; ind_resize applies it). */
static void ind_add_block(ident_ctx_t *x, ident_inductance_t *s, float l)
{
    float a;
    if (s->sized) {
        ident_blocks_add_block(ind_store(s, s->axis), l);
        return;
    }
    a = ind_amplitude(x, s, l);
    a = (a < IND_SIZE_MIN * s->amplitude) ? IND_SIZE_MIN * s->amplitude : a;
    s->resize = (a > IND_SIZE_MAX * s->amplitude) ? IND_SIZE_MAX * s->amplitude : a;
    s->sized = true;
}

/* The amplitude the probe asked for, applied in the middle of a + half period, where the
 * centred ripple crosses its mean: the ripple stays centred. The blocks start again from there
 * (the next change still the old amplitude's), and the axis' square waves are counted anew. */
static void ind_resize(ident_inductance_t *s, uint32_t t)
{
    if (!(s->resize > 0.0f) || t % (2u * IND_HALF_PERIODS) != 0u) {
        return;
    }
    s->amplitude = s->resize;
    s->resize = 0.0f;
    s->sum_pos = s->sum_neg = 0.0f;
    s->n_pos = s->n_neg = 0;
    s->skip = 1;
    s->waves = 0;
}

/* One period's change of the axis current, filed by the sign that caused it: the command of
 * two periods ago acted over the last period. */
static void ind_accumulate(ident_ctx_t *x, ident_inductance_t *s)
{
    const float i = ind_current(x, s->axis);
    const float di = i - s->last_i;
    s->last_i = i;
    if (s->skip > 0) { /* a change the amplitude before a resize caused */
        s->skip--;
        return;
    }
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
            ind_add_block(x, s, ind_droop(x, s, 2.0f * s->amplitude * x->m.ts / slope));
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

/* The rotor's motion during the axis: its largest distance from the start (reported), its
 * largest misalignment from the commanded angle (once the offset is known), and its counts
 * moved under the + and under the - half periods (the voltage of two periods ago acted over the
 * last one, as for the current's change). */
static void ind_track_motion(ident_ctx_t *x, ident_inductance_t *s, const ident_input_t *in)
{
    const int32_t d = in->position - s->p_start;
    const int32_t a = (d < 0) ? -d : d;
    const int32_t step = in->position - s->p_last;
    s->moved = (a > s->moved) ? a : s->moved;
    s->p_last = in->position;
    if (x->offset_known) {
        const float e = ident_wrap_half(ident_rotor_angle(x, in) - x->traj.angle);
        const float m = (e < 0.0f) ? -e : e;
        s->misalign = (m > s->misalign) ? m : s->misalign;
    }
    if (s->sign[1] > 0) {
        s->sync_counts[0] += step;
        s->sync_n[0]++;
    } else if (s->sign[1] < 0) {
        s->sync_counts[1] += step;
        s->sync_n[1]++;
    }
}

/* What the rotor's motion can have done to an inductance l of the axis, relative: the larger of
 * (1) the misalignment's mixing of the other axis in, (L_q - L_d) sin^2 e / l (d and q only;
 * without a known offset, e is the motion from the start), and (2) the back-EMF of a motion in
 * step with the square wave, psi_f (w+ - w-) / (2 U) with the set's psi_f (on d, psi_f sin e:
 * the magnet's EMF lies along q; on x and y, psi_f bounds the harmonics'). A slow swing (a
 * heavy rotor still settling, issue 25's grid) does neither: it drifts the same under + and -
 * and stays well aligned, so the result is kept; a load that turns the rotor does both. */
static float ind_motion_bias(const ident_ctx_t *x, const ident_inductance_t *s, float l)
{
    const float cpe = (x->cpe > 0.0f) ? x->cpe : -x->cpe;
    const float e = (x->offset_known || cpe <= 0.0f) ? s->misalign : (float)s->moved / cpe;
    float sn, cs, align = 0.0f, sync = 0.0f, k_emf = x->m.psi_f;
    ident_sincos(e, &sn, &cs);
    sn = (sn < 0.0f) ? -sn : sn;
    if (s->axis < IDENT_AXIS_X) {
        const float ld = ident_known(x, COMM_Q_LD, x->m.ld),
                    lq = ident_known(x, COMM_Q_LQ, x->m.lq);
        align = ((lq > ld) ? lq - ld : ld - lq) * sn * sn / l;
    }
    if (s->axis == IDENT_AXIS_D) {
        k_emf *= sn; /* the magnet's EMF lies along q: on d only by the misalignment */
    }
    if (cpe > 0.0f && s->sync_n[0] > 0 && s->sync_n[1] > 0 && s->amplitude > 0.0f) {
        const float dc = (float)s->sync_counts[0] / (float)s->sync_n[0] -
                         (float)s->sync_counts[1] / (float)s->sync_n[1];
        const float dw = IND_TWO_PI * dc / (cpe * x->m.ts); /* electrical rad/s */
        sync = k_emf * ((dw < 0.0f) ? -dw : dw) / (2.0f * s->amplitude);
    }
    return (align > sync) ? align : sync;
}

static void ind_result(ident_ctx_t *x, const ident_inductance_t *s, comm_quantity_t q,
                       const ident_blocks_t *b)
{
    const float l = ident_blocks_mean(b);
    const float sigma = ident_blocks_sigma(b);
    int16_t quality = COMM_QUALITY_OK;
    int16_t reason = COMM_REASON_NONE;
    if (b->blocks < 2 || !(l > 1.0e-6f && l < 10.0f)) {
        quality = COMM_QUALITY_FAILED;
        reason = COMM_REASON_OUT_OF_RANGE;
    } else if (ind_motion_bias(x, s, l) > IND_MOTION_BIAS) {
        quality = COMM_QUALITY_POOR;
        reason = COMM_REASON_ROTOR_MOVED;
    } else if (sigma > IND_POOR_RELATIVE * l) {
        quality = COMM_QUALITY_POOR;
        reason = COMM_REASON_SCATTER;
    }
    ident_set_result(x, q, l, sigma, (float)s->moved, quality, reason);
}

/* The axis is done: back to regulation, the next axis or the results. */
static ident_status_t ind_end_axis(ident_ctx_t *x, ident_inductance_t *s)
{
    ind_inject(x, s->axis, 0.0f);
    x->reg.hold = 0u;
    if (s->axis == IDENT_AXIS_D) {
        ind_result(x, s, COMM_Q_LD, ind_store(s, s->axis));
    } else if (s->axis == IDENT_AXIS_Q) {
        ind_result(x, s, COMM_Q_LQ, ind_store(s, s->axis));
    } else if (s->axis == IDENT_AXIS_Y) {
        ind_result(x, s, COMM_Q_LXY, ind_store(s, s->axis));
    }
    if (s->axis >= s->last_axis) {
        return IDENT_DONE;
    }
    s->axis++;
    ident_goto(x, IN_SETTLE);
    return IDENT_RUNNING;
}

/* Settling before an axis: at least IND_SETTLE_S, and until the rotor has stayed within
 * IND_STILL_COUNTS for IND_STILL_S (at most IND_SETTLE_MAX_S): the swing a step change of the
 * current leaves dies away with the damping the encoder step sized from the set's inertia, ten
 * times slower on a rotor ten times heavier (issue 25's grid: rotor_moved). The axis' bias
 * voltage is averaged over the settling's second half while the rotor is still. */
static bool ind_settled(ident_ctx_t *x, ident_inductance_t *s, const ident_input_t *in)
{
    const uint32_t n = ident_periods(x, IND_SETTLE_S);
    if (x->t == 0u) {
        ident_still_reset(&s->still, in->position);
    } else {
        (void)ident_still_step(&s->still, in->position, IND_STILL_COUNTS);
    }
    if (x->t <= n / 2u || s->still.n == 0u) {
        s->u_sum = 0.0f;
        s->u_n = 0;
    } else {
        s->u_sum += ind_output(x, s->axis);
        s->u_n++;
    }
    if (x->t >= ident_periods(x, IND_SETTLE_MAX_S) && s->u_n == 0) {
        s->u_sum = ind_output(x, s->axis); /* swinging throughout: this period's output */
        s->u_n = 1;
    }
    return (x->t >= n && s->still.n >= ident_periods(x, IND_STILL_S)) ||
           x->t >= ident_periods(x, IND_SETTLE_MAX_S);
}

ident_status_t ident_inductance_step(ident_ctx_t *x, ident_inductance_t *s, const ident_input_t *in)
{
    if (x->phase == IN_SETTLE) {
        if (ind_settled(x, s, in)) {
            ind_start_axis(x, s, in);
        }
        return IDENT_RUNNING;
    }
    ind_track_motion(x, s, in);
    ind_accumulate(x, s);
    s->sign[1] = s->sign[0];
    if (s->waves >= IND_WAVES) {
        s->sign[0] = 0;
        ind_inject(x, s->axis, 0.0f);
        return (s->sign[1] == 0) ? ind_end_axis(x, s) : IDENT_RUNNING;
    }
    ind_resize(s, x->t - 1u);
    s->sign[0] = ind_next_sign(s, x->t - 1u);
    if (s->waves >= IND_WAVES) {
        s->sign[0] = 0;
    }
    ind_inject(x, s->axis, (float)s->sign[0] * s->amplitude);
    return IDENT_RUNNING;
}
