/* Inverter over one carrier period, see inverter.h. */
#include "inverter.h"

#include <math.h>

#define INV_MAX_LEG_EVENTS (3 * PLANT_PHASES)
#define INV_MAX_BREAKS (4 * INV_MAX_LEG_EVENTS + PLANT_PHASES + 4)

void inverter_init(inverter_t *inv, const plant_params_t *p, double ts)
{
    unsigned st;
    int k;
    inv->ts = ts;
    inv->td = p->dead_time_on ? p->dead_time_s : 0.0;
    for (k = 0; k < PLANT_PHASES; k++) {
        inv->nominal[k] = 0;
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
    plant_stepper_init(&inv->stepper);
}

typedef struct {
    double t;
    int leg;
    int state;
} inv_event_t;

/* The period's commanded leg transitions and the sorted instants at which the voltage may
 * change (transitions, ends of dead intervals, the period end). */
typedef struct {
    inv_event_t ev[INV_MAX_LEG_EVENTS];
    double br[INV_MAX_BREAKS];
    int n_ev, n_br;
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
        inv->nominal[k] = 0;
        inv->dead_until[k] = -1.0;
    }
    inv->nominal_bits = 0u;
    inv->dead_last = -1.0;
    inv->eff = 0u;
    inv->off = true;
    inv->intervals = 0;
}

static void inv_add_event(inv_schedule_t *sc, double t, int leg, int state)
{
    sc->ev[sc->n_ev].t = t;
    sc->ev[sc->n_ev].leg = leg;
    sc->ev[sc->n_ev].state = state;
    sc->n_ev++;
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

/* Merges the sorted a[0..na) and b[0..nb) into out; returns the count. */
static int inv_merge(const double *a, int na, const double *b, int nb, double *out)
{
    int i = 0, j = 0, n = 0;
    while (i < na || j < nb) {
        out[n++] = (j >= nb || (i < na && a[i] <= b[j])) ? a[i++] : b[j++];
    }
    return n;
}

/* Events in time order without a general sort: transitions at the period start first, then
 * the rising edges (the longest pulse first) and the falling edges (the shortest first), since
 * a duty d rises at (1 - d) Ts / 2 and falls at (1 + d) Ts / 2. */
static void inv_schedule_events(const inverter_t *inv, const double duty[PLANT_PHASES],
                                inv_schedule_t *sc)
{
    int by_duty[PLANT_PHASES], n_mid = 0, k;
    double d_of[PLANT_PHASES];
    sc->n_ev = 0;
    for (k = 0; k < PLANT_PHASES; k++) {
        const int s0 = (duty[k] >= 1.0) ? 1 : 0;
        const double d = (duty[k] < 0.0) ? 0.0 : ((duty[k] > 1.0) ? 1.0 : duty[k]);
        if (s0 != inv->nominal[k]) {
            inv_add_event(sc, 0.0, k, s0);
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
    for (k = 0; k < n_mid; k++) {
        inv_add_event(sc, 0.5 * (1.0 - d_of[by_duty[k]]) * inv->ts, by_duty[k], 1);
    }
    for (k = n_mid - 1; k >= 0; k--) {
        inv_add_event(sc, 0.5 * (1.0 + d_of[by_duty[k]]) * inv->ts, by_duty[k], 0);
    }
}

/* Appends v unless it equals the last entry (legs with equal duties switch together). */
static void inv_push_unique(double *a, int *n, double v)
{
    if (*n == 0 || a[*n - 1] != v) {
        a[(*n)++] = v;
    }
}

/* Breakpoints: the distinct event times, the ends of their dead intervals and of those carried
 * over from the last period, each list already sorted, merged; the period end last. */
static void inv_schedule(const inverter_t *inv, const double duty[PLANT_PHASES], inv_schedule_t *sc)
{
    double times[INV_MAX_LEG_EVENTS], ends[INV_MAX_LEG_EVENTS], carried[PLANT_PHASES];
    double both[2 * INV_MAX_LEG_EVENTS];
    int n_times = 0, n_ends = 0, n_carried = 0, n_both, k;
    inv_schedule_events(inv, duty, sc);
    for (k = 0; k < PLANT_PHASES; k++) {
        if (inv->dead_until[k] > 0.0 && inv->dead_until[k] < inv->ts) {
            inv_insert_sorted(carried, n_carried++, inv->dead_until[k]);
        }
    }
    for (k = 0; k < sc->n_ev; k++) {
        inv_push_unique(times, &n_times, sc->ev[k].t);
        if (inv->td > 0.0 && sc->ev[k].t + inv->td < inv->ts) {
            inv_push_unique(ends, &n_ends, sc->ev[k].t + inv->td);
        }
    }
    n_both = inv_merge(times, n_times, ends, n_ends, both);
    sc->n_br = inv_merge(both, n_both, carried, n_carried, sc->br);
    sc->br[sc->n_br++] = inv->ts;
}

/* Leg states in force from t: the commanded state, or during a dead interval the state the
 * current's sign imposes through the diodes (sign taken at t). */
static unsigned inv_effective_legs(const inverter_t *inv, const plant_params_t *p,
                                   const plant_state_t *s, double t, double eps)
{
    unsigned eff = 0u;
    bool have_i = false;
    double iph[PLANT_PHASES];
    int k;
    if (!(t < inv->dead_last - eps)) {
        return inv->nominal_bits; /* no leg in a dead interval */
    }
    for (k = 0; k < PLANT_PHASES; k++) {
        int st = inv->nominal[k];
        if (t < inv->dead_until[k] - eps) {
            if (!have_i) {
                plant_phase_currents(p, s, iph);
                have_i = true;
            }
            if (iph[k] > 0.0) {
                st = 0;
            } else if (iph[k] < 0.0) {
                st = 1;
            }
        }
        eff |= (unsigned)st << (5 - k);
    }
    return eff;
}

/* Apply the commanded transitions due at t; returns the index of the next one. */
static int inv_apply_events(inverter_t *inv, const inv_schedule_t *sc, int i_ev, double t,
                            double eps)
{
    while (i_ev < sc->n_ev && sc->ev[i_ev].t <= t + eps) {
        const int leg = sc->ev[i_ev].leg;
        if (inv->nominal[leg] != sc->ev[i_ev].state) {
            inv->nominal[leg] = sc->ev[i_ev].state;
            inv->nominal_bits ^= 1u << (5 - leg);
            inv->dead_until[leg] = sc->ev[i_ev].t + inv->td;
            inv->dead_last =
                (inv->dead_until[leg] > inv->dead_last) ? inv->dead_until[leg] : inv->dead_last;
        }
        i_ev++;
    }
    return i_ev;
}

/* Integrate the period interval by interval; returns the torque integral. */
static double inv_run_intervals(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                                const inv_schedule_t *sc, double t_load, const inv_samples_t *smp)
{
    const double ts = inv->ts;
    const double eps = ts * 1e-12;
    int i_ev = 0, i_br = 0, i_smp = 0;
    double t = 0.0, te_int = 0.0;
    inv->intervals = 0;
    while (t < ts - eps) {
        double t_next = ts, u[4];
        unsigned eff;
        i_ev = inv_apply_events(inv, sc, i_ev, t, eps);
        eff = inv_effective_legs(inv, p, s, t, eps);
        if (inv->counting) {
            inv->transitions += popcount6(eff ^ inv->eff);
        }
        inv->eff = eff;
        /* next breakpoint: leg event, dead end or fine sample */
        while (i_br < sc->n_br && sc->br[i_br] <= t + eps) {
            i_br++;
        }
        if (i_br < sc->n_br) {
            t_next = sc->br[i_br];
        }
        while (i_smp < smp->n && smp->t[i_smp] < t - eps) {
            i_smp++;
        }
        if (i_smp < smp->n && smp->t[i_smp] <= t + eps) {
            if (smp->cb != 0) {
                smp->cb(smp->ctx, t, s, eff);
            }
            i_smp++;
        }
        if (i_smp < smp->n && smp->t[i_smp] < t_next) {
            t_next = smp->t[i_smp];
        }
        u[0] = p->vdc_v * inv->u_table[eff][0];
        u[1] = p->vdc_v * inv->u_table[eff][1];
        u[2] = p->vdc_v * inv->u_table[eff][2];
        u[3] = p->vdc_v * inv->u_table[eff][3];
        te_int += plant_stepper_step(&inv->stepper, p, s, u, t_load, t_next - t);
        inv->intervals++;
        t = t_next;
    }
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
