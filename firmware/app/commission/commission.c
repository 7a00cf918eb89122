/* The commissioning sequence, see commission.h. */
#include "commission.h"

#include "ctl_barrier.h"
#include "ident_excite.h"

#define COMM_BANDWIDTH_RAD_S 942.0f /* current regulator, 150 Hz */
#define COMM_LIMIT_DQ 0.35f         /* |u_dq| limit, of the DC link */
#define COMM_LIMIT_XY 0.10f         /* |u_x|, |u_y| limit */
/* Every step's time bound: this times its nominal duration, plus COMM_TIMEOUT_MARGIN_S. */
#define COMM_TIMEOUT_FACTOR 3.0f
#define COMM_TIMEOUT_MARGIN_S 2.0f
/* The open-phase watch: its window, and the mean share of the current (of the test current) that
 * makes a phase judged. */
#define COMM_WATCH_SECONDS 0.02f
#define COMM_WATCH_MIN_SHARE 0.1f

static const float step_seconds[COMM_STEP_COUNT] = {
    IDENT_PHASE_SECONDS,      IDENT_ENCODER_SECONDS,    IDENT_RESISTANCE_SECONDS,
    IDENT_INDUCTANCE_SECONDS, IDENT_INDUCTANCE_SECONDS, IDENT_FLUX_SECONDS,
    IDENT_MECH_SECONDS};

/* Each quantity's step, from the quantity list (commission_lists.h). */
#define COMM_QUANTITY_STEP(id, number, name, step, ...) COMM_STEP_##step,
static const int16_t quantity_step[COMM_Q_COUNT] = {COMM_QUANTITY_LIST(COMM_QUANTITY_STEP)};
#undef COMM_QUANTITY_STEP

float comm_time_bound_s(uint16_t mask)
{
    float total = 0.0f;
    int16_t k;
    for (k = 0; k < (int16_t)COMM_STEP_END; k++) {
        if ((mask & (1u << k)) != 0u) {
            total += COMM_TIMEOUT_FACTOR * step_seconds[k] + COMM_TIMEOUT_MARGIN_S;
        }
    }
    return total;
}

uint16_t comm_step_quantities(int16_t step)
{
    uint16_t mask = 0u;
    int16_t q;
    for (q = 0; q < COMM_Q_COUNT; q++) {
        mask = (uint16_t)(mask | ((quantity_step[q] == step) ? (1u << q) : 0u));
    }
    return mask;
}

void comm_init(comm_t *c)
{
    int16_t q;
    c->start_requested = 0;
    c->req_mask = 0u;
    c->req_permille = 0u;
    c->state = COMM_STATE_IDLE;
    c->step = COMM_STEP_PHASES;
    c->reason = COMM_REASON_NONE;
    c->mask = 0u;
    c->permille = 0u;
    c->periods = 0u;
    c->step_start = 0u;
    c->done_seconds = 0.0f;
    c->total_seconds = 0.0f;
    for (q = 0; q < COMM_Q_COUNT; q++) {
        ident_set_result(&c->x, (comm_quantity_t)q, 0.0f, 0.0f, 0.0f, COMM_QUALITY_NOT_RUN,
                         COMM_REASON_NONE);
    }
}

bool comm_mask_valid(uint16_t mask) { return COMM_STEPS_VALID((uint16_t)mask); }

bool comm_current_valid(uint16_t permille)
{
    return permille >= COMM_CURRENT_MIN_PERMILLE && permille <= COMM_CURRENT_MAX_PERMILLE;
}

void comm_request(comm_t *c, uint16_t mask, uint16_t permille)
{
    c->req_mask = mask;
    c->req_permille = permille;
    CTL_COMPILER_BARRIER(); /* the request is complete before it is flagged */
    c->start_requested = 1;
}

static float comm_abs(float v) { return (v < 0.0f) ? -v : v; }

static void comm_watch_restart(comm_watch_t *w)
{
    int16_t k;
    for (k = 0; k < IDENT_PHASES; k++) {
        w->meas[k] = 0.0f;
        w->ref[k] = 0.0f;
    }
    w->n = 0u;
}

/* Every step watches for an open phase. A step commands its current in one plane, alpha-beta (a
 * d-axis alignment, a spin, the resistance and d-q inductance steps) or x-y (the phase check, the
 * x-y inductance): each phase then carries its share of the measured current in that plane, and
 * an open phase none, the rest going into the other plane. Over a window, a phase whose share
 * averaged above a tenth of the test current and that carried less than the protection's
 * open-phase ratio of it is open. The measured current, not the reference: while aligning, the
 * soft regulator lets the current lag its reference by far. True when a phase is open. */
static bool comm_watch_open_phase(comm_t *c, const ident_input_t *in)
{
    comm_watch_t *w = &c->watch;
    const ident_ctx_t *x = &c->x;
    const bool ab = x->ref_dq[0] * x->ref_dq[0] + x->ref_dq[1] * x->ref_dq[1] >=
                    x->ref_xy[0] * x->ref_xy[0] + x->ref_xy[1] * x->ref_xy[1];
    float r[4];
    bool open = false;
    int16_t k;
    r[0] = ab ? x->i_ab[0] : 0.0f;
    r[1] = ab ? x->i_ab[1] : 0.0f;
    r[2] = ab ? 0.0f : x->i_xy[0];
    r[3] = ab ? 0.0f : x->i_xy[1];
    for (k = 0; k < IDENT_PHASES; k++) {
        w->meas[k] += comm_abs(in->i_phase[k]);
        w->ref[k] += comm_abs(ident_vsd_phase(r, k));
    }
    w->n++;
    if (w->n < ident_periods(x, COMM_WATCH_SECONDS)) {
        return false;
    }
    for (k = 0; k < IDENT_PHASES; k++) {
        open = open || (w->ref[k] > COMM_WATCH_MIN_SHARE * x->i_test * (float)w->n &&
                        w->meas[k] < x->m.open_ratio * w->ref[k]);
    }
    comm_watch_restart(w);
    return open;
}

/* The step's own start. */
static void comm_begin_step(comm_t *c)
{
    ident_ctx_t *x = &c->x;
    x->reason = COMM_REASON_NONE;
    comm_watch_restart(&c->watch);
    c->step_start = c->periods;
    ident_xy_harmonics_reset(&x->xy_harm);
    switch (c->step) {
    case COMM_STEP_PHASES:
        ident_phase_begin(x, &c->s.phase);
        break;
    case COMM_STEP_ENCODER:
        ident_encoder_begin(x, &c->s.encoder);
        break;
    case COMM_STEP_RESISTANCE:
        ident_resistance_begin(x, &c->s.resistance);
        break;
    case COMM_STEP_INDUCTANCE:
        ident_inductance_begin(x, &c->s.inductance, IDENT_AXIS_D, IDENT_AXIS_Q);
        break;
    case COMM_STEP_LXY:
        ident_inductance_begin(x, &c->s.inductance, IDENT_AXIS_X, IDENT_AXIS_Y);
        break;
    case COMM_STEP_FLUX:
        ident_flux_begin(x, &c->s.flux);
        ident_xy_harmonics_start(&x->xy_harm);
        break;
    default:
        ident_mech_begin(x, &c->s.mech);
        ident_xy_harmonics_start(&x->xy_harm);
        break;
    }
}

static ident_status_t comm_run_step(comm_t *c, const ident_input_t *in)
{
    ident_ctx_t *x = &c->x;
    switch (c->step) {
    case COMM_STEP_PHASES:
        return ident_phase_step(x, &c->s.phase, in);
    case COMM_STEP_ENCODER:
        return ident_encoder_step(x, &c->s.encoder, in);
    case COMM_STEP_RESISTANCE:
        return ident_resistance_step(x, &c->s.resistance, in);
    case COMM_STEP_INDUCTANCE:
    case COMM_STEP_LXY:
        return ident_inductance_step(x, &c->s.inductance, in);
    case COMM_STEP_FLUX:
        return ident_flux_step(x, &c->s.flux, in);
    default:
        return ident_mech_step(x, &c->s.mech, in);
    }
}

/* The first selected step from `from` on; COMM_STEP_END when none. */
static int16_t comm_next_step(const comm_t *c, int16_t from)
{
    int16_t k;
    for (k = from; k < (int16_t)COMM_STEP_END; k++) {
        if ((c->mask & (1u << k)) != 0u) {
            return k;
        }
    }
    return (int16_t)COMM_STEP_END;
}

void comm_start(comm_t *c, const ident_machine_t *m, uint16_t mask, uint16_t permille)
{
    ident_ctx_t *x = &c->x;
    float i_test = (float)permille * 0.001f * m->rated_a;
    int16_t k;
    comm_init(c);
    c->state = COMM_STATE_RUNNING;
    c->mask = mask;
    c->permille = permille;
    for (k = 0; k < (int16_t)COMM_STEP_END; k++) {
        if ((mask & (1u << k)) != 0u) {
            c->total_seconds += step_seconds[k];
        }
    }
    x->m = *m;
    if (i_test > COMM_TRIP_FRACTION * m->trip_a) {
        i_test = COMM_TRIP_FRACTION * m->trip_a;
    }
    x->i_test = i_test;
    ident_reg_init(&x->reg, 0.5f * (m->ld + m->lq), m->lxy, COMM_BANDWIDTH_RAD_S, m->ts,
                   COMM_LIMIT_DQ * m->vdc, COMM_LIMIT_XY * m->vdc);
    ident_traj_reset(&x->traj, 0.0f);
    x->frame = IDENT_FRAME_COMMAND;
    x->damping = 0.0f;
    x->enc_known = false;
    x->offset_known = false;
    x->cpe = 0.0f;
    x->offset_turns = 0.0f;
    x->comp_dq[0] = x->comp_dq[1] = 0.0f;
    x->comp_xy[0] = x->comp_xy[1] = 0.0f;
    c->step = comm_next_step(c, 0);
    comm_begin_step(c);
}

/* The sequence ends: state, reason; the selected quantities never reached are SKIPPED. */
static void comm_end(comm_t *c, int16_t state, int16_t reason)
{
    int16_t k, q;
    c->state = state;
    c->reason = reason;
    if (state == COMM_STATE_DONE) {
        return;
    }
    for (k = c->step; k < (int16_t)COMM_STEP_END; k++) {
        const uint16_t quantities = ((c->mask & (1u << k)) != 0u) ? comm_step_quantities(k) : 0u;
        for (q = 0; q < COMM_Q_COUNT; q++) {
            ident_result_t *r = &c->x.result[q];
            if ((quantities & (1u << q)) == 0u || r->quality != COMM_QUALITY_NOT_RUN) {
                continue;
            }
            if (k == c->step && reason == COMM_REASON_TIMEOUT) {
                r->quality = COMM_QUALITY_FAILED; /* the step ran out of time on it */
                r->reason = COMM_REASON_TIMEOUT;
            } else {
                r->reason = COMM_REASON_SKIPPED;
            }
        }
    }
}

void comm_abort(comm_t *c, int16_t reason)
{
    if (c->state == COMM_STATE_RUNNING) {
        comm_end(c, COMM_STATE_ABORTED, reason);
    }
}

/* After a step: the next one, or the end. False when the sequence ended. */
static bool comm_advance(comm_t *c, ident_status_t status)
{
    if (status == IDENT_FAILED) {
        comm_end(c, COMM_STATE_FAILED, c->x.reason);
        return false;
    }
    c->done_seconds += step_seconds[c->step];
    c->step = comm_next_step(c, (int16_t)(c->step + 1));
    if (c->step == (int16_t)COMM_STEP_END) {
        c->step = (int16_t)(COMM_STEP_END - 1);
        comm_end(c, COMM_STATE_DONE, COMM_REASON_NONE);
        return false;
    }
    comm_begin_step(c);
    return true;
}

bool comm_period(comm_t *c, const ident_input_t *in, float u[4])
{
    ident_status_t status;
    int16_t k;
    if (c->state != COMM_STATE_RUNNING) {
        return false;
    }
    c->periods++;
    ident_measure(&c->x, in);
    status = comm_watch_open_phase(c, in) ? ident_fail(&c->x, COMM_REASON_OPEN_PHASE)
                                          : comm_run_step(c, in);
    if (status == IDENT_RUNNING &&
        (float)(c->periods - c->step_start) * c->x.m.ts >
            COMM_TIMEOUT_FACTOR * step_seconds[c->step] + COMM_TIMEOUT_MARGIN_S) {
        status = ident_fail(&c->x, COMM_REASON_TIMEOUT);
    }
    if (status != IDENT_RUNNING && !comm_advance(c, status)) {
        return false;
    }
    ident_regulate(&c->x, in->vdc);
    for (k = 0; k < 4; k++) {
        u[k] = c->x.reg.u[k];
    }
    return true;
}

uint16_t comm_progress_percent(const comm_t *c)
{
    float done = c->done_seconds;
    if (c->state != COMM_STATE_RUNNING) {
        return (c->state == COMM_STATE_DONE) ? 100u : 0u;
    }
    if (c->total_seconds <= 0.0f) {
        return 0u;
    }
    {
        const float running = (float)(c->periods - c->step_start) * c->x.m.ts;
        const float cap = step_seconds[c->step];
        done += (running < cap) ? running : cap;
    }
    return (uint16_t)(100.0f * done / c->total_seconds);
}
