/* The reproduce runs, see reproduce_cases.h. */
#include "reproduce_cases.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const double rep_paper_lambda[3] = {20.0, 100.0, 200.0};
const double rep_paper_thd_mptc[3] = {43.5, 28.6, 52.5};
const double rep_paper_thd_ddc[3] = {13.5, 13.0, 12.8};
const double rep_paper_rip_mptc[3] = {0.42, 0.58, 0.89};
const double rep_paper_rip_ddc[3] = {0.29, 0.31, 0.58};

typedef enum {
    REP_PLAIN,
    REP_GUARD,        /* the core's DDC torque guard on */
    REP_FS_7K5,       /* 7.5 kHz sampling */
    REP_LXY_5MH,      /* plant x-y inductance 5 mH */
    REP_LXY_20MH,     /* 20 mH */
    REP_FLOAT,        /* float build of the core */
    REP_XY_TABLE,     /* DDC direction from the x-y table */
    REP_IDEAL,        /* every non-ideality off */
    REP_TRIP_20A,     /* 20 A hardware over-current trip, board sensors */
    REP_PROTECT,      /* the drive's protection at its default limits, board sensors */
    REP_BOARD_SENSORS /* the board's +-20 A sensors */
} rep_variant_t;

typedef struct {
    const char *group, *name; /* name: "_l<lambda>" appended when lambda is 0 (all three) */
    int controller;           /* 0 DDC, 1 MPTC-49, 2 MPTC-13 */
    sim_scenario_t scenario;
    double lambda;
    rep_variant_t variant;
} rep_spec_t;

static const rep_spec_t rep_specs[] = {
    {"steady", "steady_mptc49", 1, SIM_SCEN_STEADY, 0.0, REP_PLAIN},
    {"steady", "steady_ddc", 0, SIM_SCEN_STEADY, 0.0, REP_PLAIN},
    {"steady", "steady_mptc13", 2, SIM_SCEN_STEADY, 0.0, REP_PLAIN},
    {"steady", "guard_ddc", 0, SIM_SCEN_STEADY, 0.0, REP_GUARD},
    {"eqsw", "fs7k5_ddc", 0, SIM_SCEN_STEADY, 0.0, REP_FS_7K5},
    {"dyn", "accel_mptc49", 1, SIM_SCEN_ACCEL, 100.0, REP_PLAIN},
    {"dyn", "accel_ddc", 0, SIM_SCEN_ACCEL, 100.0, REP_PLAIN},
    {"dyn", "reversal_mptc49", 1, SIM_SCEN_REVERSAL, 100.0, REP_PLAIN},
    {"dyn", "reversal_ddc", 0, SIM_SCEN_REVERSAL, 100.0, REP_PLAIN},
    {"dyn", "load-step_mptc49", 1, SIM_SCEN_LOAD_STEP, 100.0, REP_PLAIN},
    {"dyn", "load-step_ddc", 0, SIM_SCEN_LOAD_STEP, 100.0, REP_PLAIN},
    {"lxy", "lxy5_mptc49", 1, SIM_SCEN_STEADY, 100.0, REP_LXY_5MH},
    {"lxy", "lxy5_ddc", 0, SIM_SCEN_STEADY, 100.0, REP_LXY_5MH},
    {"lxy", "lxy20_mptc49", 1, SIM_SCEN_STEADY, 100.0, REP_LXY_20MH},
    {"lxy", "lxy20_ddc", 0, SIM_SCEN_STEADY, 100.0, REP_LXY_20MH},
    {"extra", "float_ddc_l100", 0, SIM_SCEN_STEADY, 100.0, REP_FLOAT},
    {"extra", "float_mptc49_l100", 1, SIM_SCEN_STEADY, 100.0, REP_FLOAT},
    {"extra", "ddc_xytable_l20", 0, SIM_SCEN_STEADY, 20.0, REP_XY_TABLE},
    {"extra", "ddc_xytable_l100", 0, SIM_SCEN_STEADY, 100.0, REP_XY_TABLE},
    {"extra", "ddc_xytable_l200", 0, SIM_SCEN_STEADY, 200.0, REP_XY_TABLE},
    {"extra", "ddc_ideal_l100", 0, SIM_SCEN_STEADY, 100.0, REP_IDEAL},
    {"extra", "mptc49_ideal_l100", 1, SIM_SCEN_STEADY, 100.0, REP_IDEAL},
    {"extra", "board_mptc49_l100", 1, SIM_SCEN_STEADY, 100.0, REP_BOARD_SENSORS},
    {"extra", "trip20_mptc49_l100", 1, SIM_SCEN_STEADY, 100.0, REP_TRIP_20A},
    {"extra", "protect_mptc49_l100", 1, SIM_SCEN_STEADY, 100.0, REP_PROTECT},
    {"extra", "trip20_ddc_l100", 0, SIM_SCEN_STEADY, 100.0, REP_TRIP_20A},
};

static void rep_apply_variant(sim_config_t *c, rep_variant_t v)
{
    const double board_span = c->plant.current_sensor_span_a; /* before the baseline's */
    plant_params_t *p = &c->plant;
    if (c->controller == 1) { /* MPTC-49 only: MPTC-13 and the DDC stay within the board's */
        p->current_sensor_span_a = REP_BASELINE_SENSOR_SPAN_A;
    }
    switch (v) {
    case REP_GUARD: /* the product's DDC: the core's defaults */
        c->ddc_torque_guard = c->mid_period_angle = c->pulse_pattern = -1;
        c->flux_tie_band = -1.0;
        c->light_load_current_a = -1.0;
        break;
    case REP_FS_7K5:
        c->fs_hz = 7500.0;
        break;
    case REP_LXY_5MH: /* the machine's L_xy: the plant's and the controller's (as --lxy) */
        p->lxy_h = c->ctl.lxy_h = 0.005;
        break;
    case REP_LXY_20MH:
        p->lxy_h = c->ctl.lxy_h = 0.020;
        break;
    case REP_FLOAT:
        c->arith = 1;
        break;
    case REP_XY_TABLE:
        c->ddc_direction = 1;
        break;
    case REP_IDEAL:
        p->dead_time_on = p->harmonics_on = false;
        p->adc_offset_on = p->adc_gain_on = p->adc_noise_on = p->encoder_quant_on = false;
        break;
    case REP_TRIP_20A:
        c->trip_current_a = 20.0;
        p->current_sensor_span_a = board_span;
        break;
    case REP_PROTECT:
        c->protect = true;
        p->current_sensor_span_a = board_span;
        break;
    case REP_BOARD_SENSORS:
        p->current_sensor_span_a = board_span;
        break;
    case REP_PLAIN:
        break;
    }
}

rep_case_t *rep_add(rep_case_t *cases, int *n, const char *dir, const char *group, const char *name,
                    int controller, sim_scenario_t scen, double lambda)
{
    static char dirs[REP_MAX_CASES][1100];
    static rep_case_t overflow; /* written to and ignored if the case table is full */
    rep_case_t *c;
    if (*n >= REP_MAX_CASES) {
        fprintf(stderr, "sixphase-sim: too many reproduce cases, '%s' skipped\n", name);
        return &overflow;
    }
    c = &cases[*n];
    memset(c, 0, sizeof *c);
    (void)snprintf(c->name, sizeof c->name, "%s", name);
    (void)snprintf(c->group, sizeof c->group, "%s", group);
    sim_config_default(&c->cfg);
    c->cfg.controller = controller;
    c->cfg.scenario = scen;
    c->cfg.lambda = lambda;
    c->cfg.seed = 1u;
    /* the paper's method (every improvement off) unless a case asks otherwise */
    c->cfg.ddc_torque_guard = 0;
    c->cfg.mid_period_angle = 0;
    c->cfg.pulse_pattern = 0;
    c->cfg.flux_tie_band = 0.0;
    c->cfg.light_load_current_a = 0.0;
    /* MPTC-49 peaks near 30 A (beyond the 15 A limit): the firmware trips it within
     * milliseconds (row protect_mptc49_l100), so its comparison rows run with the software
     * protection out of reach */
    c->cfg.protect = (controller != 1);
    (void)snprintf(dirs[*n], sizeof dirs[*n], "%s/runs/%s", dir, name);
    c->cfg.out_dir = dirs[*n];
    c->cfg.write_fine = false; /* the plots use trace.csv; fine.csv would be ~2.4 MB per run */
    (*n)++;
    return c;
}

static void rep_add_spec(rep_case_t *cases, int *n, const char *dir, const rep_spec_t *s,
                         double lambda)
{
    char name[64];
    rep_case_t *c;
    if (s->lambda > 0.0) {
        (void)snprintf(name, sizeof name, "%s", s->name);
    } else {
        (void)snprintf(name, sizeof name, "%s_l%.0f", s->name, lambda);
    }
    c = rep_add(cases, n, dir, s->group, name, s->controller, s->scenario, lambda);
    rep_apply_variant(&c->cfg, s->variant);
}

void rep_cases_first_batch(rep_case_t *cases, int *n, const char *dir)
{
    size_t i;
    int li, k;
    for (li = 0; li < 3; li++) { /* the lambda sweeps first, lambda by lambda */
        for (i = 0; i < sizeof rep_specs / sizeof rep_specs[0]; i++) {
            if (rep_specs[i].lambda <= 0.0) {
                rep_add_spec(cases, n, dir, &rep_specs[i], rep_paper_lambda[li]);
            }
        }
    }
    for (i = 0; i < sizeof rep_specs / sizeof rep_specs[0]; i++) {
        if (rep_specs[i].lambda > 0.0) {
            rep_add_spec(cases, n, dir, &rep_specs[i], rep_specs[i].lambda);
        }
    }
    for (k = 1; k < (int)SIM_FAULT_COUNT; k++) {
        char name[64];
        rep_case_t *c;
        (void)snprintf(name, sizeof name, "fault_%s", sim_fault_info((sim_fault_t)k)->name);
        c = rep_add(cases, n, dir, "fault", name, 0, SIM_SCEN_STEADY, 100.0);
        c->cfg.fault = (sim_fault_t)k;
        /* the product's DDC, as `sixphase-sim run` */
        c->cfg.ddc_torque_guard = c->cfg.mid_period_angle = c->cfg.pulse_pattern = -1;
        c->cfg.flux_tie_band = -1.0;
        c->cfg.light_load_current_a = -1.0;
    }
}

/* The runs of one baseline at one lambda in the order they ran: the 10 kHz run first, then
 * each round's; returns how many (at most max). */
static int rep_eqsw_runs(const rep_case_t *cases, int n, const char *baseline, int li,
                         const rep_case_t **runs, int max)
{
    char name[64];
    int count = 0, r;
    (void)snprintf(name, sizeof name, "steady_%s_l%.0f", baseline, rep_paper_lambda[li]);
    runs[count] = rep_find(cases, n, name);
    count += (runs[count] != NULL);
    for (r = 1; r <= REP_EQSW_ROUNDS && count < max; r++) {
        (void)snprintf(name, sizeof name, "eqsw_%s_l%.0f_r%d", baseline, rep_paper_lambda[li], r);
        runs[count] = rep_find(cases, n, name);
        count += (runs[count] != NULL);
    }
    return count;
}

static double rep_eqsw_target(const rep_case_t *cases, int n, int li)
{
    char name[64];
    const rep_case_t *d;
    (void)snprintf(name, sizeof name, "guard_ddc_l%.0f", rep_paper_lambda[li]);
    d = rep_find(cases, n, name);
    return d ? d->res.switching_freq_hz : -1.0;
}

const rep_case_t *rep_eqsw_best(const rep_case_t *cases, int n, const char *baseline, int li,
                                double *target, int *rounds)
{
    const rep_case_t *runs[REP_EQSW_ROUNDS + 1], *best = NULL;
    const int count = rep_eqsw_runs(cases, n, baseline, li, runs, REP_EQSW_ROUNDS + 1);
    int i;
    *target = rep_eqsw_target(cases, n, li);
    *rounds = 0;
    for (i = 1; i<count && * target> 0.0; i++) { /* the 10 kHz run is not a candidate */
        if (!best || fabs(runs[i]->res.switching_freq_hz - *target) <
                         fabs(best->res.switching_freq_hz - *target)) {
            best = runs[i];
        }
        *rounds = i;
    }
    return best;
}

/* The next sampling frequency to try, or <= 0 when there is none: the secant through the two
 * latest runs (f_sw rises with fs), else proportional scaling from the latest; at most a factor
 * of two per round, within 2..50 kHz. */
static double rep_eqsw_next_fs(const rep_case_t *const *runs, int count, double target)
{
    const sim_result_t *a = &runs[count - 1]->res;
    double fs = a->fs_hz * target / a->switching_freq_hz;
    int i;
    if (count >= 2) {
        const sim_result_t *b = &runs[count - 2]->res;
        const double slope = (a->switching_freq_hz - b->switching_freq_hz) / (a->fs_hz - b->fs_hz);
        if (slope > 0.0 && isfinite(slope)) {
            fs = a->fs_hz + (target - a->switching_freq_hz) / slope;
        }
    }
    fs = fmin(fmax(fs, 0.5 * a->fs_hz), 2.0 * a->fs_hz);
    fs = 10.0 * floor(fmin(fmax(fs, 2000.0), 50000.0) / 10.0 + 0.5);
    for (i = 0; i < count; i++) {
        if (runs[i]->res.fs_hz == fs) {
            return -1.0; /* tried already: the iteration has settled as far as it can */
        }
    }
    return fs;
}

int rep_cases_equal_switching(rep_case_t *cases, int *n, const char *dir, int round)
{
    static const char *const baselines[2] = {"mptc49", "mptc13"};
    const int n1 = *n;
    int li, b, added = 0;
    for (li = 0; li < 3; li++) {
        const double target = rep_eqsw_target(cases, n1, li);
        for (b = 0; b < 2 && target > 0.0; b++) {
            const rep_case_t *runs[REP_EQSW_ROUNDS + 1];
            const int count = rep_eqsw_runs(cases, n1, baselines[b], li, runs, REP_EQSW_ROUNDS + 1);
            double best_target, fs;
            int rounds;
            const rep_case_t *best =
                rep_eqsw_best(cases, n1, baselines[b], li, &best_target, &rounds);
            char name[64];
            rep_case_t *c;
            if (count == 0 || count != round || !(runs[count - 1]->res.switching_freq_hz > 0.0) ||
                (best && fabs(best->res.switching_freq_hz / target - 1.0) <= REP_EQSW_TOLERANCE)) {
                continue; /* no run to start from, a round missing, or settled */
            }
            fs = rep_eqsw_next_fs(runs, count, target);
            if (fs <= 0.0) {
                continue;
            }
            (void)snprintf(name, sizeof name, "eqsw_%s_l%.0f_r%d", baselines[b],
                           rep_paper_lambda[li], round);
            c = rep_add(cases, n, dir, "eqsw", name, b + 1, SIM_SCEN_STEADY, rep_paper_lambda[li]);
            rep_apply_variant(&c->cfg, REP_PLAIN);
            c->cfg.fs_hz = fs;
            added++;
        }
    }
    return added;
}

const char *const rep_sweep_variant[REP_SWEEP_VARIANTS] = {"paper", "guard",   "fewest",
                                                           "tie",   "product", "product_mid"};
const char *const rep_sweep_label[REP_SWEEP_VARIANTS] = {
    "the paper's DDC",
    "+ torque guard",
    "+ fewest transitions",
    "+ flux tie band 0.25 (the earlier default)",
    "+ zero state per set, tie band 0.5 (product default)",
    "+ mid-period angle (option)"};

void rep_cases_improvement_sweep(rep_case_t *cases, int *n, const char *dir)
{
    int v, li, seed;
    for (li = 0; li < REP_SWEEP_LAMBDAS; li++) {
        const double lambda = 20.0 * (li + 1);
        for (v = 0; v < REP_SWEEP_VARIANTS; v++) {
            for (seed = 1; seed <= REP_SWEEP_SEEDS; seed++) {
                char name[64];
                rep_case_t *c;
                (void)snprintf(name, sizeof name, "imp_%s_l%.0f_s%d", rep_sweep_variant[v], lambda,
                               seed);
                c = rep_add(cases, n, dir, "improve", name, 0, SIM_SCEN_STEADY, lambda);
                c->cfg.seed = (uint64_t)seed;
                c->cfg.out_dir = NULL; /* metrics only */
                c->cfg.ddc_torque_guard = (v >= 1) ? 1 : 0;
                /* -1: the core's default */
                c->cfg.pulse_pattern = (v >= REP_SWEEP_PRODUCT) ? -1 : ((v >= 2) ? 1 : 0);
                c->cfg.flux_tie_band = (v >= REP_SWEEP_PRODUCT) ? -1.0 : ((v >= 3) ? 0.25 : 0.0);
                c->cfg.mid_period_angle = (v >= REP_SWEEP_PRODUCT + 1) ? 1 : 0;
            }
        }
    }
}

const rep_case_t *rep_find(const rep_case_t *cases, int n, const char *name)
{
    int i;
    for (i = 0; i < n; i++) {
        if (strcmp(cases[i].name, name) == 0) {
            return cases[i].ok ? &cases[i] : NULL;
        }
    }
    return NULL;
}
