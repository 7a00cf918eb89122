/* Inverter over one carrier period, see inverter.h. */
#include "inverter.h"

#include <math.h>

#define INV_H3 0.86602540378443864676 /* sqrt(3)/2, as plant.c has it */

/* Transition instants per period: the start, the rising and the falling edges of six legs. */
#define INV_MAX_EDGES (1 + 2 * PLANT_PHASES)
/* Instants the voltage may change at: the edges, their dead-interval ends, the ends carried
 * over from the last period and the period end. */
#define INV_MAX_BREAKS (2 * INV_MAX_EDGES + PLANT_PHASES + 1)

#define INV_LEG_BIT(k) (1u << (5 - (k))) /* S_A = bit 5 */

void inverter_init(inverter_t *inv, const plant_params_t *p, double ts)
{
    unsigned st;
    int k;
    inv->ts = ts;
    inv->td = p->dead_time_on ? p->dead_time_s : 0.0;
    for (k = 0; k < PLANT_PHASES; k++) {
        inv->dead_until[k] = -1.0;
    }
    inv->nominal_bits = 0u;
    inv->dead_last = -1.0;
    inv->eff = 0u;
    inv->off = true;
    inv->counting = false;
    inv->transitions = 0u;
    inv->intervals = 0;
    for (st = 0u; st < 64u; st++) {
        plant_vector_voltage(st, 1.0, inv->u_table[st]);
    }
    inv->u_vdc_of = -1.0; /* no DC link voltage is negative: inv_voltages builds u_vdc */
    plant_stepper_init(&inv->stepper);
}

/* The legs commanded at one instant: legs with equal duties switch together, so one edge per
 * distinct instant. A leg whose pulse is too short to separate its edges in floating point is
 * in both masks: set first, then cleared, as the rising edge comes before the falling one. */
typedef struct {
    double t;
    unsigned set, clear; /* legs commanded to 1, to 0 (S_A = bit 5) */
} inv_edge_t;

/* The period's edges in time order, and the sorted instants at which the voltage may change
 * (edges, ends of dead intervals, the period end). */
typedef struct {
    inv_edge_t edge[INV_MAX_EDGES];
    double br[INV_MAX_BREAKS];
    int n_edges, n_br;
} inv_schedule_t;

/* Where the plant is sampled for the caller within the period. */
typedef struct {
    const double *t;
    int n;
    inverter_sample_fn cb;
    void *ctx;
} inv_samples_t;

static unsigned popcount6(unsigned v)
{
    unsigned c = 0u;
    v &= 63u;
    while (v != 0u) {
        c += v & 1u;
        v >>= 1;
    }
    return c;
}

static void inv_coast(const plant_params_t *p, plant_state_t *s, double t_load, bool lock_mech,
                      double h)
{
    /* no current: only friction and load act on the rotor */
    const int steps = 4;
    int i;
    const double hs = h / (double)steps;
    for (i = 0; i < steps; i++) {
        if (!lock_mech) {
            const double dw = (-t_load - p->b_nms * s->omega_m) / p->j_kgm2;
            s->theta_m += hs * (s->omega_m + 0.5 * hs * dw);
            s->omega_m += hs * dw;
        } else {
            s->theta_m += hs * s->omega_m;
        }
    }
}

/* All switches open: the currents commutate to zero at once, the rotor coasts. */
static void inv_forced_off(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                           double t_load, bool lock_mech, const inv_samples_t *smp)
{
    int k;
    s->i_d = s->i_q = s->i_x = s->i_y = 0.0;
    for (k = 0; k < smp->n; k++) {
        if (smp->cb != 0) {
            smp->cb(smp->ctx, smp->t[k], s, 0u);
        }
    }
    inv_coast(p, s, t_load, lock_mech, inv->ts);
    plant_sync_angle(p, s);
    for (k = 0; k < PLANT_PHASES; k++) {
        inv->dead_until[k] = -1.0;
    }
    inv->nominal_bits = 0u;
    inv->dead_last = -1.0;
    inv->eff = 0u;
    inv->off = true;
    inv->intervals = 0;
}

/* Inserts v into the sorted a[0..n) (n + 1 entries after). */
static void inv_insert_sorted(double *a, int n, double v)
{
    while (n > 0 && a[n - 1] > v) {
        a[n] = a[n - 1];
        n--;
    }
    a[n] = v;
}

/* Appends the legs commanded at t, merged into the last edge when that is at the same instant. */
static void inv_add_edge(inv_schedule_t *sc, double t, unsigned set, unsigned clear)
{
    const int n = sc->n_edges;
    if (n > 0 && sc->edge[n - 1].t == t) {
        sc->edge[n - 1].set |= set;
        sc->edge[n - 1].clear |= clear;
    } else {
        sc->edge[n].t = t;
        sc->edge[n].set = set;
        sc->edge[n].clear = clear;
        sc->n_edges = n + 1;
    }
}

/* Edges in time order without a general sort: the transitions at the period start first, then
 * the rising edges (the longest pulse first) and the falling edges (the shortest first), since
 * a duty d rises at (1 - d) Ts / 2 and falls at (1 + d) Ts / 2. */
static void inv_schedule_edges(const inverter_t *inv, const double duty[PLANT_PHASES],
                               inv_schedule_t *sc)
{
    int by_duty[PLANT_PHASES], n_mid = 0, k;
    double d_of[PLANT_PHASES];
    unsigned start_set = 0u, start_clear = 0u;
    for (k = 0; k < PLANT_PHASES; k++) {
        const unsigned bit = INV_LEG_BIT(k);
        const double d = (duty[k] < 0.0) ? 0.0 : ((duty[k] > 1.0) ? 1.0 : duty[k]);
        if (duty[k] >= 1.0) {
            start_set |= bit & ~inv->nominal_bits;
        } else {
            start_clear |= bit & inv->nominal_bits;
        }
        d_of[k] = d;
        if (d > 0.0 && d < 1.0) { /* insertion by falling duty */
            int i = n_mid++;
            while (i > 0 && d_of[by_duty[i - 1]] < d) {
                by_duty[i] = by_duty[i - 1];
                i--;
            }
            by_duty[i] = k;
        }
    }
    sc->n_edges = 0;
    if ((start_set | start_clear) != 0u) {
        inv_add_edge(sc, 0.0, start_set, start_clear);
    }
    for (k = 0; k < n_mid; k++) {
        inv_add_edge(sc, 0.5 * (1.0 - d_of[by_duty[k]]) * inv->ts, INV_LEG_BIT(by_duty[k]), 0u);
    }
    for (k = n_mid - 1; k >= 0; k--) {
        inv_add_edge(sc, 0.5 * (1.0 + d_of[by_duty[k]]) * inv->ts, 0u, INV_LEG_BIT(by_duty[k]));
    }
}

/* Breakpoints: the edges and the ends of their dead intervals (two sorted lists, the second the
 * first shifted by the dead time) merged, the ends carried over from the last period inserted,
 * the period end last. */
static void inv_schedule(const inverter_t *inv, const double duty[PLANT_PHASES], inv_schedule_t *sc)
{
    const double ts = inv->ts;
    int i = 0, j = 0, n = 0, k;
    inv_schedule_edges(inv, duty, sc);
    while (i < sc->n_edges) {
        const double end = sc->edge[j].t + inv->td;
        if (sc->edge[i].t <= end) {
            sc->br[n++] = sc->edge[i++].t;
        } else {
            sc->br[n++] = end; /* below the next edge, so below ts */
            j++;
        }
    }
    for (; j < sc->n_edges && sc->edge[j].t + inv->td < ts; j++) {
        sc->br[n++] = sc->edge[j].t + inv->td;
    }
    if (inv->dead_last > 0.0) { /* a dead interval runs into this period */
        for (k = 0; k < PLANT_PHASES; k++) {
            if (inv->dead_until[k] > 0.0 && inv->dead_until[k] < ts) {
                inv_insert_sorted(sc->br, n++, inv->dead_until[k]);
            }
        }
    }
    sc->br[n++] = ts;
    sc->n_br = n;
}

/* Current of phase k (A..F) as plant_phase_currents computes it (the same rows and order, so the
 * same sign), from the stationary alpha-beta current and the x-y current. */
static double inv_phase_current(const plant_state_t *s, int k, double i_alpha, double i_beta)
{
    static const double rows[PLANT_PHASES][4] = {
        {1.0, 0.0, 1.0, 0.0},        {-0.5, INV_H3, -0.5, -INV_H3}, {-0.5, -INV_H3, -0.5, INV_H3},
        {INV_H3, 0.5, -INV_H3, 0.5}, {-INV_H3, 0.5, INV_H3, 0.5},   {0.0, -1.0, 0.0, -1.0}};
    const double *r = rows[k];
    return r[0] * i_alpha + r[1] * i_beta + r[2] * s->i_x + r[3] * s->i_y;
}

/* Leg states in force from t: the commanded state, or during a dead interval the state the
 * current's sign imposes through the diodes (sign taken at t). Only the legs in a dead interval
 * need their current. */
static unsigned inv_effective_legs(const inverter_t *inv, const plant_state_t *s, double t,
                                   double eps)
{
    unsigned eff = inv->nominal_bits;
    double i_alpha, i_beta;
    int k;
    if (!(t < inv->dead_last - eps)) {
        return eff; /* no leg in a dead interval */
    }
    i_alpha = s->i_d * s->cos_e - s->i_q * s->sin_e;
    i_beta = s->i_d * s->sin_e + s->i_q * s->cos_e;
    for (k = 0; k < PLANT_PHASES; k++) {
        if (t < inv->dead_until[k] - eps) {
            const double i_k = inv_phase_current(s, k, i_alpha, i_beta);
            if (i_k > 0.0) {
                eff &= ~INV_LEG_BIT(k); /* lower diode: leg at 0 */
            } else if (i_k < 0.0) {
                eff |= INV_LEG_BIT(k); /* upper diode: leg at Vdc */
            }
        }
    }
    return eff;
}

/* Apply the edges due at t (the commanded state, and a dead interval for every leg that
 * changes); returns the index of the next edge. */
static int inv_apply_edges(inverter_t *inv, const inv_schedule_t *sc, int i_edge, double t,
                           double eps)
{
    while (i_edge < sc->n_edges && sc->edge[i_edge].t <= t + eps) {
        const inv_edge_t *e = &sc->edge[i_edge];
        const unsigned rising = e->set & ~inv->nominal_bits;
        const unsigned falling = e->clear & (inv->nominal_bits | rising);
        const unsigned changed = rising | falling;
        inv->nominal_bits = (inv->nominal_bits | rising) & ~falling;
        if (changed != 0u) {
            const double end = e->t + inv->td;
            int k;
            for (k = 0; k < PLANT_PHASES; k++) {
                if ((changed & INV_LEG_BIT(k)) != 0u) {
                    inv->dead_until[k] = end;
                }
            }
            inv->dead_last = (end > inv->dead_last) ? end : inv->dead_last;
        }
        i_edge++;
    }
    return i_edge;
}

/* The caller's sample due at t, if any; returns t_next or the next sample instant before it. */
static double inv_fine_sample(const inv_samples_t *smp, int *i_smp, const plant_state_t *s,
                              unsigned eff, double t, double t_next, double eps)
{
    while (*i_smp < smp->n && smp->t[*i_smp] < t - eps) {
        (*i_smp)++;
    }
    if (*i_smp < smp->n && smp->t[*i_smp] <= t + eps) {
        if (smp->cb != 0) {
            smp->cb(smp->ctx, t, s, eff);
        }
        (*i_smp)++;
    }
    if (*i_smp < smp->n && smp->t[*i_smp] < t_next) {
        t_next = smp->t[*i_smp];
    }
    return t_next;
}

/* The stationary-frame voltage of every leg state at the present DC link voltage (the products
 * p->vdc_v * u_table are formed once, not per interval). */
static const double (*inv_voltages(inverter_t *inv, const plant_params_t *p))[4]
{
    if (p->vdc_v != inv->u_vdc_of) {
        unsigned st;
        int j;
        for (st = 0u; st < 64u; st++) {
            for (j = 0; j < 4; j++) {
                inv->u_vdc[st][j] = p->vdc_v * inv->u_table[st][j];
            }
        }
        inv->u_vdc_of = p->vdc_v;
    }
    return (const double(*)[4])inv->u_vdc;
}

/* Integrate the period interval by interval; returns the torque integral. */
static double inv_run_intervals(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                                const inv_schedule_t *sc, double t_load, const inv_samples_t *smp)
{
    const double ts = inv->ts;
    const double eps = ts * 1e-12;
    const double(*u)[4] = inv_voltages(inv, p);
    int i_edge = 0, i_br = 0, i_smp = 0, intervals = 0;
    double t = 0.0, te_int = 0.0;
    while (t < ts - eps) {
        double t_next = ts;
        unsigned eff;
        i_edge = inv_apply_edges(inv, sc, i_edge, t, eps);
        eff = inv_effective_legs(inv, s, t, eps);
        if (inv->counting) {
            inv->transitions += popcount6(eff ^ inv->eff);
        }
        inv->eff = eff;
        /* next breakpoint: leg edge, dead end or fine sample */
        while (i_br < sc->n_br && sc->br[i_br] <= t + eps) {
            i_br++;
        }
        if (i_br < sc->n_br) {
            t_next = sc->br[i_br];
        }
        if (smp->n > 0) {
            t_next = inv_fine_sample(smp, &i_smp, s, eff, t, t_next, eps);
        }
        te_int += plant_stepper_step(&inv->stepper, p, s, u[eff], t_load, t_next - t);
        intervals++;
        t = t_next;
    }
    inv->intervals = intervals;
    return te_int;
}

double inverter_run_period(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                           const double duty[PLANT_PHASES], bool forced_off, double t_load,
                           bool lock_mech, const double *sample_t, int n_samples,
                           inverter_sample_fn cb, void *ctx)
{
    const inv_samples_t smp = {sample_t, n_samples, cb, ctx};
    inv_schedule_t sc;
    double te_int;
    int k;
    plant_sync_angle(p, s); /* once per period: no drift of the carried cos / sin */
    plant_stepper_mark_period(&inv->stepper, s);
    if (forced_off) {
        inv_forced_off(inv, p, s, t_load, lock_mech, &smp);
        return 0.0;
    }
    inv->off = false;
    inv_schedule(inv, duty, &sc);
    plant_stepper_begin(&inv->stepper, p, s, lock_mech);
    te_int = inv_run_intervals(inv, p, s, &sc, t_load, &smp);
    plant_stepper_end(&inv->stepper, p, s, t_load, te_int, inv->ts);
    for (k = 0; k < PLANT_PHASES; k++) {
        inv->dead_until[k] -= inv->ts;
    }
    inv->dead_last -= inv->ts;
    return te_int / inv->ts;
}
