/*
 * The runs of `sixphase-sim reproduce` (brief §8): one table of cases, each a sim_config_t
 * with a name the report looks it up by.
 *
 * Sensor span: MPTC-49 and MPTC-13 reach 26-37 A, beyond the board's +-20 A current sensors,
 * so on the board they would decide on clipped measurements. The comparison runs them with
 * REP_BASELINE_SENSOR_SPAN_A sensors (the drive told the same span); the rows named board_*,
 * trip20_* and protect_* keep the board's +-20 A (what the board itself would do).
 */
#ifndef SIM_REPRODUCE_CASES_H
#define SIM_REPRODUCE_CASES_H

#include "batch.h"
#include "sim.h"

#define REP_MAX_CASES 256
#define REP_BASELINE_SENSOR_SPAN_A 50.0

typedef sim_case_t rep_case_t; /* group: steady, eqsw, dyn, lxy, extra, fault, improve */

/* The paper's lambdas and its numbers at them (brief §8). */
extern const double rep_paper_lambda[3];
extern const double rep_paper_thd_mptc[3], rep_paper_thd_ddc[3];
extern const double rep_paper_rip_mptc[3], rep_paper_rip_ddc[3];

/* Every case of the first batch into cases[0..*n); run outputs under dir/runs/NAME. */
void rep_cases_first_batch(rep_case_t *cases, int *n, const char *dir);

/* After the first batch: MPTC-49 at the sampling frequency that gives DDC's switching
 * frequency at each lambda (eqsw_mptc49_l*), appended. */
void rep_cases_equal_switching(rep_case_t *cases, int *n, const char *dir);

/* The improvements over the paper's DDC, side by side (docs/improvements.md): each variant at
 * lambda 20, 40, .., 200, seeds 1..REP_SWEEP_SEEDS (cases imp_<variant>_l<lambda>_s<seed>,
 * no output files). */
#define REP_SWEEP_SEEDS 3
#define REP_SWEEP_LAMBDAS 10
#define REP_SWEEP_VARIANTS 5
#define REP_SWEEP_PRODUCT 3 /* the variant that is the core's default */
extern const char *const rep_sweep_variant[REP_SWEEP_VARIANTS]; /* names */
extern const char *const rep_sweep_label[REP_SWEEP_VARIANTS];
void rep_cases_improvement_sweep(rep_case_t *cases, int *n, const char *dir);

/* The case of that name if it ran, else NULL. */
const rep_case_t *rep_find(const rep_case_t *cases, int n, const char *name);

#endif /* SIM_REPRODUCE_CASES_H */
