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
    inv->eff = 0u;
    inv->off = true;
    inv->counting = false;
    inv->transitions = 0u;
    inv->intervals = 0;
    for (st = 0u; st < 64u; st++) {
        plant_vector_voltage(st, 1.0, inv->u_table[st]);
    }
}

typedef struct {
    double t;
    int leg;
    int state;
} inv_event_t;

static void inv_sort(double *a, int n)
{
    int i, j;
    for (i = 1; i < n; i++) {
        const double v = a[i];
        j = i - 1;
        while (j >= 0 && a[j] > v) {
            a[j + 1] = a[j];
            j--;
        }
        a[j + 1] = v;
    }
}

static void inv_sort_events(inv_event_t *a, int n)
{
    int i, j;
    for (i = 1; i < n; i++) {
        const inv_event_t v = a[i];
        j = i - 1;
        while (j >= 0 && a[j].t > v.t) {
            a[j + 1] = a[j];
            j--;
        }
        a[j + 1] = v;
    }
}

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

double inverter_run_period(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                           const double duty[PLANT_PHASES], bool forced_off, double t_load,
                           bool lock_mech, const double *sample_t, int n_samples,
                           inverter_sample_fn cb, void *ctx)
{
    inv_event_t ev[INV_MAX_LEG_EVENTS];
    double br[INV_MAX_BREAKS];
    int n_ev = 0, n_br = 0, k, i_ev = 0, i_br, i_smp = 0;
    const double ts = inv->ts;
    const double eps = ts * 1e-12;
    double t = 0.0, te_int = 0.0;

    plant_sync_angle(p, s); /* once per period: no drift of the carried cos / sin */
    if (forced_off) {
        int j;
        s->i_d = s->i_q = s->i_x = s->i_y = 0.0;
        for (j = 0; j < n_samples; j++) {
            if (cb != 0) {
                cb(ctx, sample_t[j], s, 0u);
            }
        }
        inv_coast(p, s, t_load, lock_mech, ts);
        plant_sync_angle(p, s);
        for (k = 0; k < PLANT_PHASES; k++) {
            inv->nominal[k] = 0;
            inv->dead_until[k] = -1.0;
        }
        inv->eff = 0u;
        inv->off = true;
        inv->intervals = 0;
        return 0.0;
    }
    inv->off = false;

    /* commanded transitions of this period */
    for (k = 0; k < PLANT_PHASES; k++) {
        double d = duty[k];
        const int s0 = (d >= 1.0) ? 1 : 0;
        d = (d < 0.0) ? 0.0 : ((d > 1.0) ? 1.0 : d);
        if (s0 != inv->nominal[k]) {
            ev[n_ev].t = 0.0;
            ev[n_ev].leg = k;
            ev[n_ev].state = s0;
            n_ev++;
        }
        if (d > 0.0 && d < 1.0) {
            ev[n_ev].t = 0.5 * (1.0 - d) * ts;
            ev[n_ev].leg = k;
            ev[n_ev].state = 1;
            n_ev++;
            ev[n_ev].t = 0.5 * (1.0 + d) * ts;
            ev[n_ev].leg = k;
            ev[n_ev].state = 0;
            n_ev++;
        }
        if (inv->dead_until[k] > 0.0 && inv->dead_until[k] < ts) {
            br[n_br++] = inv->dead_until[k];
        }
    }
    inv_sort_events(ev, n_ev);
    for (k = 0; k < n_ev; k++) {
        br[n_br++] = ev[k].t;
        if (inv->td > 0.0 && ev[k].t + inv->td < ts) {
            br[n_br++] = ev[k].t + inv->td;
        }
    }
    br[n_br++] = ts;
    inv_sort(br, n_br);

    inv->intervals = 0;
    i_br = 0;
    while (t < ts - eps) {
        unsigned eff = 0u;
        double t_next = ts, u[4];
        bool have_i = false;
        double iph[PLANT_PHASES];
        /* apply commanded transitions due now */
        while (i_ev < n_ev && ev[i_ev].t <= t + eps) {
            const int leg = ev[i_ev].leg;
            if (inv->nominal[leg] != ev[i_ev].state) {
                inv->nominal[leg] = ev[i_ev].state;
                inv->dead_until[leg] = ev[i_ev].t + inv->td;
            }
            i_ev++;
        }
        /* effective leg states */
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
        if (inv->counting) {
            inv->transitions += popcount6(eff ^ inv->eff);
        }
        inv->eff = eff;
        /* next breakpoint: leg event, dead end or fine sample */
        while (i_br < n_br && br[i_br] <= t + eps) {
            i_br++;
        }
        if (i_br < n_br) {
            t_next = br[i_br];
        }
        while (i_smp < n_samples && sample_t[i_smp] < t - eps) {
            i_smp++;
        }
        if (i_smp < n_samples && sample_t[i_smp] <= t + eps) {
            if (cb != 0) {
                cb(ctx, t, s, eff);
            }
            i_smp++;
        }
        if (i_smp < n_samples && sample_t[i_smp] < t_next) {
            t_next = sample_t[i_smp];
        }
        {
            const double vdc = p->vdc_v;
            const double *ut = inv->u_table[eff];
            u[0] = vdc * ut[0];
            u[1] = vdc * ut[1];
            u[2] = vdc * ut[2];
            u[3] = vdc * ut[3];
        }
        te_int += plant_integrate_nosync(p, s, u, t_load, lock_mech, t_next - t);
        inv->intervals++;
        t = t_next;
    }
    for (k = 0; k < PLANT_PHASES; k++) {
        inv->dead_until[k] -= ts;
    }
    return te_int / ts;
}
