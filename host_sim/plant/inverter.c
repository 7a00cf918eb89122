/* Inverter over one carrier period, see inverter.h. */
#include "inverter.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define INV_H3 0.86602540378443864676 /* sqrt(3)/2, as plant.c has it */

/* The interval runner is forced inline into both period loops (without, gcc calls it and saves
 * and restores its registers for every interval). */
#if defined(__GNUC__)
#define INV_INLINE inline __attribute__((always_inline))
#else
#define INV_INLINE inline
#endif

void inverter_init(inverter_t *inv, const plant_params_t *p, double ts)
{
    unsigned st;
    int k;
    inv->ts = ts;
    inv->td = p->dead_time_on ? p->dead_time_s : 0.0;
    for (k = 0; k < PLANT_PHASES; k++) {
        inv->legs.dead_until[k] = -1.0;
    }
    inv->legs.nominal_bits = 0u;
    inv->legs.dead_last = -1.0;
    inv->eff = 0u;
    inv->off = true;
    inv->counting = false;
    inv->transitions = 0u;
    inv->switched_amps = 0.0;
    inv->intervals = 0;
    for (st = 0u; st < 64u; st++) {
        plant_vector_voltage(st, 1.0, inv->u_table[st]);
    }
    inv->u_vdc_of = -1.0; /* no DC link voltage is negative: inv_voltages builds u_vdc */
    memset(&inv->cache, 0, sizeof inv->cache);
    plant_stepper_init(&inv->stepper);
    inverter_set_floating(inv, 0u);
    inv->float_conduct_s = 0.0;
}

void inverter_set_floating(inverter_t *inv, unsigned legs)
{
    int k;
    inv->floating = legs & 077u;
    for (k = 0; k < PLANT_PHASES; k++) {
        inv->float_state[k] = 0;
    }
}

void inverter_free(inverter_t *inv) { inv_cache_free(&inv->cache); }

/* Where the plant is sampled for the caller within the period. */
typedef struct {
    inv_sample_times_t times;
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
    for (k = 0; k < smp->times.n; k++) {
        if (smp->cb != 0) {
            smp->cb(smp->ctx, smp->times.t[k], s, 0u);
        }
    }
    inv_coast(p, s, t_load, lock_mech, inv->ts);
    plant_sync_angle(p, s);
    for (k = 0; k < PLANT_PHASES; k++) {
        inv->legs.dead_until[k] = -1.0;
    }
    inv->legs.nominal_bits = 0u;
    inv->legs.dead_last = -1.0;
    inv->eff = 0u;
    inv->off = true;
    inv->intervals = 0;
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

/* The state's stator current in the stationary frame (from its rotor-frame current). */
static void inv_alpha_beta(const plant_state_t *s, double *i_alpha, double *i_beta)
{
    *i_alpha = s->i_d * s->cos_e - s->i_q * s->sin_e;
    *i_beta = s->i_d * s->sin_e + s->i_q * s->cos_e;
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

/* A floating leg's state for the next step: a conducting diode stays while its current has its
 * sign; otherwise the terminal voltage that holds the phase open decides (0 open, 1 lower
 * diode, 2 upper diode). */
static int inv_float_decide(const inverter_t *inv, const plant_params_t *p, const plant_state_t *s,
                            const double (*u)[4], unsigned eff, int k)
{
    double i_alpha, i_beta, i_k, v;
    inv_alpha_beta(s, &i_alpha, &i_beta);
    i_k = inv_phase_current(s, k, i_alpha, i_beta);
    if ((inv->float_state[k] == 1 && i_k > 0.0) || (inv->float_state[k] == 2 && i_k < 0.0)) {
        return inv->float_state[k];
    }
    v = plant_open_terminal_voltage(p, s, k, u[eff & ~INV_LEG_BIT(k)]);
    return (v < 0.0) ? 1 : ((v > p->vdc_v) ? 2 : 0);
}

/* A conducting diode whose current reached zero or reversed within the last step. */
static bool inv_float_blocked(const inverter_t *inv, const plant_state_t *s, int k)
{
    double i_alpha, i_beta, i_k;
    inv_alpha_beta(s, &i_alpha, &i_beta);
    i_k = inv_phase_current(s, k, i_alpha, i_beta);
    return (inv->float_state[k] == 1 && i_k <= 0.0) || (inv->float_state[k] == 2 && i_k >= 0.0);
}

/* One interval with floating legs (RK4: sim_fault_plant sets it), in steps of at most
 * INV_FLOAT_STEP_S: each step the legs' states are decided, the open ones' phases opened, the
 * conducting ones' legs set; a diode whose current reversed within a step blocks: the current is
 * commutated to zero. */
static double inv_float_interval(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                                 const double (*u)[4], unsigned eff, double t_load, double h)
{
    const int n = (int)ceil(h / INV_FLOAT_STEP_S - 1e-9);
    const double hs = h / (double)((n < 1) ? 1 : n);
    plant_exact_span_t sp;
    double te = 0.0;
    int i;
    plant_stepper_span(&inv->stepper, hs, &sp);
    for (i = 0; i < ((n < 1) ? 1 : n); i++) {
        plant_params_t pf = *p;
        unsigned e = eff;
        bool conducting = false;
        int k;
        for (k = 0; k < PLANT_PHASES; k++) {
            if (((inv->floating >> k) & 1u) != 0u) {
                inv->float_state[k] = inv_float_decide(inv, p, s, u, eff, k);
                pf.phase_open[k] = inv->float_state[k] == 0;
                e = (inv->float_state[k] == 2) ? (e | INV_LEG_BIT(k)) : (e & ~INV_LEG_BIT(k));
                conducting = conducting || inv->float_state[k] != 0;
            }
        }
        te += plant_stepper_step(&inv->stepper, &pf, s, u[e], t_load, hs, &sp);
        if (conducting && inv->counting) {
            inv->float_conduct_s += hs;
        }
        for (k = 0; k < PLANT_PHASES; k++) {
            if (((inv->floating >> k) & 1u) != 0u && inv_float_blocked(inv, s, k)) {
                pf.phase_open[k] = true; /* the current crossed zero: the diode blocks */
                plant_open_commutate(&pf, s);
                inv->float_state[k] = 0;
            }
        }
    }
    return te;
}

/* Leg mask A = bit 0 to the inverter's S_A = bit 5. */
static unsigned inv_float_bits(unsigned legs)
{
    unsigned bits = 0u;
    int k;
    for (k = 0; k < PLANT_PHASES; k++) {
        if (((legs >> k) & 1u) != 0u) {
            bits |= INV_LEG_BIT(k);
        }
    }
    return bits;
}

/* The leg states in force: the commanded ones, and for each leg in a dead interval the state
 * its current's sign imposes through the diodes (sign taken at the interval's start). */
static unsigned inv_effective_legs(unsigned nominal, unsigned dead, const plant_state_t *s)
{
    unsigned eff = nominal;
    double i_alpha, i_beta;
    int k;
    if (dead == 0u) {
        return eff;
    }
    inv_alpha_beta(s, &i_alpha, &i_beta);
    for (k = 0; k < PLANT_PHASES; k++) {
        if ((dead & INV_LEG_BIT(k)) != 0u) {
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

/* The phase currents' magnitudes summed over the legs that switch (the switching loss's
 * measure: each transition's energy grows with the current it commutates). */
static double inv_switched_current(const plant_state_t *s, unsigned changed)
{
    double i_alpha, i_beta, sum = 0.0;
    int k;
    inv_alpha_beta(s, &i_alpha, &i_beta);
    for (k = 0; k < PLANT_PHASES; k++) {
        if ((changed & INV_LEG_BIT(k)) != 0u) {
            sum += fabs(inv_phase_current(s, k, i_alpha, i_beta));
        }
    }
    return sum;
}

/* An interval's start: the effective legs (returned), the transition count, the caller's
 * sample. */
static INV_INLINE unsigned inv_interval_start(inverter_t *inv, plant_state_t *s,
                                              const inv_interval_t *iv, const inv_samples_t *smp)
{
    const unsigned eff =
        (iv->dead != 0u) ? inv_effective_legs(iv->nominal, iv->dead, s) : iv->nominal;
    if (inv->counting && eff != inv->eff) {
        inv->transitions += popcount6(eff ^ inv->eff);
        inv->switched_amps += inv_switched_current(s, eff ^ inv->eff);
    }
    inv->eff = eff;
    if (iv->sample && smp->cb != 0) {
        smp->cb(smp->ctx, iv->t, s, eff);
    }
    return eff;
}

/* One interval: its start, then the plant; returns the torque integral. */
static INV_INLINE double inv_run_interval(inverter_t *inv, const plant_params_t *p,
                                          plant_state_t *s, const double (*u)[4],
                                          const inv_interval_t *iv, double t_load,
                                          const inv_samples_t *smp)
{
    const unsigned eff = inv_interval_start(inv, s, iv, smp);
    return plant_stepper_step(&inv->stepper, p, s, u[eff], t_load, iv->h, &iv->sp);
}

/* A cached program's intervals (their spans refreshed when the integrator's coefficients
 * changed); returns the torque integral. */
static double inv_run_program(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                              inv_program_t *pr, double t_load, const inv_samples_t *smp)
{
    const double(*u)[4] = inv_voltages(inv, p);
    double te_int = 0.0;
    int i;
    if (pr->span_generation != inv->stepper.generation) {
        for (i = 0; i < pr->n; i++) {
            plant_stepper_span(&inv->stepper, pr->iv[i].h, &pr->iv[i].sp);
        }
        pr->span_generation = inv->stepper.generation;
    }
    for (i = 0; i < pr->n; i++) {
        te_int += inv_run_interval(inv, p, s, u, &pr->iv[i], t_load, smp);
    }
    inv->intervals = pr->n;
    inv_program_finish(pr, inv->ts, &inv->legs);
    return te_int;
}

/* A period that is not cached: built interval by interval as it runs. */
static double inv_run_built(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                            const double duty[PLANT_PHASES], double t_load,
                            const inv_samples_t *smp)
{
    const double(*u)[4] = inv_voltages(inv, p);
    inv_builder_t b;
    inv_interval_t iv;
    double te_int = 0.0;
    int n = 0;
    inv_builder_start(&b, &inv->legs, duty, inv->ts, inv->td, &smp->times);
    while (inv_builder_next(&b, &iv)) {
        plant_stepper_span(&inv->stepper, iv.h, &iv.sp);
        te_int += inv_run_interval(inv, p, s, u, &iv, t_load, smp);
        n++;
    }
    inv->intervals = n;
    inv_builder_finish(&b, &inv->legs);
    return te_int;
}

/* A period with floating legs (their switches off, their phases connected): built as it runs,
 * each interval in the diode-deciding steps of inv_float_interval. */
static double inv_run_floating(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                               const double duty[PLANT_PHASES], double t_load,
                               const inv_samples_t *smp)
{
    const double(*u)[4] = inv_voltages(inv, p);
    const unsigned off = inv_float_bits(inv->floating);
    inv_builder_t b;
    inv_interval_t iv;
    double te_int = 0.0;
    int n = 0;
    inv_builder_start(&b, &inv->legs, duty, inv->ts, inv->td, &smp->times);
    while (inv_builder_next(&b, &iv)) {
        const unsigned eff = inv_interval_start(inv, s, &iv, smp);
        te_int += inv_float_interval(inv, p, s, u, eff & ~off, t_load, iv.h);
        n++;
    }
    inv->intervals = n;
    inv_builder_finish(&b, &inv->legs);
    return te_int;
}

double inverter_run_period(inverter_t *inv, const plant_params_t *p, plant_state_t *s,
                           const double duty[PLANT_PHASES], bool forced_off, double t_load,
                           bool lock_mech, const double *sample_t, int n_samples,
                           inverter_sample_fn cb, void *ctx)
{
    const inv_samples_t smp = {{sample_t, n_samples}, cb, ctx};
    inv_program_t *pr;
    double te_int;
    plant_stepper_mark_period(&inv->stepper, s);
    if (forced_off) {
        plant_sync_angle(p, s);
        inv_forced_off(inv, p, s, t_load, lock_mech, &smp);
        return 0.0;
    }
    inv->off = false;
    plant_stepper_begin(&inv->stepper, p, s, lock_mech);
    if (inv->floating != 0u) { /* rare: never cached */
        te_int = inv_run_floating(inv, p, s, duty, t_load, &smp);
    } else {
        pr = inv_cache_program(&inv->cache, &inv->legs, duty, inv->ts, inv->td, &smp.times);
        te_int = pr ? inv_run_program(inv, p, s, pr, t_load, &smp)
                    : inv_run_built(inv, p, s, duty, t_load, &smp);
    }
    plant_stepper_end(&inv->stepper, p, s, t_load, te_int, inv->ts);
    return te_int / inv->ts;
}
