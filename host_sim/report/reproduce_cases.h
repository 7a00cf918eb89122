/*
 * The runs of `sixphase-sim reproduce` (brief §8): one table of cases, each a sim_config_t
 * with a name the report looks it up by.
 *
 * Sensor span: MPTC-49 reaches 26-38 A, beyond the board's +-20 A current sensors, so on the
 * board it would decide on clipped measurements. The comparison runs it with
 * REP_BASELINE_SENSOR_SPAN_A sensors (the drive told the same span); the rows named board_*,
 * trip20_* and protect_* keep the board's +-20 A (what the board itself would do). MPTC-13
 * (peaks up to 10 A) and the DDC run on the board's sensors, each on the finest sensors that do
 * not clip it (issue 27: MPTC-13 had read 2.5 times coarser currents than it needed).
 */
#ifndef SIM_REPRODUCE_CASES_H
#define SIM_REPRODUCE_CASES_H

#include "run/batch.h"
#include "run/sim.h"

#define REP_MAX_CASES 320
#define REP_BASELINE_SENSOR_SPAN_A 50.0

typedef sim_case_t rep_case_t; /* group: steady, eqsw, dyn, lxy, extra, fault, improve */

/* The paper's lambdas and its numbers at them (brief §8). */
extern const double rep_paper_lambda[3];
extern const double rep_paper_thd_mptc[3], rep_paper_thd_ddc[3];
extern const double rep_paper_rip_mptc[3], rep_paper_rip_ddc[3];

/* Every case of the first batch into cases[0..*n); run outputs under dir/runs/NAME. */
void rep_cases_first_batch(rep_case_t *cases, int *n, const char *dir);

/* Equal average switching frequency (report section 2): MPTC-49 and MPTC-13 at the sampling
 * frequency that gives the product DDC's switching frequency at 10 kHz (case guard_ddc_l*), at
 * each lambda, found by iteration: round r appends, for every baseline and lambda whose best
 * run so far is more than REP_EQSW_TOLERANCE off, a run eqsw_<mptc49|mptc13>_l<lambda>_r<r>
 * at the next estimate (the first from the 10 kHz run, then the secant through the two latest
 * runs; the estimate is deterministic, rounded to 10 Hz). Returns the number of runs appended
 * (0: every pair settled, or no new frequency to try). At most REP_EQSW_ROUNDS rounds. */
#define REP_EQSW_TOLERANCE 0.02
#define REP_EQSW_ROUNDS 6
int rep_cases_equal_switching(rep_case_t *cases, int *n, const char *dir, int round);

/* The run of a baseline ("mptc49" or "mptc13") at paper lambda index li whose switching
 * frequency is closest to the product DDC's at 10 kHz (*target), and the rounds it took;
 * NULL if none ran. */
const rep_case_t *rep_eqsw_best(const rep_case_t *cases, int n, const char *baseline, int li,
                                double *target, int *rounds);

/* The improvements over the paper's DDC, side by side (docs/improvements.md): each variant at
 * lambda 20, 40, .., 200, seeds 1..REP_SWEEP_SEEDS (cases imp_<variant>_l<lambda>_s<seed>,
 * no output files). */
#define REP_SWEEP_SEEDS 3
#define REP_SWEEP_LAMBDAS 10
#define REP_SWEEP_VARIANTS 6
#define REP_SWEEP_PRODUCT 4 /* the variant that is the core's default */
extern const char *const rep_sweep_variant[REP_SWEEP_VARIANTS]; /* names */
extern const char *const rep_sweep_label[REP_SWEEP_VARIANTS];
void rep_cases_improvement_sweep(rep_case_t *cases, int *n, const char *dir);

/* Appends a case with the paper's method (improvements off), output under dir/runs/NAME (no
 * fine.csv); the caller adjusts its configuration. */
rep_case_t *rep_add(rep_case_t *cases, int *n, const char *dir, const char *group, const char *name,
                    int controller, sim_scenario_t scen, double lambda);

/* The case of that name if it ran, else NULL. */
const rep_case_t *rep_find(const rep_case_t *cases, int n, const char *name);

#endif /* SIM_REPRODUCE_CASES_H */
